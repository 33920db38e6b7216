//! `TERM=dumb`: a terminal that promises nothing beyond printing lines (Emacs' shell buffer, some
//! CI logs and editors' consoles). The sandbox needs cursor movement, the alternate screen, raw
//! mode and colours; drawing into such a terminal floods it with escape sequences it shows as
//! text, so the sandbox refuses it, as `less` and `top` warn or refuse, and points at what works.

/// `Err` with a message when `term` (the value of `TERM`) says the terminal cannot show the
/// sandbox; what to run instead is part of the message.
pub fn refuse_dumb(term: Option<&str>) -> Result<(), String> {
    match term {
        Some("dumb") => Err(
            "TERM=dumb: this terminal cannot move the cursor or show colours, so the \
             sandbox cannot run in it (to print a frame instead, use `nudge snapshot --plain`)"
                .into(),
        ),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_dumb_is_refused() {
        assert!(refuse_dumb(Some("dumb")).unwrap_err().contains("snapshot"));
        for term in [None, Some("xterm-256color"), Some("linux"), Some("")] {
            assert!(refuse_dumb(term).is_ok(), "{term:?}");
        }
    }
}
