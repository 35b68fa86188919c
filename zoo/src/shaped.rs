//! Correct rasterizers shaped like the ones that exposed false verdicts: a GPU that rasterizes
//! homogeneously (screen-space weights across `w = 0`), one whose sample fragments carry
//! `FragCoord.z` at the pixel centre, one that keeps points pop-free, and a 2D scan converter
//! in Skia's style (truncating snap, bottom-right ties, no 3D clipping). Each is the reference
//! differing only where the specification it claims leaves room, and declares what it does;
//! each must pass, be `n/a` or be beyond the claimed specification on every rule
//! (`tests/integration/shaped.rs`), so that a class of false verdict, once fixed, stays fixed.

use refrast::{
    DepthRange, Draw, DrawError, FillConvention, Fragment, PointClipping, Profile, Rasterizer, Reference,
    ReferenceConfig, Resolved, SamplePattern, SnapAccuracy, SnapRounding, Snapping, Spec, SubpixelBits,
    Viewport,
};

/// How a [`Shaped`] rasterizer differs from the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Screen-space barycentrics of a triangle with a vertex at `w < 0` taken from the
    /// unclipped triangle's screen plane, as a GPU rasterizing homogeneously evaluates
    /// `noperspective` inputs (NVIDIA: −0.57 to −1.09; SwiftShader the same). Claims Vulkan.
    ScreenPlaneAcrossEye,
    /// At several samples, each sample fragment's depth is the triangle's at the pixel centre
    /// (`FragCoord.z` read by a shader run per sample); the depth test still uses each sample's
    /// own. Claims Vulkan, which ties `FragCoord.z` to no sample.
    FragCoordAtCentre,
    /// Points outside the viewport kept, so the samples their squares reach inside are drawn,
    /// while the profile reports `ALL_CLIP_PLANES` (lavapipe, SwiftShader, NVIDIA). Claims Vulkan.
    PopFreePoints,
    /// A 2D scan converter as Skia fills a path: 26.6 fixed point by truncation toward zero
    /// (`snap toward-zero` on a 6-bit grid), bottom-right ties, triangles only, and no 3D
    /// clipping (`clipping none`): a draw that would need it is refused, so a case the suite
    /// should not send fails. Claims refrast's conventions.
    ScanConverter,
}

impl Shape {
    /// Every shape.
    pub const ALL: [Shape; 4] = [
        Self::ScreenPlaneAcrossEye,
        Self::FragCoordAtCentre,
        Self::PopFreePoints,
        Self::ScanConverter,
    ];

    /// The name after `shaped:`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::ScreenPlaneAcrossEye => "screen-plane-across-eye",
            Self::FragCoordAtCentre => "fragcoord-at-centre",
            Self::PopFreePoints => "pop-free-points",
            Self::ScanConverter => "scan-converter",
        }
    }

    /// One line on what it is.
    #[must_use]
    pub fn description(self) -> &'static str {
        match self {
            Self::ScreenPlaneAcrossEye => {
                "screen-space weights across w = 0 from the unclipped triangle's plane, as a GPU gives them (Vulkan)"
            }
            Self::FragCoordAtCentre => {
                "sample fragments carrying the pixel centre's depth, a per-sample depth test (Vulkan)"
            }
            Self::PopFreePoints => {
                "points outside the viewport drawn pop-free, reported all-clip-planes (Vulkan)"
            }
            Self::ScanConverter => {
                "a 2D scan converter: 26.6 fixed point truncated, bottom-right ties, no 3D clipping (refrast)"
            }
        }
    }
}

/// The reference, shaped as [`Shape`] says.
#[derive(Clone, Debug)]
pub struct Shaped {
    shape: Shape,
    inner: Reference,
}

impl Shaped {
    /// The reference shaped as `shape`.
    #[must_use]
    pub fn new(shape: Shape) -> Self {
        let config = match shape {
            Shape::PopFreePoints => ReferenceConfig {
                point_clipping: PointClipping::UserClipPlanesOnly,
                ..ReferenceConfig::default()
            },
            Shape::ScanConverter => ReferenceConfig {
                subpixel_bits: SubpixelBits::new(6).expect("6 is in range"),
                snap_rounding: SnapRounding::TowardZero,
                fill: FillConvention::BottomRight,
                ..ReferenceConfig::default()
            },
            Shape::ScreenPlaneAcrossEye | Shape::FragCoordAtCentre => ReferenceConfig::default(),
        };
        Self {
            shape,
            inner: Reference::new(config),
        }
    }

    /// What a scan converter refuses: a draw with a finite vertex behind the eye or outside
    /// the near or far plane the draw clips at.
    fn needs_clipping(draw: &Draw) -> Option<String> {
        draw.positions.iter().enumerate().find_map(|(i, p)| {
            let [_, _, z, w] = p.map(f64::from);
            let finite = p.iter().all(|c| c.is_finite());
            let outside = w <= 0.0
                || (draw.state.clip_near && near_distance(draw.state.depth_range, z, w) < 0.0)
                || (draw.state.clip_far && z > w);
            (finite && outside).then(|| {
                format!("vertex {i} {p:?} needs clipping in 3D, which this scan converter does not do")
            })
        })
    }
}

