//! `lab000`: the software rasterizer of seed 000 (Graphics Programming I, "Software Rasterization
//! Part I"), built as its five lab steps build it.
//!
//! What the seed does, and what this module therefore does:
//!
//! - **Projection stage**: the perspective divide by the view-space depth (clip `w`), keeping that
//!   depth as the projected `z`, then `x = (x + 1)/2 · W`, `y = (1 − y)/2 · H`. The lab has no
//!   clipping, so vertices behind the eye are divided by a negative depth and drawn mirrored.
//! - **Inside test**: the 2D cross products of each edge with the vector from its start vertex
//!   to the pixel, in `f32` on unsnapped coordinates. The pixel is the point `Vector2(px, py)`:
//!   the seed never adds ½, so the sample sits at the pixel's top-left corner, not its centre.
//! - **Signs**: the seed's triangle is "clockwise" and its cross products are all non-negative
//!   inside (y down), so a pixel is inside when all three are `≥ 0` (on an edge counts, as in the
//!   ray tracer's triangle test it reuses). Counter-clockwise triangles therefore draw nothing: the
//!   lab has no winding switch and no fill convention.
//! - **Bounding box**: the vertices' smallest and largest x and y, clamped to `0..=W−1`, `0..=H−1`.
//! - **Barycentrics**: each cross product divided by the total `Cross(V1 − V0, V2 − V0)`,
//!   screen-space weights (the lab never corrects them for perspective).
//! - **Depth**: the weights interpolate the view-space depth; the depth buffer starts at the
//!   largest `f32` and keeps a fragment when its depth is smaller ([`Rasterizer::resolve`]).
//!
//! [`Fragment::depth`] must lie in `[0, 1]`, and view depth does not, so fragments carry
//! [`window_depth`], a strictly increasing map of it; the lab's test is done on the raw value.

use refrast::{
    CullMode, DepthConvention, DepthRange, Draw, DrawError, Features, Fragment, Profile, Rasterizer,
    Resolved, SnapAccuracy, Snapping, Spec, Supported, Winding,
};

/// Seed 000's rasterizer: `f32` cross products at pixel corners, view-depth buffer, no clipping.
#[derive(Clone, Copy, Debug, Default)]
pub struct Lab000;

/// A fragment and the view-space depth the lab's depth buffer compares.
type LabFragment = (Fragment, f32);

/// Maps the lab's view-space depth strictly increasingly into `[0, 1]`, because fragments must
/// carry depth in that range: `½ + ½ · z/(1 + |z|)`, so the clear value `f32::MAX` maps to 1.
#[must_use]
pub fn window_depth(view_z: f32) -> f32 {
    let z = f64::from(view_z);
    (0.5 + 0.5 * z / (1.0 + z.abs())) as f32
}

/// The 2D cross product (signed parallelogram area) of seed 000.
fn cross(a: [f32; 2], b: [f32; 2]) -> f32 {
    a[0] * b[1] - a[1] * b[0]
}

