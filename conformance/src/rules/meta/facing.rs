//! Facing and culling: a fragment's facing follows its triangle's winding, culling removes
//! exactly one facing, a triangle of zero area draws nothing, and lines and points face front
//! whatever the cull mode.

use proptest::prelude::*;

use refrast::{CullMode, Fragment, FrontFace, Profile, Rasterizer};

use super::translate;
use crate::oracle::facing::Turn;
use crate::oracle::outline::{distance_to_outline, visible_outline};
use crate::oracle::raster::{self, sample_centre, sample_ndc};
use crate::oracle::ray_cast::ray_cast;
use crate::rules::common::{check_draws_nothing, compare_sets, deep_sample, fragments};
use crate::rules::samples::sample_fragments;
use crate::scene::PrimitiveScene;
use crate::scene::Scene;
use crate::strategy::{self, primitive};
use crate::violation::{Findings, Violation, plural};

/// Overlapping grid triangles, or one across clip planes (w of either sign or 0): culling must
/// follow the facing of clipped triangles too, not a wrongly signed area before clipping.
pub(super) fn cull_scene(profile: &Profile) -> impl Strategy<Value = Scene> + use<> {
    prop_oneof![
        2 => strategy::overlapping_scene(),
        2 => strategy::crossing_scene(),
        1 => strategy::flipped_sliver(profile),
    ]
}

/// Lines or points, whichever the implementation declares (both when it declares both).
pub(super) fn lines_or_points(declared: &Profile) -> BoxedStrategy<PrimitiveScene> {
    match (declared.lines.is_some(), declared.points) {
        (true, true) => prop_oneof![primitive::lines(), primitive::points()].boxed(),
        (true, false) => primitive::lines().boxed(),
        _ => primitive::points().boxed(),
    }
}

/// `(x, y, sample, primitive)` of a covered sample.
type CoveredSample = (u32, u32, u8, u32);

/// Every fragment of a line or point faces front, and every supported cull mode (both faces
/// included, where declared) and front face leaves the same samples covered: facing and
/// culling belong to polygons.
pub fn check_lines_points_front(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let profile = r.profile();
    let features = profile.features;
    let mut first: Option<(CullMode, FrontFace, Vec<CoveredSample>)> = None;
    // Culling of both faces, where declared, leaves them alone too.
    let both = profile.state.cull_both.then_some(CullMode::FrontAndBack);
    for cull in features.cull_modes.values().chain(both) {
        for front in features.front_faces.values() {
            let mut drawn = case.clone();
            drawn.scene.state.cull = cull;
            drawn.scene.state.front_face = front;
            let frags = sample_fragments(r, &drawn)?;
            if let Some(f) = frags.iter().find(|f| !f.front_facing) {
                return Err(Violation::new(format!(
                    "({}, {}) of primitive {} reports back-facing under cull {cull:?}, front face {front:?}: \
                     line and point fragments always face front",
                    f.x, f.y, f.primitive
                )));
            }
            let mut covered: Vec<_> = frags.iter().map(|f| (f.x, f.y, f.sample, f.primitive)).collect();
            covered.sort_unstable();
            match &first {
                None => first = Some((cull, front, covered)),
                Some((c0, f0, seen)) if *seen != covered => {
                    return Err(Violation::new(format!(
                        "cull {cull:?} with front face {front:?} covers {} samples where cull {c0:?} with \
                         {f0:?} covers {}: culling and facing must leave lines and points alone",
                        covered.len(),
                        seen.len()
                    )));
                }
                Some(_) => {}
            }
        }
    }
    Ok(())
}

/// With both faces culled, the scene's triangles draw nothing.
pub fn check_culled_both(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    check_draws_nothing(r, scene).map_err(|v| v.on("with both faces culled (front-and-back)"))
}

/// [`cull_scene`] with both faces culled.
pub(super) fn cull_both_scene(profile: &Profile) -> impl Strategy<Value = Scene> + use<> {
    cull_scene(profile).prop_map(|mut s| {
        s.state.cull = CullMode::FrontAndBack;
        s
    })
}

/// Unclipped grid triangles, triangles across clip planes with `w` of either sign, and slivers
/// that snapping turns over (whose facing is that of their snapped area), under either front
/// face.
pub(super) fn facing_scene(profile: &Profile) -> impl Strategy<Value = Scene> + use<> {
    let scene = prop_oneof![
        2 => strategy::inside_scene(),
        2 => strategy::crossing_scene(),
        1 => strategy::flipped_sliver(profile),
    ];
    (scene, any::<bool>()).prop_map(|(mut s, cw)| {
        s.state.front_face = if cw {
            FrontFace::Clockwise
        } else {
            FrontFace::CounterClockwise
        };
        s
    })
}

