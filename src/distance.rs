//! User clip and cull distances: values a vertex carries besides its position (Vulkan's
//! `ClipDistance` and `CullDistance`, OpenGL's `gl_ClipDistance` and `gl_CullDistance`, D3D's
//! `SV_ClipDistance` and `SV_CullDistance`, WGSL's `clip_distances`), which cut primitives
//! where they are negative and cull those wholly negative in one of them.

use glam::DVec3;

/// The most clip and cull distances a vertex may carry together: Vulkan's minimum
/// `maxCombinedClipAndCullDistances`, D3D11's two four-component registers, WGSL's array.
pub const MAX_DISTANCES: usize = 8;

/// The clip and cull distances of a draw's vertices: `clip + cull` values per vertex, its clip
/// distances first, vertex after vertex (vertex `v`'s at `v·(clip + cull)`).
///
/// A primitive is drawn where every clip distance, interpolated perspective-correctly (linearly
/// in clip space), is `≥ 0`; it is discarded whole when every one of its vertices has a negative
/// value of one cull distance. None by default, which draws as before distances existed.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Distances {
    /// Clip distances per vertex.
    pub clip: usize,
    /// Cull distances per vertex.
    pub cull: usize,
    /// `clip + cull` values per vertex, in vertex order.
    pub values: Vec<f32>,
}

impl Distances {
    /// `clip` clip distances and `cull` cull distances per vertex, given vertex by vertex as
    /// `[clip..., cull...]`.
    #[must_use]
    pub fn new(clip: usize, cull: usize, per_vertex: &[Vec<f32>]) -> Self {
        Self {
            clip,
            cull,
            values: per_vertex.iter().flatten().copied().collect(),
        }
    }

    /// Whether there are none: no primitive is cut or culled by them.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.clip + self.cull == 0
    }

    /// Values per vertex.
    #[must_use]
    pub fn per_vertex(&self) -> usize {
        self.clip + self.cull
    }

    /// Vertex `v`'s clip distances; empty past the last vertex.
    #[must_use]
    pub fn clip_of(&self, v: u32) -> &[f32] {
        self.of(v).get(..self.clip).unwrap_or_default()
    }

    /// Vertex `v`'s cull distances; empty past the last vertex.
    #[must_use]
    pub fn cull_of(&self, v: u32) -> &[f32] {
        self.of(v).get(self.clip..).unwrap_or_default()
    }

    fn of(&self, v: u32) -> &[f32] {
        let n = self.per_vertex();
        let start = v as usize * n;
        self.values.get(start..start + n).unwrap_or_default()
    }

    /// The same with clip distance `k` negated at every vertex: the complement of its cut, so
    /// that the two draws together cover what the draw without it covers.
    #[must_use]
    pub fn with_clip_negated(&self, k: usize) -> Self {
        let mut negated = self.clone();
        let n = self.per_vertex();
        if k < self.clip {
            negated
                .values
                .iter_mut()
                .skip(k)
                .step_by(n)
                .for_each(|d| *d = -*d);
        }
        negated
    }

    /// Only the first `clip` clip distances and `cull` cull distances of each vertex: what a
    /// rasterizer declaring that many receives.
    #[must_use]
    pub fn truncated(&self, clip: usize, cull: usize) -> Self {
        let (clip, cull) = (clip.min(self.clip), cull.min(self.cull));
        let n = self.per_vertex();
        if n == 0 || (clip, cull) == (self.clip, self.cull) {
            return self.clone();
        }
        let values = self
            .values
            .chunks(n)
            .flat_map(|v| v[..clip].iter().chain(&v[self.clip..self.clip + cull]))
            .copied()
            .collect();
        Self { clip, cull, values }
    }

    /// Why a draw of `vertices` vertices cannot carry these, if it cannot: more than
    /// [`MAX_DISTANCES`], or not `clip + cull` values for each vertex.
    pub fn validate(&self, vertices: usize) -> Result<(), String> {
        if self.per_vertex() > MAX_DISTANCES {
            return Err(format!(
                "{} clip and {} cull distances per vertex: at most {MAX_DISTANCES} together",
                self.clip, self.cull
            ));
        }
        if self.values.len() != self.per_vertex() * vertices {
            return Err(format!(
                "{} distance values for {vertices} vertices of {} each: give clip + cull values per vertex",
                self.values.len(),
                self.per_vertex()
            ));
        }
        Ok(())
    }
}

/// Why a primitive's distances leave nothing of it to clip.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unkept {
    /// A NaN or infinite distance (D3D11.3 §15.4.1 discards for a NaN clip distance).
    NonFinite,
    /// Every vertex negative in one cull distance.
    Culled,
}

/// The bit of a primitive's outcode for its first clip distance: the clip volume's planes take
/// the bits below ([`outcode`](crate::stage::outcode)).
pub(crate) const FIRST_USER_BIT: u32 = 8;

/// One primitive's clip distances at its corners (`x`, `y`, `z` for corners 0, 1, 2; 0 past a
/// line's or point's last), so that a clip vertex's distance is its barycentrics' dot product
/// with them: linear in clip space, as the specifications interpolate them.
#[derive(Clone, Copy, Debug, Default)]
pub struct CornerDistances {
    planes: [DVec3; MAX_DISTANCES],
    len: usize,
}

