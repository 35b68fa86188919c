//! The course rasterizers: the algorithms of four lab documents, implemented as they describe them,
//! so that `refrast certify` can tell a student what their lab gets right and wrong.
//!
//! | name | module | seed | algorithm |
//! |---|---|---|---|
//! | `lab000` | [`lab000`] | 000 | f32 cross products at pixel corners, view-depth buffer, no clipping |
//! | `lab002-scanline` | [`lab002`] | 002 | whole-pixel vertices, rows from interpolated edges, 1/z depth |
//! | `lab003-painter` | [`painter`] | 003 | triangles sorted by their farthest vertex, painted back to front, no depth buffer |
//! | `lab003-scanline-zbuffer` | [`scanline`] | 003 | an active polygon list, x-intercept spans, depth stepped along a one-row buffer |
//! | `lab003-area-average` | [`area_average`] | 003 | each pixel's covered area, told as `round(n · fraction)` of its samples |
//! | `lab004-lineeq` | [`lab004`] | 004 | Sutherland–Hodgman (six planes, 1e-6 nudge), `O_i ≤ 0` |
//! | `lab004-dda` | [`dda`] | 004, 002 | lines by a DDA between the ends' pixels, both drawn; points by `floor` |
//!
//! The labs of seeds 000, 002 and 004 have no fill convention and declare none; seed 003's scanline
//! z-buffer has one by its half-open spans, and its painter draws with the reference's coverage.
//! They are course code, not certified correct: each fails some rules (`tests/integration/course.rs`).

pub mod area_average;
pub mod dda;
pub mod lab000;
pub mod lab002;
pub mod lab004;
pub mod painter;
pub mod scanline;
pub mod screen;

pub use area_average::AreaAverage;
pub use dda::Dda;
pub use lab000::Lab000;
pub use lab002::Lab002;
pub use lab004::Lab004;
pub use painter::Painter;
pub use scanline::ScanlineZBuffer;

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
pub fn labs() -> [CourseLab; 7] {
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
            name: "lab003-painter",
            description: "seed 003: painter's algorithm, triangles sorted by farthest vertex and painted back to front, no depth buffer",
            make: || Box::new(Painter),
        },
        CourseLab {
            name: "lab003-scanline-zbuffer",
            description: "seed 003: scanline z-buffer, active polygon list, x-intercept spans, f32 depth stepped in a one-row buffer",
            make: || Box::new(ScanlineZBuffer),
        },
        CourseLab {
            name: "lab003-area-average",
            description: "seed 003: area averaging, each pixel's covered fraction told as round(n * fraction) of its samples",
            make: || Box::new(AreaAverage),
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
