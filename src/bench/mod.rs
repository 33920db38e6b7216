//! (being built)
pub mod hard_case;
pub mod penetration;
pub mod poke;
