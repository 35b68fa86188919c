//! fast's integration tests, one module each, in one binary: one link instead of three
//! (`catalogue` runs without the test harness and stays apart).

#[path = "../support/mod.rs"]
mod support;

mod differential;
mod levels;
mod render;
