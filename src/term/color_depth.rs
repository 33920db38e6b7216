//! How many colours the terminal can show, and how to guess it from the environment.
//!
//! Detection follows the de-facto conventions (see termstandard/colors):
//! - `COLORTERM=truecolor` or `COLORTERM=24bit` → 24-bit colour, certain.
//! - `TERM` ending in `-direct` (terminfo's direct-colour entries, e.g. `xterm-direct`) → 24-bit, certain.
//! - `TERM_PROGRAM` naming a terminal that always does 24-bit colour (iTerm2, WezTerm, VS Code, Ghostty,
//!   Hyper, Warp, Rio, Tabby) → 24-bit, certain: they set it even where `COLORTERM` got lost (a login
//!   shell that resets the environment, `sudo`). ssh forwards neither, so it cannot misfire remotely.
//!   Apple's Terminal is not listed: only its newest versions do 24-bit colour.
//! - `TERM` containing `256color` → the xterm 256-colour palette, **not certain**: ssh does not forward
//!   `COLORTERM`, so a truecolor terminal reached over ssh looks exactly like this. The app should say
//!   in its status bar that `--colors truecolor` may look better ([`Detected::hint`]).
//! - any other `TERM` (`xterm`, `screen`, `linux`, …) → the 16 ANSI colours, **not certain**, with the
//!   same hint: many terminals reached as plain `xterm` or `screen` do far more.
//! - no `TERM` at all → the 16 ANSI colours, certain (nothing to go on).

use std::fmt;

/// The colour palette used to draw cells.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorDepth {
    /// 24-bit colour (`ESC[38;2;r;g;bm`).
    #[default]
    TrueColor,
    /// The xterm 256-colour palette; we use only indices 16..=255 (the 6×6×6 cube and the grey ramp),
    /// whose values are fixed, never the user-themable 0..=15.
    Ansi256,
    /// The 16 standard ANSI colours (themable; we match against xterm's default values).
    Ansi16,
}

impl ColorDepth {
    /// All depths, richest first.
    pub const ALL: [ColorDepth; 3] = [
        ColorDepth::TrueColor,
        ColorDepth::Ansi256,
        ColorDepth::Ansi16,
    ];

    /// The canonical command-line spelling: `"truecolor"`, `"256"` or `"16"` (what `--colors` accepts,
    /// with `"24bit"` for truecolor; see `cli`).
    pub const fn name(self) -> &'static str {
        match self {
            ColorDepth::TrueColor => "truecolor",
            ColorDepth::Ansi256 => "256",
            ColorDepth::Ansi16 => "16",
        }
    }
}