/// `front_facing` follows the winding and the front face: the snapped signed area for a
/// triangle that needs no clipping, `−sign(det[x y w])` for one that does.
pub fn check_facing(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let front_is_cw = scene.state.front_face == FrontFace::Clockwise;
    let p = scene.corners(0);
    let frags = fragments(r, scene)?;
    let turn = |clockwise: bool| {
        if clockwise {
            "clockwise"
        } else {
            "counter-clockwise"
        }
    };
    let mut found = Findings::new();
    // Under a cull mode, a triangle surely facing the culled way draws nothing at all.
    let sure = scene.turns(&profile)[0];
    if sure.drawn(&scene.state) == Some(false) && sure != Turn::Degenerate {
        for f in &frags {
            found.add((f.x, f.y), || {
                format!(
                    "{:?} is drawn, but the triangle turns {} on screen, so it faces {} and {:?} culling discards it",
                    (f.x, f.y),
                    turn_word(sure),
                    if sure.front_facing(&scene.state) == Some(true) { "front" } else { "back" },
                    scene.state.cull
                )
            });
        }
        return found.verdict(|n| format!("a culled triangle drew {}", plural(n, "fragment")));
    }
    let mut judge = |f: &Fragment, clockwise: bool, how: &str| {
        if f.front_facing != (clockwise == front_is_cw) {
            found.add((f.x, f.y), || {
                format!(
                    "{:?} says front_facing = {}, but the triangle turns {} there ({how})",
                    (f.x, f.y),
                    f.front_facing,
                    turn(clockwise)
                )
            });
        }
    };
    if profile.snapping.grid_bits().is_some() && raster::unclipped(&p, &scene.state) {
        // Unclipped on a grid: exactly as the snapped triangle turns, for every way the
        // profile lets it snap (not judged where those disagree).
        let clockwise = match sure {
            Turn::Clockwise => true,
            Turn::CounterClockwise => false,
            Turn::Degenerate | Turn::Unsure => return Ok(()),
        };
        for f in &frags {
            judge(f, clockwise, "its snapped signed area");
        }
    } else {
        // Clipped, or without a grid: the visible part turns as det[x y w] says, whatever the
        // signs of w (Olano–Greer), and the ray cast decides that sign exactly at each sample it
        // hits. A rasterizer may take facing from its snapped, clipped polygon instead (Vulkan):
        // snapping moves each vertex by less than the band, which can turn over a sliver but not
        // the polygon around a sample more than twice the band inside it (a heuristic, not a
        // proof; cuts at the viewport snap onto the grid and add no risk). Samples nearer the
        // visible outline are not judged.
        let tri = scene.positions_of(0);
        let outline = visible_outline(&tri, scene.width, scene.height, &scene.state);
        let band = profile.band_px();
        for f in &frags {
            if distance_to_outline(&outline, sample_centre(f.x, f.y), |_, _| true) <= 2.0 * band {
                continue;
            }
            let [nx, ny] = sample_ndc(scene.width, scene.height, f.x, f.y);
            if let Some(hit) = ray_cast(&tri, nx, ny, &scene.state) {
                judge(f, hit.clockwise, "the sign of det[x y w] of its visible part");
            }
        }
    }
    found.verdict(|n| {
        format!(
            "the wrong facing for {:?} front faces at {}",
            scene.state.front_face,
            plural(n, "fragment")
        )
    })
}

/// Zero-area triangles drawn whole ([`collinear_scene`]), and a sixth of the time one the near
/// plane cuts ([`strategy::zero_area_across_near`]).
pub(super) fn degenerate_scene() -> impl Strategy<Value = Scene> {
    prop_oneof![5 => collinear_scene(), 1 => strategy::zero_area_across_near()]
}

