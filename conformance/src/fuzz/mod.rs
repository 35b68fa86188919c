//! Fuzz targets as library functions: the same `check_*` the proptests run, fed by `arbitrary`.
//!
//! `fuzz/` at the repository root holds one thin `fuzz_target!` per [`Target`]; `cargo test`
//! replays the committed corpus through [`Target::run`], which decodes bytes exactly as
//! `fuzz_target!` does ([`decode`]). A third-party rasterizer is fuzzed by calling the same
//! functions with its own [`Rasterizer`] (see docs/fuzzing.md).

mod input;

use std::fmt;

use arbitrary::{Arbitrary, Unstructured};
use glam::{Mat4, Vec3};
use refrast::pipeline::{Framebuffer, Mesh, Renderer, Vertex};
use refrast::{Distances, PolygonMode, Profile, Rasterizer, Spec, Topology};

pub use input::{Clipping, GridTriangles, Overlapping, Perspective, Points, RawDraw, RawPipeline};

use crate::rules::bary::{check_equal_w, check_matches_raycast, check_reconstructs, check_sum_one};
use crate::rules::depth::{check_depth_matches_raycast, check_order_independent, extreme_depth};
use crate::rules::distance::check_culls;
use crate::rules::fill::{check_exactly_once, check_guard_band};
use crate::rules::meta::{check_same_as_list, check_same_as_list_away_from_edges};
use crate::rules::polygon::{check_edges, check_edges_inside, check_vertices, check_vertices_inside};
use crate::rules::robust::check_well_formed;
use crate::rules::{
    EXACT_COVERAGE, EXTREME_WINS, GUARD_BAND, Need, PERSPECTIVE_BARYCENTRICS, SCREEN_BARYCENTRICS,
    Z_OVER_W_DEPTH,
};
use crate::scene::{PrimitiveScene, Scene};
use crate::violation::Violation;

/// A check that failed on a fuzz input.
#[derive(Clone, Debug)]
pub struct Failure {
    /// What the check found.
    pub violation: Box<Violation>,
    /// The input as Rust (its `Debug`): paste it into a regression test.
    pub input: String,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}\ninput:\n{}", self.violation, self.input)
    }
}

impl std::error::Error for Failure {}

/// Whether the profile has everything `needs` asks for (else the target does not judge it);
/// the fuzz targets draw triangles at one sample, which every implementation declares.
fn applies(needs: &[Need], profile: &Profile) -> bool {
    needs.iter().all(|n| n.check(profile).is_ok())
}

/// Runs `check` and attaches the input's `Debug` to a violation.
fn judged(input: &impl fmt::Debug, check: impl FnOnce() -> Result<(), Violation>) -> Result<(), Failure> {
    check().map_err(|violation| Failure {
        violation: Box::new(violation),
        input: format!("{input:?}"),
    })
}

/// Any bit patterns: no panic, only well-formed fragments, none outside a scissor, none under
/// a sample mask without bit 0 (where declared and applied at one sample), `resolve`
/// works, the indices drawn as a strip and as a fan (where the profile declares them) draw
/// what the list of their triangles draws, the triangles in line and point mode (where
/// declared) draw what their edges and vertices draw as lines and points, and with clip and
/// cull distances (where declared) well-formed fragments and exact culling.
pub fn robustness(r: &mut dyn Rasterizer, input: &RawDraw) -> Result<(), Failure> {
    let Some(scene) = input.scene() else { return Ok(()) };
    let scene = scene.fitted(&r.profile());
    judged(input, || {
        check_well_formed(r, &scene)?;
        check_inside_scissor(r, &scene)?;
        check_masked_away(r, &scene)?;
        r.resolve(&scene.draw())
            .map(drop)
            .map_err(|e| Violation::new(format!("resolve returned an error on in-range indices: {e}")))?;
        check_strips_and_fans(r, &scene)?;
        check_polygon_modes(r, &scene)?;
        check_distances(r, &scene)
    })
}

