//! The tie rule: which edges own a sample lying exactly on them.
//!
//! The sample (8.5, 8.5) of a 64×64 target lies on one edge of each of 64 single triangles (16
//! edge directions, half of them with slopes inexact in binary, the triangle on either side,
//! each edge in both vertex orders) and at the vertex of each of 6 fan triangles; 192 more
//! triangles have random samples on edges of random slopes and lengths (a float rasterizer's
//! rounding shows there). Every vertex is on the 1/8-px grid, so snapping moves nothing on any
//! grid Vulkan allows. The reference with each of the four conventions says which of these
//! triangles would cover it; the driver's pattern matches one convention exactly, or none.
//! The same triangles make 128 pairs sharing an edge and a fan sharing a vertex: Vulkan and
//! OpenGL require a sample on a shared edge covered exactly once. A shared edge covered twice is
//! a bug, which is counted and reported, never read as a declaration.

use refrast::{ClipMode, DrawError, FillConvention, Rasterizer, Reference, ReferenceConfig};

use refrast::Fragment;

use super::{Raster, batch, clip};

/// What the tie probe saw.
#[derive(Clone, Debug, PartialEq)]
pub struct TieRule {
    /// The convention whose pattern the driver matched on every single triangle, if one did.
    pub chosen: Option<FillConvention>,
    /// Single triangles with the sample on an edge or a vertex.
    pub samples: usize,
    /// Per convention, on how many of them the driver did what it says.
    pub matches: Vec<(FillConvention, usize)>,
    /// Groups sharing the sample (pairs sharing an edge, one fan sharing a vertex).
    pub groups: usize,
    /// Groups in which exactly one triangle covered it.
    pub once: usize,
    /// Groups in which more than one did (a bug).
    pub twice: usize,
}

impl TieRule {
    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        let shared = if self.twice > 0 {
            format!(
                "; shared edges and vertices: {}/{} covered exactly once, {} covered twice (a bug: \
                 Vulkan and OpenGL require exactly one)",
                self.once, self.groups, self.twice
            )
        } else {
            format!(
                "; {}/{} shared edges and vertices covered exactly once",
                self.once, self.groups
            )
        };
        let best = self.matches.iter().max_by_key(|(_, n)| *n);
        match (self.chosen, best) {
            (Some(c), _) => format!(
                "{} ({}/{} tie samples on single edges and vertices{shared})",
                name(Some(c)),
                self.samples,
                self.samples
            ),
            (None, Some((c, n))) => format!(
                "no tie rule (no convention fits every tie sample on single edges and vertices: \
                 {} fits {n}/{}{shared})",
                name(Some(*c)),
                self.samples
            ),
            (None, None) => "no tie rule".to_owned(),
        }
    }
}

/// A convention as reports name it.
#[must_use]
pub fn name(fill: Option<FillConvention>) -> &'static str {
    match fill {
        Some(FillConvention::TopLeft) => "top-left",
        Some(FillConvention::TopRight) => "top-right",
        Some(FillConvention::BottomLeft) => "bottom-left",
        Some(FillConvention::BottomRight) => "bottom-right",
        None => "no tie rule",
    }
}

/// The target: room for edges up to 15 px either side of a sample.
const SIDE: u32 = 64;

/// Triangles sharing a sample (a pair sharing an edge through it, or a fan around it), with
/// the sample's pixel.
type Group = ((u32, u32), Vec<[[f64; 2]; 3]>);

