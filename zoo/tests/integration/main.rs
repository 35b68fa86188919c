//! The zoo's integration tests, one module each, in one binary: one link instead of four.

mod course;
mod hints;
mod mutants;
mod visibility;