/// The scene drawn again with distances where the profile declares them: each vertex's `x`
/// as a clip distance, whatever its bits (NaN, infinities, huge), fragments well-formed; then
/// cull distances of −1, −0, 0 or 1 picked by its bits, the primitives culled exactly as
/// `clip.cull-distance.discards` says.
fn check_distances(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let declared = r.profile().state;
    let n = scene.positions.len();
    if declared.clip_distances > 0 {
        let mut clipped = scene.clone();
        let values = scene.positions.iter().map(|p| vec![p[0]]).collect::<Vec<_>>();
        clipped.distances = Distances::new(1, 0, &values);
        check_well_formed(r, &clipped)?;
    }
    if declared.cull_distances > 0 && n > 0 {
        const PICKS: [f32; 4] = [-1.0, -0.0, 0.0, 1.0];
        let mut culled = scene.clone();
        let values = scene
            .positions
            .iter()
            .map(|p| vec![PICKS[(p[1].to_bits() % 4) as usize]])
            .collect::<Vec<_>>();
        culled.distances = Distances::new(0, 1, &values);
        check_culls(r, &PrimitiveScene::triangles(culled, 1))?;
    }
    Ok(())
}

/// The scene's triangles in each polygon mode the profile declares: well-formed fragments, and
/// what its edges drawn as lines (`line.polygon-mode.edges`) and its vertices drawn as points
/// (`point.polygon-mode.vertices`) draw, exactly under refrast's conventions, under another
/// specification what it requires.
fn check_polygon_modes(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let exact = profile.spec == Spec::Refrast;
    // OpenGL ES has no polygon modes to hold a driver to (the rules are not covered there).
    if profile.spec == Spec::OpenGlEs {
        return Ok(());
    }
    for mode in profile.state.polygon_modes.values() {
        let mut moded = scene.clone();
        moded.state.polygon_mode = mode;
        check_well_formed(r, &moded)?;
        let case = PrimitiveScene::triangles(moded, 1);
        match mode {
            PolygonMode::Line if profile.lines.is_some() => {
                if exact {
                    check_edges(r, &case)
                } else {
                    check_edges_inside(r, &case)
                }?;
            }
            PolygonMode::Point if profile.points && profile.spec != Spec::D3d11 => {
                if exact {
                    check_vertices(r, &case)
                } else {
                    check_vertices_inside(r, &case)
                }?;
            }
            _ => {}
        }
    }
    Ok(())
}

/// The scene's indices, one after another, drawn as a strip and as a fan where the profile
/// declares them, each against the list of its own triangles (`meta.strip.same-as-list`):
/// exactly under refrast's conventions, under another specification what it requires.
fn check_strips_and_fans(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let check = if profile.spec == Spec::Refrast {
        check_same_as_list
    } else {
        check_same_as_list_away_from_edges
    };
    for topology in [Topology::TriangleStrip, Topology::TriangleFan] {
        if !profile.draws(topology, 1) {
            continue;
        }
        let indices = scene.triangles.iter().flatten().copied().collect();
        let mut case = PrimitiveScene::of(
            scene.width,
            scene.height,
            scene.positions.clone(),
            topology,
            indices,
        );
        case.scene.state = scene.state;
        check(r, &case)?;
    }
    Ok(())
}

/// No fragment of `scene` outside its scissor rectangle, whatever its numbers.
fn check_inside_scissor(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let Some(scissor) = scene.state.scissor else {
        return Ok(());
    };
    let draw = scene.draw();
    let fragments = r
        .rasterize(&draw)
        .map_err(|e| Violation::of_draw_error("rasterize", &e))?;
    match fragments.iter().find(|f| !scissor.contains(f.x, f.y)) {
        Some(f) => Err(Violation::at(
            (f.x, f.y),
            format!("a fragment at ({}, {}) outside the scissor {scissor:?}", f.x, f.y),
        )),
        None => Ok(()),
    }
}

/// Nothing drawn or resolved of `scene` under a sample mask whose bit 0 is clear (its other
/// bits the first vertex's `x`), whatever its numbers, where the profile declares a mask its
/// specification applies at one sample.
fn check_masked_away(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    if !profile.state.sample_mask || !crate::rules::sample_mask::masks_at(profile.spec, 1) {
        return Ok(());
    }
    let mut masked = scene.clone();
    masked.state.sample_mask = scene.positions.first().map_or(0, |v| v[0].to_bits()) & !1;
    let draw = masked.draw();
    let fragments = r
        .rasterize(&draw)
        .map_err(|e| Violation::of_draw_error("rasterize", &e))?;
    if let Some(f) = fragments.first() {
        return Err(Violation::at(
            (f.x, f.y),
            format!(
                "a fragment at ({}, {}) under the sample mask {:#x}, whose bit 0 (the one sample's) is clear",
                f.x, f.y, masked.state.sample_mask
            ),
        ));
    }
    let resolved = r
        .resolve(&draw)
        .map_err(|e| Violation::of_draw_error("resolve", &e))?;
    match resolved.primitive.iter().position(Option::is_some) {
        Some(i) => Err(Violation::new(format!(
            "resolve names a primitive at sample {i} under the sample mask {:#x}, whose bit 0 is clear",
            masked.state.sample_mask
        ))),
        None => Ok(()),
    }
}

