//! Helpers of the line, point and multisampling rules: drawing a [`PrimitiveScene`], counting
//! its fragments per sample, and picturing samples.
//!
//! A picture of `n` samples per pixel lays each pixel's samples out as a small grid (2 × 1,
//! 2 × 2, 4 × 2, 4 × 4), sample `k` at column `k mod cols`, row `k div cols`, so one cell of the
//! picture is one sample.

use refrast::{Draw, Fragment, Profile, Rasterizer, Resolved, Snapping};

use crate::oracle::segment::SampleGrid;

use crate::scene::PrimitiveScene;
use crate::violation::{Class, Counts, Expect, Findings, Picture, Violation, compare_coverage};

/// The columns and rows a pixel's samples take in a picture.
#[must_use]
pub fn layout(samples: u8) -> (u32, u32) {
    match samples {
        0 | 1 => (1, 1),
        2 => (2, 1),
        4 => (2, 2),
        8 => (4, 2),
        _ => (4, 4),
    }
}

/// The index of sample `k` of pixel `(x, y)` in a picture of `case`'s samples.
#[must_use]
pub fn cell(case: &PrimitiveScene, x: u32, y: u32, k: u8) -> usize {
    let (cols, rows) = layout(case.samples);
    let k = u32::from(k);
    let (cx, cy) = (x * cols + k % cols, y * rows + k / cols);
    cy as usize * (case.scene.width * cols) as usize + cx as usize
}

/// How many cells a picture of `case`'s samples has.
#[must_use]
pub fn cells(case: &PrimitiveScene) -> usize {
    let (cols, rows) = layout(case.samples);
    (case.scene.width * cols * case.scene.height * rows) as usize
}

/// The grid bits a profile snaps line and point ends to, if it snaps them to a grid.
#[must_use]
pub fn endpoint_bits(profile: &Profile) -> Option<u8> {
    snapping_bits(profile.endpoint_snapping.unwrap_or(profile.snapping))
}

/// The grid points are snapped to, in bits: [`Profile::point_snapping`], else the line ends'
/// grid ([`endpoint_bits`]).
#[must_use]
pub fn point_bits(profile: &Profile) -> Option<u8> {
    match profile.point_snapping {
        Some(snapping) => snapping_bits(snapping),
        None => endpoint_bits(profile),
    }
}

/// A grid's bits, at most the 16 the oracles hold.
fn snapping_bits(snapping: Snapping) -> Option<u8> {
    snapping.grid_bits().map(|b| b.min(16))
}

/// The rasterizer's fragments for `case`; an error, a fragment outside the viewport, a sample
/// index past the draw's count or a primitive the draw does not have becomes a violation.
pub fn sample_fragments(r: &mut dyn Rasterizer, case: &PrimitiveScene) -> Result<Vec<Fragment>, Violation> {
    checked_fragments(r, case, true)
}

/// [`sample_fragments`] but any primitive a fragment names: for a rule that does not judge
/// which primitive of the draw made a fragment.
pub fn unattributed_fragments(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
) -> Result<Vec<Fragment>, Violation> {
    checked_fragments(r, case, false)
}

/// The rasterizer's fragments for `case`, checked as [`sample_fragments`] says, the primitive
/// each names only where `named`.
fn checked_fragments(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    named: bool,
) -> Result<Vec<Fragment>, Violation> {
    let draw = case.draw();
    let frags = r
        .rasterize(&draw)
        .map_err(|e| Violation::of_draw_error(&format!("rasterize ({})", draw.describe()), &e))?;
    let (w, h, n) = (case.scene.width, case.scene.height, case.primitive_count());
    for f in &frags {
        let (g, sample) = (f, f.sample);
        let wrong = if g.x >= w || g.y >= h {
            Some(format!("outside the {w}×{h} viewport"))
        } else if sample >= case.samples {
            Some(format!(
                "with sample index {sample} of a draw at {} samples",
                case.samples
            ))
        } else if named && g.primitive as usize >= n {
            Some(format!("naming primitive {} of a draw of {n}", g.primitive))
        } else {
            None
        };
        if let Some(wrong) = wrong {
            let at = (g.x.min(w.saturating_sub(1)), g.y.min(h.saturating_sub(1)));
            return Err(Violation::at(
                at,
                format!("a fragment at ({}, {}) {wrong}", g.x, g.y),
            ));
        }
    }
    Ok(frags)
}

