//! Testing support shared by the tests and `nudge bench`: the hard-case runners, which run a scene of
//! [`crate::scene::cases`] and measure its error from the bodies alone; the penetration oracle they
//! measure overlap with (geometry the engine did not compute); the corpus of hard-case families
//! generated from parameters; and the random pokes of a simulated user. Not used by the sandbox
//! itself.

pub mod corpus;
pub mod hard_case;
pub mod penetration;
pub mod poke;