/// Each grid triangle alone against the brute-force oracle, bit for bit (where the profile has
/// exact coverage and a guard band, as `fill.guard-band.exact` needs), on snap ties where the
/// profile declares how they round.
pub fn differential(r: &mut dyn Rasterizer, input: &GridTriangles) -> Result<(), Failure> {
    let profile = r.profile();
    if !applies(&[EXACT_COVERAGE, GUARD_BAND], &profile) {
        return Ok(());
    }
    let scene = if profile.features.ties_to_even {
        input.scene_with_ties()
    } else {
        input.scene()
    };
    let Some(scene) = scene else { return Ok(()) };
    let scene = scene.fitted(&profile);
    for t in 0..scene.triangles.len() {
        let mut one = scene.clone();
        one.triangles = vec![scene.triangles[t]];
        let one = one.compact();
        judged(&one, || check_guard_band(r, &one))?;
    }
    Ok(())
}

/// A spade mesh of the points covers every sample exactly once.
pub fn watertight(r: &mut dyn Rasterizer, input: &Points) -> Result<(), Failure> {
    let scene = input.scene().fitted(&r.profile());
    judged(input, || check_exactly_once(r, &scene))
}

/// Triangles and meshes across the clip planes agree with the ray cast outside the band.
pub fn clipping(r: &mut dyn Rasterizer, input: &Clipping) -> Result<(), Failure> {
    let scene = input.scene().fitted(&r.profile());
    judged(input, || check_exactly_once(r, &scene))
}

/// Overlapping triangles leave the same depth buffer in any draw order (where the profile has
/// a depth test keeping the nearest or farthest fragment).
pub fn depth_order(r: &mut dyn Rasterizer, input: &Overlapping) -> Result<(), Failure> {
    let profile = r.profile();
    if !applies(&[EXTREME_WINS], &profile) {
        return Ok(());
    }
    let Some(scene) = input.scene() else { return Ok(()) };
    let mut scene = scene.fitted(&profile);
    scene.state.depth = extreme_depth(&profile);
    judged(input, || check_order_independent(r, &scene))
}

/// Barycentrics sum to one and, where the profile declares them, perspective-correct
/// barycentrics and z/w depth equal the ray cast's within the claimed precision, screen-space
/// barycentrics give back the sample, and with equal w both kinds agree; clipped triangles
/// (at the near plane) included.
pub fn interpolation(r: &mut dyn Rasterizer, input: &Perspective) -> Result<(), Failure> {
    let profile = r.profile();
    let scene = input.scene().fitted(&profile);
    judged(input, || {
        check_sum_one(r, &scene)?;
        if applies(&[PERSPECTIVE_BARYCENTRICS], &profile) {
            check_matches_raycast(r, &scene)?;
        }
        if applies(&[SCREEN_BARYCENTRICS], &profile) {
            check_reconstructs(r, &scene)?;
            if input.equal_w() && applies(&[PERSPECTIVE_BARYCENTRICS], &profile) {
                check_equal_w(r, &scene)?;
            }
        }
        if applies(&[Z_OVER_W_DEPTH], &profile) {
            check_depth_matches_raycast(r, &scene)?;
        }
        Ok(())
    })
}

