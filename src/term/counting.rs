//! Counting the bytes sent to the terminal, for the "bytes per frame / per second" readout: the
//! number that matters over ssh, and the one our half-block choices (blank cells, quantising before
//! comparing) try to keep small.
//!
//! Wrap the backend's writer: `CrosstermBackend::new(CountingWriter::new(stdout()))`, keep a
//! [`ByteCounter`] from [`CountingWriter::counter`], and read it after each draw.

use std::io::{self, IoSlice, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// A shared, cheap-to-clone handle on a byte count. Counts only ever increase, except through
/// [`ByteCounter::take`].
#[derive(Clone, Debug, Default)]
pub struct ByteCounter(Arc<AtomicU64>);

impl ByteCounter {
    /// Bytes counted so far (since creation or the last [`take`](Self::take)).
    pub fn get(&self) -> u64 {
        self.0.load(Ordering::Relaxed)
    }

    /// Returns the count and resets it to zero in one step (for per-frame or per-second figures).
    pub fn take(&self) -> u64 {
        self.0.swap(0, Ordering::Relaxed)
    }

    fn add(&self, n: usize) {
        self.0.fetch_add(n as u64, Ordering::Relaxed);
    }
}

/// A [`Write`] adapter that forwards to `W` and counts the bytes `W` accepted (what `write`
/// returned, not what was offered), so partial writes and errors are counted correctly.
#[derive(Debug)]
pub struct CountingWriter<W: Write> {
    inner: W,
    counter: ByteCounter,
}

impl<W: Write> CountingWriter<W> {
    /// Wraps `inner` with a fresh counter at zero.
    pub fn new(inner: W) -> Self {
        Self::with_counter(inner, ByteCounter::default())
    }

    /// Wraps `inner`, adding to an existing `counter` (e.g. one that outlives a terminal re-creation).
    pub fn with_counter(inner: W, counter: ByteCounter) -> Self {
        Self { inner, counter }
    }

    /// A handle on this writer's count, readable while the writer is owned elsewhere.
    pub fn counter(&self) -> ByteCounter {
        self.counter.clone()
    }

    /// The wrapped writer.
    pub fn get_ref(&self) -> &W {
        &self.inner
    }

    /// The wrapped writer, mutably (bytes written through this are not counted).
    pub fn get_mut(&mut self) -> &mut W {
        &mut self.inner
    }

    /// Unwraps the writer.
    pub fn into_inner(self) -> W {
        self.inner
    }
}

impl<W: Write> Write for CountingWriter<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.counter.add(n);
        Ok(n)
    }

    fn write_vectored(&mut self, bufs: &[IoSlice<'_>]) -> io::Result<usize> {
        let n = self.inner.write_vectored(bufs)?;
        self.counter.add(n);
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_every_byte_written() {
        let mut w = CountingWriter::new(Vec::new());
        let counter = w.counter();
        w.write_all(b"hello").unwrap();
        write!(w, "{}m", 42).unwrap();
        w.flush().unwrap();
        assert_eq!(counter.get(), 8);
        assert_eq!(w.get_ref().len(), 8);
    }

    #[test]
    fn take_returns_the_count_and_restarts_from_zero() {
        let mut w = CountingWriter::new(Vec::new());
        let counter = w.counter();
        w.write_all(&[0; 100]).unwrap();
        assert_eq!(counter.take(), 100);
        assert_eq!(counter.get(), 0);
        w.write_all(&[0; 7]).unwrap();
        assert_eq!(counter.take(), 7);
    }

    #[test]
    fn vectored_writes_are_counted() {
        let mut w = CountingWriter::new(Vec::new());
        let n = w
            .write_vectored(&[IoSlice::new(b"ab"), IoSlice::new(b"cde")])
            .unwrap();
        assert_eq!(w.counter().get(), n as u64);
        assert_eq!(w.into_inner().len(), n);
    }

    /// A writer that accepts at most 3 bytes per call.
    struct Trickle(Vec<u8>);
    impl Write for Trickle {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            let n = buf.len().min(3);
            self.0.extend_from_slice(&buf[..n]);
            Ok(n)
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn partial_writes_count_only_what_was_accepted() {
        let mut w = CountingWriter::new(Trickle(Vec::new()));
        assert_eq!(w.write(b"abcdefgh").unwrap(), 3);
        assert_eq!(w.counter().get(), 3);
        w.write_all(b"12345678").unwrap();
        assert_eq!(w.counter().get(), 11);
    }

    #[test]
    fn a_shared_counter_sums_several_writers() {
        let counter = ByteCounter::default();
        let mut a = CountingWriter::with_counter(Vec::new(), counter.clone());
        let mut b = CountingWriter::with_counter(Vec::new(), counter.clone());
        a.write_all(b"12").unwrap();
        b.write_all(b"345").unwrap();
        assert_eq!(counter.get(), 5);
    }
}
