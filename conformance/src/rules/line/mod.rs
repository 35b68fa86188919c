//! Lines of width one: exact coverage under the declared rule, strips, clipping, depth and
//! barycentrics along the segment (`values.rs`), and what reversing a segment may change.

use refrast::{FillConvention, Fragment, LineRule, Profile, Rasterizer, Topology};

use super::level::Level;
use super::samples::{
    compare_samples, counts, endpoint_bits, expect_covered, grid, keys, positions, sample_fragments,
};
use super::viewport_depth::varied_depth;
use super::{CLIPS_IN_3D, Family, PERSPECTIVE_BARYCENTRICS, Rule, needs};
use crate::oracle::facing::snap_candidates;
use crate::oracle::raster::{Point, near_distance, project};
use crate::oracle::segment::SampleGrid;
use crate::runner::{property, property_for};
use crate::scene::PrimitiveScene;
use crate::strategy::primitive as lines;
use crate::strategy::reach;
use crate::violation::{Expect, Findings, Violation, plural};

mod clip;
mod values;
pub use clip::{check_clip, check_clip_allowance};
pub use values::{check_bary_perspective, check_depth_linear};

/// The implementation draws lines by the diamond-exit rule.
const DIAMOND_EXIT: super::Need = needs(
    |p| p.lines == Some(LineRule::DiamondExit) && endpoint_grid(p),
    "no lines by the diamond-exit rule on a snapping grid",
);
/// The implementation draws lines as rectangles or parallelograms.
const AREA_LINES: super::Need = needs(
    |p| matches!(p.lines, Some(LineRule::Rectangle | LineRule::Parallelogram)) && endpoint_grid(p),
    "no lines as rectangles or parallelograms on a snapping grid",
);
/// The implementation draws lines of any rule.
const LINES: super::Need = needs(
    |p| p.lines.is_some() && endpoint_grid(p),
    "no lines on a snapping grid",
);

fn endpoint_grid(p: &Profile) -> bool {
    endpoint_bits(p).is_some()
}

/// Vulkan's and OpenGL's allowance for other algorithms than the diamond-exit rule itself.
const OTHER_ALGORITHMS: &str = "Vulkan (Bresenham Line Segment Rasterization) and OpenGL 4.6 §14.5.1 let an implementation use another algorithm whose fragments lie within one pixel in x and y of the diamond-exit rule's, number within one of them, and never two in one column of an x-major line (one row of a y-major one); D3D11.3 (aliased line rules) breaks ties on a diamond's boundary its own way (an x-major line's diamond holds its lower edges and bottom corner): the ε-nudged rule is judged bit for bit under refrast's conventions, and only that allowance under these";

/// What reversing a segment may change is pinned only by the exact rule, which no
/// specification requires of every implementation.
const REVERSAL_OPEN: &str = "Vulkan (Bresenham Line Segment Rasterization) and OpenGL 4.6 §14.5.1 let another algorithm within one pixel of the diamond-exit rule draw each segment, in its own direction, and D3D11.3 names no rule for a reversed segment: that reversing one changes only its end pixels is refrast's convention (exact for the diamond-exit rule itself, whose nudge is the same both ways)";