/// `a − b` in 2D.
fn sub(a: [f32; 2], b: [f32; 2]) -> [f32; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The projection stage: divide by view depth (`w`), keep it as `z`, map to screen space;
/// `None` for a vertex with any non-finite coordinate (clip `z` included, though the lab ignores it).
fn project(p: [f32; 4], width: f32, height: f32) -> Option<([f32; 2], f32)> {
    let [x, y, _, w] = p;
    let (nx, ny) = (x / w, y / w);
    let screen = [(nx + 1.0) / 2.0 * width, (1.0 - ny) / 2.0 * height];
    p.iter()
        .chain(&screen)
        .all(|c| c.is_finite())
        .then_some((screen, w))
}

impl Lab000 {
    /// Every fragment of the draw with its raw view depth, in primitive order.
    fn fragments(draw: &Draw) -> Result<Vec<LabFragment>, DrawError> {
        draw.validate()?;
        let (width, height) = (draw.viewport.width(), draw.viewport.height());
        let (wf, hf) = (width as f32, height as f32);
        // Every drawn triangle is clockwise on screen, the only winding the sign test accepts.
        let front_facing = draw
            .state
            .front_face
            .is_front(Winding::Clockwise)
            .unwrap_or(false);
        let mut out = Vec::new();
        for (t, indices) in draw.triangles().iter().enumerate() {
            let projected = indices.map(|i| project(draw.positions[i as usize], wf, hf));
            let [Some((v0, z0)), Some((v1, z1)), Some((v2, z2))] = projected else {
                continue;
            };
            let total = cross(sub(v1, v0), sub(v2, v0));
            // Zero area: weights would be 0/0, whose NaN depth fails the lab's depth test.
            // Negative area (counter-clockwise): no pixel has three non-negative cross products.
            if !(total > 0.0 && total.is_finite()) {
                continue;
            }
            let clamp = |v: f32, max: u32| v.clamp(0.0, (max - 1) as f32) as u32;
            let (x0, x1) = (
                clamp(v0[0].min(v1[0]).min(v2[0]), width),
                clamp(v0[0].max(v1[0]).max(v2[0]), width),
            );
            let (y0, y1) = (
                clamp(v0[1].min(v1[1]).min(v2[1]), height),
                clamp(v0[1].max(v1[1]).max(v2[1]), height),
            );
            for py in y0..=y1 {
                for px in x0..=x1 {
                    let p = [px as f32, py as f32];
                    let c0 = cross(sub(v2, v1), sub(p, v1));
                    let c1 = cross(sub(v0, v2), sub(p, v2));
                    let c2 = cross(sub(v1, v0), sub(p, v0));
                    if !(c0 >= 0.0 && c1 >= 0.0 && c2 >= 0.0) {
                        continue;
                    }
                    let weights = [c0 / total, c1 / total, c2 / total];
                    let z = weights[0] * z0 + weights[1] * z1 + weights[2] * z2;
                    // f32 overflow on huge coordinates: a weight that is not a number draws nothing.
                    if !(z.is_finite() && weights.iter().all(|w| w.is_finite())) {
                        continue;
                    }
                    let fragment = Fragment {
                        x: px,
                        y: py,
                        sample: 0,
                        primitive: t as u32,
                        depth: window_depth(z),
                        barycentric: weights,
                        flat: None,
                        screen_barycentric: Some(weights),
                        front_facing,
                    };
                    out.push((fragment, z));
                }
            }
        }
        Ok(out)
    }
}

impl Rasterizer for Lab000 {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab000".into(),
            // No snapping: f32 cross products on raw coordinates.
            snapping: Snapping::Float,
            // `≥ 0` on every edge: no tie rule.
            fill: None,
            // Interpolated view-space depth, not z/w.
            depth: DepthConvention::Other,
            tolerance_subpixels: 1,
            // Held to the reference's precision: the labs compute in f32 or f64 from exact inputs.
            precision_bits: 18,
            features: Features {
                perspective_barycentrics: false,
                screen_barycentrics: true,
                cull_modes: Supported::only(&[CullMode::None]),
                front_faces: Supported::ALL,
                // Only LESS against a max-float clear: no compare ops, no write mask.
                depth_test: false,
                compare_ops: Supported::ALL,
                depth_writes: Supported::ALL,
                far_clipping: Supported::only(&[false]),
                depth_ranges: Supported::only(&[DepthRange::ZeroToOne]),
                // No x/y clipping at all, so none can move an edge.
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
        Ok(Self::fragments(draw)?.into_iter().map(|(f, _)| f).collect())
    }

    /// The lab's own depth buffer: cleared to `f32::MAX`, LESS on view depth, always written.
    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let viewport = draw.viewport;
        let mut depth = vec![f32::MAX; viewport.pixel_count()];
        let mut primitive = vec![None; viewport.pixel_count()];
        for (f, z) in Self::fragments(draw)? {
            let i = viewport.index(f.x, f.y);
            if z < depth[i] {
                depth[i] = z;
                primitive[i] = Some(f.primitive);
            }
        }
        Ok(Resolved {
            viewport,
            samples: 1,
            depth: depth.into_iter().map(window_depth).collect(),
            primitive,
        })
    }
}
