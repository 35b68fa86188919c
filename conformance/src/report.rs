//! What certification reports: a status per rule, the profile as printed, and the whole
//! report of one implementation (text, HTML and JSON are written from these).

use std::path::{Path, PathBuf};

use refrast::{
    CompareOp, CullMode, DepthRange, FillConvention, FrontFace, PolygonMode, Profile, ProvokingVertex,
    Rasterizer, SnapAccuracy, Supported,
};
use serde::{Deserialize, Serialize};

use crate::picture;
use crate::rules::{Family, Kind, Rule};
use crate::runner::guarded;
use crate::scene::CaseData;
pub use crate::status::Status;
use crate::violation::{Counts, Picture};
use refrast_pipe::wire::{FAR_CLIPPING, Word, depth_word};

/// One rule's line in the report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RuleReport {
    /// The rule's ID.
    pub id: String,
    /// Its family.
    pub family: Family,
    /// Invariant or exact.
    pub kind: Kind,
    /// Pass, fail or not applicable.
    pub status: Status,
    /// Cases tried (0 when not applicable): up to the failing one, or fewer than planned when
    /// the time budget ran out.
    pub cases: u32,
    /// Cases the rule would have tried (0 when not applicable).
    #[serde(default)]
    pub planned: u32,
    /// Whether the time budget ran out before every planned case was tried.
    #[serde(default)]
    pub budget_spent: bool,
    /// The generator's seed.
    pub seed: u64,
    /// The tolerance band used, in subpixels.
    pub tolerance_subpixels: u32,
    /// Why it failed, or why it does not apply.
    pub message: Option<String>,
    /// The numbers behind a failure, one line per wrong sample (the first few).
    #[serde(default)]
    pub details: Vec<String>,
    /// Sample tallies of a failed coverage check.
    pub counts: Option<Counts>,
    /// For [`Status::BeyondSpec`]: what the claimed specification says instead, with its sentence.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spec_note: Option<String>,
    /// Where the failure has the shape of a misdeclared profile, one line saying so, with the
    /// bug that looks the same.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hint: Option<String>,
    /// The shrunk failing input, as Rust.
    pub counterexample: Option<String>,
    /// Why shrinking stopped before the counterexample was as small as it could be (the time
    /// budget ran out, or the step limit); `None` when it is minimal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shrinking_cut: Option<String>,
    /// The shrunk failing input as data, in the form `refrast replay` reads.
    #[serde(default, skip_serializing_if = "Option::is_none", rename = "case")]
    pub case_file: Option<CaseFile>,
    /// Where that case was written, if it was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub case_path: Option<PathBuf>,
    /// The counterexample picture, if one was written.
    pub picture: Option<PathBuf>,
    /// The failure's files before they are written ([`RuleReport::save_exhibit`]); not part of
    /// the JSON document, which names the files instead.
    #[serde(skip)]
    pub exhibit: Option<Exhibit>,
    /// Seconds the rule took where it ran (in its child process, for an isolated rule; from the
    /// parent's side when the child died without a report).
    #[serde(default)]
    pub seconds: f64,
}

impl RuleReport {
    /// The report of `rule` before it runs: a pass of no case, with the `seed` and the band
    /// (in grid steps) it runs under.
    #[must_use]
    pub fn new(rule: &Rule, seed: u64, tolerance_subpixels: u32) -> Self {
        Self {
            id: rule.id.to_owned(),
            family: rule.family,
            kind: rule.kind,
            status: Status::Pass,
            cases: 0,
            planned: 0,
            budget_spent: false,
            seed,
            tolerance_subpixels,
            message: None,
            details: Vec::new(),
            counts: None,
            spec_note: None,
            hint: None,
            counterexample: None,
            shrinking_cut: None,
            case_file: None,
            case_path: None,
            picture: None,
            exhibit: None,
            seconds: 0.0,
        }
    }
}

