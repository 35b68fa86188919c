//! The suite's input: a draw that prints as pasteable Rust and reads and writes as data, and
//! exact ways to build one.

pub mod data;
mod primitive;

use std::fmt;

use refrast::{
    Conservative, CullMode, DepthRange, Distances, Draw, DrawState, FrontFace, Interpolation, PolygonMode,
    Profile, ProvokingVertex, Viewport, ViewportDepth,
};

use crate::oracle::facing::{Turn, turn};
use crate::oracle::raster::to_ndc;
pub use data::{CaseData, Coordinate, DistanceData, DrawData, Poison};
pub use primitive::PrimitiveScene;

/// A rule's input: it shows as a scene and can be made smaller after proptest has shrunk it.
///
/// Proptest shrinks each part of an input in one greedy pass; a failing mesh may keep a vertex
/// it does not need. Dropping whole triangles while the check still fails (as lyon's reducer
/// does) leaves the fewest triangles that show the failure.
pub trait Case: Sized {
    /// Candidate inputs one step smaller; empty when there is none.
    fn reductions(&self) -> Vec<Self>;

    /// The scene drawn, for the counterexample picture.
    fn scene(&self) -> &Scene;

    /// The scene drawn, to fit its state to what the rasterizer supports.
    fn scene_mut(&mut self) -> &mut Scene;

    /// The input as data ([`CaseData`]): the draw in the pipe protocol's words, so that a
    /// counterexample can be replayed in any language.
    fn data(&self) -> CaseData;

    /// The input `data` describes, or what in it does not fit this kind of input.
    fn from_data(data: &CaseData) -> Result<Self, String>;
}

/// One draw call as the rules generate it; `Debug` prints Rust that rebuilds it.
///
/// Paste a counterexample after `use refrast::*; use refrast_conformance::*;`. Not a
/// [`Draw`]: a scene keeps the viewport's sides as generated (they may be out of range, which a
/// [`Viewport`] cannot be), shrinks triangle by triangle, and prints as code; [`Scene::draw`]
/// makes the draw.
#[derive(Clone, PartialEq)]
pub struct Scene {
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
    /// Clip-space positions.
    pub positions: Vec<[f32; 4]>,
    /// Vertex indices, one triple per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Culling, depth and clipping state.
    pub state: DrawState,
    /// Each vertex's clip and cull distances: none but in the rules that judge them.
    pub distances: Distances,
}

