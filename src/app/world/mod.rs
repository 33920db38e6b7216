//! Changes the sandbox makes to the world's bodies besides the hand's pushes: dropping new ones
//! (`b`, `s`), growing and shrinking one (`<`, `>`), freezing those that fell off, and switching to
//! another built-in scene.

pub mod grow;
pub mod lost;
pub mod scene_cycle;
pub mod spawn;