/// What a failed rule leaves to be written (judging gathers it; whoever runs the suite, the
/// CLI, the test harness or a certifier of its own, decides whether and where it goes): the name its files share and the picture.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Exhibit {
    /// The file name without its extension: the implementation, then the rule.
    pub stem: String,
    /// The counterexample picture, when the check drew one.
    pub picture: Option<Picture>,
    /// The lines under the picture: the rule, the implementation and what went wrong.
    pub caption: Vec<String>,
}

impl Exhibit {
    /// The exhibit of `rule`'s failure on `implementation`.
    #[must_use]
    pub fn new(implementation: &str, rule: &str, picture: Option<Picture>, caption: Vec<String>) -> Self {
        Self {
            stem: file_stem(implementation, rule),
            picture,
            caption,
        }
    }
}

/// The name, without extension, of the files of `rule`'s failure on `implementation`: a name
/// any file system takes, one per implementation and rule, so that a rerun replaces its own.
fn file_stem(implementation: &str, rule: &str) -> String {
    let safe: String = implementation
        .chars()
        .map(|c| if c.is_alphanumeric() || c == '-' { c } else { '_' })
        .collect();
    format!("{safe}__{rule}")
}

impl RuleReport {
    /// Writes this failure's files into `dir` (`STEM.case.json`, `STEM.png`) and records where
    /// ([`RuleReport::case_path`], [`RuleReport::picture`]); nothing for a report without an
    /// exhibit. An error says which file could not be written; the report keeps the others.
    pub fn save_exhibit(&mut self, dir: &Path) -> Result<(), String> {
        let Some(exhibit) = &self.exhibit else {
            return Ok(());
        };
        let write = |extension: &str, bytes: &[u8]| -> Result<PathBuf, String> {
            let path = dir.join(format!("{}.{extension}", exhibit.stem));
            std::fs::create_dir_all(dir)
                .and_then(|()| std::fs::write(&path, bytes))
                .map_err(|e| format!("could not write {}: {e}", path.display()))?;
            Ok(path)
        };
        let mut failed = Vec::new();
        if let Some(case) = &self.case_file {
            match write("case.json", (case.to_json() + "\n").as_bytes()) {
                Ok(path) => self.case_path = Some(path),
                Err(why) => failed.push(why),
            }
        }
        if let Some(picture) = &exhibit.picture {
            let png = picture::png(picture, &exhibit.caption)
                .map_err(|e| format!("could not draw the picture of {}: {e}", exhibit.stem));
            match png.and_then(|bytes| write("png", &bytes)) {
                Ok(path) => self.picture = Some(path),
                Err(why) => failed.push(why),
            }
        }
        if failed.is_empty() {
            Ok(())
        } else {
            Err(failed.join("; "))
        }
    }
}

/// A counterexample as data: what `refrast replay` reads and a report's `case` holds
/// (docs/json.md).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct CaseFile {
    /// The rule it fails.
    pub rule: String,
    /// Which of the rule's properties failed on it.
    pub part: Part,
    /// The implementation it failed on, as its profile names it (for the reader).
    #[serde(default)]
    pub implementation: String,
    /// The seed of the run that found it (for the reader).
    #[serde(default)]
    pub seed: u64,
    /// The case: the draw in the pipe protocol's words, and what the rule does beside it.
    pub case: CaseData,
}

impl CaseFile {
    /// The file as `refrast replay` reads it: pretty JSON with each list of numbers (a vertex,
    /// the indices) on one line.
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self)
            .map_or_else(|e| format!("{{\"error\": \"{e}\"}}"), |text| flat_lists(&text))
    }
}

/// Pretty JSON with every list that holds no list or object written on one line.
fn flat_lists(pretty: &str) -> String {
    let mut out = String::with_capacity(pretty.len());
    let mut rest = pretty;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        let close = rest.find(']').unwrap_or(rest.len());
        let inner = &rest[..close];
        if inner.contains(['[', '{']) {
            continue;
        }
        let items: Vec<&str> = inner
            .split(',')
            .map(str::trim)
            .filter(|i| !i.is_empty())
            .collect();
        out.push_str(&items.join(", "));
        rest = &rest[close..];
    }
    out.push_str(rest);
    out
}

