//! The refrast conformance suite: a catalogue of rules that certifies any [`refrast::Rasterizer`].
//!
//! | piece | module | what |
//! |---|---|---|
//! | the rules | `rules` | [`catalogue`], [`Rule`], [`Family`], [`Kind`] — six families, each rule a proptest property |
//! | input | `scene` | [`Scene`]: a draw whose `Debug` is pasteable Rust |
//! | generators | [`strategy`] | free functions that build valid scenes: grid triangles, spade meshes, fans, quads, clip crossings |
//! | oracles | [`oracle`] | brute force (i128 `orient2d`) and ray casting (f64, clip space), sharing no code with the reference |
//! | verdicts | `violation` | [`Violation`], [`Counts`], [`Picture`] |
//! | pictures | [`picture`] | the zoomed sample grid: missing purple, unexpected red, double blue, don't-care yellow |
//! | running | `runner`, `certify` | [`certify`], [`Options`], [`Report`] |
//! | fuzzing | [`fuzz`] | the cargo-fuzz targets as functions on any rasterizer, and the corpus decoder `cargo test` replays with |
//! | `cargo test` | `harness` | [`run_as_tests`]: one test per rule in your own crate |
//! | built-ins | `impls` | [`builtins`]: the implementations `refrast certify --impl` knows |
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
pub mod oracle;
pub mod picture;
pub mod rules;
mod runner;
mod scene;
pub mod strategy;
mod violation;

pub use certify::{Options, ProfileReport, Report, RuleReport, Status, certify, matches, run_rule};
pub use harness::{failure_text, run_as_tests};
pub use impls::{BuiltIn, Maker, Named, builtins};
pub use rules::meta::Translated;
pub use rules::robust::Poisoned;
pub use rules::{Family, Kind, Rule, catalogue};
pub use runner::{Case, DEFAULT_SEED, RunConfig, Verdict, property};
pub use scene::{Scene, clip_of};
pub use violation::{Class, Counts, Expect, Picture, Violation, compare_coverage, count_fragments};