impl Scene {
    /// A scene with default state.
    #[must_use]
    pub fn new(width: u32, height: u32, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            width,
            height,
            positions,
            triangles,
            state: DrawState::default(),
            distances: Distances::default(),
        }
    }

    /// Triangles given in raster space, in units of `2^-bits` pixel, at depth `z` with `w = 1`.
    ///
    /// Exact when the viewport sides are powers of two: `X / 2^bits / W · 2 − 1` then has few
    /// enough significant bits for f32, so every implementation snaps to exactly `X`.
    #[must_use]
    pub fn from_subpixels(width: u32, height: u32, bits: u8, triangles: &[[(i64, i64); 3]], z: f32) -> Self {
        let mut positions = Vec::with_capacity(3 * triangles.len());
        for t in triangles {
            positions.extend(t.iter().map(|&(x, y)| clip_of(width, height, bits, x, y, z, 1.0)));
        }
        let indices = (0..triangles.len() as u32)
            .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        Self::new(width, height, positions, indices)
    }

    /// The viewport, or `None` when its size is out of range.
    #[must_use]
    pub fn viewport(&self) -> Option<Viewport> {
        Viewport::new(self.width, self.height).ok()
    }

    /// The scene as a rule draws it for a rasterizer with `profile`: its state fitted to what
    /// the profile supports ([`Profile::fit`]), its triangles turned to face front under a cull
    /// mode the profile cannot switch off ([`Scene::orient_to_face_front`]).
    #[must_use]
    pub fn fitted(mut self, profile: &Profile) -> Self {
        self.state = profile.fit(self.state);
        self.keep_unclipped(profile);
        self.orient_to_face_front(profile);
        self
    }

    /// For a profile that clips nothing in 3D ([`refrast::Features::clips_in_3d`] false), moves
    /// each vertex to where such a rasterizer can draw it, vertex by vertex so that shared
    /// vertices stay shared: one behind the eye to `−v`, which projects to the same point (at
    /// `w = 0`, to `w` as large as its `x` and `y`), its `x/w` and `y/w` then pulled within the
    /// guard band; `z` onto the near plane when before it, and onto the far plane when beyond
    /// it under far clipping. Non-finite vertices stay as they are (the robustness rules send
    /// them on purpose); a profile that clips in 3D is left alone.
    pub fn keep_unclipped(&mut self, profile: &Profile) {
        if profile.features.clips_in_3d {
            return;
        }
        // Half-extents of the reachable region in NDC: the viewport plus the guard band.
        let reach = f64::from(profile.features.guard_band.min(8192));
        let limit = [
            1.0 + 2.0 * reach / f64::from(self.width.max(1)),
            1.0 + 2.0 * reach / f64::from(self.height.max(1)),
        ];
        let state = self.state;
        for p in &mut self.positions {
            if p.iter().any(|c| !c.is_finite()) {
                continue;
            }
            let mut v = p.map(f64::from);
            if v[3] < 0.0 {
                v = v.map(|c| -c);
            }
            if v[3] <= 0.0 {
                v[3] = v[0].abs().max(v[1].abs()).max(1.0);
            }
            if p[3] <= 0.0 {
                for axis in 0..2 {
                    v[axis] = v[axis].clamp(-limit[axis] * v[3], limit[axis] * v[3]);
                }
            }
            let near = match state.depth_range {
                DepthRange::ZeroToOne => 0.0,
                DepthRange::NegativeOneToOne => -v[3],
            };
            if state.clip_near {
                v[2] = v[2].max(near);
            }
            if state.clip_far {
                v[2] = v[2].min(v[3]);
            }
            *p = v.map(|c| c as f32);
        }
    }

    /// How each triangle turns as an implementation with `profile` may see it; `Turn::Unsure`
    /// for a triangle naming a vertex that does not exist.
    #[must_use]
    pub fn turns(&self, profile: &Profile) -> Vec<Turn> {
        (0..self.triangles.len())
            .map(|t| {
                if self.triangles[t]
                    .iter()
                    .any(|&i| i as usize >= self.positions.len())
                {
                    return Turn::Unsure;
                }
                turn(&self.corners(t), self.width, self.height, &self.state, profile)
            })
            .collect()
    }

    /// Reverses the winding of every triangle its state surely culls, so that the rule still
    /// asks its question of a rasterizer that cannot switch culling off: one that culls back
    /// faces draws every triangle as a front face. Zero-area and unsure triangles are left as
    /// they are (the rules accept either outcome for the unsure ones).
    pub fn orient_to_face_front(&mut self, profile: &Profile) {
        // No cull, or both faces culled: no winding makes a triangle drawn.
        if matches!(self.state.cull, CullMode::None | CullMode::FrontAndBack) {
            return;
        }
        for (t, turn) in self.turns(profile).into_iter().enumerate() {
            if turn.drawn(&self.state) == Some(false) && turn != Turn::Degenerate {
                self.triangles[t].swap(1, 2);
            }
        }
    }

    /// The draw the rasterizer under test receives.
    ///
    /// # Panics
    /// When the viewport is out of range; strategies only build valid sizes.
    #[must_use]
    pub fn draw(&self) -> Draw {
        Draw {
            state: self.state,
            distances: self.distances.clone(),
            ..Draw::new(
                self.viewport().expect("strategies build valid viewports"),
                self.positions.clone(),
                self.triangles.clone(),
            )
        }
    }
}

impl Scene {
    /// The clip-space positions of triangle `t`'s vertices, widened to f64 (indices must be in range).
    #[must_use]
    pub fn positions_of(&self, t: usize) -> [[f64; 4]; 3] {
        self.corners(t).map(|p| p.map(f64::from))
    }

