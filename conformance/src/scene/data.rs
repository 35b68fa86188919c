//! A case as data: the draw in the pipe protocol's words, as JSON, so that a counterexample can
//! be read and replayed in any language (`refrast replay`, docs/json.md).

use std::fmt;

use refrast::{
    CompareOp, Conservative, CullMode, DepthBias, DepthRange, DepthState, Distances, DrawState, FrontFace,
    Interpolation, PolygonMode, ProvokingVertex, Scissor, Topology, Viewport, ViewportDepth,
};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::Scene;
use refrast_pipe::wire::{FAR_CLIPPING, NEAR_CLIPPING, Word};

/// One f32 of a draw: a JSON number when finite (the shortest decimal that reads back to the
/// same f32); a string otherwise, which JSON has no number for: `"NaN"`, `"Infinity"`,
/// `"-Infinity"`, or the bits (`"0xffc00001"`) of any NaN but the positive quiet one.
#[derive(Clone, Copy, Debug)]
pub struct Coordinate(pub f32);

impl PartialEq for Coordinate {
    /// Bit for bit: a NaN equals the same NaN, and -0.0 is not 0.0.
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}

impl Serialize for Coordinate {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let v = self.0;
        if v.is_finite() {
            s.serialize_f32(v)
        } else if v == f32::INFINITY {
            s.serialize_str("Infinity")
        } else if v == f32::NEG_INFINITY {
            s.serialize_str("-Infinity")
        } else if v.to_bits() == f32::NAN.to_bits() {
            s.serialize_str("NaN")
        } else {
            s.serialize_str(&format!("{:#010x}", v.to_bits()))
        }
    }
}

impl<'de> Deserialize<'de> for Coordinate {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(CoordinateVisitor)
    }
}

/// Reads a [`Coordinate`] from a number or one of its strings.
struct CoordinateVisitor;

impl Visitor<'_> for CoordinateVisitor {
    type Value = Coordinate;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number, or \"NaN\", \"Infinity\", \"-Infinity\" or an f32's bits as \"0x…\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Coordinate, E> {
        // A shortest decimal of an f32 reads as the f64 nearest it, which rounds back to that f32.
        Ok(Coordinate(v as f32))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Coordinate, E> {
        Ok(Coordinate(v as f32))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Coordinate, E> {
        Ok(Coordinate(v as f32))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Coordinate, E> {
        let value = match v {
            "NaN" => f32::NAN,
            "Infinity" => f32::INFINITY,
            "-Infinity" => f32::NEG_INFINITY,
            _ => {
                let bits = v
                    .strip_prefix("0x")
                    .and_then(|hex| u32::from_str_radix(hex, 16).ok())
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Str(v), &self))?;
                f32::from_bits(bits)
            }
        };
        Ok(Coordinate(value))
    }
}

/// One draw as the pipe protocol sends it (docs/protocol.md, requests): the header's keys and
/// words, the positions, and the indices as one flat list (three a triangle, two a line of a
/// list, one a point; a strip's vertices in order).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct DrawData {
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
    /// `triangle-list`, `line-list`, `line-strip`, `point-list`, `triangle-strip` or
    /// `triangle-fan`.
    pub topology: String,
    /// Samples per pixel.
    pub samples: u8,
    /// Clip-space positions `[x, y, z, w]`.
    pub positions: Vec<[Coordinate; 4]>,
    /// Vertex indices, flat.
    pub indices: Vec<u32>,
    /// `none`, `front` or `back`.
    pub cull: String,
    /// `ccw` or `cw`.
    pub front_face: String,
    /// `less`, `less-equal`, …, `always`, `never`.
    pub depth_compare: String,
    /// `on` or `off`.
    pub depth_write: String,
    /// The value the depth buffer starts from.
    pub depth_clear: Coordinate,
    /// `zero-to-one` or `negative-one-to-one`.
    pub depth_range: String,
    /// `on` or `off`.
    pub far_clipping: String,
    /// The scissor rectangle `[x, y, width, height]` in pixels, when the draw has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scissor: Option<[u32; 4]>,
    /// The sample mask, bit `i` keeping sample `i`; absent for all ones (no mask).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sample_mask: Option<u32>,
    /// `centroid` under centroid interpolation; absent at the sample.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interpolation: Option<String>,
    /// `over,EXTRA` or `under` under conservative rasterization; absent without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conservative: Option<String>,
    /// `first` or `last`: which vertex gives a primitive its flat values; absent for first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub provoking_vertex: Option<String>,
    /// `off` when depth clipping is off (the near plane clips nothing); absent for on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub near_clipping: Option<String>,
    /// The viewport's depth range `[minDepth, maxDepth]`; absent for `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viewport_depth: Option<[Coordinate; 2]>,
    /// The triangles' depth bias `[constant, slope, clamp]`; absent for none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth_bias: Option<[Coordinate; 3]>,
    /// `line` or `point`: how triangles are drawn; absent for `fill`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polygon_mode: Option<String>,
    /// Each vertex's clip and cull distances; absent for none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distances: Option<DistanceData>,
}

