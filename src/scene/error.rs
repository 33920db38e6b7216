//! Why a scene could not be loaded, and where in its file.
//!
//! Locations are 1-based: line 1 is the first line, column 1 the first character of a line. Columns count
//! Unicode scalar values (characters), not bytes, so they match what an editor shows for non-ASCII text.

use std::fmt;
use std::ops::Range;

/// What kind of problem stopped a scene from loading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneErrorKind {
    /// Neither a built-in scene name nor an existing file.
    UnknownScene,
    /// The file exists but could not be read (a directory, no permission, not UTF-8).
    Io,
    /// Not valid TOML, or not the scene schema: unknown key, wrong type, missing `shape`, unknown variant.
    Syntax,
    /// Well-formed, but a value is out of range or inconsistent (negative radius, sphere with
    /// half_extents, zero rotation axis, ...).
    Invalid,
}

/// A 1-based line and column in a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
}

impl Location {
    /// The location of byte offset `offset` in `text`. Offsets past the end map to the end of the text;
    /// an offset inside a multi-byte character maps to that character.
    pub fn of_offset(text: &str, offset: usize) -> Location {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &text[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Location {
            line: before.matches('\n').count() + 1,
            column: before[line_start..].chars().count() + 1,
        }
    }
}

/// A scene that could not be loaded.
///
/// `Display` gives one line, `SOURCE:LINE:COLUMN: MESSAGE` when the location is known (every problem
/// inside a file has one), `SOURCE: MESSAGE` otherwise. Messages are made [`readable`]: long quoted
/// values are cut, long numbers shortened.
///
/// [`readable`]: super::readable::readable
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub kind: SceneErrorKind,
    /// The scene name or file path as the user gave it.
    pub source_name: String,
    /// Where in the file, for `Syntax` and `Invalid` errors.
    pub location: Option<Location>,
    /// What is wrong, without the source and location.
    pub message: String,
}

impl SceneError {
    /// An error not tied to a place in a file.
    pub fn new(kind: SceneErrorKind, source_name: &str, message: impl Into<String>) -> Self {
        Self {
            kind,
            source_name: source_name.to_owned(),
            location: None,
            message: super::readable::readable(&message.into()),
        }
    }

    /// An error at byte span `span` of `text`, the contents of `source_name`.
    pub fn at(
        kind: SceneErrorKind,
        source_name: &str,
        text: &str,
        span: Range<usize>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            location: Some(Location::of_offset(text, span.start)),
            ..Self::new(kind, source_name, message)
        }
    }

    /// 1-based line, if known.
    pub fn line(&self) -> Option<usize> {
        self.location.map(|l| l.line)
    }

    /// 1-based column, if known.
    pub fn column(&self) -> Option<usize> {
        self.location.map(|l| l.column)
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some(Location { line, column }) => {
                write!(f, "{}:{line}:{column}: {}", self.source_name, self.message)
            }
            None => write!(f, "{}: {}", self.source_name, self.message),
        }
    }
}

impl std::error::Error for SceneError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_map_to_one_based_lines_and_columns() {
        let text = "a = 1\nbb = 2\n";
        assert_eq!(
            Location::of_offset(text, 0),
            Location { line: 1, column: 1 }
        );
        assert_eq!(
            Location::of_offset(text, 5),
            Location { line: 1, column: 6 }
        );
        assert_eq!(
            Location::of_offset(text, 6),
            Location { line: 2, column: 1 }
        );
        assert_eq!(
            Location::of_offset(text, 11),
            Location { line: 2, column: 6 }
        );
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let text = "# é\nname = \"ü\" x";
        let offset = text.find('x').unwrap();
        assert_eq!(
            Location::of_offset(text, offset),
            Location {
                line: 2,
                column: 12
            }
        );
    }

    #[test]
    fn offsets_past_the_end_or_inside_a_character_do_not_panic() {
        let text = "é";
        assert_eq!(
            Location::of_offset(text, 1),
            Location { line: 1, column: 1 }
        );
        assert_eq!(
            Location::of_offset(text, 99),
            Location { line: 1, column: 2 }
        );
    }

    #[test]
    fn display_puts_source_line_and_column_first() {
        let err = SceneError::at(
            SceneErrorKind::Invalid,
            "scenes/bad.toml",
            "a\nradius = -1\n",
            11..13,
            "radius must be finite and > 0, got -1",
        );
        assert_eq!(
            err.to_string(),
            "scenes/bad.toml:2:10: radius must be finite and > 0, got -1"
        );
    }
}