/// Zero-area triangles: three points of the half-pixel lattice on one line (or one repeated),
/// each at its own `w`, under either front face.
fn collinear_scene() -> impl Strategy<Value = Scene> {
    // Half-pixel points stay collinear on every grid of one subpixel bit or more.
    let half = strategy::GRID / 2;
    let point = || (-8i64..72, -8i64..72);
    // Powers of two, so that x·w and (x·w)/w are exact in f32: with any other w a driver that
    // divides in f32 and snaps by truncation can land a vertex one unit off and give the
    // triangle area (softpipe did, a false positive; `degenerate_scenes_project_exactly`).
    let ws = prop::array::uniform3((-3i32..=2).prop_map(|k| 2.0f32.powi(k)));
    let shape = (point(), point(), -3i64..4, 0..2u8);
    (shape, ws, any::<bool>(), strategy::side()).prop_map(move |((a, b, k, shape), ws, cw, s)| {
        let a = (a.0 * half, a.1 * half);
        let b = (b.0 * half, b.1 * half);
        // c on the line through a and b at a whole multiple of b − a, or a repeated vertex.
        let c = if shape == 0 {
            (a.0 + k * (b.0 - a.0), a.1 + k * (b.1 - a.1))
        } else {
            a
        };
        let mut scene = Scene::from_subpixels(s, s, 8, &[[a, b, c]], 0.5);
        // Each vertex at its own w: the same screen points exactly, so still zero area, but no
        // longer an affine triangle.
        for (p, w) in scene.positions.iter_mut().zip(ws) {
            *p = p.map(|v| v * w);
        }
        if cw {
            scene.state.front_face = FrontFace::Clockwise;
        }
        scene
    })
}

/// A zero-area triangle draws nothing, unless clipping may have made it a real polygon: x/y
/// clipping beyond the guard band, or the near plane where the profile does not claim to decide
/// zero area before clipping (then only samples away from its line are judged).
pub fn check_degenerate(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let range = scene.state.depth_range;
    let cut = scene.state.clip_near
        && scene
            .corners(0)
            .iter()
            .any(|&[_, _, z, w]| raster::near_distance(range, z, w) < 0.0);
    if cut && !profile.features.zero_area_before_clipping {
        // Clipping first, a cut vertex snapped off the line makes a sliver along it (Vulkan
        // decides zero area on the clipped polygon).
        return check_degenerate_off_line(r, scene);
    }
    // Beyond the guard band a triangle reaching outside the viewport is clipped, and the new
    // vertices, computed on the boundary and snapped, need not stay on the old line (Vulkan
    // §"Primitive Clipping": intersecting edges are reconnected by new edges along the
    // boundary): the clipped polygon may have area.
    let reach = f64::from(profile.features.guard_band);
    let beyond = scene.positions.iter().any(|&p| {
        let [x, y] = raster::project(scene.width, scene.height, p.map(f64::from));
        !(-reach..=f64::from(scene.width) + reach).contains(&x)
            || !(-reach..=f64::from(scene.height) + reach).contains(&y)
    });
    if beyond {
        return Ok(());
    }
    check_draws_nothing(r, scene)
}

/// [`check_degenerate`] away from the line: no fragment farther than the band (and a grid step
/// where the profile's snapping is not exact) from the triangle's edges, what every
/// specification requires of a zero-area triangle ([`crate::rules::level::ZERO_AREA_LINE`]).
pub fn check_degenerate_off_line(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let limit = profile.band_px() + translate::snap_slack(&profile);
    let mut found = Findings::new();
    for f in fragments(r, scene)? {
        if !translate::near_edge(scene, profile.snapping, f.x, f.y, limit) {
            found.add((f.x, f.y), || format!("{:?}, away from the line", (f.x, f.y)));
        }
    }
    found.verdict(|n| {
        format!(
            "a zero-area triangle drew {} away from its line",
            plural(n, "fragment")
        )
    })
}
/// Culling removes exactly the fragments of the culled facing.
///
/// With `None` among the cull modes, each culled draw is compared with the unculled one. A
/// rasterizer that cannot switch culling off is drawn the scene and its reversal under every
/// supported cull mode and front face: a triangle surely facing the culled way draws nothing, one
/// surely facing the other way has the facing it should and, where a sample lies farther than
/// twice the band inside it, draws.
pub fn check_culling(r: &mut dyn Rasterizer, scene: &Scene) -> Result<(), Violation> {
    let profile = r.profile();
    let features = profile.features;
    if !features.cull_modes.contains(CullMode::None) {
        return check_culling_by_facing(r, &profile, scene);
    }
    for front_face in features.front_faces.values() {
        let mut none = scene.clone();
        none.state.front_face = front_face;
        none.state.cull = CullMode::None;
        let all = fragments(r, &none)?;
        for cull in [CullMode::Front, CullMode::Back] {
            if !features.cull_modes.contains(cull) {
                continue;
            }
            let mut culled = none.clone();
            culled.state.cull = cull;
            let want: Vec<Fragment> = all
                .iter()
                .filter(|f| !cull.culls(f.front_facing))
                .copied()
                .collect();
            compare_sets(
                scene,
                &fragments(r, &culled)?,
                &want,
                &format!("{cull:?} culling with {front_face:?} front faces"),
            )?;
        }
    }
    Ok(())
}

