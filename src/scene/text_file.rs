//! Reading a text file a user named (a scene, a recording) without trusting its size or encoding:
//! `--scene /dev/zero` used to read until memory ran out, and a stray byte that is not UTF-8 got a
//! message without a place.

use std::io::Read;

use super::error::Location;

/// Largest file read, bytes: a generous bound (a million bodies fit in a scene this size) that
/// keeps `/dev/zero` or a runaway file from filling memory.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Why a file could not be read as text.
#[derive(Debug)]
pub enum TextFileError {
    /// Opening or reading failed.
    Io(std::io::Error),
    /// The file holds more than [`MAX_FILE_BYTES`]; reading stopped there.
    TooLarge,
    /// Not UTF-8: where the first bad byte is.
    NotUtf8(Location),
}

impl TextFileError {
    /// What went wrong, for a message after the file's name (the location, if any, is separate).
    pub fn message(&self, what: &str) -> String {
        match self {
            TextFileError::Io(err) => format!("cannot read {what}: {err}"),
            TextFileError::TooLarge => format!(
                "{what} is larger than {} MB; not read further",
                MAX_FILE_BYTES >> 20
            ),
            TextFileError::NotUtf8(_) => format!("{what} is not valid UTF-8 text here"),
        }
    }

    /// Where in the file, for text that is not UTF-8.
    pub fn location(&self) -> Option<Location> {
        match self {
            TextFileError::NotUtf8(location) => Some(*location),
            _ => None,
        }
    }
}

/// The text of the file at `path`: at most [`MAX_FILE_BYTES`] read, UTF-8 required.
pub fn read_text(path: &str) -> Result<String, TextFileError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|file| file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(TextFileError::Io)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(TextFileError::TooLarge);
    }
    String::from_utf8(bytes).map_err(|err| {
        let bytes = err.as_bytes();
        let valid_up_to = err.utf8_error().valid_up_to();
        let valid = std::str::from_utf8(&bytes[..valid_up_to]).unwrap_or_default();
        TextFileError::NotUtf8(Location::of_offset(valid, valid.len()))
    })
}
