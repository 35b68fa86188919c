//! The course rasterizers: the algorithms of three lab documents, implemented as they describe them,
//! so that `refrast certify` can tell a student what their lab gets right and wrong.
//!
//! | name | module | seed | algorithm |
//! |---|---|---|---|
//! | `lab000` | [`lab000`] | 000 | f32 cross products at pixel corners, view-depth buffer, no clipping |
//! | `lab002-scanline` | [`lab002`] | 002 | whole-pixel vertices, rows from interpolated edges, 1/z depth |
//! | `lab004-lineeq` | [`lab004`] | 004 | Sutherland–Hodgman (six planes, 1e-6 nudge), `O_i ≤ 0` |
//! | `lab004-dda` | [`dda`] | 004, 002 | lines by a DDA between the ends' pixels, both drawn; points by `floor` |
//!
//! None has a fill convention; each profile names top-left because a profile must name one.
//! They are course code, not certified correct: each fails some rules (`tests/course.rs`).

pub mod dda;
pub mod lab000;
pub mod lab002;
pub mod lab004;

pub use dda::Dda;
pub use lab000::Lab000;
pub use lab002::Lab002;
pub use lab004::Lab004;

use refrast::Rasterizer;

/// A course lab as `refrast impls` lists it: the name `--impl` takes, one line on what the lab
/// does, and how to build one.
#[derive(Clone, Copy, Debug)]
pub struct CourseLab {
    /// The name `--impl` takes.
    pub name: &'static str,
    /// The seed it comes from and what it does differently from the reference.
    pub description: &'static str,
    /// Builds a fresh one.
    pub make: fn() -> Box<dyn Rasterizer>,
}

/// The course rasterizers, in seed order.
#[must_use]
pub fn labs() -> [CourseLab; 4] {
    [
        CourseLab {
            name: "lab000",
            description: "seed 000: f32 cross-product inside test at pixel corners, view-depth buffer, no clipping",
            make: || Box::new(Lab000),
        },
        CourseLab {
            name: "lab002-scanline",
            description: "seed 002: scanline fill of left/right rows from interpolated edges, 1/z depth",
            make: || Box::new(Lab002),
        },
        CourseLab {
            name: "lab004-lineeq",
            description: "seed 004: Sutherland–Hodgman with a 1e-6 nudge, then line equations O_i <= 0",
            make: || Box::new(Lab004),
        },
        CourseLab {
            name: "lab004-dda",
            description: "seeds 004 and 002: lines by a DDA between the ends' pixels (both drawn), points by floor; triangles by the reference",
            make: || Box::new(Dda),
        },
    ]
}