/// [`check_culling`] for a rasterizer that always culls: each triangle judged by its facing.
fn check_culling_by_facing(
    r: &mut dyn Rasterizer,
    profile: &Profile,
    scene: &Scene,
) -> Result<(), Violation> {
    let mut reversed = scene.clone();
    for t in &mut reversed.triangles {
        t.swap(1, 2);
    }
    let band = profile.band_px();
    for front_face in profile.features.front_faces.values() {
        for cull in profile.features.cull_modes.values() {
            for (drawn, how) in [(scene, "as generated"), (&reversed, "reversed")] {
                let mut s = drawn.clone();
                s.state.front_face = front_face;
                s.state.cull = cull;
                let turns = s.turns(profile);
                let frags = fragments(r, &s)?;
                let mut found = Findings::new();
                for f in &frags {
                    let turn = turns[f.primitive as usize];
                    match turn.drawn(&s.state) {
                        Some(false) => found.add((f.x, f.y), || {
                            format!(
                                "{:?} of triangle {} is drawn, but the triangle turns {} on screen and {cull:?} culling discards it",
                                (f.x, f.y),
                                f.primitive,
                                turn_word(turn)
                            )
                        }),
                        Some(true) if turn.front_facing(&s.state) != Some(f.front_facing) => {
                            found.add((f.x, f.y), || {
                                format!(
                                    "{:?} of triangle {} says front_facing = {}, but the triangle turns {} on screen",
                                    (f.x, f.y),
                                    f.primitive,
                                    f.front_facing,
                                    turn_word(turn)
                                )
                            });
                        }
                        _ => {}
                    }
                }
                for (t, turn) in turns.iter().enumerate() {
                    if turn.drawn(&s.state) == Some(true)
                        && !frags.iter().any(|f| f.primitive as usize == t)
                        && let Some(at) = deep_sample(&s, t, 2.0 * band)
                    {
                        found.add(at, || {
                            format!(
                                "triangle {t} turns {} on screen, so {cull:?} culling keeps it, but it drew nothing (not even {at:?}, deep inside it)",
                                turn_word(*turn)
                            )
                        });
                    }
                }
                found.verdict(|n| {
                    format!(
                        "{cull:?} culling with {front_face:?} front faces, the scene {how}: {} wrong",
                        plural(n, "sample")
                    )
                })?;
            }
        }
    }
    Ok(())
}

/// A turn in words.
fn turn_word(turn: Turn) -> &'static str {
    match turn {
        Turn::Clockwise => "clockwise",
        Turn::CounterClockwise => "counter-clockwise",
        Turn::Degenerate => "nowhere (zero area)",
        Turn::Unsure => "either way",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (softpipe, once the generators were widened: docs/reach.md): with w from a
    /// continuous range, a vertex of a "zero-area" triangle projected to 383.9995 of 1/256 px in
    /// f32, which truncating snaps to 383 and rounding to 384, so the triangle had area for some
    /// drivers. Every vertex must project, in f32 as in f64, exactly onto the half-pixel lattice
    /// it was built on.
    #[test]
    fn degenerate_scenes_project_exactly() {
        for scene in strategy::samples(collinear_scene(), 2000) {
            let (w, h) = (scene.width as f32, scene.height as f32);
            for p in &scene.positions {
                let (nx, ny) = (p[0] / p[3], p[1] / p[3]);
                let raster = [(nx + 1.0) * 0.5 * w, (1.0 - ny) * 0.5 * h];
                for c in raster {
                    assert_eq!((c * 2.0).fract(), 0.0, "{p:?} projects to {raster:?}");
                    assert_eq!(f64::from(c), f64::from(c * 2.0) / 2.0);
                }
                assert_eq!(f64::from(nx), f64::from(p[0]) / f64::from(p[3]), "{p:?}");
            }
        }
    }
}