/// Fragments per picture cell (sample), of primitive `primitive` or of all when `None`.
#[must_use]
pub fn counts(case: &PrimitiveScene, frags: &[Fragment], primitive: Option<u32>) -> Vec<u32> {
    let mut counts = vec![0; cells(case)];
    for f in frags {
        if primitive.is_none_or(|p| p == f.primitive) {
            counts[cell(case, f.x, f.y, f.sample)] += 1;
        }
    }
    counts
}

/// Expectations per picture cell: `One` for each of `covered` (`(x, y, sample)`), else `Zero`.
#[must_use]
pub fn expect_covered(case: &PrimitiveScene, covered: &[(u32, u32, u8)]) -> Vec<Expect> {
    let mut expected = vec![Expect::Zero; cells(case)];
    for &(x, y, k) in covered {
        expected[cell(case, x, y, k)] = Expect::One;
    }
    expected
}

/// Compares per-sample counts with expectations, the picture one cell per sample with the
/// case's outlines drawn over it.
pub fn compare_samples(
    case: &PrimitiveScene,
    counts: &[u32],
    expected: &[Expect],
    what: &str,
) -> Result<(), Violation> {
    let (cols, rows) = layout(case.samples);
    let outlines = crate::picture::primitive_outlines(case)
        .into_iter()
        .map(|o| {
            o.into_iter()
                .map(|[x, y]| [x * f64::from(cols), y * f64::from(rows)])
                .collect()
        })
        .collect();
    let samples = if case.samples > 1 {
        format!(" ({} samples per pixel, one cell each)", case.samples)
    } else {
        String::new()
    };
    compare_coverage(
        counts,
        expected,
        case.scene.width * cols,
        case.scene.height * rows,
        outlines,
        &format!("{what}{samples}"),
    )
}

/// Whether every vertex of `case` projects within the declared guard band: x and y clipping
/// then moves no edge or end, so the oracles, which know nothing of clipping, apply.
#[must_use]
pub fn within_guard_band(case: &PrimitiveScene, profile: &Profile) -> bool {
    let (w, h) = (case.scene.width, case.scene.height);
    let reach = f64::from(profile.features.guard_band);
    case.scene.positions.iter().all(|p| {
        let [x, y] = crate::oracle::raster::project(w, h, p.map(f64::from));
        p[3] > 0.0
            && (-reach..=f64::from(w) + reach).contains(&x)
            && (-reach..=f64::from(h) + reach).contains(&y)
    })
}

/// The declared positions of the case's sample count, or the pixel centre.
#[must_use]
pub fn positions(r: &dyn Rasterizer, case: &PrimitiveScene) -> Vec<[u8; 2]> {
    r.profile()
        .pattern(case.samples)
        .map_or(vec![[8, 8]], |p| p.positions().to_vec())
}

/// The oracle's sample grid over the case's viewport at `bits`, samples at `positions`.
#[must_use]
pub fn grid<'a>(case: &PrimitiveScene, bits: u8, positions: &'a [[u8; 2]]) -> SampleGrid<'a> {
    SampleGrid {
        width: case.scene.width,
        height: case.scene.height,
        bits,
        positions,
    }
}

/// `(y, x, sample, primitive)` of every fragment, sorted: a draw's coverage as a multiset.
pub fn keys<'a>(frags: impl IntoIterator<Item = &'a Fragment>) -> Vec<(u32, u32, u8, u32)> {
    let mut k: Vec<_> = frags
        .into_iter()
        .map(|f| (f.y, f.x, f.sample, f.primitive))
        .collect();
    k.sort_unstable();
    k
}

/// Fragments per picture cell (a sample of a pixel).
pub fn cell_counts<'a>(case: &PrimitiveScene, frags: impl IntoIterator<Item = &'a Fragment>) -> Vec<u32> {
    let mut counts = vec![0; cells(case)];
    for f in frags {
        counts[cell(case, f.x, f.y, f.sample)] += 1;
    }
    counts
}