pub(super) fn rules() -> Vec<Rule> {
    vec![
        Rule::exact(Family::Line, "line.diamond-exit.exact")
            .sentence("Each segment of a line list or strip covers exactly the pixels the diamond-exit rule gives on its snapped ends (ends nudged by −(ε, ε²), the last end's diamond left out).")
            .source("Vulkan 1.4, Bresenham Line Segment Rasterization; OpenGL 4.6 §14.5.1; dEQP-VK.rasterization.primitives.lines")
            .cases(1500)
            .needs(DIAMOND_EXIT)
            .every_spec(Level::Partly {
                part: |r, cfg| property_for(r, cfg, reach::any_lines, check_diamond_allowance),
                note: OTHER_ALGORITHMS,
            })
            .run(|r, cfg| property_for(r, cfg, reach::any_lines, check_diamond_exact)),
        Rule::invariant(Family::Line, "line.area.matches-oracle")
            .sentence("A segment drawn as a rectangle or parallelogram one pixel wide covers the samples inside that shape on its snapped ends, samples within the tolerance band of its outline aside.")
            .source("Vulkan 1.4, Basic Line Segment Rasterization (strictLines rectangles, non-strict parallelograms)")
            .cases(1500)
            .needs(AREA_LINES)
            .run(|r, cfg| property_for(r, cfg, reach::any_lines, check_area)),
        Rule::invariant(Family::Line, "line.strip.same-as-list")
            .sentence("A line strip draws each of its segments exactly as a line list of those segments does.")
            .source("Vulkan 1.4, Line Lists and Line Strips (topologies); OpenGL 4.6 §10.1.2")
            .cases(500)
            .needs(LINES)
            .run(|r, cfg| property(r, cfg, lines::line_strip(), check_strip_same_as_list)),
        Rule::invariant(Family::Line, "line.strip.shared-end-once")
            .sentence("Two segments of a strip that share an end and run the same way along the same major axis draw no pixel twice.")
            .source("Vulkan 1.4, Bresenham Line Segment Rasterization (\"must not produce duplicate fragments\"); OpenGL 4.6 §14.5.1")
            .cases(1000)
            .needs(DIAMOND_EXIT)
            .run(|r, cfg| property(r, cfg, lines::line_strip(), check_shared_end_once)),
        Rule::invariant(Family::Line, "line.clip.visible-part")
            .sentence("A segment crossing the near plane covers what its visible part covers, the pixels near the cut aside.")
            .source("Vulkan 1.4, Primitive Clipping (a clipped line segment ends at the clip plane); seed 004 (clipping)")
            .cases(800)
            .needs(LINES)
            .needs(CLIPS_IN_3D)
            .every_spec(Level::Partly {
                part: |r, cfg| property(r, cfg, near_crossing(), check_clip_allowance),
                note: OTHER_ALGORITHMS,
            })
            .run(|r, cfg| property(r, cfg, near_crossing(), check_clip)),
        Rule::invariant(Family::Line, "line.depth.linear")
            .sentence("A line fragment's depth is the ends' window depths (through the viewport's depth range, where declared) interpolated linearly in screen space at the sample's projection on the segment's line (held at the end's or extrapolated beyond it), clamped to the range with depth clipping off (where declared), within a pixel's worth and the claimed precision.")
            .source("Vulkan 1.4, Basic Line Segment Rasterization (z_f = (1 − t) z_a + t z_b); seed 004 (lines with depth)")
            .cases(800)
            .needs(LINES)
            .run(|r, cfg| {
                property_for(
                    r,
                    cfg,
                    |p| varied_depth(p, lines::perspective_line()),
                    check_depth_linear,
                )
            }),
        Rule::invariant(Family::Line, "line.bary.perspective")
            .sentence("A line fragment's barycentrics are (1 − t′, t′, 0) with t′ the perspective-correct position along the segment's line (held at an end or extrapolated beyond it), within a pixel's worth and the claimed precision.")
            .source("Vulkan 1.4, Basic Line Segment Rasterization (perspective-correct interpolation along the line)")
            .cases(800)
            .needs(LINES)
            .needs(PERSPECTIVE_BARYCENTRICS)
            .run(|r, cfg| property(r, cfg, lines::perspective_line(), check_bary_perspective)),
        Rule::invariant(Family::Line, "line.reversal.ends-only")
            .sentence("Drawing a segment from its other end changes only the pixels whose diamonds hold an end (diamond-exit) and nothing else (rectangles, parallelograms), the tolerance band aside.")
            .source("refrast's own metamorphic property (a segment's direction may change only its ends); OpenGL 4.6 §14.5.1 (the diamond-exit rule it follows from, which lets an implementation choose otherwise)")
            .cases(1000)
            .needs(LINES)
            .every_spec(Level::NotCovered(REVERSAL_OPEN))
            .run(|r, cfg| property_for(r, cfg, reach::any_lines, check_reversal)),
    ]
}