/// The groups: at (8.5, 8.5), 16 directions and the fan; then 96 edges of random slopes and
/// lengths, on the 1/8-px grid, through random samples.
fn groups() -> Vec<Group> {
    let s = [8.5, 8.5];
    let mut groups: Vec<Group> = Vec::new();
    let mut pair = |s: [f64; 2], d: [f64; 2], along: [f64; 2], across: f64| {
        let a = [s[0] - along[0] * d[0], s[1] - along[0] * d[1]];
        let b = [s[0] + along[1] * d[0], s[1] + along[1] * d[1]];
        let c1 = [s[0] - across * d[1], s[1] + across * d[0]];
        let c2 = [s[0] + across * d[1], s[1] - across * d[0]];
        groups.push(((s[0] as u32, s[1] as u32), vec![[a, b, c1], [b, a, c2]]));
    };
    // Edge directions whose slopes are exact in binary (0, ±½, ±1, ±2, ∞), two steps either side
    // of the sample, then ones whose slopes are not (±⅓, ±3, ±⅗, ±5/3), one step.
    let short = [(1, 0), (0, 1), (1, 1), (1, -1), (2, 1), (1, 2), (2, -1), (1, -2)];
    let long = [(3, 1), (1, 3), (3, -1), (1, -3), (3, 5), (5, 3), (3, -5), (5, -3)];
    let directions = short
        .map(|d| (d, 2.0, 3.0))
        .into_iter()
        .chain(long.map(|d| (d, 1.0, 1.0)));
    for ((dx, dy), along, across) in directions {
        for sign in [1.0, -1.0] {
            pair(
                s,
                [sign * f64::from(dx), sign * f64::from(dy)],
                [along; 2],
                across,
            );
        }
    }
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move |n: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n) as f64
    };
    for _ in 0..96 {
        let s = [16.5 + next(32), 16.5 + next(32)];
        let d = [(1.0 + next(15)) / 8.0, (next(31) - 15.0) / 8.0];
        pair(s, d, [2.0 + next(7), 2.0 + next(7)], 2.0 + next(5));
    }
    let ring = [
        [3.0, 0.0],
        [1.0, 3.0],
        [-2.0, 2.0],
        [-3.0, -1.0],
        [-1.0, -3.0],
        [2.0, -2.0],
    ];
    let at = |o: [f64; 2]| [s[0] + o[0], s[1] + o[1]];
    groups.push((
        (8, 8),
        (0..6).map(|i| [s, at(ring[i]), at(ring[(i + 1) % 6])]).collect(),
    ));
    groups
}

/// Per triangle of `groups`, how many fragments it has at its group's sample.
fn owners(frags: &[Fragment], groups: &[Group]) -> Vec<usize> {
    let mut count = std::collections::HashMap::new();
    for f in frags {
        *count.entry((f.primitive, f.x, f.y)).or_insert(0) += 1;
    }
    let mut primitive = 0u32;
    let mut out = Vec::new();
    for (pixel, tris) in groups {
        for _ in tris {
            out.push(count.get(&(primitive, pixel.0, pixel.1)).copied().unwrap_or(0));
            primitive += 1;
        }
    }
    out
}

/// Draws every triangle once and compares with each convention.
pub fn probe(draw: &mut Raster<'_>) -> Result<TieRule, DrawError> {
    let groups = groups();
    let positions = groups
        .iter()
        .flat_map(|(_, tris)| tris.iter().flatten())
        .map(|&p| clip(SIDE, SIDE, p, 0.5, 1.0))
        .collect();
    let d = batch(SIDE, SIDE, positions);
    let got = owners(&draw(&d)?, &groups);
    let n = got.len();
    let matches = FillConvention::ALL
        .into_iter()
        .map(|fill| {
            let mut reference = Reference::new(ReferenceConfig {
                fill,
                clip: ClipMode::GuardBand,
                ..ReferenceConfig::default()
            });
            let want = owners(&reference.rasterize(&d)?, &groups);
            let fits = got
                .iter()
                .zip(&want)
                .filter(|(g, w)| (**g > 0) == (**w > 0))
                .count();
            Ok((fill, fits))
        })
        .collect::<Result<Vec<_>, DrawError>>()?;
    let chosen = matches.iter().find(|(_, fits)| *fits == n).map(|(c, _)| *c);
    let (mut once, mut twice, mut first) = (0, 0, 0);
    for (_, g) in &groups {
        let owners: usize = got[first..first + g.len()].iter().map(|&c| c.min(1)).sum();
        once += usize::from(owners == 1);
        twice += usize::from(owners > 1);
        first += g.len();
    }
    Ok(TieRule {
        chosen,
        samples: n,
        matches,
        groups: groups.len(),
        once,
        twice,
    })
}