/// The tally of `got` against `want`, cell by cell.
#[must_use]
pub fn difference_counts(got: &[u32], want: &[u32]) -> Counts {
    let mut counts = Counts::default();
    for (&g, &w) in got.iter().zip(want) {
        counts.missing += usize::from(g < w);
        counts.unexpected += usize::from(g > w);
        counts.double += usize::from(g == w && g > 1);
    }
    counts
}

/// The samples of a draw compared with the same implementation's draw of something that must
/// cover alike, one cell each: as expected grey (blue where covered more than once), missing
/// purple, unexpected red; the primitives' outlines and `extra` outlines (in pixels) over them.
#[must_use]
pub fn difference_picture(
    case: &PrimitiveScene,
    got: &[u32],
    want: &[u32],
    extra: Vec<Vec<[f64; 2]>>,
) -> Picture {
    let (cols, rows) = layout(case.samples);
    let classes = got
        .iter()
        .zip(want)
        .map(|(&g, &w)| match (g, w) {
            (g, w) if g < w => Class::Missing,
            (g, w) if g > w => Class::Unexpected,
            (0, _) => Class::Empty,
            (1, _) => Class::Covered,
            _ => Class::Double,
        })
        .collect();
    let outlines = crate::picture::primitive_outlines(case)
        .into_iter()
        .chain(extra)
        .map(|o| {
            o.into_iter()
                .map(|[x, y]| [x * f64::from(cols), y * f64::from(rows)])
                .collect()
        })
        .collect();
    Picture {
        width: case.scene.width * cols,
        height: case.scene.height * rows,
        classes,
        outlines,
    }
}

/// The resolved buffers of `draw`, or the violation of a failed call.
pub fn resolved(r: &mut dyn Rasterizer, draw: &Draw) -> Result<Resolved, Violation> {
    let out = r
        .resolve(draw)
        .map_err(|e| Violation::of_draw_error(&format!("resolve ({})", draw.describe()), &e))?;
    let expected =
        draw.viewport.width() as usize * draw.viewport.height() as usize * usize::from(draw.samples);
    if out.depth.len() != expected || out.primitive.len() != expected {
        return Err(Violation::new(format!(
            "resolve ({}) returned {} depths and {} primitives for {expected} samples",
            draw.describe(),
            out.depth.len(),
            out.primitive.len()
        )));
    }
    Ok(out)
}

/// How [`resolved_split`] names a sample the test keeps and one it drops, and the draw that
/// keeps everything: `["inside the rectangle", "outside the rectangle", "the draw without a
/// scissor"]`.
pub type SplitWords<'a> = [&'a str; 3];

/// The depth and primitive buffers `case` resolves to, compared sample by sample with those of
/// `whole` (the same draw without a per-sample test) where `kept` holds and with those of a draw
/// of nothing elsewhere: a finding per sample that differs, bit for bit.
pub fn resolved_split(
    r: &mut dyn Rasterizer,
    case: &PrimitiveScene,
    whole: &PrimitiveScene,
    kept: impl Fn(u32, u32, u8) -> bool,
    [inside, outside, without]: SplitWords<'_>,
) -> Result<Findings, Violation> {
    let draw = case.draw();
    let cut = resolved(r, &draw)?;
    let whole = resolved(r, &whole.draw())?;
    let nothing = resolved(
        r,
        &Draw {
            indices: Vec::new(),
            ..draw.clone()
        },
    )?;
    let mut findings = Findings::new();
    for y in 0..case.scene.height {
        for x in 0..case.scene.width {
            for s in 0..case.samples {
                let keeps = kept(x, y, s);
                let want = if keeps { &whole } else { &nothing };
                let i = cut.index(x, y, s);
                let same = cut.depth[i].to_bits() == want.depth[i].to_bits()
                    && cut.primitive[i] == want.primitive[i];
                if !same {
                    findings.add((x, y), || {
                        format!(
                            "({x}, {y}) sample {s}, {}: depth {:?} and primitive {:?}, where {} leaves depth {:?} and primitive {:?}",
                            if keeps { inside } else { outside },
                            cut.depth[i],
                            cut.primitive[i],
                            if keeps { without } else { "a draw of nothing" },
                            want.depth[i],
                            want.primitive[i]
                        )
                    });
                }
            }
        }
    }
    Ok(findings)
}
