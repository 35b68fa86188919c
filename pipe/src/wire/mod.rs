//! The protocol's words and bytes: the child's profile lines, the request header and payload,
//! and the reply headers. `docs/protocol.md` is the specification.

use refrast::{
    CompareOp, CullMode, DepthConvention, DepthRange, Draw, FillConvention, Fragment, FrontFace, LineRule,
    PointClipping, PolygonMode, Profile, ProvokingVertex, SamplePattern, Setting, SnapAccuracy, Snapping,
    Spec, Supported,
};

/// The newest protocol version this refrast speaks, the one its messages suggest.
pub const VERSION: u32 = 3;

/// Every version this refrast speaks: 1; 2, which adds a draw's topology and sample count and
/// each fragment's sample (reserved for lines, points and multisampling, so that the protocol
/// changes once); 3, which adds the provoking vertex and each fragment's flat vertex.
pub const VERSIONS: [u32; 3] = [1, 2, 3];

/// Bytes per fragment record: x, y, primitive, front-facing (u32), depth, three perspective and
/// three screen-space barycentrics (f32), all little-endian; version 2 adds the sample (u32),
/// version 3 the flat vertex (u32, `0xFFFF_FFFF` for none).
#[must_use]
pub fn fragment_bytes(version: u32) -> usize {
    match version {
        0 | 1 => 44,
        2 => 48,
        _ => 52,
    }
}

/// A primitive topology, as version 2 spells it in the profile and in requests: the
/// contract's own ([`refrast::Topology::name`]).
pub use refrast::Topology;

mod profile;
pub use profile::{Declared, default_profile, parse_profile, shown, version};

/// Sample counts a version 2 profile may list: Vulkan's standard counts ([`refrast::SAMPLE_COUNTS`]).
pub const SAMPLE_COUNTS: [u32; 5] = [1, 2, 4, 8, 16];

/// The profile key that says whether the child clips in 3D (`homogeneous`, the default) or
/// not at all (`none`: a 2D scan converter).
pub const CLIPPING: &str = "clipping";

/// The longest line either side may send, in bytes.
pub const MAX_LINE: usize = 4096;

/// What the parent asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// Every covered sample, before the depth test.
    Rasterize,
    /// The depth and primitive buffers after the child's own depth test.
    Resolve,
}

impl Op {
    /// The request's first word.
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Self::Rasterize => "rasterize",
            Self::Resolve => "resolve",
        }
    }
}

/// A draw-state setting as the protocol spells its values.
pub trait Word: Setting {
    /// The key naming the setting, in the profile and in requests.
    const KEY: &'static str;
    /// The value as a word.
    fn word(self) -> &'static str;
    /// The value a word names.
    fn parse(word: &str) -> Option<Self> {
        Self::VALUES.iter().copied().find(|v| v.word() == word)
    }
    /// Every word, for messages.
    fn words() -> String {
        Self::VALUES
            .iter()
            .map(|v| v.word())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// `front-and-back` is not among [`Setting::VALUES`]: a child declares it beside the others in
/// its `cull` line, and is sent it only then ([`refrast::StateSupport::cull_both`]).
impl Word for CullMode {
    const KEY: &'static str = "cull";
    fn word(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Front => "front",
            Self::Back => "back",
            Self::FrontAndBack => CULL_BOTH,
        }
    }
    fn parse(word: &str) -> Option<Self> {
        [Self::None, Self::Front, Self::Back, Self::FrontAndBack]
            .into_iter()
            .find(|v| v.word() == word)
    }
    fn words() -> String {
        format!("none, front, back, {CULL_BOTH}")
    }
}

/// The cull mode of both faces, as the protocol spells it.
pub const CULL_BOTH: &str = "front-and-back";

impl Word for FrontFace {
    const KEY: &'static str = "front-face";
    fn word(self) -> &'static str {
        match self {
            Self::CounterClockwise => "ccw",
            Self::Clockwise => "cw",
        }
    }
}

