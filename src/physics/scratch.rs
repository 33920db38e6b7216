//! Buffers a stage keeps from step to step: reset in place, so a world at its steady-state size
//! allocates nothing (see `world::Scratch`).

/// `buffer` as `len` copies of `value`, its allocation kept.
#[inline]
pub(crate) fn refill<T: Clone>(buffer: &mut Vec<T>, len: usize, value: T) {
    buffer.clear();
    buffer.resize(len, value);
}
