//! The renderer's integration tests, one module each, in one binary: one link instead of four.

mod draw;
mod fuzz_corpus;
mod load;
mod shapes;