/// The clip and cull distances of a draw's vertices, as [`Distances`] holds them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct DistanceData {
    /// Clip distances per vertex.
    pub clip: usize,
    /// Cull distances per vertex.
    pub cull: usize,
    /// `clip + cull` values per vertex, clip distances first, vertex after vertex.
    pub values: Vec<Coordinate>,
}

impl DrawData {
    /// `scene`'s viewport, positions and state drawn as `topology` over `indices` at `samples`
    /// samples per pixel.
    #[must_use]
    pub fn new(scene: &Scene, topology: Topology, indices: Vec<u32>, samples: u8) -> Self {
        let s = &scene.state;
        Self {
            width: scene.width,
            height: scene.height,
            topology: topology.name().to_owned(),
            samples,
            positions: scene.positions.iter().map(|p| p.map(Coordinate)).collect(),
            indices,
            cull: s.cull.word().to_owned(),
            front_face: s.front_face.word().to_owned(),
            depth_compare: s.depth.compare.word().to_owned(),
            depth_write: s.depth.write.word().to_owned(),
            depth_clear: Coordinate(s.depth.clear),
            depth_range: s.depth_range.word().to_owned(),
            far_clipping: s.clip_far.word().to_owned(),
            scissor: s.scissor.map(|r| [r.x, r.y, r.width, r.height]),
            sample_mask: (s.sample_mask != DrawState::ALL_SAMPLES).then_some(s.sample_mask),
            interpolation: (s.interpolation != Interpolation::Sample)
                .then(|| s.interpolation.name().to_owned()),
            conservative: s.conservative.map(Conservative::words),
            provoking_vertex: (s.provoking_vertex != ProvokingVertex::First)
                .then(|| s.provoking_vertex.word().to_owned()),
            near_clipping: (!s.clip_near).then(|| s.clip_near.word().to_owned()),
            viewport_depth: (s.viewport_depth != ViewportDepth::FULL)
                .then_some([Coordinate(s.viewport_depth.min), Coordinate(s.viewport_depth.max)]),
            depth_bias: s
                .depth_bias
                .map(|b| [Coordinate(b.constant), Coordinate(b.slope), Coordinate(b.clamp)]),
            polygon_mode: (s.polygon_mode != PolygonMode::Fill).then(|| s.polygon_mode.name().to_owned()),
            distances: (!scene.distances.is_empty()).then(|| DistanceData {
                clip: scene.distances.clip,
                cull: scene.distances.cull,
                values: scene.distances.values.iter().copied().map(Coordinate).collect(),
            }),
        }
    }