impl CornerDistances {
    /// The distances of the primitive of vertices `corners` (one to three), or why it is not
    /// drawn. Indices must be in range.
    pub fn of(distances: &Distances, corners: &[u32]) -> Result<Self, Unkept> {
        let mut this = Self::default();
        if distances.is_empty() {
            return Ok(this);
        }
        let finite = |v: &[f32]| v.iter().all(|d| d.is_finite());
        if !corners
            .iter()
            .all(|&c| finite(distances.clip_of(c)) && finite(distances.cull_of(c)))
        {
            return Err(Unkept::NonFinite);
        }
        if (0..distances.cull).any(|j| corners.iter().all(|&c| distances.cull_of(c)[j] < 0.0)) {
            return Err(Unkept::Culled);
        }
        this.len = distances.clip.min(MAX_DISTANCES);
        for (k, &c) in corners.iter().enumerate().take(3) {
            for (plane, &d) in this.planes.iter_mut().zip(distances.clip_of(c)) {
                plane[k] = f64::from(d);
            }
        }
        Ok(this)
    }

    /// Each clip distance at the corners.
    #[must_use]
    pub fn planes(&self) -> &[DVec3] {
        &self.planes[..self.len]
    }

    /// The outcode bits of corner `k`: bit `8 + j` where its clip distance `j` is negative (the
    /// clip volume's planes take the bits below).
    #[must_use]
    pub fn outcode(&self, k: usize) -> u32 {
        user_outcode(self.planes(), k)
    }

    /// Whether the point at `barycentric` over the corners is inside every clip distance.
    #[must_use]
    pub fn keeps(&self, barycentric: DVec3) -> bool {
        self.planes().iter().all(|d| barycentric.dot(*d) >= 0.0)
    }
}

/// The outcode bits of corner `k` under user clip distances `user` (each at the three
/// corners): bit [`FIRST_USER_BIT`]` + j` where distance `j` is negative.
#[must_use]
pub(crate) fn user_outcode(user: &[DVec3], k: usize) -> u32 {
    user.iter()
        .enumerate()
        .filter(|(_, d)| d[k] < 0.0)
        .fold(0, |code, (j, _)| code | 1 << (FIRST_USER_BIT as usize + j))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_and_one() -> Distances {
        Distances::new(2, 1, &[vec![1.0, -2.0, 3.0], vec![-4.0, 5.0, -6.0]])
    }

    #[test]
    fn values_are_read_per_vertex_clip_first() {
        let d = two_and_one();
        assert_eq!(d.validate(2), Ok(()));
        assert!(d.validate(3).is_err());
        assert_eq!(d.clip_of(1), [-4.0, 5.0]);
        assert_eq!(d.cull_of(0), [3.0]);
        assert!(d.clip_of(2).is_empty());
        assert_eq!(d.with_clip_negated(1).clip_of(1), [-4.0, -5.0]);
        assert_eq!(d.with_clip_negated(1).cull_of(1), [-6.0]);
        let fewer = d.truncated(1, 1);
        assert_eq!((fewer.clip_of(1), fewer.cull_of(1)), (&[-4.0][..], &[-6.0][..]));
        assert_eq!(d.truncated(0, 0).values, Vec::<f32>::new());
        let many = Distances::new(5, 4, &[vec![0.0; 9]]);
        assert!(many.validate(1).is_err_and(|e| e.contains("at most 8")));
    }

    #[test]
    fn a_primitive_wholly_negative_in_one_cull_distance_is_culled() {
        let d = Distances::new(0, 2, &[vec![-1.0, 1.0], vec![-1.0, -1.0], vec![1.0, -1.0]]);
        assert!(
            CornerDistances::of(&d, &[0, 1, 2]).is_ok(),
            "no distance negative at every corner"
        );
        assert_eq!(CornerDistances::of(&d, &[0, 1]).err(), Some(Unkept::Culled));
        assert!(CornerDistances::of(&d, &[2]).is_err());
        let nan = Distances::new(1, 0, &[vec![f32::NAN]]);
        assert_eq!(CornerDistances::of(&nan, &[0]).err(), Some(Unkept::NonFinite));
    }

    #[test]
    fn corners_give_outcodes_and_interpolated_distances() {
        let d = Distances::new(2, 0, &[vec![1.0, -1.0], vec![-1.0, 0.0], vec![0.0, 2.0]]);
        let c = CornerDistances::of(&d, &[0, 1, 2]).expect("finite, no cull");
        assert_eq!(c.outcode(0), 1 << (FIRST_USER_BIT + 1));
        assert_eq!(c.outcode(1), 1 << FIRST_USER_BIT);
        assert_eq!(c.outcode(2), 0);
        assert!(c.keeps(DVec3::Z) && !c.keeps(DVec3::X));
        assert!(c.keeps(DVec3::new(0.25, 0.25, 0.5)), "0 on the cut is inside");
    }
}