/// Which property of a rule a case failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Part {
    /// The whole rule.
    Rule,
    /// The part of it that the claimed specification requires (docs/levels.md).
    Required,
}

/// The profile as the report prints it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfileReport {
    /// Declared name.
    pub name: String,
    /// What the implementation reports itself to be ([`Rasterizer::about`]).
    #[serde(default)]
    pub about: String,
    /// Snapping: a grid's bits, or none.
    pub snapping: String,
    /// Tie rule on edges, or none.
    pub fill: String,
    /// Depth convention, in the pipe protocol's word (`z-over-w`, `other`).
    pub depth: String,
    /// Tolerance band in grid steps, as declared.
    pub tolerance_subpixels: u32,
    /// The band used, in pixels.
    pub band_px: f64,
    /// Optional abilities declared, and the supported values of each draw-state setting in
    /// the pipe protocol's words (`cull none|back|front`).
    pub features: Vec<String>,
    /// The specification it claims to follow ([`refrast::Spec::title`]).
    #[serde(default)]
    pub spec: String,
}

impl ProfileReport {
    /// The report of `rasterizer`'s profile, with what it says about itself; a panic in either
    /// is reported as the name.
    #[must_use]
    pub fn of(rasterizer: &dyn Rasterizer) -> Self {
        match guarded(|| (rasterizer.profile(), rasterizer.about())) {
            Ok((profile, about)) => Self {
                about,
                ..Self::from(&profile)
            },
            Err(what) => Self {
                name: format!("unknown (profile() or about() panicked: {what})"),
                ..Self::unknown()
            },
        }
    }
}

impl From<&Profile> for ProfileReport {
    fn from(p: &Profile) -> Self {
        Self {
            name: p.name.clone(),
            about: String::new(),
            snapping: p.snapping.to_string(),
            fill: fill_name(p.fill).to_owned(),
            depth: depth_word(p.depth).to_owned(),
            tolerance_subpixels: p.tolerance_subpixels,
            band_px: p.band_px(),
            features: feature_list(p),
            spec: p.spec.title().to_owned(),
        }
    }
}

impl ProfileReport {
    /// A profile nobody reported (every rule's process died before it could).
    #[must_use]
    pub fn unknown() -> Self {
        Self {
            name: "unknown (no rule's process reported a profile)".into(),
            about: String::new(),
            snapping: String::new(),
            fill: String::new(),
            depth: String::new(),
            tolerance_subpixels: 1,
            band_px: 0.0,
            features: Vec::new(),
            spec: String::new(),
        }
    }
}

/// A tie rule as reports print it.
#[must_use]
pub fn fill_name(fill: Option<FillConvention>) -> &'static str {
    fill.map_or("no tie rule", FillConvention::name)
}