/// Segments crossing the near plane: at `w = 1`, or from an end in perspective to one often
/// behind the eye.
fn near_crossing() -> impl proptest::strategy::Strategy<Value = PrimitiveScene> {
    proptest::prop_oneof![lines::near_crossing_line(), reach::behind_eye_line()]
}

/// What a line rule needs declared: the profile, the line rule, the ends' grid and the tie rule.
struct Declared {
    profile: Profile,
    rule: LineRule,
    bits: u8,
    fill: FillConvention,
}

fn declared(r: &dyn Rasterizer) -> Option<Declared> {
    let profile = r.profile();
    Some(Declared {
        rule: profile.lines?,
        bits: endpoint_bits(&profile)?,
        fill: profile.fill.unwrap_or_default(),
        profile,
    })
}

/// Segment `i`'s ends snapped as refrast snaps them on the declared grid (the first of
/// [`end_variants`]).
fn snapped_ends(case: &PrimitiveScene, i: usize, d: &Declared) -> Option<[Point; 2]> {
    end_variants(case, i, d)?.first().copied()
}

/// Every way the profile may snap end `p` to its line ends' grid, refrast's first.
fn end_candidates(case: &PrimitiveScene, p: [f32; 4], d: &Declared) -> Option<Vec<Point>> {
    let on_ends = Profile {
        snapping: refrast::Snapping::Grid(d.bits),
        ..d.profile.clone()
    };
    snap_candidates(p, case.scene.width, case.scene.height, &on_ends)
}

/// Every way the profile may snap segment `i`'s ends (one, unless it may round either way),
/// refrast's first, when both project and stay within the guard band (beyond it, clipping in
/// x and y may move them).
fn end_variants(case: &PrimitiveScene, i: usize, d: &Declared) -> Option<Vec<[Point; 2]>> {
    let ends = case.segment(i)?;
    let (w, h) = (case.scene.width, case.scene.height);
    let reach = f64::from(d.profile.features.guard_band);
    let inside = |p: [f32; 4]| {
        let [x, y] = project(w, h, p.map(f64::from));
        (-reach..=f64::from(w) + reach).contains(&x) && (-reach..=f64::from(h) + reach).contains(&y)
    };
    if !ends.iter().all(|&p| p[3] > 0.0 && inside(p)) {
        return None;
    }
    let (a, b) = (
        end_candidates(case, ends[0], d)?,
        end_candidates(case, ends[1], d)?,
    );
    Some(a.iter().flat_map(|&a| b.iter().map(move |&b| [a, b])).collect())
}

/// How far sample `s` (pixels) lies from the outline of segment `a → b`'s shape under `rule`,
/// in pixels (roughly; exact at the long sides): where snapping may move it over.
#[must_use]
pub fn outline_margin(rule: LineRule, a: [f64; 2], b: [f64; 2], s: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (rx, ry) = (s[0] - a[0], s[1] - a[1]);
    let cross = dx * ry - dy * rx;
    let length = dx.hypot(dy);
    if length == 0.0 {
        return f64::INFINITY;
    }
    let (across, along, span) = match rule {
        LineRule::Parallelogram if dx.abs() >= dy.abs() => {
            (cross.abs() / dx.abs(), rx * dx.signum(), dx.abs())
        }
        LineRule::Parallelogram => (cross.abs() / dy.abs(), ry * dy.signum(), dy.abs()),
        _ => (cross.abs() / length, (rx * dx + ry * dy) / length, length),
    };
    (across - 0.5).max(-along).max(along - span).abs()
}