/// The reference's whole pipeline (mesh with a shading hook, lines, points) on any bit
/// patterns: no panic, no error on in-range indices, and every depth left in [0, 1].
pub fn pipeline(input: &RawPipeline) -> Result<(), Failure> {
    let Some(scene) = input.draw.scene() else {
        return Ok(());
    };
    judged(input, || {
        let mut target = Framebuffer::new(scene.width, scene.height)
            .map_err(|e| Violation::new(format!("the scene's viewport was refused: {e}")))?;
        target.clear([0, 0, 0, 255], 1.0);
        let vertices: Vec<Vertex> = scene
            .positions
            .iter()
            .map(|p| Vertex::colored(Vec3::new(p[0], p[1], p[2]), Vec3::splat(p[3])))
            .collect();
        let mesh = Mesh {
            vertices,
            triangles: scene.triangles.clone(),
        };
        let mvp = Mat4::from_cols_array(&input.matrix());
        let renderer = Renderer {
            state: input.draw.state(),
            ..Renderer::default()
        };
        renderer
            .draw_mesh(&mut target, &mesh, Mat4::IDENTITY, mvp, |s| Some(s.color))
            .map_err(|e| Violation::new(format!("draw_mesh returned an error on in-range indices: {e}")))?;
        let segments: Vec<[u32; 2]> = mesh
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
            .collect();
        renderer.draw_lines(&mut target, &mesh.vertices, &segments, mvp);
        renderer.draw_points(&mut target, &mesh.vertices, mvp);
        let width = scene.width as usize;
        match target.depth().iter().position(|d| !(0.0..=1.0).contains(d)) {
            None => Ok(()),
            Some(i) => Err(Violation::at(
                ((i % width) as u32, (i / width) as u32),
                format!("depth {} left in the buffer, outside [0, 1]", target.depth()[i]),
            )),
        }
    })
}

/// Decodes `bytes` as `fuzz_target!` does: too short for `T`'s size hint, or not decodable, is `None`.
#[must_use]
pub fn decode<'a, T: Arbitrary<'a>>(bytes: &'a [u8]) -> Option<T> {
    if bytes.len() < T::size_hint(0).0 {
        return None;
    }
    T::arbitrary_take_rest(Unstructured::new(bytes)).ok()
}

/// What one fuzz input did.
#[derive(Debug)]
pub enum Checked {
    /// The bytes do not decode to an input (libFuzzer rejects them too).
    Skipped,
    /// The check held.
    Passed,
    /// The check failed.
    Failed(Failure),
}

/// A fuzz target: its name in `fuzz/fuzz_targets/` and the check it runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// [`robustness`] on [`RawDraw`].
    Robustness,
    /// [`differential`] on [`GridTriangles`].
    Differential,
    /// [`watertight`] on [`Points`].
    Watertight,
    /// [`clipping`] on [`Clipping`].
    Clipping,
    /// [`depth_order`] on [`Overlapping`].
    DepthOrder,
    /// [`interpolation`] on [`Perspective`].
    Interpolation,
    /// [`pipeline`] on [`RawPipeline`]: refrast's own renderer, whatever rasterizer is passed.
    Pipeline,
}

impl Target {
    /// Every target, in the order `fuzz/nightly.sh` runs them.
    pub const ALL: [Self; 7] = [
        Self::Robustness,
        Self::Differential,
        Self::Watertight,
        Self::Clipping,
        Self::DepthOrder,
        Self::Interpolation,
        Self::Pipeline,
    ];

    /// Whether the check judges the rasterizer it is given (all but [`Target::Pipeline`], which
    /// drives refrast's own renderer).
    #[must_use]
    pub fn judges_rasterizer(self) -> bool {
        self != Self::Pipeline
    }

    /// The name of the fuzz target binary and of its corpus folder.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Robustness => "robustness",
            Self::Differential => "differential",
            Self::Watertight => "watertight",
            Self::Clipping => "clipping",
            Self::DepthOrder => "depth_order",
            Self::Interpolation => "interpolation",
            Self::Pipeline => "pipeline",
        }
    }

    /// The target called `name` (as in [`Target::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Decodes `bytes` as this target's `fuzz_target!` does and runs its check on `r`.
    pub fn run(self, r: &mut dyn Rasterizer, bytes: &[u8]) -> Checked {
        let result = match self {
            Self::Robustness => decode(bytes).map(|i| robustness(r, &i)),
            Self::Differential => decode(bytes).map(|i| differential(r, &i)),
            Self::Watertight => decode(bytes).map(|i| watertight(r, &i)),
            Self::Clipping => decode(bytes).map(|i| clipping(r, &i)),
            Self::DepthOrder => decode(bytes).map(|i| depth_order(r, &i)),
            Self::Interpolation => decode(bytes).map(|i| interpolation(r, &i)),
            Self::Pipeline => decode(bytes).map(|i| pipeline(&i)),
        };
        match result {
            None => Checked::Skipped,
            Some(Ok(())) => Checked::Passed,
            Some(Err(f)) => Checked::Failed(f),
        }
    }
}
