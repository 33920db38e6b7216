//! Error messages a person can read whatever the file held: a 5 MB string or a 309-digit number in a
//! scene file must not become a 5 MB or 309-digit error line.
//!
//! [`readable`] rewrites a finished message: quoted text (between `"` or `` ` ``) longer than
//! [`MAX_QUOTED`] characters is cut with an ellipsis, any other run of non-space characters longer
//! than [`MAX_WORD`] too, and runs of more than 17 digits (serde prints `1e308` in full) become the
//! number's short scientific form.

/// Most characters of a quoted value shown.
pub const MAX_QUOTED: usize = 60;
/// Most characters of any other word shown.
pub const MAX_WORD: usize = 80;

/// `message` with long numbers shortened and long values cut (see the module docs).
pub fn readable(message: &str) -> String {
    cut_long(&shorten_numbers(message))
}

/// Runs of digits (with at most one `.`) holding more than 17 digits, as `{:e}` of their value.
fn shorten_numbers(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4096));
    let mut chars = message.char_indices().peekable();
    while let Some((start, c)) = chars.next() {
        if !c.is_ascii_digit() {
            out.push(c);
            continue;
        }
        let mut end = start + 1;
        let mut digits = 1;
        let mut dots = 0;
        while let Some(&(i, next)) = chars.peek() {
            if next.is_ascii_digit() {
                digits += 1;
            } else if next == '.' && dots == 0 {
                dots += 1;
            } else {
                break;
            }
            end = i + 1;
            chars.next();
        }
        let run = &message[start..end];
        match run.trim_end_matches('.').parse::<f64>() {
            Ok(value) if digits > 17 => {
                out.push_str(&format!("{value:e}"));
                if run.ends_with('.') {
                    out.push('.');
                }
            }
            _ => out.push_str(run),
        }
    }
    out
}

/// Quoted spans over [`MAX_QUOTED`] characters and other words over [`MAX_WORD`], cut.
fn cut_long(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4096));
    let mut rest = message;
    while let Some(c) = rest.chars().next() {
        if c == '"' || c == '`' {
            // A quoted span: up to the matching quote, or the end of the message.
            let body = &rest[1..];
            let (inner, after, closed) = match body.find(c) {
                Some(i) => (&body[..i], &body[i + 1..], true),
                None => (body, "", false),
            };
            out.push(c);
            push_cut(&mut out, inner, MAX_QUOTED);
            if closed {
                out.push(c);
            }
            rest = after;
        } else if c.is_whitespace() {
            out.push(c);
            rest = &rest[c.len_utf8()..];
        } else {
            let end = rest
                .find(|ch: char| ch.is_whitespace() || ch == '"' || ch == '`')
                .unwrap_or(rest.len());
            push_cut(&mut out, &rest[..end], MAX_WORD);
            rest = &rest[end..];
        }
    }
    out
}

/// `text` cut to `max` characters with an ellipsis if longer: for a value quoted in a message.
pub fn cut(text: &str, max: usize) -> String {
    let mut out = String::new();
    push_cut(&mut out, text, max);
    out
}

/// Appends `text`, cut to `max` characters with an ellipsis if longer.
fn push_cut(out: &mut String, text: &str, max: usize) {
    match text.char_indices().nth(max) {
        Some((cut, _)) => {
            out.push_str(&text[..cut]);
            out.push('…');
        }
        None => out.push_str(text),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_309_digit_number_prints_in_short_form() {
        let long = format!("1{}", "0".repeat(308));
        let message =
            format!("gravity: invalid type: floating point `{long}`, expected a sequence");
        assert_eq!(
            readable(&message),
            "gravity: invalid type: floating point `1e308`, expected a sequence"
        );
    }

    #[test]
    fn ordinary_numbers_are_untouched() {
        let message = "t.toml: radius must be between 0.001 and 1000, got 1e-20 at 12345";
        assert_eq!(readable(message), message);
    }

    #[test]
    fn long_quoted_values_are_cut_with_an_ellipsis() {
        let value = "x".repeat(5_000_000);
        let shown = readable(&format!("color must be \"#rrggbb\", got \"{value}\""));
        assert_eq!(
            shown,
            format!(
                "color must be \"#rrggbb\", got \"{}…\"",
                "x".repeat(MAX_QUOTED)
            )
        );
        let key = "k".repeat(1000);
        let shown = readable(&format!("{key}: unknown field `{key}`"));
        assert!(shown.chars().count() < 200, "{shown}");
    }

    #[test]
    fn an_unclosed_quote_and_multibyte_text_do_not_panic() {
        let shown = readable(&format!("got \"{}", "é".repeat(100)));
        assert_eq!(shown, format!("got \"{}…", "é".repeat(MAX_QUOTED)));
    }
}