    /// The clip-space positions of triangle `t`'s vertices as drawn, in f32 (indices must be in
    /// range).
    #[must_use]
    pub fn corners(&self, t: usize) -> [[f32; 4]; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }

    /// The scene without triangle `t`, its unused vertices dropped.
    #[must_use]
    pub fn without(&self, t: usize) -> Self {
        let mut s = self.clone();
        s.triangles.remove(t);
        s.compact()
    }

    /// Drops vertices no triangle uses, renumbering the rest (a bad index is kept as it is) and
    /// keeping the distances of those kept.
    #[must_use]
    pub fn compact(mut self) -> Self {
        let n = self.positions.len();
        let mut used = vec![false; n];
        for &i in self.triangles.iter().flatten() {
            if let Some(u) = used.get_mut(i as usize) {
                *u = true;
            }
        }
        let mut new_index = vec![0u32; n];
        let mut positions = Vec::new();
        let mut distances = Vec::new();
        for (i, p) in self.positions.iter().enumerate() {
            if used[i] {
                new_index[i] = positions.len() as u32;
                positions.push(*p);
                let v = i as u32;
                distances.extend(self.distances.clip_of(v).iter().chain(self.distances.cull_of(v)));
            }
        }
        self.distances.values = distances;
        for i in self.triangles.iter_mut().flatten() {
            if (*i as usize) < n {
                *i = new_index[*i as usize];
            }
        }
        self.positions = positions;
        self
    }
}

impl Case for Scene {
    /// Every way of dropping one triangle (a scene keeps at least one).
    fn reductions(&self) -> Vec<Self> {
        if self.triangles.len() < 2 {
            return Vec::new();
        }
        (0..self.triangles.len()).map(|t| self.without(t)).collect()
    }

    fn scene(&self) -> &Scene {
        self
    }

    fn scene_mut(&mut self) -> &mut Scene {
        self
    }

    fn data(&self) -> CaseData {
        CaseData::of_draw(self.draw_data())
    }

    fn from_data(data: &CaseData) -> Result<Self, String> {
        data.only_draw()?;
        data.draw.triangle_scene()
    }
}

/// Clip-space position of the raster point `(x, y)` given in `2^-bits` pixel units, scaled by `w`.
#[must_use]
pub fn clip_of(width: u32, height: u32, bits: u8, x: i64, y: i64, z: f32, w: f32) -> [f32; 4] {
    let one = f64::from(1u32 << bits);
    let [nx, ny] = to_ndc(width, height, x as f64 / one, y as f64 / one);
    let w64 = f64::from(w);
    [(nx * w64) as f32, (ny * w64) as f32, z * w, w]
}

/// A float as Rust source: `1.5`, `-0.0`, `f32::NAN`, `f32::INFINITY`.
pub(crate) fn rust_f32(v: f32) -> String {
    if v.is_nan() {
        "f32::NAN".into()
    } else if v.is_infinite() {
        if v > 0.0 {
            "f32::INFINITY"
        } else {
            "f32::NEG_INFINITY"
        }
        .into()
    } else {
        // `{:?}` prints the shortest string that reads back to the same f32.
        format!("{v:?}")
    }
}

