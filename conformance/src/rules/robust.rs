//! Bad and extreme input: no panic, no error where the outcome is defined, sane output.

use proptest::prelude::*;
use refrast::{DrawError, Fragment, Rasterizer};

use super::common::{compare_sets, fragments, precision};
use super::level::{
    BAD_INDEX_D3D, BAD_INDEX_UNDEFINED, BARYCENTRICS_UNJUDGED, DEPTH_OUT_OF_RANGE, IN_RANGE_ONLY,
    INFINITY_EITHER_WAY, Level, NON_FINITE_UNSPECIFIED,
};
use super::{Family, Rule};
use crate::picture;
use crate::runner::property;
use crate::scene::rust_f32;
use crate::scene::{CaseData, Coordinate, Poison, Scene};
use crate::strategy;
use crate::violation::{Findings, Violation, plural};

/// A scene with one coordinate of triangle 0 replaced by a non-finite value.
#[derive(Clone)]
pub struct Poisoned {
    /// The scene before poisoning; triangle 1 may share the poisoned vertex, the rest share none.
    pub scene: Scene,
    /// Which vertex of triangle 0 (0..3) and which component (0..4).
    pub at: (usize, usize),
    /// The bad value.
    pub value: f32,
}

impl std::fmt::Debug for Poisoned {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let value = rust_f32(self.value);
        write!(
            f,
            "Poisoned {{ scene: {:?}, at: {:?}, value: {value} }}",
            self.scene, self.at
        )
    }
}

impl crate::scene::Case for Poisoned {
    /// Drops any triangle but the poisoned one (triangle 0).
    fn reductions(&self) -> Vec<Self> {
        (1..self.scene.triangles.len())
            .map(|t| Self {
                scene: self.scene.without(t),
                at: self.at,
                value: self.value,
            })
            .collect()
    }

    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
    }

    /// The scene before poisoning, and the coordinate poisoned.
    fn data(&self) -> CaseData {
        CaseData {
            poison: Some(Poison {
                vertex: self.at.0,
                component: self.at.1,
                value: Coordinate(self.value),
            }),
            ..CaseData::of_draw(self.scene.draw_data())
        }
    }

    fn from_data(data: &CaseData) -> Result<Self, String> {
        let poison = data
            .poison
            .ok_or("this rule's cases poison a coordinate: the case has no poison")?;
        if poison.vertex > 2 || poison.component > 3 {
            return Err(format!(
                "poison names vertex {} and component {}: a triangle has vertices 0 to 2, each \
                 with components 0 to 3",
                poison.vertex, poison.component
            ));
        }
        if data.translate.is_some() {
            return Err("this rule's cases have no translate".into());
        }
        let scene = data.draw.triangle_scene()?;
        if scene.triangles.is_empty() {
            return Err("the poisoned triangle 0 is missing: the draw has no triangle".into());
        }
        Ok(Self {
            scene,
            at: (poison.vertex, poison.component),
            value: poison.value.0,
        })
    }
}

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::invariant(Family::Robust, "robust.non-finite.discarded")
            .sentence("A NaN or infinite coordinate discards every triangle using its vertex and nothing else, without an error.")
            .source("D3D11.3 §15.4 and §15.16.1 (NaN positions are discarded); refrast convention (ARCHITECTURE.md, Conventions: bad numbers)")
            .cases(3000)
            .vulkan_and_opengl(Level::Undefined(NON_FINITE_UNSPECIFIED))
            .d3d11(Level::Partly {
                part: |r, cfg| property(r, cfg, poisoned(), check_poisoned_by_nan),
                note: INFINITY_EITHER_WAY,
            })
            .run(|r, cfg| property(r, cfg, poisoned(), check_poisoned)),
        Rule::invariant(Family::Robust, "robust.bit-patterns.sane-output")
            .sentence("Arbitrary f32 bit patterns (NaN, Inf, subnormal, huge, w = 0) give no panic, no error, and only well-formed fragments.")
            .source("zeno #1, raqote #107, tiny-skia #112 (panics and hangs on extreme input); D3D11.3 §15.4, §15.16.1")
            .cases(20000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, bit_pattern_scene(), check_sane_where_defined),
                note: IN_RANGE_ONLY,
            })
            .d3d11(Level::Partly {
                part: |r, cfg| property(r, cfg, bit_pattern_scene(), check_raw_bits_but_barycentrics),
                note: BARYCENTRICS_UNJUDGED,
            })
            .run(|r, cfg| property(r, cfg, bit_pattern_scene(), check_raw_bits)),
        Rule::invariant(Family::Robust, "robust.output.well-formed")
            .sentence("Fragments lie in the viewport, name a real primitive, cover a pixel at most once per primitive, and have depth in the viewport's depth range ([0, 1] unless the draw sets one) within the claimed precision.")
            .source("the Rasterizer contract (src/rasterizer.rs: Fragment); Vulkan 1.4, Rasterization (no fragments outside the framebuffer) and Depth Clamping and Range Adjustment")
            .cases(5000)
            .vulkan_and_opengl(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::crossing_scene(), check_well_formed_but_depth),
                note: DEPTH_OUT_OF_RANGE,
            })
            .d3d11(Level::Partly {
                part: |r, cfg| property(r, cfg, strategy::crossing_scene(), check_well_formed_but_barycentrics),
                note: BARYCENTRICS_UNJUDGED,
            })
            .run(|r, cfg| property(r, cfg, strategy::crossing_scene(), check_well_formed)),
        Rule::invariant(Family::Robust, "robust.bad-index.error")
            .sentence("A triangle naming a vertex that does not exist makes the draw fail with an error, not a panic.")
            .source("refrast convention (ARCHITECTURE.md, Conventions: bad numbers)")
            .cases(1000)
            .vulkan_and_opengl(Level::Undefined(BAD_INDEX_UNDEFINED))
            .d3d11(Level::NotCovered(BAD_INDEX_D3D))
            .run(|r, cfg| property(r, cfg, bad_index_scene(), check_bad_index)),
    ]
}