impl fmt::Display for ColorDepth {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The result of guessing the colour depth from the environment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Detected {
    /// The depth to use.
    pub depth: ColorDepth,
    /// `false` when the environment is ambiguous and a richer depth may well work (a 256-colour `TERM`
    /// with no `COLORTERM`, typical of ssh sessions); the app should then show [`Detected::hint`].
    pub certain: bool,
}

impl Detected {
    /// A short status-bar note when the guess is uncertain, telling the user how to switch;
    /// `None` when certain.
    pub fn hint(&self) -> Option<String> {
        (!self.certain).then(|| guessed_hint(self.depth))
    }
}

/// The status-bar note for a colour depth that was guessed: how to ask for a richer one.
pub fn guessed_hint(depth: ColorDepth) -> String {
    format!("{} (guessed; try --colors truecolor)", depth.name())
}

/// `TERM_PROGRAM` values of terminals that always do 24-bit colour.
const TRUECOLOR_PROGRAMS: [&str; 8] = [
    "iTerm.app",
    "WezTerm",
    "vscode",
    "ghostty",
    "Hyper",
    "WarpTerminal",
    "rio",
    "Tabby",
];

/// Guesses the colour depth from the values of `COLORTERM`, `TERM` and `TERM_PROGRAM` (pure, for
/// testing; see the module docs for the rules). Empty values count as unset.
pub fn detect(colorterm: Option<&str>, term: Option<&str>, term_program: Option<&str>) -> Detected {
    let colorterm = colorterm.map(str::trim).filter(|s| !s.is_empty());
    let term = term.map(str::trim).filter(|s| !s.is_empty());

    let says_truecolor = colorterm
        .is_some_and(|c| c.eq_ignore_ascii_case("truecolor") || c.eq_ignore_ascii_case("24bit"));
    let truecolor_program = term_program.is_some_and(|p| {
        TRUECOLOR_PROGRAMS
            .iter()
            .any(|known| p.trim().eq_ignore_ascii_case(known))
    });
    if says_truecolor || truecolor_program || term.is_some_and(|t| t.ends_with("-direct")) {
        return Detected {
            depth: ColorDepth::TrueColor,
            certain: true,
        };
    }
    if term.is_some_and(|t| t.contains("256color")) {
        return Detected {
            depth: ColorDepth::Ansi256,
            certain: false,
        };
    }
    Detected {
        depth: ColorDepth::Ansi16,
        certain: term.is_none(),
    }
}

/// Why the sandbox cannot run under `TERM` (`None` if it can): a `dumb` terminal has no cursor
/// movement or colour, and full-screen escape codes would only litter it.
pub fn unusable_term(term: Option<&str>) -> Option<String> {
    (term.map(str::trim) == Some("dumb")).then(|| {
        "TERM=dumb: this terminal cannot show the sandbox (no cursor movement, no colour); \
         print a frame with `nudge snapshot --plain` instead"
            .to_string()
    })
}

/// [`unusable_term`] for this process's `TERM`, as an error message.
pub fn check_term_env() -> Result<(), String> {
    match unusable_term(std::env::var("TERM").ok().as_deref()) {
        Some(message) => Err(message),
        None => Ok(()),
    }
}

/// [`detect`] applied to this process's `COLORTERM`, `TERM` and `TERM_PROGRAM` (non-UTF-8 values count
/// as unset).
pub fn detect_from_env() -> Detected {
    let colorterm = std::env::var("COLORTERM").ok();
    let term = std::env::var("TERM").ok();
    let term_program = std::env::var("TERM_PROGRAM").ok();
    detect(
        colorterm.as_deref(),
        term.as_deref(),
        term_program.as_deref(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn depth_of(colorterm: Option<&str>, term: Option<&str>) -> (ColorDepth, bool) {
        let d = detect(colorterm, term, None);
        (d.depth, d.certain)
    }

    #[test]
    fn display_is_the_name() {
        for depth in ColorDepth::ALL {
            assert_eq!(depth.to_string(), depth.name());
        }
    }

    #[test]
    fn colorterm_truecolor_or_24bit_is_certain_truecolor() {
        let expected = (ColorDepth::TrueColor, true);
        assert_eq!(
            depth_of(Some("truecolor"), Some("xterm-256color")),
            expected
        );
        assert_eq!(depth_of(Some("24bit"), Some("xterm")), expected);
        assert_eq!(depth_of(Some("truecolor"), None), expected);
    }

    #[test]
    fn direct_colour_term_is_certain_truecolor_without_colorterm() {
        assert_eq!(
            depth_of(None, Some("xterm-direct")),
            (ColorDepth::TrueColor, true)
        );
    }

    #[test]
    fn a_truecolor_terminal_program_is_certain_truecolor_without_colorterm() {
        for program in ["iTerm.app", "WezTerm", "vscode", "ghostty"] {
            let d = detect(None, Some("xterm-256color"), Some(program));
            assert_eq!(
                (d.depth, d.certain),
                (ColorDepth::TrueColor, true),
                "{program}"
            );
        }
        // Apple's Terminal and tmux say nothing either way: the TERM rules decide.
        for program in ["Apple_Terminal", "tmux", ""] {
            let d = detect(None, Some("xterm-256color"), Some(program));
            assert_eq!(
                (d.depth, d.certain),
                (ColorDepth::Ansi256, false),
                "{program}"
            );
        }
    }

    #[test]
    fn a_256color_term_without_colorterm_is_an_uncertain_256() {
        // The ssh case: the local terminal may do truecolor but COLORTERM did not travel.
        for term in ["xterm-256color", "screen-256color", "tmux-256color"] {
            assert_eq!(
                depth_of(None, Some(term)),
                (ColorDepth::Ansi256, false),
                "{term}"
            );
        }
        let hint = detect(None, Some("xterm-256color"), None).hint().unwrap();
        assert!(hint.contains("--colors truecolor"), "{hint}");
    }

    #[test]
    fn other_colorterm_values_do_not_promise_truecolor() {
        assert_eq!(
            depth_of(Some("rxvt-xpm"), Some("rxvt-unicode-256color")),
            (ColorDepth::Ansi256, false)
        );
    }

    #[test]
    fn a_missing_term_falls_back_to_certain_16() {
        for term in [None, Some("")] {
            assert_eq!(depth_of(None, term), (ColorDepth::Ansi16, true), "{term:?}");
        }
        assert_eq!(detect(Some(""), None, None).hint(), None);
    }

    /// `TERM=xterm`, `screen` and `linux` dropped to 16 colours without a word.
    #[test]
    fn a_plain_term_is_an_uncertain_16_with_the_256_colour_guess_hint() {
        for term in ["xterm", "screen", "linux", "vt100"] {
            let d = detect(None, Some(term), None);
            assert_eq!((d.depth, d.certain), (ColorDepth::Ansi16, false), "{term}");
            assert_eq!(d.hint().unwrap(), guessed_hint(ColorDepth::Ansi16));
        }
        assert!(guessed_hint(ColorDepth::Ansi16).contains("--colors truecolor"));
    }

    #[test]
    fn a_dumb_terminal_is_refused_with_a_pointer_to_plain_snapshots() {
        let message = unusable_term(Some("dumb")).unwrap();
        assert!(message.contains("nudge snapshot --plain"), "{message}");
        for term in [None, Some("xterm"), Some("xterm-256color")] {
            assert_eq!(unusable_term(term), None, "{term:?}");
        }
    }
}