    /// The scene it draws, its topology, the indices of its lines or points (a triangle list's
    /// are the scene's triangles) and samples; an error that names what is not as the protocol
    /// has it: a key's word, or a triangle list's indices not in threes.
    pub fn scene(&self) -> Result<(Scene, Topology, Vec<u32>, u8), String> {
        let topology = Topology::from_name(&self.topology).ok_or_else(|| {
            let names: Vec<&str> = Topology::ALL.iter().map(|t| t.name()).collect();
            format!("topology '{}' is none of {}", self.topology, names.join(", "))
        })?;
        let state = DrawState {
            cull: word(CullMode::KEY, &self.cull)?,
            front_face: word(FrontFace::KEY, &self.front_face)?,
            depth: DepthState {
                compare: word(CompareOp::KEY, &self.depth_compare)?,
                write: word(bool::KEY, &self.depth_write)?,
                clear: self.depth_clear.0,
            },
            depth_range: word(DepthRange::KEY, &self.depth_range)?,
            clip_far: word(FAR_CLIPPING, &self.far_clipping)?,
            scissor: self
                .scissor
                .map(|[x, y, width, height]| Scissor { x, y, width, height }),
            sample_mask: self.sample_mask.unwrap_or(DrawState::ALL_SAMPLES),
            interpolation: match &self.interpolation {
                None => Interpolation::Sample,
                Some(text) => Interpolation::from_name(text)
                    .ok_or_else(|| format!("interpolation '{text}' is none of sample, centroid"))?,
            },
            conservative: match &self.conservative {
                None => None,
                Some(text) => Some(Conservative::from_words(text).ok_or_else(|| {
                    format!("conservative '{text}' is neither under nor over,EXTRA with EXTRA ≥ 0")
                })?),
            },
            provoking_vertex: match &self.provoking_vertex {
                Some(text) => word(ProvokingVertex::KEY, text)?,
                None => ProvokingVertex::First,
            },
            clip_near: match &self.near_clipping {
                Some(text) => word(NEAR_CLIPPING, text)?,
                None => true,
            },
            viewport_depth: self
                .viewport_depth
                .map_or(ViewportDepth::FULL, |[min, max]| ViewportDepth {
                    min: min.0,
                    max: max.0,
                }),
            depth_bias: self.depth_bias.map(|[constant, slope, clamp]| DepthBias {
                constant: constant.0,
                slope: slope.0,
                clamp: clamp.0,
            }),
            polygon_mode: match &self.polygon_mode {
                None => PolygonMode::Fill,
                Some(text) => PolygonMode::from_name(text)
                    .ok_or_else(|| format!("polygon-mode '{text}' is none of fill, line, point"))?,
            },
        };
        // A draw needs a viewport and a depth range in range; the rules build none other.
        Viewport::new(self.width, self.height)
            .map_err(|e| format!("width {} and height {}: {e}", self.width, self.height))?;
        state.viewport_depth.validate()?;
        state.depth_bias.map_or(Ok(()), DepthBias::validate)?;
        let mut scene = Scene {
            width: self.width,
            height: self.height,
            positions: self.positions.iter().map(|p| p.map(|c| c.0)).collect(),
            triangles: Vec::new(),
            state,
            distances: self
                .distances
                .as_ref()
                .map_or_else(Distances::default, |d| Distances {
                    clip: d.clip,
                    cull: d.cull,
                    values: d.values.iter().map(|c| c.0).collect(),
                }),
        };
        scene.distances.validate(scene.positions.len())?;
        let mut indices = self.indices.clone();
        if topology == Topology::TriangleList {
            if !indices.len().is_multiple_of(3) {
                return Err(format!(
                    "a triangle list's indices come in threes, not {}",
                    indices.len()
                ));
            }
            scene.triangles = indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect();
            indices.clear();
        }
        Ok((scene, topology, indices, self.samples))
    }

    /// The scene of a triangle list at one sample per pixel.
    pub fn triangle_scene(&self) -> Result<Scene, String> {
        match self.scene()? {
            (scene, Topology::TriangleList, _, 1) => Ok(scene),
            (_, topology, _, samples) => Err(format!(
                "this rule draws triangle lists at one sample, not {} at {samples}",
                topology.name()
            )),
        }
    }
}