impl Word for CompareOp {
    const KEY: &'static str = "depth-compare";
    fn word(self) -> &'static str {
        match self {
            Self::Never => "never",
            Self::Less => "less",
            Self::Equal => "equal",
            Self::LessOrEqual => "less-equal",
            Self::Greater => "greater",
            Self::NotEqual => "not-equal",
            Self::GreaterOrEqual => "greater-equal",
            Self::Always => "always",
        }
    }
}

impl Word for DepthRange {
    const KEY: &'static str = "depth-range";
    fn word(self) -> &'static str {
        match self {
            Self::ZeroToOne => "zero-to-one",
            Self::NegativeOneToOne => "negative-one-to-one",
        }
    }
}

/// Which vertex gives a primitive its flat values: a version 3 profile line listing the modes
/// the child reports flat values under, and a version 3 request key.
impl Word for ProvokingVertex {
    const KEY: &'static str = "provoking-vertex";
    fn word(self) -> &'static str {
        match self {
            Self::First => "first",
            Self::Last => "last",
        }
    }
}

/// How triangles are drawn: a profile line `polygon-mode line point` listing the modes besides
/// fill the child draws, and a request key on triangle draws in one of them (fill is never sent).
impl Word for PolygonMode {
    const KEY: &'static str = "polygon-mode";
    fn word(self) -> &'static str {
        self.name()
    }
}

/// Depth writes; far clipping has the same words under its own key ([`FAR_CLIPPING`]).
impl Word for bool {
    const KEY: &'static str = "depth-write";
    fn word(self) -> &'static str {
        if self { "on" } else { "off" }
    }
}

/// The depth convention as the protocol's `depth` key spells it: `z-over-w` or `other`.
#[must_use]
pub fn depth_word(depth: DepthConvention) -> &'static str {
    match depth {
        DepthConvention::ScreenLinearZOverW => "z-over-w",
        DepthConvention::Other => "other",
    }
}

/// The key of far clipping, whose values are `on` and `off` like depth writes'.
pub const FAR_CLIPPING: &str = "far-clipping";

/// The feature word a child declares to be sent a scissor, and the request key that carries
/// it: `scissor=X,Y,WIDTH,HEIGHT` in pixels, origin top-left.
pub const SCISSOR: &str = "scissor";

/// The feature word a child declares to be sent a sample mask, and the request key that
/// carries it: `sample-mask=MASK`, a decimal `u32` whose bit `i` keeps sample `i`.
pub const SAMPLE_MASK: &str = "sample-mask";

/// The feature word a child declares to be sent centroid interpolation
/// ([`refrast::StateSupport::centroid`]).
pub const CENTROID: &str = "centroid";

/// The request key of a triangle draw's interpolation other than at the sample:
/// `interpolation=centroid`, sent after the sample mask.
pub const INTERPOLATION: &str = "interpolation";

/// The profile line a child declares conservative rasterization with
/// (`conservative OVERESTIMATION MAX_EXTRA GRANULARITY [under] [degenerates-drawn |
/// degenerates-culled]`, sizes in pixels), and the request key of a filled triangle draw under
/// it: `conservative=over,EXTRA` or `conservative=under`, sent last.
pub const CONSERVATIVE: &str = "conservative";

/// The `conservative` line's words: three sizes in pixels (the overestimation it may add, the
/// largest extra size it honours, the extra size's granularity), then `under` where it
/// underestimates too, and `degenerates-drawn` or `degenerates-culled` where it says what a
/// triangle of zero area once snapped does.
pub fn conservative(words: &[&str]) -> Result<refrast::ConservativeSupport, String> {
    let shape = "say `conservative OVERESTIMATION MAX_EXTRA GRANULARITY`, three sizes in pixels \
                 (0 or more), then any of `under` and `degenerates-drawn` or `degenerates-culled`";
    let size = |w: &str| w.parse::<f32>().ok().filter(|s| s.is_finite() && *s >= 0.0);
    let [o, m, g, rest @ ..] = words else {
        return Err(shape.to_owned());
    };
    let (Some(overestimation_size), Some(max_extra), Some(extra_granularity)) = (size(o), size(m), size(g))
    else {
        return Err(shape.to_owned());
    };
    let mut support = refrast::ConservativeSupport {
        overestimation_size,
        max_extra,
        extra_granularity,
        underestimate: false,
        degenerate_triangles: None,
    };
    for word in rest {
        match *word {
            "under" => support.underestimate = true,
            "degenerates-drawn" => support.degenerate_triangles = Some(true),
            "degenerates-culled" => support.degenerate_triangles = Some(false),
            _ => return Err(shape.to_owned()),
        }
    }
    Ok(support)
}