/// Expectations for one segment: its oracle samples, with those within `band` px of the
/// shape's outline (rectangles, parallelograms) not judged.
fn segment_expectations(
    case: &PrimitiveScene,
    g: &SampleGrid<'_>,
    d: &Declared,
    ends: [Point; 2],
    band: f64,
) -> Vec<Expect> {
    let covered = g.line(d.rule, ends[0], ends[1], d.fill);
    let mut expected = expect_covered(case, &covered);
    if d.rule != LineRule::DiamondExit {
        let one = f64::from(1u32 << d.bits);
        let [a, b] = ends.map(|p| [p.0 as f64 / one, p.1 as f64 / one]);
        let [sa, sb] = ends.map(|p| g.scale(p));
        let (xs, ys) = g.pixels_near((sa.0.min(sb.0), sa.1.min(sb.1)), (sa.0.max(sb.0), sa.1.max(sb.1)));
        for y in ys {
            for x in xs.clone() {
                for (k, &[u, v]) in g.positions.iter().enumerate() {
                    let s = [
                        f64::from(x) + f64::from(u) / 16.0,
                        f64::from(y) + f64::from(v) / 16.0,
                    ];
                    if outline_margin(d.rule, a, b, s) < band {
                        expected[super::samples::cell(case, x, y, k as u8)] = Expect::ZeroOrOne;
                    }
                }
            }
        }
    }
    expected
}

/// Each segment against the diamond-exit oracle, bit for bit.
pub fn check_diamond_exact(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    check_against_oracle(r, case, 0.0)
}

/// Each segment against the rectangle or parallelogram oracle, the band aside.
pub fn check_area(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let band = r.profile().band_px();
    check_against_oracle(r, case, band)
}

fn check_against_oracle(r: &mut dyn Rasterizer, case: &PrimitiveScene, band: f64) -> Result<(), Violation> {
    let Some(d) = declared(r) else { return Ok(()) };
    let frags = sample_fragments(r, case)?;
    let positions = positions(r, case);
    let g = grid(case, d.bits, &positions);
    for i in 0..case.primitive_count() {
        let Some(variants) = end_variants(case, i, &d) else {
            continue;
        };
        let got = counts(case, &frags, Some(i as u32));
        let judged = |ends: [Point; 2], what: &str| {
            compare_samples(case, &got, &segment_expectations(case, &g, &d, ends, band), what)
        };
        let what = format!("the {} oracle for segment {i}", d.rule.name());
        let first = judged(variants[0], &what);
        // Another way the profile may snap the ends that explains every sample is no failure.
        if first.is_err() && variants[1..].iter().any(|&ends| judged(ends, "").is_ok()) {
            continue;
        }
        first?;
    }
    Ok(())
}