impl Rasterizer for Shaped {
    fn profile(&self) -> Profile {
        let mut profile = self.inner.profile();
        profile.name = format!("shaped:{}", self.shape.name());
        match self.shape {
            Shape::ScanConverter => {
                // Triangles at one sample, lists, strips and fans, with their flat vertices
                // (a scan converter assembles and shades them as the reference does).
                let all = profile.state;
                profile = std::mem::take(&mut profile).triangles_only();
                profile.state.triangle_strips = all.triangle_strips;
                profile.state.triangle_fans = all.triangle_fans;
                profile.state.flat = all.flat;
                profile.snapping = Snapping::Grid(6);
                profile.features.snap = SnapAccuracy::TowardZero;
                profile.features.ties_to_even = false;
                profile.features.clips_in_3d = false;
            }
            // What the GPUs report, whatever they do.
            Shape::PopFreePoints => {
                profile.spec = Spec::Vulkan;
                profile.point_clipping = PointClipping::AllClipPlanes;
            }
            _ => profile.spec = Spec::Vulkan,
        }
        profile
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        if self.shape == Shape::ScanConverter
            && let Some(why) = Self::needs_clipping(draw)
        {
            return Err(DrawError::Unsupported(why));
        }
        let mut fragments = self.inner.rasterize(draw)?;
        let triangles = draw.topology.is_triangles();
        if self.shape == Shape::FragCoordAtCentre && triangles && draw.samples > 1 {
            for f in &mut fragments {
                let centre = [f64::from(f.x) + 0.5, f64::from(f.y) + 0.5];
                if let Some(z) = screen_depth(draw, f.primitive, centre) {
                    f.depth = draw.state.viewport_depth.fragment_depth(z);
                }
            }
        }
        if self.shape == Shape::ScreenPlaneAcrossEye && triangles {
            let pattern = SamplePattern::standard(draw.samples);
            for f in &mut fragments {
                let [u, v] = pattern
                    .and_then(|p| p.positions().get(usize::from(f.sample)).copied())
                    .unwrap_or([8, 8]);
                let s = [
                    f64::from(f.x) + f64::from(u) / 16.0,
                    f64::from(f.y) + f64::from(v) / 16.0,
                ];
                if let Some(b) = unclipped_screen_weights(draw, f.primitive, s) {
                    f.screen_barycentric = Some(b);
                }
            }
        }
        Ok(fragments)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        if self.shape == Shape::ScanConverter
            && let Some(why) = Self::needs_clipping(draw)
        {
            return Err(DrawError::Unsupported(why));
        }
        self.inner.resolve(draw)
    }
}

/// `p` divided by `w` and mapped to raster space, in pixels.
fn project(viewport: Viewport, p: [f64; 4]) -> [f64; 2] {
    let (x, y) = viewport.to_raster(p[0] / p[3], p[1] / p[3]);
    [x, y]
}

/// How far `(z, w)` lies inside the near plane of `range`'s clip volume (`z ≥ 0` or `z ≥ −w`).
fn near_distance(range: DepthRange, z: f64, w: f64) -> f64 {
    match range {
        DepthRange::ZeroToOne => z,
        DepthRange::NegativeOneToOne => z + w,
    }
}

/// The projected vertices of `draw`'s triangle `t`, in pixels, with their `w`; `None` for an
/// index out of range or a vertex at `w = 0` or not finite.
fn projected(draw: &Draw, t: u32) -> Option<[([f64; 2], [f64; 4]); 3]> {
    let tri = draw.triangle(t as usize)?;
    let mut out = [([0.0; 2], [0.0; 4]); 3];
    for (k, &i) in tri.iter().enumerate() {
        let p = draw.positions.get(i as usize)?.map(f64::from);
        if p[3] == 0.0 || !p.iter().all(|c| c.is_finite()) {
            return None;
        }
        out[k] = (project(draw.viewport, p), p);
    }
    Some(out)
}

/// The 2D barycentrics of `s` in the triangle of the projected vertices, in f64.
fn plane_weights(v: [[f64; 2]; 3], s: [f64; 2]) -> Option<[f64; 3]> {
    let e = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (s[1] - a[1]) - (b[1] - a[1]) * (s[0] - a[0]);
    let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
    (area != 0.0 && area.is_finite())
        .then(|| [e(v[1], v[2]) / area, e(v[2], v[0]) / area, e(v[0], v[1]) / area])
}

/// Screen-space weights at `s` of triangle `t` when it has a vertex behind the eye: those of
/// the triangle through its vertices' projections, as homogeneous rasterization evaluates a
/// `noperspective` input. `None` when every vertex is in front (the reference's weights stand).
fn unclipped_screen_weights(draw: &Draw, t: u32, s: [f64; 2]) -> Option<[f32; 3]> {
    let v = projected(draw, t)?;
    if v.iter().all(|(_, p)| p[3] > 0.0) {
        return None;
    }
    plane_weights(v.map(|(q, _)| q), s).map(|b| b.map(|c| c as f32))
}

/// The window depth at `s` of triangle `t`'s depth plane through its projected vertices (all in
/// front of the eye), as a GPU interpolates `FragCoord.z`.
fn screen_depth(draw: &Draw, t: u32, s: [f64; 2]) -> Option<f64> {
    let v = projected(draw, t)?;
    if v.iter().any(|(_, p)| p[3] <= 0.0) {
        return None;
    }
    let b = plane_weights(v.map(|(q, _)| q), s)?;
    let range = draw.state.viewport_depth;
    let z = v.map(|(_, p)| range.window(draw.state.depth_range.window_depth(p[2], p[3])));
    Some(b[0] * z[0] + b[1] * z[1] + b[2] * z[2])
}

/// Every shaped rasterizer, as `shaped:NAME`.
#[must_use]
pub fn shapes() -> Vec<Shaped> {
    Shape::ALL.into_iter().map(Shaped::new).collect()
}
