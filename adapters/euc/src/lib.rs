//! The euc crate (0.5.3, its latest release) behind refrast's [`Rasterizer`] trait.
//!
//! euc draws through a `Pipeline` of Rust closures: a vertex shader gives clip-space positions,
//! euc rasterizes in homogeneous coordinates (no clipping), interpolates the shader's outputs
//! perspective-correctly and writes what the fragment shader returns. The adapter feeds the
//! draw's clip-space positions straight to it and reads back what it produced:
//!
//! - **coverage and barycentrics**: one draw per triangle into a fresh target, with no depth
//!   test, the fragment shader writing the interpolated barycentric unit vectors;
//! - **depth**: the same triangle again with euc's `IfLessWrite` test into a depth buffer cleared
//!   to +∞, so every covered sample leaves the depth euc computed (a sample whose depth fails
//!   `≤ +∞` can only be NaN);
//! - **facing**: the same triangle with euc's back-face culling on: it draws when euc takes it for
//!   front-facing;
//! - **resolve**: every triangle in order into one colour and depth target with euc's own depth
//!   test, the colour being the primitive id.
//!
//! The profile declares what euc cannot do: no snapping grid and no tie rule (it tests `w ≥ 0`
//! on f32 weights), no screen-space barycentrics, culling of back faces only, counter-clockwise
//! front faces only, the `≤` and `≥` depth tests only, no far clipping, the `0 ≤ z` range only.
//!
//! euc's `Target::set` is unchecked: on some inputs it writes outside its buffers (see
//! docs/certified.md). refrast runs each rule in a child process, so that stays there.
#![forbid(unsafe_code)]

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, BackfaceCullingEnabled, Triangles};
use euc::{DepthStrategy, Pipeline};
use refrast::{
    CompareOp, CullMode, DepthConvention, DepthRange, Draw, DrawError, Features, Fragment, FrontFace,
    Profile, Rasterizer, Resolved, SnapAccuracy, Snapping, Spec, Supported,
};

/// euc's rasterizer, certified through refrast.
#[derive(Clone, Copy, Debug, Default)]
pub struct Euc;

/// A vertex as euc's vertex shader takes it: the clip-space position and what it carries.
type Vertex = ([f32; 4], Carried);

/// What a vertex carries for euc to interpolate: its barycentric unit vector.
type Carried = (f32, f32, f32);

/// A pipeline whose vertex shader passes positions through and whose fragment shader writes
/// `pixel` of what it is given.
struct Capture<F> {
    depth: DepthStrategy,
    pixel: F,
}

impl<P: Clone, F: Fn(Carried) -> P> Pipeline for Capture<F> {
    type Vertex = Vertex;
    type VsOut = Carried;
    type Pixel = Option<P>;

    fn vert(&self, vertex: &Vertex) -> ([f32; 4], Carried) {
        *vertex
    }

    fn frag(&self, carried: &Carried) -> Option<P> {
        Some((self.pixel)(*carried))
    }

    fn get_depth_strategy(&self) -> DepthStrategy {
        self.depth
    }
}

/// Draws `vertices` (three per triangle) with or without euc's back-face culling.
fn draw_into<P: Clone, F: Fn(Carried) -> P>(
    pipeline: &Capture<F>,
    vertices: &[Vertex],
    cull_back: bool,
    color: &mut Buffer2d<Option<P>>,
    depth: Option<&mut Buffer2d<f32>>,
) {
    if cull_back {
        pipeline.draw::<Triangles<Buffer2d<f32>, BackfaceCullingEnabled>, _>(vertices, color, depth);
    } else {
        pipeline.draw::<Triangles<Buffer2d<f32>, BackfaceCullingDisabled>, _>(vertices, color, depth);
    }
}

/// The three vertices of triangle `indices`, each carrying its barycentric unit vector.
fn triangle(draw: &Draw, indices: [u32; 3]) -> [Vertex; 3] {
    let units = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)];
    [0, 1, 2].map(|k| (draw.positions[indices[k] as usize], units[k]))
}

/// euc's depth strategy for a depth test it supports.
fn strategy(compare: CompareOp, write: bool) -> Result<DepthStrategy, DrawError> {
    match (compare, write) {
        (CompareOp::LessOrEqual, true) => Ok(DepthStrategy::IfLessWrite),
        (CompareOp::LessOrEqual, false) => Ok(DepthStrategy::IfLessNoWrite),
        (CompareOp::GreaterOrEqual, true) => Ok(DepthStrategy::IfMoreWrite),
        (CompareOp::GreaterOrEqual, false) => Ok(DepthStrategy::IfMoreNoWrite),
        _ => Err(DrawError::Unsupported(format!(
            "euc's depth tests are ≤ and ≥ only, not {compare:?}"
        ))),
    }
}