impl fmt::Debug for Scene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Scene {{")?;
        writeln!(f, "    width: {},", self.width)?;
        writeln!(f, "    height: {},", self.height)?;
        writeln!(f, "    positions: vec![")?;
        for p in &self.positions {
            let c: Vec<String> = p.iter().map(|&v| rust_f32(v)).collect();
            writeln!(f, "        [{}],", c.join(", "))?;
        }
        writeln!(f, "    ],")?;
        let t: Vec<String> = self
            .triangles
            .iter()
            .map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2]))
            .collect();
        writeln!(f, "    triangles: vec![{}],", t.join(", "))?;
        let s = &self.state;
        writeln!(f, "    state: DrawState {{")?;
        writeln!(f, "        cull: CullMode::{},", cull_name(s.cull))?;
        writeln!(f, "        front_face: FrontFace::{},", front_name(s.front_face))?;
        writeln!(
            f,
            "        depth: DepthState {{ compare: CompareOp::{:?}, write: {}, clear: {} }},",
            s.depth.compare,
            s.depth.write,
            rust_f32(s.depth.clear)
        )?;
        writeln!(
            f,
            "        depth_range: DepthRange::{},",
            range_name(s.depth_range)
        )?;
        writeln!(f, "        clip_far: {},", s.clip_far)?;
        // State the contract gained later prints only when set, the rest left to the default,
        // so a counterexample without it reads as before it existed.
        if let Some(r) = s.scissor {
            writeln!(
                f,
                "        scissor: Some(Scissor {{ x: {}, y: {}, width: {}, height: {} }}),",
                r.x, r.y, r.width, r.height
            )?;
        }
        if s.sample_mask != DrawState::ALL_SAMPLES {
            writeln!(f, "        sample_mask: {:#x},", s.sample_mask)?;
        }
        if s.interpolation != Interpolation::Sample {
            writeln!(f, "        interpolation: Interpolation::{:?},", s.interpolation)?;
        }
        match s.conservative {
            Some(Conservative::Overestimate { extra }) => writeln!(
                f,
                "        conservative: Some(Conservative::Overestimate {{ extra: {} }}),",
                rust_f32(extra)
            )?,
            Some(Conservative::Underestimate) => {
                writeln!(f, "        conservative: Some(Conservative::Underestimate),")?;
            }
            None => {}
        }
        if s.provoking_vertex != ProvokingVertex::First {
            writeln!(
                f,
                "        provoking_vertex: ProvokingVertex::{:?},",
                s.provoking_vertex
            )?;
        }
        if !s.clip_near {
            writeln!(f, "        clip_near: false,")?;
        }
        if s.viewport_depth != ViewportDepth::FULL {
            writeln!(
                f,
                "        viewport_depth: ViewportDepth {{ min: {}, max: {} }},",
                rust_f32(s.viewport_depth.min),
                rust_f32(s.viewport_depth.max)
            )?;
        }
        if let Some(b) = s.depth_bias {
            writeln!(
                f,
                "        depth_bias: Some(DepthBias {{ constant: {}, slope: {}, clamp: {} }}),",
                rust_f32(b.constant),
                rust_f32(b.slope),
                rust_f32(b.clamp)
            )?;
        }
        if s.polygon_mode != PolygonMode::Fill {
            writeln!(f, "        polygon_mode: PolygonMode::{:?},", s.polygon_mode)?;
        }
        // The rest, where a field was left out (a struct update with none left is a lint).
        if s.scissor.is_none()
            || s.sample_mask == DrawState::ALL_SAMPLES
            || s.interpolation == Interpolation::Sample
            || s.conservative.is_none()
            || s.provoking_vertex == ProvokingVertex::First
            || s.clip_near
            || s.viewport_depth == ViewportDepth::FULL
            || s.depth_bias.is_none()
            || s.polygon_mode == PolygonMode::Fill
        {
            writeln!(f, "        ..DrawState::default()")?;
        }
        writeln!(f, "    }},")?;
        let d = &self.distances;
        if d.is_empty() {
            writeln!(f, "    distances: Distances::default(),")?;
        } else {
            let values: Vec<String> = d.values.iter().map(|&v| rust_f32(v)).collect();
            writeln!(
                f,
                "    distances: Distances {{ clip: {}, cull: {}, values: vec![{}] }},",
                d.clip,
                d.cull,
                values.join(", ")
            )?;
        }
        write!(f, "}}")
    }
}

fn cull_name(c: CullMode) -> &'static str {
    match c {
        CullMode::None => "None",
        CullMode::Front => "Front",
        CullMode::Back => "Back",
        CullMode::FrontAndBack => "FrontAndBack",
    }
}

fn front_name(f: FrontFace) -> &'static str {
    match f {
        FrontFace::Clockwise => "Clockwise",
        FrontFace::CounterClockwise => "CounterClockwise",
    }
}

fn range_name(r: DepthRange) -> &'static str {
    match r {
        DepthRange::ZeroToOne => "ZeroToOne",
        DepthRange::NegativeOneToOne => "NegativeOneToOne",
    }
}
