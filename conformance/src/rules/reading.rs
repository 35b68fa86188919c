//! The rasterizer as a hint reads it: declaring what the hint suggests, or with the difference
//! the hint names undone, so that the failing case can be run again to verify the hint.

use refrast::{
    DepthRange, Draw, DrawError, FillConvention, Fragment, Profile, Rasterizer, Resolved, Topology,
};

use super::ties::{self, Ties};
use crate::oracle::facing::{Turn, turn};

/// How the rasterizer reads under a hint: what it would declare (the case is fitted to that),
/// or what difference it makes, undone.
#[derive(Clone, Debug)]
pub(super) enum Reading {
    /// It declares this profile instead.
    Declares(Profile),
    /// It drops triangles that turn this way: each is sent to it reversed, its weights put back.
    Drops(Turn),
    /// Its fragments' facing is inverted.
    InvertedFacing,
    /// Its perspective barycentrics go to vertex `order[k]` for weight `k`.
    Permuted([usize; 3]),
    /// It has no tie rule (samples on edges decided as `Ties` says): each is decided by this
    /// fill convention instead ([`ties::with_tie_rule`]).
    TieRule(Ties, FillConvention),
}

/// The rasterizer as a hint reads it ([`Reading`]).
pub(super) struct Read<'a> {
    /// The rasterizer.
    pub(super) inner: &'a mut dyn Rasterizer,
    /// How the hint reads it.
    pub(super) reading: Reading,
}

impl Read<'_> {
    /// The draw as the rasterizer is sent it under the reading, and which triangles were
    /// reversed.
    fn told(&self, draw: &Draw) -> (Draw, Vec<bool>) {
        let mut told = draw.clone();
        let mut reversed = vec![false; draw.triangles().len()];
        if let Reading::Drops(lost) = self.reading {
            let profile = self.inner.profile();
            let (w, h) = (draw.viewport.width(), draw.viewport.height());
            for (t, tri) in told.triangles_mut().iter_mut().enumerate() {
                let Some(corners) = tri
                    .iter()
                    .map(|&i| draw.positions.get(i as usize).copied())
                    .collect::<Option<Vec<_>>>()
                else {
                    continue;
                };
                let corners = [corners[0], corners[1], corners[2]];
                if turn(&corners, w, h, &draw.state, &profile) == lost {
                    tri.swap(1, 2);
                    reversed[t] = true;
                }
            }
        }
        (told, reversed)
    }

    /// A fragment as the reading undoes its difference.
    fn undo(&self, f: &mut Fragment, reversed: &[bool]) {
        match self.reading {
            Reading::InvertedFacing => f.front_facing = !f.front_facing,
            Reading::Permuted(order) => {
                let b = f.barycentric;
                for k in 0..3 {
                    f.barycentric[order[k]] = b[k];
                }
            }
            Reading::Drops(_) if reversed.get(f.primitive as usize) == Some(&true) => {
                f.barycentric.swap(1, 2);
                if let Some(s) = &mut f.screen_barycentric {
                    s.swap(1, 2);
                }
            }
            _ => {}
        }
    }
}

impl Rasterizer for Read<'_> {
    fn profile(&self) -> Profile {
        match &self.reading {
            Reading::Declares(profile) => profile.clone(),
            _ => self.inner.profile(),
        }
    }

    /// Lines, points, samples, strips and fans are read only for facing and weights: no
    /// triangle is reversed and no tie rule applied (a strip's triangles share their indices).
    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        if draw.topology != Topology::TriangleList || draw.samples != 1 {
            let mut frags = self.inner.rasterize(draw)?;
            frags.iter_mut().for_each(|f| self.undo(f, &[]));
            return Ok(frags);
        }
        let (told, reversed) = self.told(draw);
        let mut frags = self.inner.rasterize(&told)?;
        frags.iter_mut().for_each(|f| self.undo(f, &reversed));
        if let Reading::TieRule(ties, fill) = self.reading {
            frags = ties::with_tie_rule(draw, frags, ties, fill);
        }
        Ok(frags)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        if draw.topology != Topology::TriangleList || draw.samples != 1 {
            return self.inner.resolve(draw);
        }
        let (told, _) = self.told(draw);
        self.inner.resolve(&told)
    }
}

/// The other clip volume.
pub(super) fn other_range(range: DepthRange) -> DepthRange {
    match range {
        DepthRange::ZeroToOne => DepthRange::NegativeOneToOne,
        DepthRange::NegativeOneToOne => DepthRange::ZeroToOne,
    }
}