impl Euc {
    /// Refuses what euc cannot do, rather than draw something else.
    fn check(&self, draw: &Draw) -> Result<(), DrawError> {
        draw.validate()?;
        if !self.profile().supports(&draw.state) {
            return Err(DrawError::Unsupported(format!(
                "euc cannot draw with {:?} (it culls back faces only, takes counter-clockwise \
                 front faces, has no far clipping and the 0 ≤ z range only)",
                draw.state
            )));
        }
        Ok(())
    }
}

impl Rasterizer for Euc {
    fn profile(&self) -> Profile {
        Profile {
            name: "euc".into(),
            // f32 weights on unsnapped coordinates, `w ≥ 0` on all three: no grid, no tie rule.
            snapping: Snapping::Float,
            fill: None,
            // z interpolated perspective-correctly and divided by w: z/w, linear on screen.
            depth: DepthConvention::ScreenLinearZOverW,
            // f32 on raster coordinates as large as the suite's ±30000·w (about 10^6 px) has an
            // ulp of 1/16 px, so an edge may move that far: 16 units of 1/256 px. It is also
            // Vulkan's coarsest vertex precision (subPixelPrecisionBits = 4).
            tolerance_subpixels: 16,
            // What an f32 rasterizer keeps (see `Profile::precision_bits`); euc promises nothing.
            precision_bits: 14,
            features: Features {
                perspective_barycentrics: true,
                screen_barycentrics: false,
                cull_modes: Supported::only(&[CullMode::None, CullMode::Back]),
                front_faces: Supported::only(&[FrontFace::CounterClockwise]),
                depth_test: true,
                compare_ops: Supported::only(&[CompareOp::LessOrEqual, CompareOp::GreaterOrEqual]),
                depth_writes: Supported::ALL,
                far_clipping: Supported::only(&[false]),
                depth_ranges: Supported::only(&[DepthRange::ZeroToOne]),
                // No x/y clipping at all, so none moves an edge.
                guard_band: u32::MAX,
                // No grid, so no snap ties.
                ties_to_even: false,
                snap: SnapAccuracy::Nearest,
                zero_area_before_clipping: false,
                clips_in_3d: true,
                z_rewritten_in_f32: false,
            },
            spec: Spec::Refrast,
            ..Profile::default()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        self.check(draw)?;
        let size = [draw.viewport.width() as usize, draw.viewport.height() as usize];
        let cull_back = draw.state.cull == CullMode::Back;
        let mut fragments = Vec::new();
        for (primitive, &indices) in draw.triangles().iter().enumerate() {
            let vertices = triangle(draw, indices);
            let mut weights = Buffer2d::new(size, None);
            let barycentric = Capture {
                depth: DepthStrategy::None,
                pixel: |(a, b, c)| [a, b, c],
            };
            draw_into(&barycentric, &vertices, cull_back, &mut weights, None);
            let coverage = weights.as_ref();
            if coverage.iter().all(Option::is_none) {
                continue;
            }
            // Facing as euc decides it: drawn with back faces culled means front-facing.
            let mut front = Buffer2d::new(size, None);
            let covered = Capture {
                depth: DepthStrategy::None,
                pixel: |_| (),
            };
            draw_into(&covered, &vertices, true, &mut front, None);
            let front_facing = front.as_ref().iter().any(Option::is_some);
            let mut depth = Buffer2d::new(size, f32::INFINITY);
            let mut written = Buffer2d::new(size, None);
            let tested = Capture {
                depth: DepthStrategy::IfLessWrite,
                pixel: |_| (),
            };
            draw_into(&tested, &vertices, cull_back, &mut written, Some(&mut depth));
            for (i, b) in coverage.iter().enumerate() {
                let Some(barycentric) = *b else { continue };
                // Not written past `≤ +∞`: euc's depth there is NaN.
                let z = if written.as_ref()[i].is_some() {
                    depth.as_ref()[i]
                } else {
                    f32::NAN
                };
                fragments.push(Fragment {
                    x: (i % size[0]) as u32,
                    y: (i / size[0]) as u32,
                    sample: 0,
                    primitive: primitive as u32,
                    depth: z,
                    flat: None,
                    barycentric,
                    screen_barycentric: None,
                    front_facing,
                });
            }
        }
        Ok(fragments)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        self.check(draw)?;
        let size = [draw.viewport.width() as usize, draw.viewport.height() as usize];
        let depth_strategy = strategy(draw.state.depth.compare, draw.state.depth.write)?;
        let cull_back = draw.state.cull == CullMode::Back;
        let mut ids = Buffer2d::new(size, None);
        let mut depth = Buffer2d::new(size, draw.state.depth.clear);
        // One triangle at a time onto the same targets: euc draws a vertex list in order anyway.
        for (primitive, &indices) in draw.triangles().iter().enumerate() {
            let id = Capture {
                depth: depth_strategy,
                pixel: move |_| primitive as u32,
            };
            draw_into(
                &id,
                &triangle(draw, indices),
                cull_back,
                &mut ids,
                Some(&mut depth),
            );
        }
        Ok(Resolved {
            viewport: draw.viewport,
            samples: 1,
            depth: depth.as_ref().to_vec(),
            primitive: ids.as_ref().to_vec(),
        })
    }
}
