//! (being built)
pub mod hard_case;
pub mod penetration;
pub mod physics;
pub mod poke;
pub mod table;