/// The value `text` names for the setting `key`, or an error listing the words.
fn word<T: Word>(key: &str, text: &str) -> Result<T, String> {
    T::parse(text).ok_or_else(|| format!("{key} '{text}' is none of {}", T::words()))
}

/// A rule's input as data: the draw, and what the rule does with it beside drawing it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct CaseData {
    /// The draw as the rule first sends it.
    pub draw: DrawData,
    /// For a translation rule: the whole pixels the draw is also moved by, right and down.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<[i32; 2]>,
    /// For a robustness rule: the coordinate replaced by a non-finite value in the draw it
    /// sends beside this one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poison: Option<Poison>,
}

/// Which coordinate a robustness rule poisons, and with what.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct Poison {
    /// Which vertex of triangle 0 (0, 1 or 2).
    pub vertex: usize,
    /// Which component of it (0 for x, …, 3 for w).
    pub component: usize,
    /// The value put there.
    pub value: Coordinate,
}

impl CaseData {
    /// A case that is a draw and nothing more.
    #[must_use]
    pub fn of_draw(draw: DrawData) -> Self {
        Self {
            draw,
            translate: None,
            poison: None,
        }
    }

    /// `Ok` for a case that is a draw and nothing more; else an error naming what is extra.
    pub fn only_draw(&self) -> Result<(), String> {
        if self.translate.is_some() {
            return Err("this rule's cases are a draw alone, with no translate".into());
        }
        if self.poison.is_some() {
            return Err("this rule's cases are a draw alone, with no poison".into());
        }
        Ok(())
    }
}

impl Scene {
    /// The scene as data: a triangle list at one sample.
    #[must_use]
    pub fn draw_data(&self) -> DrawData {
        let indices = self.triangles.iter().flatten().copied().collect();
        DrawData::new(self, Topology::TriangleList, indices, 1)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// Every f32 reads back bit for bit from its JSON: numbers, infinities and any NaN.
        #[test]
        fn coordinates_round_trip(bits in any::<u32>()) {
            let c = Coordinate(f32::from_bits(bits));
            let text = serde_json::to_string(&c).unwrap();
            let back: Coordinate = serde_json::from_str(&text).unwrap();
            prop_assert_eq!(back, c, "{} read back from {}", back.0, text);
        }
    }

    #[test]
    fn a_scene_reads_back_from_its_data() {
        let mut scene = Scene::new(
            16,
            8,
            vec![
                [0.1, -0.5, 0.25, 1.0],
                [f32::NAN, 1.0, -0.0, 2.0],
                [1e-30, 3.0, 0.5, -1.0],
            ],
            vec![[0, 1, 2]],
        );
        scene.state.cull = CullMode::Back;
        scene.state.clip_far = false;
        let text = serde_json::to_string(&CaseData::of_draw(scene.draw_data())).unwrap();
        assert!(
            text.contains("\"cull\":\"back\"") && text.contains("\"NaN\"") && text.contains("0.1,"),
            "{text}"
        );
        let data: CaseData = serde_json::from_str(&text).unwrap();
        let back = data.draw.triangle_scene().unwrap();
        assert_eq!(format!("{back:?}"), format!("{scene:?}"));
    }

    #[test]
    fn a_wrong_word_is_named() {
        let mut data = Scene::new(4, 4, vec![[0.0; 4]; 3], vec![[0, 1, 2]]).draw_data();
        data.cull = "sideways".into();
        let err = data.triangle_scene().unwrap_err();
        assert!(
            err.contains("cull 'sideways' is none of none, front, back, front-and-back"),
            "{err}"
        );
        data.cull = "none".into();
        data.indices.pop();
        assert!(data.triangle_scene().unwrap_err().contains("threes"));
        data.indices.push(2);
        data.width = 0;
        assert!(data.triangle_scene().unwrap_err().contains("width 0"));
    }
}
