//! Helpers shared by the integration tests (each test crate — `tests/app`, `tests/physics`, ... —
//! uses a part of these, hence the allowance for unused ones).
#![allow(dead_code)]

pub mod app;
pub mod cli;
pub mod joints;
pub mod render;
pub mod temp;