/// The values a coordinate is poisoned with.
const NON_FINITE: [f32; 3] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];

/// Scenes with one coordinate of triangle 0 set to NaN or an infinity.
fn poisoned() -> impl Strategy<Value = Poisoned> {
    let value = proptest::sample::select(NON_FINITE.to_vec());
    (
        strategy::overlapping_scene(),
        0..3usize,
        0..4usize,
        value,
        any::<bool>(),
    )
        .prop_map(|(mut scene, v, c, value, share)| {
            // Half the time triangle 1 uses the poisoned vertex too: both must go.
            if share && scene.triangles.len() > 1 {
                scene.triangles[1][0] = scene.triangles[0][v];
            }
            Poisoned {
                scene,
                at: (v, c),
                value,
            }
        })
}

fn bit_pattern_scene() -> impl Strategy<Value = Scene> {
    (1..48u32, 1..48u32, prop::array::uniform12(any::<u32>())).prop_map(|(w, h, bits)| {
        let c: Vec<f32> = bits.iter().map(|&b| f32::from_bits(b)).collect();
        let positions = c.chunks(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
        Scene::new(w, h, positions, vec![[0, 1, 2]])
    })
}

/// A grid triangle and a triangle naming a vertex past the last, before or after it: often
/// exactly one past (the `>` for `>=` slip), or `u32::MAX`.
fn bad_index_scene() -> impl Strategy<Value = Scene> {
    let bad = prop_oneof![
        2 => Just(3u32),
        1 => 3u32..8,
        1 => Just(u32::MAX),
        2 => 3u32..=u32::MAX,
    ];
    (strategy::grid_scene(), bad, any::<bool>()).prop_map(|(mut s, bad, first)| {
        if first {
            s.triangles.insert(0, [0, bad, 1]);
        } else {
            s.triangles.push([0, bad, 1]);
        }
        s
    })
}

/// [`check_poisoned`] for a NaN, which D3D11.3 discards; an infinity may go either way there.
pub fn check_poisoned_by_nan(r: &mut dyn Rasterizer, p: &Poisoned) -> Result<(), Violation> {
    if p.value.is_nan() {
        check_poisoned(r, p)
    } else {
        Ok(())
    }
}

/// A non-finite coordinate discards every triangle using its vertex and nothing else.
pub fn check_poisoned(r: &mut dyn Rasterizer, p: &Poisoned) -> Result<(), Violation> {
    let clean = fragments(r, &p.scene)?;
    let mut bad = p.scene.clone();
    let vertex = p.scene.triangles[0][p.at.0];
    bad.positions[vertex as usize][p.at.1] = p.value;
    let poisoned: Vec<bool> = p.scene.triangles.iter().map(|t| t.contains(&vertex)).collect();
    let is_poisoned = |f: &Fragment| poisoned.get(f.primitive as usize).copied().unwrap_or(false);
    let got = fragments(r, &bad).map_err(|v| {
        v.on(&format!(
            "on a draw whose vertex {vertex} has {} = {} (a triangle using a NaN or infinite \
             coordinate is to be skipped, the others drawn, and no error returned)",
            ["x", "y", "z", "w"][p.at.1.min(3)],
            p.value
        ))
    })?;
    let mut found = Findings::new();
    for f in got.iter().filter(|f| is_poisoned(f)) {
        found.add((f.x, f.y), || {
            format!(
                "{:?} of triangle {} at depth {}",
                (f.x, f.y),
                f.primitive,
                f.depth
            )
        });
    }
    if let Err(mut violation) = found.verdict(|n| {
        format!(
            "the triangles using a {} coordinate (vertex {}, component {}) drew {}",
            rust_f32(p.value),
            p.at.0,
            p.at.1,
            plural(n, "fragment")
        )
    }) {
        // The fragments drawn, over the outline of the triangle as it was before poisoning.
        violation.picture = Some(Box::new(picture::of_fragments(
            &p.scene,
            &got,
            &violation.samples,
        )));
        return Err(violation);
    }
    let others: Vec<Fragment> = clean.into_iter().filter(|f| !is_poisoned(f)).collect();
    compare_sets(
        &p.scene,
        &got,
        &others,
        "the other triangles without the poisoned one",
    )
}

/// Fragments are unique, have depth in the viewport's depth range within [`precision`] and
/// finite barycentrics where the profile declares them (that they lie in the viewport and name
/// real primitives, [`fragments`] checks for every rule).
pub fn check_well_formed(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    well_formed(
        r,
        scene,
        Judged {
            barycentrics: true,
            depth: true,
        },
    )
}

/// [`check_well_formed`] without the barycentrics, which D3D11.3 does not define.
pub fn check_well_formed_but_barycentrics(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    well_formed(
        r,
        scene,
        Judged {
            barycentrics: false,
            depth: true,
        },
    )
}

/// [`check_well_formed`] without the depth range, which Vulkan and OpenGL leave undefined
/// outside `[0, 1]` (a sample a grid step outside a steep clipped polygon extrapolates its
/// plane there; refrast clamps).
pub fn check_well_formed_but_depth(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    well_formed(
        r,
        scene,
        Judged {
            barycentrics: true,
            depth: false,
        },
    )
}

/// What Vulkan and OpenGL define for any input: fragments inside the viewport, naming real
/// primitives (the scissor sets coverage outside it to 0 whatever the input); where the
/// arithmetic stays within 2^32 ([`within_float_range_as_received`]), well-formed values too,
/// the depth range aside.
pub fn check_sane_where_defined(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let result = if within_float_range_as_received(scene, &r.profile()) {
        check_well_formed_but_depth(r, scene)
    } else {
        fragments(r, scene).map(drop)
    };
    result.map_err(|v| v.on(RAW_BITS))
}

/// [`check_well_formed`] on a draw of raw bit patterns, saying so on failure.
pub fn check_raw_bits(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_well_formed(r, scene).map_err(|v| v.on(RAW_BITS))
}

/// [`check_well_formed_but_barycentrics`] on a draw of raw bit patterns, saying so on failure.
pub fn check_raw_bits_but_barycentrics(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_well_formed_but_barycentrics(r, scene).map_err(|v| v.on(RAW_BITS))
}

/// What a draw of raw bit patterns is, and what it asks.
const RAW_BITS: &str = "on a draw of raw f32 bit patterns (NaN, infinities, huge values and w = 0 \
                        must give no crash, no error and only well-formed fragments)";

/// The magnitude Vulkan and OpenGL ask floats to represent at least (Floating-Point
/// Computation; OpenGL 4.6 §2.3.4.1).
const FLOAT_RANGE: f64 = 4_294_967_296.0;

/// [`within_float_range`] of the draw as an implementation with `profile` receives it: for one
/// whose `z` arrives rewritten to `2z − w` in f32 ([`refrast::Features::z_rewritten_in_f32`]),
/// also no vertex that the rewrite's rounding moves across or onto the near plane, since that
/// can leave a sliver at `w` far below 2^-32 where the exact volume leaves nothing.
#[must_use]
pub fn within_float_range_as_received(scene: &Scene, profile: &refrast::Profile) -> bool {
    within_float_range(scene)
        && (!profile.features.z_rewritten_in_f32
            || scene
                .positions
                .iter()
                .all(|&p| near_side_kept_by_rewrite(p, scene.state.depth_range)))
}

/// Whether vertex `p` lies on the same side of the near plane (strictly inside, on it, or
/// outside) after `z` is rewritten to `fl(fl(2z) − w)` under `−w ≤ z ≤ w`, as wgpu's OpenGL ES
/// backend hands it to the driver, as before.
fn near_side_kept_by_rewrite(p: [f32; 4], range: refrast::DepthRange) -> bool {
    let [_, _, z, w] = p;
    let (exact, rewritten) = match range {
        // The rewrite's near distance `z' + w`, `z'` rounded to f32 once (2z is exact).
        refrast::DepthRange::ZeroToOne => (f64::from(z), f64::from(2.0 * z - w) + f64::from(w)),
        // Already in OpenGL's volume: nothing is rewritten.
        refrast::DepthRange::NegativeOneToOne => return true,
    };
    exact.partial_cmp(&0.0) == rewritten.partial_cmp(&0.0)
}

/// Whether drawing `scene` needs no value beyond 2^32: every coordinate finite and within it
/// (subnormals included: they "must yield deterministic results"), and every vertex of each
/// clipped polygon at w ≥ 2^-32, since perspective interpolation divides by w (Basic Polygon
/// Rasterization). A vertex clipped away may have any w: nothing divides by it.
#[must_use]
pub fn within_float_range(scene: &Scene) -> bool {
    use refrast::stage::{ClipOutcome, assemble, clip_planes, clip_triangle};
    let finite = scene
        .positions
        .iter()
        .flatten()
        .all(|c| c.is_finite() && f64::from(c.abs()) <= FLOAT_RANGE);
    let Some(viewport) = scene.viewport() else {
        return false;
    };
    let planes = clip_planes(refrast::ClipMode::Full, viewport, scene.state.depth_clip());
    let (mut polygon, mut scratch) = (Vec::new(), Vec::new());
    finite
        && scene.triangles.iter().all(|&t| {
            let Some(corners) = assemble(&scene.positions, t) else {
                return true;
            };
            let kept = match clip_triangle(&corners, &planes, &[], &mut polygon, &mut scratch) {
                ClipOutcome::Outside => return true,
                ClipOutcome::Inside => &corners[..],
                ClipOutcome::Clipped => &polygon[..],
            };
            kept.iter().all(|v| v.position.w * FLOAT_RANGE >= 1.0)
        })
}

/// Which values [`well_formed`] judges besides positions and uniqueness.
#[derive(Clone, Copy)]
struct Judged {
    /// Declared barycentrics finite.
    barycentrics: bool,
    /// Depth in the viewport's depth range within the claimed precision.
    depth: bool,
}

/// Counts one more fragment at `key`: whether that makes more than `most`.
fn overcovered(
    seen: &mut std::collections::HashMap<(u32, u32, u32), u32>,
    key: (u32, u32, u32),
    most: u32,
) -> bool {
    let times = seen.entry(key).or_insert(0);
    *times += 1;
    *times > most
}

/// Fragments well formed; their depth in range and barycentrics finite as `judged` says.
fn well_formed(r: &mut dyn Rasterizer, scene: &Scene, judged: Judged) -> Result<(), Violation> {
    // Window depth is claimed within the precision of its exact value, which lies in the
    // viewport's depth range ([0, 1] unless the draw sets one).
    let profile = r.profile();
    let eps = precision(&profile);
    let [lo, hi] = crate::oracle::raster::depth_bounds(&scene.state);
    // Barycentrics the profile does not declare are whatever the fragment carries.
    let declared = judged.barycentrics && profile.features.perspective_barycentrics;
    let frags = fragments(r, scene)?;
    // A filled triangle draws a pixel once; in line or point mode each of its three edges or
    // vertices may draw it.
    let most = if scene.state.polygon_mode == refrast::PolygonMode::Fill {
        1
    } else {
        3
    };
    let mut seen = std::collections::HashMap::new();
    let mut found = Findings::new();
    // What to change for the first fragment found wrong.
    let mut fix = None;
    for f in &frags {
        let (problem, change) = if judged.depth && !(lo - eps..=hi + eps).contains(&f64::from(f.depth)) {
            (
                "has depth outside the viewport's depth range by more than the claimed precision",
                "clip triangles against the near plane (z < 0, or z < -w under \
                 negative-one-to-one) and the far plane when the draw asks for them, else clamp \
                 depth to the viewport's depth range [min(minDepth, maxDepth), max(…)]",
            )
        } else if declared && f.barycentric.iter().any(|b| !b.is_finite()) {
            (
                "has a non-finite barycentric",
                "a division by zero: a zero area, or a w of 0 that clipping should have removed",
            )
        } else if overcovered(&mut seen, (f.primitive, f.x, f.y), most) {
            (
                if most == 1 {
                    "covers its pixel a second time"
                } else {
                    "covers its pixel a fourth time (three edges or vertices at most)"
                },
                if most == 1 {
                    "one triangle draws each pixel once: the triangles a clipped polygon is cut \
                     into must not overlap"
                } else {
                    "each edge or vertex of a triangle in line or point mode draws each pixel once"
                },
            )
        } else {
            continue;
        };
        fix.get_or_insert(change);
        found.add((f.x, f.y), || format!("{f:?} {problem}"));
    }
    found.verdict(|n| {
        format!(
            "{} not well formed ({})",
            plural(n, "fragment"),
            fix.unwrap_or_default()
        )
    })
}

/// An out-of-range index is an error, not a panic.
pub fn check_bad_index(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    match r.rasterize(&scene.draw()) {
        // A crash or a garbled answer is no error report: it fails here as everywhere.
        Err(e @ DrawError::Misbehaved(_)) => Err(Violation::of_draw_error(
            "a draw with vertex index out of range",
            &e,
        )),
        Err(_) => Ok(()),
        Ok(frags) => Err(Violation::new(format!(
            "a draw with vertex index out of range succeeded with {} fragments",
            frags.len()
        ))),
    }
}
