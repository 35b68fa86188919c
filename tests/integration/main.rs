//! The reference's integration tests, one module each, in one binary: one link instead of
//! twelve (`catalogue` and `catalogue_full_clip` run without the test harness and stay apart).

#[path = "../support/mod.rs"]
mod support;

mod architecture;
mod clipping;
mod facing;
mod fill_rule;
mod golden;
mod lines;
mod oracle;
mod pipeline;
mod regressions;
mod robustness;
mod snapping;
mod stats;