/// The abilities a profile declares, then each setting's supported values.
#[must_use]
pub fn feature_list(p: &Profile) -> Vec<String> {
    let f = &p.features;
    let abilities = [
        (f.perspective_barycentrics, "perspective-barycentrics"),
        (f.screen_barycentrics, "screen-barycentrics"),
        (f.depth_test, "depth-test"),
        (f.ties_to_even, "ties-to-even"),
        (f.zero_area_before_clipping, "zero-area-before-clipping"),
        (p.state.scissor, "scissor"),
        (p.state.sample_mask, "sample-mask"),
        (p.state.centroid, "centroid"),
        (p.state.conservative.is_some(), "conservative"),
        (p.state.cull_both, "cull front-and-back"),
        (p.state.triangle_strips, "triangle-strip"),
        (p.state.triangle_fans, "triangle-fan"),
        (
            p.state.honours_viewport_depth() && !p.state.inverted_depth,
            "viewport-depth",
        ),
        (p.state.inverted_depth, "inverted-depth"),
        (p.state.unclipped_depth, "unclipped-depth"),
    ];
    let mut list: Vec<String> = abilities
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, name)| (*name).to_owned())
        .collect();
    if !f.clips_in_3d {
        list.push("clipping none".to_owned());
    }
    if f.snap != SnapAccuracy::Nearest {
        list.push(format!("snap {}", f.snap.name().replace('-', " ")));
    }
    match f.guard_band {
        0 => {}
        u32::MAX => list.push("guard-band unbounded".to_owned()),
        px => list.push(format!("guard-band {px} px")),
    }
    list.push(setting(CullMode::KEY, f.cull_modes));
    list.push(setting(FrontFace::KEY, f.front_faces));
    list.push(setting(CompareOp::KEY, f.compare_ops));
    list.push(setting(bool::KEY, f.depth_writes));
    list.push(format!("{FAR_CLIPPING} {}", words(f.far_clipping)));
    list.push(setting(DepthRange::KEY, f.depth_ranges));
    if !p.state.flat.is_empty() {
        list.push(setting(ProvokingVertex::KEY, p.state.flat));
    }
    if !p.state.polygon_modes.is_empty() {
        list.push(setting(PolygonMode::KEY, p.state.polygon_modes));
    }
    for (key, n) in [
        ("clip-distances", p.state.clip_distances),
        ("cull-distances", p.state.cull_distances),
    ] {
        if n > 0 {
            list.push(format!("{key} {n}"));
        }
    }
    if let Some(b) = p.state.depth_bias {
        // As the pipe protocol's `depth-bias` line says it.
        let clamp = if b.clamp { " clamp" } else { "" };
        list.push(format!(
            "depth-bias {} {}{clamp}",
            b.format.name(),
            b.slope.name()
        ));
    }
    list
}

/// A setting's supported values as the pipe protocol words them: `cull none|back|front`.
fn setting<T: Word>(key: &str, supported: Supported<T>) -> String {
    format!("{key} {}", words(supported))
}

/// Supported values in the protocol's words, joined by `|`.
fn words<T: Word>(supported: Supported<T>) -> String {
    supported.values().map(Word::word).collect::<Vec<_>>().join("|")
}

/// The whole certification of one implementation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The implementation's name.
    pub implementation: String,
    /// Its declared profile.
    pub profile: ProfileReport,
    /// One entry per rule run.
    pub rules: Vec<RuleReport>,
    /// The selected rules left unrun after a failure under [`crate::Options::fail_fast`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_run: Vec<String>,
    /// Why no rule ran: a profile the suite cannot judge ([`Profile::judgeable`]), with what to
    /// declare instead. A refused implementation has not passed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refused: Option<String>,
}

impl Report {
    /// Whether it was judged and no rule failed it ([`Status::is_failure`]: a crash, a
    /// timeout or a flake is no pass).
    #[must_use]
    pub fn passed(&self) -> bool {
        self.refused.is_none() && self.rules.iter().all(|r| !r.status.is_failure())
    }

    /// How many rules failed only on what the claimed specification does not require.
    #[must_use]
    pub fn beyond_spec(&self) -> usize {
        self.rules
            .iter()
            .filter(|r| r.status == Status::BeyondSpec)
            .count()
    }

    /// How many rules passed, failed (crashes, timeouts and flakes included), and did not
    /// apply ([`Report::beyond_spec`] counts the rest).
    #[must_use]
    pub fn tally(&self) -> (usize, usize, usize) {
        let n = |s| self.rules.iter().filter(|r| r.status == s).count();
        let failed = self.rules.iter().filter(|r| r.status.is_failure()).count();
        (n(Status::Pass), failed, n(Status::NotApplicable))
    }

    /// How many rules ended in `status`.
    #[must_use]
    pub fn count(&self, status: Status) -> usize {
        self.rules.iter().filter(|r| r.status == status).count()
    }
}
