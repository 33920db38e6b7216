//! Time in the sandbox: the fixed-step clock, the timeline of inputs and keyframes, rewinding and
//! replaying through it, recording a session, and saving the world as it is now. Kept together
//! because each of them reads or writes the same timeline.

pub mod clock;
pub mod record;
pub mod rewind;
pub mod save;
pub mod timeline;
