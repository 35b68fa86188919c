//! The course rasterizers: the algorithms of three lab documents, implemented as they describe them,
//! so that `refrast certify` can tell a student what their lab gets right and wrong.
//!
//! | name | module | seed | algorithm |
//! |---|---|---|---|
//! | `lab000` | [`lab000`] | 000 | f32 cross products at pixel corners, view-depth buffer, no clipping |
//! | `lab002-scanline` | [`lab002`] | 002 | whole-pixel vertices, rows from interpolated edges, 1/z depth |
//! | `lab004-lineeq` | [`lab004`] | 004 | Sutherland–Hodgman (six planes, 1e-6 nudge), `O_i ≤ 0` |
//!
//! None has a fill convention; each profile names top-left because a profile must name one.
//! They are course code, not certified correct: each fails some rules (`tests/course.rs`).

pub mod lab000;
pub mod lab002;
pub mod lab004;

pub use lab000::Lab000;
pub use lab002::Lab002;
pub use lab004::Lab004;

use refrast_conformance::{BuiltIn, Origin};

/// The course rasterizers as built-ins, in seed order.
#[must_use]
pub fn builtins() -> Vec<BuiltIn> {
    vec![
        BuiltIn::new(
            "lab000",
            "seed 000: f32 cross-product inside test at pixel corners, view-depth buffer, no clipping",
            Origin::Course,
            || Box::new(Lab000),
        ),
        BuiltIn::new(
            "lab002-scanline",
            "seed 002: scanline fill of left/right rows from interpolated edges, 1/z depth",
            Origin::Course,
            || Box::new(Lab002),
        ),
        BuiltIn::new(
            "lab004-lineeq",
            "seed 004: Sutherland–Hodgman with a 1e-6 nudge, then line equations O_i <= 0",
            Origin::Course,
            || Box::new(Lab004),
        ),
    ]
}
