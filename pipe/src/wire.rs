//! The protocol's words and bytes: the child's profile lines, the request header and payload,
//! and the reply headers. `docs/protocol.md` is the specification.

use refrast::{
    CompareOp, CullMode, DepthConvention, DepthRange, Draw, FillConvention, Fragment, FrontFace, LineRule,
    PointClipping, Profile, ProvokingVertex, SamplePattern, Setting, SnapAccuracy, Snapping, Spec, Supported,
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
/// range other than `[0, 1]` with `viewport-depth=MIN,MAX`, in any version.
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

/// What the handshake declared: the profile and what the child says it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Declared {
    /// The profile, defaults filled in.
    pub profile: Profile,
    /// The `about` line, empty when there is none.
    pub about: String,
    /// The protocol version it speaks, one of [`VERSIONS`].
    pub version: u32,
    /// The topologies it draws (version 2's `topology`; triangle lists in version 1).
    pub topologies: Vec<Topology>,
    /// The sample counts it draws at (version 2's `samples`; 1 in version 1).
    pub sample_counts: Vec<u32>,
    /// How it covers lines (version 2's `lines`; diamond-exit unless said).
    pub lines: LineRule,
    /// Sample positions it declares instead of the standard ones (version 2's
    /// `sample-positions`), one pattern per count.
    pub sample_positions: Vec<SamplePattern>,
    /// What clipping does to a point outside the viewport (version 2's `point-clipping`).
    pub point_clipping: PointClipping,
}

impl Declared {
    /// A child's declaration before its handshake: the defaults, named `name`, in `version`.
    #[must_use]
    pub fn defaults(name: &str, version: u32) -> Self {
        Self {
            profile: default_profile(name),
            about: String::new(),
            version,
            topologies: vec![Topology::TriangleList],
            sample_counts: vec![1],
            lines: LineRule::DiamondExit,
            sample_positions: Vec::new(),
            point_clipping: PointClipping::AllClipPlanes,
        }
    }

    /// Its profile with what it declares about lines, points and samples folded in: lines when
    /// it lists both line topologies, points when it lists point lists, strips and fans when it
    /// lists them, each count above one at its declared positions or the standard ones.
    fn folded(self) -> Self {
        let lists = |t: Topology| self.topologies.contains(&t);
        let profile = Profile {
            lines: (lists(Topology::LineList) && lists(Topology::LineStrip)).then_some(self.lines),
            points: lists(Topology::PointList),
            endpoint_snapping: None,
            point_snapping: None,
            multisample: self
                .sample_counts
                .iter()
                .filter(|&&n| n > 1)
                .filter_map(|&n| {
                    let n = u8::try_from(n).ok()?;
                    self.sample_positions
                        .iter()
                        .find(|p| p.count() == n)
                        .copied()
                        .or_else(|| SamplePattern::standard(n))
                })
                .collect(),
            point_clipping: self.point_clipping,
            state: refrast::StateSupport {
                triangle_strips: lists(Topology::TriangleStrip),
                triangle_fans: lists(Topology::TriangleFan),
                ..self.profile.state
            },
            ..self.profile
        };
        Self { profile, ..self }
    }
}

/// The profile of a child that declares nothing but its name: the defaults of `docs/protocol.md`.
#[must_use]
pub fn default_profile(name: &str) -> Profile {
    Profile {
        name: name.to_owned(),
        snapping: Snapping::Float,
        fill: None,
        depth: DepthConvention::ScreenLinearZOverW,
        tolerance_subpixels: 1,
        precision_bits: 14,
        features: refrast::Features {
            perspective_barycentrics: false,
            screen_barycentrics: false,
            cull_modes: Supported::only(&[CullMode::None]),
            front_faces: Supported::ALL,
            depth_test: false,
            compare_ops: Supported::only(&[CompareOp::Less]),
            depth_writes: Supported::only(&[true]),
            far_clipping: Supported::only(&[false]),
            depth_ranges: Supported::only(&[DepthRange::ZeroToOne]),
            guard_band: 0,
            ties_to_even: false,
            snap: SnapAccuracy::Nearest,
            zero_area_before_clipping: false,
            clips_in_3d: true,
            z_rewritten_in_f32: false,
        },
        spec: Spec::Refrast,
        ..Profile::default()
    }
}