/// Vulkan's allowance: within one pixel of the diamond-exit rule's fragments, their number
/// within one, one per column (row) of an x-major (y-major) segment.
///
/// The rule's fragments are found off the viewport too (on a grid two pixels wider each way, the
/// segment moved by whole pixels, which the rule does not notice): a fragment of the driver's may
/// correspond to one just outside, and the driver's own outside the viewport are not seen, so
/// near the border the count is judged within those. The one fragment more that the count
/// allows has no corresponding fragment, and is not judged by distance.
pub fn check_diamond_allowance(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    const MARGIN: u32 = 2;
    let Some(d) = declared(r) else { return Ok(()) };
    let frags = sample_fragments(r, case)?;
    let (w, h) = (case.scene.width, case.scene.height);
    let wide = SampleGrid {
        width: w + 2 * MARGIN,
        height: h + 2 * MARGIN,
        bits: d.bits,
        positions: &[[8, 8]],
    };
    let shift = i128::from(MARGIN) << d.bits;
    let moved = |p: Point| (p.0 + shift, p.1 + shift);
    let inside = |&(x, y): &(i64, i64)| (0..i64::from(w)).contains(&x) && (0..i64::from(h)).contains(&y);
    let border = |&(x, y): &(i64, i64)| x == 0 || y == 0 || x == i64::from(w) - 1 || y == i64::from(h) - 1;
    let judge = |i: usize, [a, b]: [Point; 2]| -> Result<(), Violation> {
        let want: Vec<(i64, i64)> = wide
            .line(d.rule, moved(a), moved(b), d.fill)
            .into_iter()
            .map(|(x, y, _)| (i64::from(x) - i64::from(MARGIN), i64::from(y) - i64::from(MARGIN)))
            .collect();
        let want_in = want.iter().filter(|p| inside(p)).count();
        let near_in = want.iter().filter(|p| inside(p) && border(p)).count();
        let outside = want.len() - want_in;
        let mut got: Vec<(u32, u32)> = frags
            .iter()
            .filter(|f| f.primitive == i as u32 && f.sample == 0)
            .map(|f| (f.x, f.y))
            .collect();
        got.sort_unstable();
        let x_major = (b.0 - a.0).abs() >= (b.1 - a.1).abs();
        let (fewest, most) = ((want_in - near_in).saturating_sub(1), want_in + outside + 1);
        if !(fewest..=most).contains(&got.len()) {
            let border_note = if near_in + outside > 0 {
                format!(
                    " ({} of them at or beyond the viewport's border)",
                    near_in + outside
                )
            } else {
                String::new()
            };
            return Err(Violation::new(format!(
                "segment {i} draws {} where the diamond-exit rule draws {want_in}{border_note}: more than one apart",
                plural(got.len(), "fragment"),
            )));
        }
        let far: Vec<(u32, u32)> = got
            .iter()
            .copied()
            .filter(|&(x, y)| {
                !want
                    .iter()
                    .any(|&(u, v)| (i64::from(x) - u).abs() <= 1 && (i64::from(y) - v).abs() <= 1)
            })
            .collect();
        let mut found = Findings::new();
        // The count's one extra fragment corresponds to none.
        let extra = usize::from(got.len() > want_in.saturating_sub(near_in));
        if far.len() > extra {
            for &(x, y) in &far {
                found.add((x, y), || {
                    format!("({x}, {y}) is more than a pixel from every diamond-exit fragment")
                });
            }
        }
        for pair in got.windows(2) {
            let same_line = if x_major { pair[0].0 == pair[1].0 } else { false };
            if same_line {
                found.add(pair[1], || {
                    format!("two fragments in column {} of an x-major segment", pair[1].0)
                });
            }
        }
        if !x_major {
            let mut by_row = got.clone();
            by_row.sort_unstable_by_key(|&(x, y)| (y, x));
            for pair in by_row.windows(2).filter(|p| p[0].1 == p[1].1) {
                found.add(pair[1], || {
                    format!("two fragments in row {} of a y-major segment", pair[1].1)
                });
            }
        }
        found.verdict(|n| {
            format!(
                "segment {i} breaks Vulkan's allowance for other line algorithms at {}",
                plural(n, "pixel")
            )
        })
    };
    for i in 0..case.primitive_count() {
        let Some(variants) = end_variants(case, i, &d) else {
            continue;
        };
        // Judged on each way the profile may snap the ends: one that passes is enough.
        let first = judge(i, variants[0]);
        if first.is_err() && variants[1..].iter().any(|&ends| judge(i, ends).is_ok()) {
            continue;
        }
        first?;
    }
    Ok(())
}

/// A strip's fragments are its segments' drawn as a list.
pub fn check_strip_same_as_list(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let strip = sample_fragments(r, case)?;
    let list = sample_fragments(r, &case.as_list())?;
    if keys(&strip) == keys(&list) {
        return Ok(());
    }
    let want = counts(case, &list, None);
    let expected: Vec<Expect> = want
        .iter()
        .map(|&n| match n {
            0 => Expect::Zero,
            1 => Expect::One,
            _ => Expect::OneOrTwo,
        })
        .collect();
    compare_samples(
        case,
        &counts(case, &strip, None),
        &expected,
        "its segments drawn as a line list",
    )?;
    Err(Violation::new(
        "the strip covers the samples its segments cover as a list, but names other segments for them",
    ))
}

