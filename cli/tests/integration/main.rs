//! The command line's integration tests, one module each, in one binary: each test binary
//! links the whole suite, so one instead of eight saves their links.

#[path = "../support/mod.rs"]
mod support;

mod clients;
mod expect;
mod impls;
mod render;
mod report;
mod results;
mod student;
mod view;
