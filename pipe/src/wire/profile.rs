//! The child's profile lines: the handshake that declares what it draws and how, read into a
//! [`Profile`] with every default filled in.

use super::*;

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
    pub(super) fn folded(self) -> Self {
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
            state.sample_mask,
            state.centroid,
            state.viewport_depth,
            state.inverted_depth,
            state.unclipped_depth,
        ) = (false, false, false, false, false, false);
        for word in rest.split_whitespace() {
            let flag = match word {
                "perspective-barycentrics" => &mut f.perspective_barycentrics,
                "screen-barycentrics" => &mut f.screen_barycentrics,
                "depth-test" => &mut f.depth_test,
                "ties-to-even" => &mut f.ties_to_even,
                "zero-area-before-clipping" => &mut f.zero_area_before_clipping,
                SCISSOR => &mut state.scissor,
                SAMPLE_MASK => &mut state.sample_mask,
                CENTROID => &mut state.centroid,
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
                         ties-to-even, zero-area-before-clipping, scissor, sample-mask, centroid, viewport-depth, \
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
                DEPTH_BIAS => self.profile.state.depth_bias = Some(depth_bias(&words).map_err(|w| bad(&w))?),
                CONSERVATIVE => {
                    self.profile.state.conservative = Some(conservative(&words).map_err(|w| bad(&w))?)
                }
                CLIP_DISTANCES | CULL_DISTANCES => {
                    let n = match words.as_slice() {
                        [n] => n.parse::<usize>().ok().filter(|&n| n <= refrast::MAX_DISTANCES),
                        _ => None,
                    }
                    .ok_or_else(|| bad("give how many per vertex, 0 to 8"))?;
                    let state = &mut self.profile.state;
                    if key == CLIP_DISTANCES {
                        state.clip_distances = n;
                    } else {
                        state.cull_distances = n;
                    }
                    if state.clip_distances + state.cull_distances > refrast::MAX_DISTANCES {
                        return Err(bad("clip and cull distances are at most 8 together"));
                    }
                }
                FrontFace::KEY => f.front_faces = supported(&words, bad)?,
                CompareOp::KEY => f.compare_ops = supported(&words, bad)?,
                DepthRange::KEY => f.depth_ranges = supported(&words, bad)?,
                ProvokingVertex::KEY => self.profile.state.flat = supported(&words, bad)?,
                PolygonMode::KEY => self.profile.state.polygon_modes = supported(&words, bad)?,
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
            DEPTH_BIAS,
            CONSERVATIVE,
            PolygonMode::KEY,
            CLIP_DISTANCES,
            CULL_DISTANCES,
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