/// The feature word a child declares to be sent a viewport depth range other than `[0, 1]`
/// with `minDepth ≤ maxDepth`, and the request key that carries it: `viewport-depth=MIN,MAX`.
pub const VIEWPORT_DEPTH: &str = "viewport-depth";

/// The feature word a child declares to be sent `minDepth > maxDepth` too.
pub const INVERTED_DEPTH: &str = "inverted-depth";

/// The feature word a child declares to be sent draws with depth clipping off, and the
/// request key that says so: `near-clipping=off` (with `far-clipping=off`).
pub const UNCLIPPED_DEPTH: &str = "unclipped-depth";

/// The request key of near clipping, sent only as `near-clipping=off`.
pub const NEAR_CLIPPING: &str = "near-clipping";

/// The profile line a child declares depth bias with (`depth-bias FORMAT SLOPE [clamp]`), and
/// the request key that carries a triangle draw's: `depth-bias=CONSTANT,SLOPE,CLAMP`.
pub const DEPTH_BIAS: &str = "depth-bias";

/// The `depth-bias` line's words: the depth format (`unorm16`, `unorm24`, `float32`), the slope
/// measure (`exact`, `max`, `either`), then `clamp` when it honours the bias clamp.
pub fn depth_bias(words: &[&str]) -> Result<refrast::BiasSupport, String> {
    let shape = "say `depth-bias FORMAT SLOPE` or `depth-bias FORMAT SLOPE clamp`, FORMAT one of \
                 unorm16, unorm24, float32 (what r is computed for) and SLOPE one of exact, max, \
                 either (how m is measured)";
    let (format, slope, clamp) = match words {
        [f, s] => (f, s, false),
        [f, s, c] if *c == "clamp" => (f, s, true),
        _ => return Err(shape.to_owned()),
    };
    match (
        refrast::DepthFormat::from_name(format),
        refrast::DepthSlope::from_name(slope),
    ) {
        (Some(format), Some(slope)) => Ok(refrast::BiasSupport { format, slope, clamp }),
        _ => Err(shape.to_owned()),
    }
}

/// The profile lines a child declares how many clip and cull distances per vertex it honours
/// with (`clip-distances N`, `cull-distances N`; at most 8 together), and the request key of a
/// draw that has some: `distances=CLIP,CULL`, the values following the indices.
pub const CLIP_DISTANCES: &str = "clip-distances";

/// See [`CLIP_DISTANCES`].
pub const CULL_DISTANCES: &str = "cull-distances";

/// The request key of a draw's distances: `distances=CLIP,CULL`.
pub const DISTANCES: &str = "distances";

/// The key of the guard band's reach: pixels beyond each side of the viewport.
pub const GUARD_BAND: &str = "guard-band";

/// The reach the feature word `guard-band` alone declares: what `fill.guard-band.exact` drew
/// before a guard band had a size.
pub const LEGACY_GUARD_BAND: u32 = 1500;

/// The largest reach a profile may declare: [`COORD_LIMIT`](refrast::COORD_LIMIT) pixels.
pub const GUARD_BAND_LIMIT: u32 = refrast::COORD_LIMIT as u32;

