//! The suite's integration tests, one module each, in one binary: each test binary links the
//! whole suite, so one instead of fifteen saves their links (`isolation` and `process` run
//! without the test harness and stay apart).

mod broken;
mod depth_bias;
mod distances;
mod driver_findings;
mod expect;
mod facing;
mod fuzz_corpus;
mod layers;
mod levels;
mod outside;
mod pasteable;
mod polygon_modes;
mod readme;
mod restricted;
mod segment_oracle;
mod shaped;
mod shrinking;
mod spec_map;
mod unclipped_depth;
