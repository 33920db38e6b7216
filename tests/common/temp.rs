//! Files and directories under the temp directory for a test to write, each with a path of its own.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A path under the temp directory, unique per process and per call (the tests of one crate run
/// on parallel threads of one process: a path from the process id alone was shared by two tests,
/// and one read the file after the other removed it), removed with whatever is there when dropped.
pub struct TempPath(pub PathBuf);

impl TempPath {
    /// A new path ending in `tag` (a file name such as `session.toml`, or a directory's).
    pub fn new(tag: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let name = format!("nudge-test-{}-{n}-{tag}", std::process::id());
        Self(std::env::temp_dir().join(name))
    }

    /// A new file ending in `tag`, holding `text`.
    pub fn with_text(tag: &str, text: &str) -> Self {
        let file = Self::new(tag);
        std::fs::write(&file.0, text).expect("write a temp file");
        file
    }

    /// The path as text, for a command line.
    pub fn as_str(&self) -> &str {
        self.0.to_str().expect("temp path is UTF-8")
    }
}

impl Drop for TempPath {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