/// Consecutive segments of one major axis and direction share no pixel.
pub fn check_shared_end_once(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let frags = sample_fragments(r, case)?;
    let pixels = |i: usize| -> Vec<(u32, u32)> {
        frags
            .iter()
            .filter(|f| f.primitive == i as u32)
            .map(|f| (f.x, f.y))
            .collect()
    };
    // The major axis and direction as the implementation sees them, on its snapped ends; none
    // where a grid step or two of snapping could change either (a near-diagonal or near-zero
    // move), since Vulkan's sentence is about what is drawn.
    let Some(d) = declared(r) else { return Ok(()) };
    let way = |i: usize| {
        let [a, b] = snapped_ends(case, i, &d)?;
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let margin = 2;
        if (dx.abs() - dy.abs()).abs() <= margin {
            return None;
        }
        let (axis, along) = if dx.abs() > dy.abs() { (0, dx) } else { (1, dy) };
        (along.abs() > margin).then_some((axis, along > 0))
    };
    for i in 1..case.primitive_count() {
        if way(i - 1).is_none() || way(i - 1) != way(i) {
            continue;
        }
        let (before, after) = (pixels(i - 1), pixels(i));
        if let Some(&p) = after.iter().find(|p| before.contains(p)) {
            return Err(Violation::at(
                p,
                format!(
                    "segments {} and {i} share an end, run the same way, and both draw ({}, {})",
                    i - 1,
                    p.0,
                    p.1
                ),
            ));
        }
    }
    Ok(())
}

/// The case with every segment drawn from its other end, and which segment each one is.
fn reversed(case: &PrimitiveScene) -> (PrimitiveScene, Vec<usize>) {
    let n = case.primitive_count();
    let mut flipped = case.clone();
    match case.topology {
        Topology::LineStrip => {
            flipped.indices.reverse();
            (flipped, (0..n).rev().collect())
        }
        _ => {
            flipped.indices.chunks_exact_mut(2).for_each(|p| p.swap(0, 1));
            (flipped, (0..n).collect())
        }
    }
}

/// Reversing a segment changes only the pixels whose diamonds hold an end (diamond-exit), or
/// nothing outside the band (the area rules).
pub fn check_reversal(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<(), Violation> {
    let Some(d) = declared(r) else { return Ok(()) };
    let forward = sample_fragments(r, case)?;
    let (back_case, map) = reversed(case);
    let backward = sample_fragments(r, &back_case)?;
    let positions = positions(r, case);
    let band = d.profile.band_px();
    let one = f64::from(1u32 << d.bits);
    let mut found = Findings::new();
    for (i, &j) in map.iter().enumerate() {
        let Some(ends) = snapped_ends(case, i, &d) else {
            continue;
        };
        let [a, b] = ends.map(|p| [p.0 as f64 / one, p.1 as f64 / one]);
        let set = |frags: &[Fragment], p: usize| -> Vec<(u32, u32, u8)> {
            let mut v: Vec<_> = frags
                .iter()
                .filter(|f| f.primitive == p as u32)
                .map(|f| (f.x, f.y, f.sample))
                .collect();
            v.sort_unstable();
            v
        };
        let (there, back) = (set(&forward, i), set(&backward, j));
        for &(x, y, k) in there
            .iter()
            .filter(|c| !back.contains(c))
            .chain(back.iter().filter(|c| !there.contains(c)))
        {
            let c = [f64::from(x) + 0.5, f64::from(y) + 0.5];
            let allowed = match d.rule {
                LineRule::DiamondExit => [a, b]
                    .iter()
                    .any(|e| (e[0] - c[0]).abs() + (e[1] - c[1]).abs() <= 0.5 + band),
                rule => {
                    let [u, v] = positions.get(usize::from(k)).copied().unwrap_or([8, 8]);
                    let s = [
                        f64::from(x) + f64::from(u) / 16.0,
                        f64::from(y) + f64::from(v) / 16.0,
                    ];
                    outline_margin(rule, a, b, s) < band
                }
            };
            if !allowed {
                found.add((x, y), || format!("segment {i}: ({x}, {y}) sample {k} is drawn one way and not the other, away from its ends"));
            }
        }
    }
    found.verdict(|n| {
        format!(
            "reversing segments changes {} away from their ends",
            plural(n, "sample")
        )
    })
}
