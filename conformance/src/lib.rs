//! The refrast conformance suite: a catalogue of rules that certifies any [`refrast::Rasterizer`].
//!
//! A certifier needs the root's names: [`run_as_tests`] or [`certify`], [`Options`], the
//! [`Report`] types, the [`catalogue`], [`replay`], the [`spec`] map, [`expect`] files and the
//! [`fuzz`] targets. The modules in *italics* below are the suite's inner workings: public only
//! with the `internals` feature (its own tests and the workspace's cross-checks use them), and
//! free to change in any release.
//!
//! The modules form layers, each using only those above it (`tests/integration/layers.rs` checks it):
//!
//! | layer | module | what |
//! |---|---|---|
//! | 0 | `status` | [`Status`]: pass, fail, crash, timeout, flake, beyond-spec, n/a |
//! | 1 | *`oracle`* | the conventions' geometry (`oracle::raster`), brute force (i128 `orient2d`), ray casting (f64 with exact fallback, clip space), visible outlines, lines, points and samples (`oracle::segment`); no code shared with the reference |
//! | 2 | `scene` | [`Scene`]: a draw whose `Debug` is pasteable Rust; [`PrimitiveScene`]: a scene drawn as lines or points, or at several samples per pixel; [`Case`]: what a rule's input is; [`CaseData`]: an input as data, the draw in the pipe protocol's words |
//! | 3 | `violation` | `Violation`, [`Counts`], `Expect`, [`Picture`] |
//! | 4 | *`picture`* | the zoomed sample grid: missing purple, unexpected red, double blue, don't-care yellow; outlines |
//! | 5 | *`strategy`* | free functions that build valid scenes: grid triangles, spade meshes, fans, quads, clip crossings |
//! | 6 | `runner` | `property`: one rule's property, seeded, shrunk, panics caught |
//! | 7 | *`rules`* | [`catalogue`], [`Rule`], [`Family`], [`Kind`], [`Need`]: nine families, each rule a proptest property |
//! | 8 | `report`, [`spec`] | [`Report`], [`RuleReport`] (with its [`Exhibit`], the files a failure leaves for the runner to write), [`Status`], [`ProfileReport`]; [`SpecMap`]: each normative statement of Vulkan, D3D11.3, OpenGL and OpenGL ES, the seeds' results and refrast's conventions, with the rules that check it |
//! | 9 | `judge` | [`run_rule`], [`replay`], [`Options`]: one rule on one rasterizer, its verdict read under the claimed specification, a hint, a picture, the case as data |
//! | 10 | `certify` | [`certify`]: the selected rules, in order or on several workers |
//! | 11 | [`isolate`], [`expect`] | rules in child processes: a hang is a `timeout`, an abort or a crash a `crash` of the rule it was running; expectation files |
//! | 12 | `harness`, [`fuzz`] | [`run_as_tests`]: one test per rule in your own crate; the cargo-fuzz targets as functions on any rasterizer |
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
pub mod expect;
pub mod fuzz;
mod harness;
pub mod isolate;
mod judge;
mod report;
mod runner;
mod scene;
pub mod spec;
mod status;
mod violation;

// The suite's inner workings: public only with the `internals` feature, for the suite's own
// tests and the workspace's cross-checks of oracles against implementations. They are not the
// certifier's API and may change in any release.
#[cfg(feature = "internals")]
pub mod oracle;
#[cfg(not(feature = "internals"))]
mod oracle;
#[cfg(feature = "internals")]
pub mod picture;
#[cfg(not(feature = "internals"))]
mod picture;
#[cfg(feature = "internals")]
pub mod rules;
#[cfg(not(feature = "internals"))]
mod rules;
#[cfg(feature = "internals")]
pub mod strategy;
#[cfg(not(feature = "internals"))]
mod strategy;

// What a certifier uses: run the rules, read the reports, replay a counterexample.
pub use certify::{certify, certify_with, matches, refusal, selected};
pub use harness::run_as_tests;
pub use judge::{DEFAULT_CASE_TIMEOUT, Options, Shard, cases_for, replay, run_rule};
pub use report::{
    CaseFile, Exhibit, Part, ProfileReport, Report, RuleReport, Status, feature_list, fill_name,
};
pub use rules::{Family, Kind, Level, Levels, Need, Rule, catalogue, levels_markdown, markdown_table};
pub use runner::DEFAULT_SEED;
// A counterexample printed as Rust names these (`use refrast_conformance::*;` pastes it).
pub use rules::{meta::Translated, robust::Poisoned};
pub use scene::{Case, CaseData, Coordinate, DistanceData, DrawData, Poison, PrimitiveScene, Scene};
pub use spec::{Coverage, SpecMap, Statement, spec_map};
pub use violation::{Class, Counts, Picture};

// The inner workings' names at the root, with the feature.
#[cfg(feature = "internals")]
pub use harness::{band_words, failure_text};
#[cfg(feature = "internals")]
pub use rules::{RuleDraft, needs};
#[cfg(feature = "internals")]
pub use runner::{Replay, RunConfig, Verdict, property, property_for};
#[cfg(feature = "internals")]
pub use violation::{Expect, Findings, Violation, compare_coverage, count_fragments};