/// The versions this refrast speaks, as a sentence lists them: "1, 2 and 3".
fn spoken() -> String {
    let words: Vec<String> = VERSIONS.iter().map(u32::to_string).collect();
    match words.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => words.join(""),
    }
}

/// The version a first line declares: `Err` when it is not `refrast-protocol N`, or when this
/// refrast does not speak version N.
pub fn version(line: &str) -> Result<u32, String> {
    let mut words = line.split_whitespace();
    match (words.next(), words.next().map(str::parse::<u32>), words.next()) {
        (Some("refrast-protocol"), Some(Ok(v)), None) if VERSIONS.contains(&v) => Ok(v),
        (Some("refrast-protocol"), Some(Ok(v)), None) => Err(format!(
            "the child speaks refrast protocol version {v}, but this refrast speaks versions {} \
             (docs/protocol.md): write `refrast-protocol {VERSION}` and the version {VERSION} \
             messages, or use a refrast that speaks version {v}",
            spoken()
        )),
        _ => Err(format!(
            "the child's first line must be `refrast-protocol N` for a version this refrast speaks ({}), but it is `{}`",
            spoken(),
            shown(line)
        )),
    }
}

/// Builds the declaration from the handshake lines between the version line and `ready`.
pub fn parse_profile(lines: &[String], fallback_name: &str, version: u32) -> Result<Declared, String> {
    let mut reading = Reading {
        declared: Declared::defaults(fallback_name, version),
        profile: default_profile(fallback_name),
        about: String::new(),
        guard_band_word: false,
    };
    let mut seen: Vec<&str> = Vec::new();
    for line in lines {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (key, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        if seen.contains(&key) {
            return Err(format!("the profile says `{key}` twice"));
        }
        let bad = |what: &str| format!("profile line `{}`: {what}", shown(line));
        reading.line(key, rest.trim(), &bad)?;
        seen.push(key);
    }
    let Reading {
        declared,
        mut profile,
        about,
        guard_band_word,
    } = reading;
    if guard_band_word {
        if seen.contains(&GUARD_BAND) {
            return Err(format!(
                "the profile says `guard-band` as a feature and as a line; keep the line `{GUARD_BAND} PIXELS`"
            ));
        }
        // The word alone, from before a guard band had a size: the reach the rule drew then.
        profile.features.guard_band = LEGACY_GUARD_BAND;
    }
    Ok(Declared {
        profile,
        about,
        ..declared
    }
    .folded())
}

/// A handshake being read: what its lines have declared so far.
struct Reading {
    /// The declaration, its version's defaults until a line says otherwise.
    declared: Declared,
    /// The profile, the protocol's defaults until a line says otherwise.
    profile: Profile,
    /// The `about` line.
    about: String,
    /// Whether `features` named `guard-band`, the word alone from before it had a size.
    guard_band_word: bool,
}

/// What a line names a value of: its check's words, for `bad`.
type Bad<'a> = &'a dyn Fn(&str) -> String;

impl Reading {
    /// Reads one line, `key` and the `rest` of it; `Err` says what is wrong, through `bad`.
    fn line(&mut self, key: &str, rest: &str, bad: Bad<'_>) -> Result<(), String> {
        let version = self.declared.version;
        match key {
            "name" | "about" | "snapping" | "fill" | "depth" | "tolerance" | "precision" | "spec" => {
                self.conventions(key, rest, bad)
            }
            "features" => self.features(rest, bad),
            "topology" | "samples" | "lines" | "point-clipping" | "sample-positions" if version >= 2 => {
                self.primitives(key, rest, bad)
            }
            _ => self.settings(key, rest, bad).unwrap_or_else(|| {
                Err(format!(
                    "the profile has an unknown key `{key}`; docs/protocol.md lists the keys of version \
                     {version}"
                ))
            }),
        }
    }

    /// The profile's conventions and what the child says it is: `name`, `about`, `snapping`,
    /// `fill`, `depth`, `tolerance`, `precision`, `spec`.
    fn conventions(&mut self, key: &str, rest: &str, bad: Bad<'_>) -> Result<(), String> {
        let profile = &mut self.profile;
        match key {
            "name" if rest.is_empty() => return Err(bad("the name is empty")),
            "name" => profile.name = rest.to_owned(),
            "about" => self.about = rest.to_owned(),
            "snapping" => {
                profile.snapping = match rest.split_whitespace().collect::<Vec<_>>().as_slice() {
                    ["float"] => Snapping::Float,
                    ["grid", bits] => match bits.parse::<u8>() {
                        Ok(b @ 1..=16) => Snapping::Grid(b),
                        _ => return Err(bad("the grid's bits must be 1 to 16")),
                    },
                    _ => return Err(bad("say `snapping float` or `snapping grid BITS`")),
                }
            }
            "fill" => {
                profile.fill = match rest {
                    "none" => None,
                    word => Some(
                        FillConvention::ALL
                            .into_iter()
                            .find(|c| c.name() == word)
                            .ok_or_else(|| {
                                bad("use none, top-left, top-right, bottom-left or bottom-right")
                            })?,
                    ),
                }
            }
            "depth" => {
                profile.depth = [DepthConvention::ScreenLinearZOverW, DepthConvention::Other]
                    .into_iter()
                    .find(|d| depth_word(*d) == rest)
                    .ok_or_else(|| bad("use z-over-w or other"))?;
            }
            "tolerance" => {
                profile.tolerance_subpixels = rest
                    .parse()
                    .ok()
                    .filter(|t| (1..=1024).contains(t))
                    .ok_or_else(|| bad("a number of grid steps, 1 to 1024"))?;
            }
            "precision" => {
                profile.precision_bits = rest
                    .parse()
                    .ok()
                    .filter(|p| (1..=30).contains(p))
                    .ok_or_else(|| bad("a number of bits, 1 to 30"))?;
            }
            _ => {
                profile.spec = Spec::from_name(rest)
                    .ok_or_else(|| bad("say refrast, vulkan, opengl, opengles or d3d11"))?;
            }
        }
        Ok(())
    }

    /// The `features` line: the flags it names are on, every other off.
    fn features(&mut self, rest: &str, bad: Bad<'_>) -> Result<(), String> {
        let f = &mut self.profile.features;
        (
            f.perspective_barycentrics,
            f.screen_barycentrics,
            f.depth_test,
            f.ties_to_even,
            f.zero_area_before_clipping,
        ) = (false, false, false, false, false);
        let state = &mut self.profile.state;
        (
            state.scissor,
            state.viewport_depth,
            state.inverted_depth,
            state.unclipped_depth,
        ) = (false, false, false, false);
        for word in rest.split_whitespace() {
            let flag = match word {
                "perspective-barycentrics" => &mut f.perspective_barycentrics,
                "screen-barycentrics" => &mut f.screen_barycentrics,
                "depth-test" => &mut f.depth_test,
                "ties-to-even" => &mut f.ties_to_even,
                "zero-area-before-clipping" => &mut f.zero_area_before_clipping,
                SCISSOR => &mut state.scissor,
                VIEWPORT_DEPTH => &mut state.viewport_depth,
                // Reversed ranges are ranges too.
                INVERTED_DEPTH => {
                    state.viewport_depth = true;
                    &mut state.inverted_depth
                }
                UNCLIPPED_DEPTH => &mut state.unclipped_depth,
                // The word alone, from before the guard band had a size: the reach the rule drew
                // then. A `guard-band PIXELS` line says more.
                "guard-band" => &mut self.guard_band_word,
                _ => {
                    return Err(bad(
                        "features are perspective-barycentrics, screen-barycentrics, depth-test, \
                         ties-to-even, zero-area-before-clipping, scissor, viewport-depth, \
                         inverted-depth, unclipped-depth and guard-band",
                    ));
                }
            };
            *flag = true;
        }
        Ok(())
    }

    /// A line of the supported states and how it clips and snaps; `None` for another key.
    fn settings(&mut self, key: &str, rest: &str, bad: Bad<'_>) -> Option<Result<(), String>> {
        let words: Vec<&str> = rest.split_whitespace().collect();
        let f = &mut self.profile.features;
        let read = || -> Result<(), String> {
            match key {
                "snap" => {
                    f.snap = SnapAccuracy::from_name(rest)
                        .ok_or_else(|| bad("say nearest, within-one-step, floor or toward-zero"))?;
                }
                CLIPPING => {
                    f.clips_in_3d = match rest {
                        "homogeneous" => true,
                        "none" => false,
                        _ => return Err(bad("say homogeneous or none")),
                    };
                }
                GUARD_BAND => f.guard_band = guard_band(rest, bad)?,
                CullMode::KEY => {
                    // Both faces are declared apart: the other words are the supported modes.
                    self.profile.state.cull_both = words.contains(&CULL_BOTH);
                    let modes: Vec<&str> = words.iter().copied().filter(|w| *w != CULL_BOTH).collect();
                    if modes.is_empty() && !words.is_empty() {
                        return Err(bad(&format!(
                            "{CULL_BOTH} needs one of none, front, back beside it"
                        )));
                    }
                    f.cull_modes = supported(&modes, bad)?;
                }
                FrontFace::KEY => f.front_faces = supported(&words, bad)?,
                CompareOp::KEY => f.compare_ops = supported(&words, bad)?,
                DepthRange::KEY => f.depth_ranges = supported(&words, bad)?,
                ProvokingVertex::KEY => self.profile.state.flat = supported(&words, bad)?,
                bool::KEY => f.depth_writes = supported(&words, bad)?,
                _ => f.far_clipping = supported(&words, bad)?,
            }
            Ok(())
        };
        let flat = (self.declared.version >= 3).then_some(ProvokingVertex::KEY);
        let known = [
            "snap",
            CLIPPING,
            GUARD_BAND,
            CullMode::KEY,
            FrontFace::KEY,
            CompareOp::KEY,
            DepthRange::KEY,
            bool::KEY,
            FAR_CLIPPING,
        ];
        (known.contains(&key) || flat == Some(key)).then(read)
    }

    /// Version 2's lines of lines, points and samples.
    fn primitives(&mut self, key: &str, rest: &str, bad: Bad<'_>) -> Result<(), String> {
        let words: Vec<&str> = rest.split_whitespace().collect();
        let declared = &mut self.declared;
        match key {
            "topology" => declared.topologies = topologies(&words, bad)?,
            "samples" => declared.sample_counts = sample_counts(&words, bad)?,
            "lines" => {
                declared.lines = match words.as_slice() {
                    [rule] => LineRule::from_name(rule),
                    _ => None,
                }
                .ok_or_else(|| bad("name one of diamond-exit, rectangle, parallelogram"))?;
            }
            "point-clipping" => {
                declared.point_clipping = PointClipping::from_name(rest)
                    .ok_or_else(|| bad("say all-clip-planes or user-clip-planes-only"))?;
            }
            _ => {
                let pattern = sample_positions(&words).map_err(|why| bad(&why))?;
                declared.sample_positions.retain(|p| p.count() != pattern.count());
                declared.sample_positions.push(pattern);
            }
        }
        Ok(())
    }
}

/// The `guard-band` line's reach: pixels, or `unbounded` (no x/y clipping at all, so no edge
/// ever moves: the Rust side's `u32::MAX`).
fn guard_band(rest: &str, bad: Bad<'_>) -> Result<u32, String> {
    if rest == "unbounded" {
        return Ok(u32::MAX);
    }
    rest.parse()
        .ok()
        .filter(|&px| px <= GUARD_BAND_LIMIT)
        .ok_or_else(|| {
            bad(&format!(
                "pixels beyond each side of the viewport, 0 to {GUARD_BAND_LIMIT}, or unbounded for a \
             rasterizer that clips nothing in x and y"
            ))
        })
}

/// Version 2's `topology` line: known words, triangle lists among them (all refrast sends today).
fn topologies(words: &[&str], bad: Bad<'_>) -> Result<Vec<Topology>, String> {
    let all = || Topology::ALL.map(Topology::name).join(", ");
    let listed: Option<Vec<Topology>> = words.iter().map(|w| Topology::from_name(w)).collect();
    match listed {
        Some(listed) if listed.contains(&Topology::LineList) != listed.contains(&Topology::LineStrip) => Err(
            bad("list line-list and line-strip together: the line rules draw both"),
        ),
        Some(listed) if listed.contains(&Topology::TriangleList) => Ok(listed),
        Some(_) => Err(bad("list triangle-list too: every child draws triangle lists")),
        None => Err(bad(&format!("list one or more of {}", all()))),
    }
}

/// Version 2's `samples` line: counts among [`SAMPLE_COUNTS`], 1 among them (all refrast sends today).
fn sample_counts(words: &[&str], bad: Bad<'_>) -> Result<Vec<u32>, String> {
    let listed: Option<Vec<u32>> = words
        .iter()
        .map(|w| w.parse().ok().filter(|n| SAMPLE_COUNTS.contains(n)))
        .collect();
    match listed {
        Some(listed) if listed.contains(&1) => Ok(listed),
        Some(_) => Err(bad("list 1 too: every child draws one sample a pixel")),
        None => Err(bad("list one or more of 1, 2, 4, 8, 16")),
    }
}

/// Version 2's `sample-positions N X,Y …` line: N positions in sixteenths of a pixel (0 to 15).
fn sample_positions(words: &[&str]) -> Result<SamplePattern, String> {
    let shape = "give the count, then that many `X,Y` pairs in sixteenths of a pixel (0 to 15)";
    let Some((count, pairs)) = words.split_first() else {
        return Err(shape.to_owned());
    };
    let positions: Option<Vec<[u8; 2]>> = pairs
        .iter()
        .map(|p| {
            let (x, y) = p.split_once(',')?;
            Some([x.parse().ok()?, y.parse().ok()?])
        })
        .collect();
    match (count.parse::<usize>(), positions) {
        (Ok(n), Some(positions)) if n == positions.len() => SamplePattern::new(&positions),
        _ => Err(shape.to_owned()),
    }
}

/// The values a profile line lists, each a known word, at least one.
fn supported<T: Word>(words: &[&str], bad: Bad<'_>) -> Result<Supported<T>, String> {
    let values: Option<Vec<T>> = words.iter().map(|w| T::parse(w)).collect();
    match values {
        Some(values) if !values.is_empty() => Ok(Supported::only(&values)),
        _ => Err(bad(&format!("list one or more of {}", T::words()))),
    }
}

/// A line as a message shows it: at most 120 characters, control characters escaped.
#[must_use]
pub fn shown(line: &str) -> String {
    let mut s: String = line.chars().take(120).flat_map(char::escape_debug).collect();
    if line.chars().count() > 120 {
        s.push('…');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(lines: &[&str]) -> Result<Profile, String> {
        let lines: Vec<String> = lines.iter().map(|&l| l.to_owned()).collect();
        parse_profile(&lines, "child", 1).map(|d| d.profile)
    }

    /// Three NaN screen-barycentric words say "none" (a triangle with a vertex at w ≤ 0);
    /// one NaN among finite words stays a value, which the rules judge.
    #[test]
    fn three_nan_screen_words_say_none() {
        let record = |screen: [f32; 3]| {
            let mut words: Vec<u32> = vec![1, 2, 0, 1];
            words.extend([0.5f32, 1.0, 0.0, 0.0].map(f32::to_bits));
            words.extend(screen.map(f32::to_bits));
            words.push(0);
            words.iter().flat_map(|w| w.to_le_bytes()).collect::<Vec<u8>>()
        };
        let none = fragment(&record([f32::NAN; 3]), true, 1).expect("a record");
        assert_eq!(none.screen_barycentric, None);
        let one = fragment(&record([f32::NAN, 0.5, 0.5]), true, 1).expect("a record");
        assert!(one.screen_barycentric.is_some_and(|s| s[0].is_nan()));
        let undeclared = fragment(&record([0.2, 0.3, 0.5]), false, 1).expect("a record");
        assert_eq!(undeclared.screen_barycentric, None);
        assert_eq!(
            fragment(&record([0.2, 0.3, 0.5]), true, 1)
                .expect("a record")
                .screen_barycentric,
            Some([0.2, 0.3, 0.5])
        );
    }

    /// `snap`, `clipping` and `point-clipping` read their words; a wrong one names the choices.
    #[test]
    fn the_new_profile_words_are_read() {
        let p = parsed(&["snapping grid 6", "snap toward-zero", "clipping none"]).expect("a profile");
        assert_eq!(p.features.snap, SnapAccuracy::TowardZero);
        assert!(!p.features.clips_in_3d);
        assert_eq!(
            parsed(&["snap floor"]).expect("floor").features.snap,
            SnapAccuracy::Floor
        );
        let why = parsed(&["clipping sometimes"]).expect_err("a bad word");
        assert!(why.contains("homogeneous or none"), "{why}");
        let why = parsed(&["snap truncate"]).expect_err("a bad word");
        assert!(why.contains("toward-zero"), "{why}");
        let lines: Vec<String> = [
            "topology triangle-list point-list",
            "point-clipping user-clip-planes-only",
        ]
        .iter()
        .map(|&l| l.to_owned())
        .collect();
        let declared = parse_profile(&lines, "child", 2).expect("version 2");
        assert_eq!(declared.profile.point_clipping, PointClipping::UserClipPlanesOnly);
        assert_eq!(parsed(&["spec opengles"]).expect("ES").spec, Spec::OpenGlEs);
    }

    /// The guard band is a line with its reach, or the feature word alone for the reach the rule
    /// drew before it had a size; saying both is an error that names the fix.
    #[test]
    fn the_guard_band_is_declared_with_its_reach() {
        assert_eq!(parsed(&[]).unwrap().features.guard_band, 0);
        assert_eq!(parsed(&["guard-band 8192"]).unwrap().features.guard_band, 8192);
        assert_eq!(
            parsed(&["guard-band unbounded"]).unwrap().features.guard_band,
            u32::MAX
        );
        let word = parsed(&["features depth-test guard-band"]).unwrap().features;
        assert_eq!((word.guard_band, word.depth_test), (LEGACY_GUARD_BAND, true));
        let both = parsed(&["features guard-band", "guard-band 8192"]).unwrap_err();
        assert!(both.contains("keep the line `guard-band PIXELS`"), "{both}");
        let far = parsed(&["guard-band 40000"]).unwrap_err();
        assert!(far.contains("0 to 32768"), "{far}");
    }

    /// The specification claimed, how exactly snapping lands and the zero-area claim: refrast's
    /// conventions, the nearest grid point and no claim unless said.
    #[test]
    fn spec_snap_and_zero_area_are_declared() {
        let plain = parsed(&[]).unwrap();
        assert_eq!(plain.spec, Spec::Refrast);
        assert_eq!(plain.features.snap, SnapAccuracy::Nearest);
        assert!(!plain.features.zero_area_before_clipping);
        let said = parsed(&[
            "spec vulkan",
            "snap within-one-step",
            "features zero-area-before-clipping",
        ])
        .unwrap();
        assert_eq!(said.spec, Spec::Vulkan);
        assert_eq!(said.features.snap, SnapAccuracy::WithinOneStep);
        assert!(said.features.zero_area_before_clipping);
        assert!(parsed(&["spec metal"]).unwrap_err().contains("vulkan"));
        assert!(parsed(&["snap exact"]).unwrap_err().contains("within-one-step"));
    }

    /// Ties round to even only when the child says so.
    #[test]
    fn ties_to_even_is_a_feature_word() {
        assert!(!parsed(&["snapping grid 8"]).unwrap().features.ties_to_even);
        let f = parsed(&["snapping grid 8", "features ties-to-even"])
            .unwrap()
            .features;
        assert!(f.ties_to_even && !f.depth_test);
        let bad = parsed(&["features ties-up"]).unwrap_err();
        assert!(bad.contains("ties-to-even"), "{bad}");
    }

    /// The scissor and culling of both faces are declared apart (a feature word; a word in the
    /// cull line), sent only when declared, and carried in the request's header.
    #[test]
    fn the_scissor_and_both_faces_are_declared_and_sent() {
        let plain = parsed(&["cull none back"]).unwrap();
        assert!(!plain.state.scissor && !plain.state.cull_both);
        let both = parsed(&["cull none front-and-back", "features scissor"]).unwrap();
        assert!(both.state.scissor && both.state.cull_both);
        assert!(both.features.cull_modes.contains(CullMode::None));
        assert!(!both.features.cull_modes.contains(CullMode::Back));
        assert!(parsed(&["cull front-and-sides"]).unwrap_err().contains("cull"));
        let alone = parsed(&["cull front-and-back"]).unwrap_err();
        assert!(alone.contains("needs one of none, front, back"), "{alone}");
        let mut draw = Draw::new(
            refrast::Viewport::new(4, 4).unwrap(),
            vec![[0.0; 4]; 3],
            vec![[0, 1, 2]],
        );
        let header = |draw: &Draw| {
            let bytes = request(Op::Rasterize, draw, 2);
            let end = bytes.iter().position(|&b| b == b'\n').unwrap();
            String::from_utf8(bytes[..end].to_vec()).unwrap()
        };
        assert!(!header(&draw).contains("scissor"));
        draw.state.cull = CullMode::FrontAndBack;
        draw.state.scissor = Some(refrast::Scissor {
            x: 1,
            y: 2,
            width: 3,
            height: 0,
        });
        let text = header(&draw);
        assert!(
            text.contains(" cull=front-and-back ") && text.ends_with(" scissor=1,2,3,0"),
            "{text}"
        );
        assert_eq!(CullMode::parse("front-and-back"), Some(CullMode::FrontAndBack));
    }

    /// Strips and fans are declared in the topology line, each on its own, and a request sends
    /// `T + 2` indices for `T` triangles, none for a strip too short to make one.
    #[test]
    fn strips_and_fans_are_declared_and_sent() {
        let declared = |line: &str| {
            parse_profile(&[line.to_owned()], "child", 2)
                .expect("version 2")
                .folded()
                .profile
        };
        let strips = declared("topology triangle-list triangle-strip");
        assert!(strips.state.triangle_strips && !strips.state.triangle_fans);
        assert!(strips.draws(Topology::TriangleStrip, 1) && !strips.draws(Topology::TriangleFan, 1));
        let fans = declared("topology triangle-list triangle-fan");
        assert!(fans.state.triangle_fans && !fans.state.triangle_strips);
        assert!(!declared("topology triangle-list").state.triangle_strips);
        let vp = refrast::Viewport::new(4, 4).unwrap();
        let body = |indices: Vec<u32>| {
            let draw = Draw::of(vp, vec![[0.0; 4]; 4], Topology::TriangleFan, indices);
            let bytes = request(Op::Rasterize, &draw, 2);
            let end = bytes.iter().position(|&b| b == b'\n').unwrap();
            let header = String::from_utf8(bytes[..end].to_vec()).unwrap();
            (header, bytes.len() - end - 1 - 4 * 16)
        };
        let (header, bytes) = body(vec![0, 1, 2, 3]);
        assert!(
            header.contains(" triangles=2 ") && header.contains(" topology=triangle-fan "),
            "{header}"
        );
        assert_eq!(bytes, 4 * 4);
        assert_eq!(body(vec![0, 1]).1, 0);
    }

    /// Version 3 declares the provoking modes, sends the draw's, and reads each fragment's flat
    /// vertex from a thirteenth word (`0xFFFF_FFFF`: none); version 2 knows none of it.
    #[test]
    fn version_3_carries_the_provoking_vertex_and_the_flat_vertex() {
        let line = vec!["provoking-vertex last".to_owned()];
        let declared = parse_profile(&line, "child", 3).expect("version 3");
        assert!(declared.profile.state.flat.contains(ProvokingVertex::Last));
        assert!(!declared.profile.state.flat.contains(ProvokingVertex::First));
        let refused = parse_profile(&line, "child", 2).expect_err("version 2");
        assert!(refused.contains("unknown key `provoking-vertex`"), "{refused}");
        let mut draw = Draw::new(
            refrast::Viewport::new(4, 4).unwrap(),
            vec![[0.0; 4]; 3],
            vec![[0, 1, 2]],
        );
        draw.state.provoking_vertex = ProvokingVertex::Last;
        let header = |version| {
            let bytes = request(Op::Rasterize, &draw, version);
            let end = bytes.iter().position(|&b| b == b'\n').unwrap();
            String::from_utf8(bytes[..end].to_vec()).unwrap()
        };
        assert!(
            header(3).ends_with(" samples=1 provoking-vertex=last"),
            "{}",
            header(3)
        );
        assert!(!header(2).contains("provoking"));
        assert_eq!(
            (fragment_bytes(1), fragment_bytes(2), fragment_bytes(3)),
            (44, 48, 52)
        );
        let mut record = vec![0u8; 52];
        record[48..].copy_from_slice(&7u32.to_le_bytes());
        assert_eq!(fragment(&record, false, 1).unwrap().flat, Some(7));
        record[48..].copy_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(fragment(&record, false, 1).unwrap().flat, None);
        assert_eq!(fragment(&record[..48], false, 1).unwrap().flat, None);
        assert_eq!(version("refrast-protocol 3"), Ok(3));
        let why = version("refrast-protocol 9").unwrap_err();
        assert!(why.contains("speaks versions 1, 2 and 3"), "{why}");
    }
}