/// The request for `op` on `draw` in protocol `version`: its header line, then positions and
/// indices. `triangles=T` counts the draw's primitives, whose indices follow: `3T` of a triangle
/// list, `2T` of a line list, `T + 1` of a line strip and `T + 2` of a triangle strip or fan
/// (none when `T = 0`), `T` of a point list.
/// Version 2 ends the header with the topology and the samples per pixel (a version 1 child is
/// only ever sent triangle lists at one sample), version 3 then with the provoking vertex (the
/// caller sends only a mode the child declared). A draw with a scissor ends it with
/// `scissor=X,Y,W,H`, one with depth clipping off with `near-clipping=off`, one with a depth
/// range other than `[0, 1]` with `viewport-depth=MIN,MAX`, a triangle draw with depth bias
/// with `depth-bias=CONSTANT,SLOPE,CLAMP`, a triangle draw in line or point mode with
/// `polygon-mode=line` or `polygon-mode=point`, one with clip or cull distances with
/// `distances=CLIP,CULL` (then `vertices × (CLIP + CULL)` f32 words follow the indices, each
/// vertex's clip distances then its cull distances), one with a sample mask with
/// `sample-mask=MASK`, a triangle draw at several samples under centroid interpolation with
/// `interpolation=centroid`, and a filled triangle draw under conservative rasterization with
/// `conservative=over,EXTRA` or `conservative=under` last, in any version.
#[must_use]
pub fn request(op: Op, draw: &Draw, version: u32) -> Vec<u8> {
    request_in(op, draw, version, draw.state.provoking_vertex)
}

