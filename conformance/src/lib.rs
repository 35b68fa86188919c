//! The refrast conformance suite: a catalogue of rules that certifies any [`refrast::Rasterizer`].
//!
//! The modules form layers, each using only those above it (`tests/layers.rs` checks it):
//!
//! | layer | module | what |
//! |---|---|---|
//! | 0 | [`oracle`] | the conventions' geometry ([`oracle::raster`]), brute force (i128 `orient2d`), ray casting (f64 with exact fallback, clip space), visible outlines; no code shared with the reference |
//! | 1 | `scene` | [`Scene`]: a draw whose `Debug` is pasteable Rust; [`Case`]: what a rule's input is |
//! | 2 | `violation` | [`Violation`], [`Counts`], [`Expect`], [`Picture`] |
//! | 3 | [`picture`] | the zoomed sample grid: missing purple, unexpected red, double blue, don't-care yellow; outlines |
//! | 4 | [`strategy`] | free functions that build valid scenes: grid triangles, spade meshes, fans, quads, clip crossings |
//! | 5 | `runner` | [`property`]: one rule's property, seeded, shrunk, panics caught |
//! | 6 | [`rules`] | [`catalogue`], [`Rule`], [`Family`], [`Kind`], [`Need`]: six families, each rule a proptest property |
//! | 7 | `report` | [`Report`], [`RuleReport`], [`Status`], [`ProfileReport`] |
//! | 8 | `certify` | [`certify`], [`Options`] |
//! | 9 | [`isolate`] | rules in child processes: a hang, an abort or a crash fails the rule it was running |
//! | 10 | `harness`, [`fuzz`] | [`run_as_tests`]: one test per rule in your own crate; the cargo-fuzz targets as functions on any rasterizer |
//! | — | `impls` | [`builtins`]: the implementations `refrast certify --impl` knows (refrast only) |
//! | — | [`restricted`] | the reference restricted to one setting or a few, declaring and using only those (refrast only) |
//! | — | [`process`] | [`Process`]: a rasterizer in any language, in a child speaking `PROTOCOL.md` (refrast only) |
//!
//! # Kinds and tolerance
//!
//! An *invariant* rule must hold for any correct rasterizer; it ignores samples within the
//! profile's tolerance band of an edge (never less than one subpixel, since snapping moves edges
//! by up to √2/2 subpixel). An *exact* rule compares bit for bit with the reference (or the
//! brute-force oracle) configured with the implementation's own profile. A rule that needs a
//! feature the profile lacks is *not applicable*, which is never counted as passed.
#![forbid(unsafe_code)]

mod certify;
pub mod fuzz;
mod harness;
mod impls;
pub mod isolate;
pub mod oracle;
pub mod picture;
pub mod process;
mod report;
pub mod restricted;
pub mod rules;
mod runner;
mod scene;
pub mod strategy;
mod violation;

pub use certify::{DEFAULT_CASE_TIMEOUT, Options, cases_for, certify, matches, refusal, run_rule};
pub use harness::{failure_text, run_as_tests};
pub use impls::{BuiltIn, Maker, Named, Origin, Unavailable, builtins};
pub use process::{Process, ProcessError};
pub use report::{ProfileReport, Report, RuleReport, Status, feature_list, fill_name};
pub use rules::meta::Translated;
pub use rules::robust::Poisoned;
pub use rules::{
    Family, Kind, Level, Levels, Need, Rule, RuleDraft, catalogue, levels_markdown, markdown_table, needs,
};
pub use runner::{DEFAULT_SEED, RunConfig, Verdict, property, property_for};
pub use scene::{Case, Scene, clip_of};
pub use violation::{Class, Counts, Expect, Findings, Picture, Violation, compare_coverage, count_fragments};