/// [`request`] asking for flat values under `provoking` rather than the draw's own mode: the
/// one the child declares (a draw may ask any), without copying the draw.
#[must_use]
pub fn request_in(op: Op, draw: &Draw, version: u32, provoking: ProvokingVertex) -> Vec<u8> {
    let s = &draw.state;
    let count = draw.primitive_count();
    let mut extra = if version >= 2 {
        format!(" topology={} samples={}", draw.topology.name(), draw.samples)
    } else {
        String::new()
    };
    if version >= 3 {
        extra += &format!(" {}={}", ProvokingVertex::KEY, provoking.word());
    }
    // Only a child that declares the feature is ever sent a scissor (Profile::fit drops it).
    if let Some(r) = s.scissor {
        extra += &format!(" {SCISSOR}={},{},{},{}", r.x, r.y, r.width, r.height);
    }
    // The same for depth clipping off and the depth range (Profile::fit keeps the defaults).
    if !s.clip_near {
        extra += &format!(" {NEAR_CLIPPING}=off");
    }
    if s.viewport_depth != refrast::ViewportDepth::FULL {
        let d = s.viewport_depth;
        extra += &format!(" {VIEWPORT_DEPTH}={:?},{:?}", d.min, d.max);
    }
    // Lines and points are drawn unbiased: the key goes with triangles only.
    if let Some(b) = s.depth_bias.filter(|_| draw.topology.is_triangles()) {
        extra += &format!(" {DEPTH_BIAS}={:?},{:?},{:?}", b.constant, b.slope, b.clamp);
    }
    if s.polygon_mode != PolygonMode::Fill && draw.topology.is_triangles() {
        extra += &format!(" {}={}", PolygonMode::KEY, s.polygon_mode.word());
    }
    // Only to a child that declares them (Process::declares refuses the rest).
    let d = &draw.distances;
    if !d.is_empty() {
        extra += &format!(" {DISTANCES}={},{}", d.clip, d.cull);
    }
    // Only to a child that declares it (Profile::fit keeps every sample for the rest).
    if s.sample_mask != refrast::DrawState::ALL_SAMPLES {
        extra += &format!(" {SAMPLE_MASK}={}", s.sample_mask);
    }
    // The same; lines and points, and a draw at one sample, are alike under both samplings.
    if s.interpolation != refrast::Interpolation::Sample && draw.topology.is_triangles() && draw.samples > 1 {
        extra += &format!(" {INTERPOLATION}={}", s.interpolation.name());
    }
    // The same; lines, points and the polygon modes are drawn as without it.
    if let Some(mode) = s
        .conservative
        .filter(|_| draw.topology.is_triangles() && s.polygon_mode == PolygonMode::Fill)
    {
        extra += &format!(" {CONSERVATIVE}={}", mode.words());
    }
    let header = format!(
        "{} width={} height={} vertices={} triangles={count} cull={} front-face={} depth-compare={} \
         depth-write={} depth-clear={:?} depth-range={} far-clipping={}{extra}\n",
        op.word(),
        draw.viewport.width(),
        draw.viewport.height(),
        draw.positions.len(),
        s.cull.word(),
        s.front_face.word(),
        s.depth.compare.word(),
        s.depth.write.word(),
        s.depth.clear,
        s.depth_range.word(),
        s.clip_far.word(),
    );
    let indices: &[u32] = match draw.topology {
        Topology::LineStrip | Topology::TriangleStrip | Topology::TriangleFan if count == 0 => &[],
        _ => &draw.indices,
    };
    let mut bytes = header.into_bytes();
    bytes.reserve(draw.positions.len() * 16 + indices.len() * 4);
    for c in draw.positions.iter().flatten() {
        bytes.extend_from_slice(&c.to_le_bytes());
    }
    for i in indices {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    for v in &d.values {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    bytes
}

/// The `u32` at word `k` of a record.
fn u32_at(record: &[u8], k: usize) -> u32 {
    let mut word = [0; 4];
    word.copy_from_slice(&record[4 * k..4 * k + 4]);
    u32::from_le_bytes(word)
}

/// The `f32` at word `k` of a record.
pub fn f32_at(record: &[u8], k: usize) -> f32 {
    f32::from_bits(u32_at(record, k))
}

/// Decodes one fragment record of [`fragment_bytes`] of a draw at `samples` samples a pixel,
/// its sample 0 in version 1 and no flat vertex before version 3; `Err` names a front-facing
/// word that is neither 0 nor 1, or (version 2) a sample the draw does not have.
pub fn fragment(record: &[u8], screen_barycentrics: bool, samples: u8) -> Result<Fragment, String> {
    let front = u32_at(record, 3);
    if front > 1 {
        return Err(format!("its front-facing word is {front}, not 0 or 1"));
    }
    let sample = if record.len() >= 48 { u32_at(record, 11) } else { 0 };
    if sample >= u32::from(samples) {
        let a = if samples == 1 { "sample" } else { "samples" };
        return Err(format!(
            "it names sample {sample}, but the draw has {samples} {a} a pixel (samples={samples}: sample 0 to {})",
            samples - 1
        ));
    }
    let screen = [f32_at(record, 8), f32_at(record, 9), f32_at(record, 10)];
    Ok(Fragment {
        x: u32_at(record, 0),
        y: u32_at(record, 1),
        sample: sample as u8,
        primitive: u32_at(record, 2),
        front_facing: front == 1,
        depth: f32_at(record, 4),
        barycentric: [f32_at(record, 5), f32_at(record, 6), f32_at(record, 7)],
        flat: (record.len() >= 52)
            .then(|| u32_at(record, 12))
            .filter(|&v| v != u32::MAX),
        // Three NaN words say "none": the triangle has a vertex at w ≤ 0 and no screen shape
        // (the rules accept none only there; docs/protocol.md).
        screen_barycentric: (screen_barycentrics && !screen.iter().all(|c| c.is_nan())).then_some(screen),
    })
}

/// Decodes the `u32` values of a primitive buffer, `0xFFFF_FFFF` meaning none.
pub fn primitives(bytes: &[u8]) -> Vec<Option<u32>> {
    (0..bytes.len() / 4)
        .map(|k| Some(u32_at(bytes, k)).filter(|&p| p != u32::MAX))
        .collect()
}

/// Decodes little-endian `f32` values.
pub fn floats(bytes: &[u8]) -> Vec<f32> {
    (0..bytes.len() / 4).map(|k| f32_at(bytes, k)).collect()
}

#[cfg(test)]
mod tests;
