//! Results a team keeps across runs: the JSON document `certify --json` writes (its schema is
//! docs/json.md), and what is made from such documents: JUnit XML, a comparison of two runs,
//! and one document merged from the shards of a run.

pub mod compare;
pub mod html;
pub mod junit;
pub mod merge;
pub mod outputs;

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use refrast_conformance::{DEFAULT_CASE_TIMEOUT, Report, RuleReport, Shard};
use serde::{Deserialize, Serialize};

/// The version of the JSON document's schema (docs/json.md); raised on any change a reader
/// could trip over.
pub const SCHEMA_VERSION: u32 = 1;

/// What `certify --json` writes.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Document {
    /// [`SCHEMA_VERSION`] of the writer.
    pub schema_version: u32,
    /// How the run was made.
    pub run: Run,
    /// One entry per implementation, in the order of the run.
    pub implementations: Vec<Entry>,
    /// Implementations not certified after a failure under `--fail-fast`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_certified: Vec<String>,
}

/// How a run was made: which refrast, where, when, with what options.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Run {
    /// refrast's version.
    pub refrast_version: String,
    /// The git revision refrast was built from (`unknown` outside a git checkout).
    pub git_revision: String,
    /// When the run started, RFC 3339 in UTC.
    pub started: String,
    /// Seconds the run took.
    pub seconds: f64,
    /// The machine: host name, operating system, architecture, processors.
    pub host: Host,
    /// The command line, as given.
    pub command: Vec<String>,
    /// Every option that decides the verdicts.
    pub options: RunOptions,
}

/// The machine a run was made on.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Host {
    /// Its name (`unknown` where it cannot be read).
    pub name: String,
    /// `linux`, `macos`, …
    pub os: String,
    /// `x86_64`, `aarch64`, …
    pub arch: String,
    /// Processors available to the run.
    pub cpus: usize,
}

impl Host {
    /// This machine.
    #[must_use]
    pub fn this() -> Self {
        let name = std::fs::read_to_string("/proc/sys/kernel/hostname")
            .ok()
            .or_else(|| std::env::var("HOSTNAME").ok())
            .map_or_else(|| "unknown".to_owned(), |n| n.trim().to_owned());
        Self {
            name,
            os: std::env::consts::OS.to_owned(),
            arch: std::env::consts::ARCH.to_owned(),
            cpus: std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get),
        }
    }
}

/// The options of a run, as they decide its verdicts.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunOptions {
    /// `--cases`; `null` is each rule's default (or `PROPTEST_CASES`).
    pub cases: Option<u32>,
    /// `PROPTEST_CASES` when it chose the cases.
    pub proptest_cases: Option<String>,
    /// `--scale`.
    pub scale: u32,
    /// `--seed`.
    pub seed: u64,
    /// `--rule` patterns (empty: every rule).
    pub rules: Vec<String>,
    /// `--shard`, as `I/N`.
    pub shard: Option<Shard>,
    /// `--budget` in seconds per rule, as given (`--exec` subjects get 10 without it).
    pub budget: Option<f64>,
    /// `--case-timeout` in seconds.
    pub case_timeout: f64,
    /// `--fail-fast`.
    pub fail_fast: bool,
    /// `--jobs`.
    pub jobs: usize,
    /// `--in-process`.
    pub in_process: bool,
    /// `--memory-limit` in MiB per child (`null`: no limit, `--memory-limit 0`); absent in
    /// documents written before it was recorded.
    #[serde(default)]
    pub memory_limit_mib: Option<u64>,
    /// `--expect` files.
    pub expect: Vec<PathBuf>,
}

/// How the command line named what it certified.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Subject {
    /// A built-in: `--impl NAME`.
    #[serde(rename = "impl")]
    BuiltIn(String),
    /// A child speaking the pipe protocol: `--exec CMD`.
    #[serde(rename = "exec")]
    Exec(String),
}

impl Subject {
    /// The flag and its value.
    #[must_use]
    pub fn flag(&self) -> [&str; 2] {
        match self {
            Self::BuiltIn(name) => ["--impl", name],
            Self::Exec(command) => ["--exec", command],
        }
    }

    /// The name as the command line gave it: what expectation sections are called.
    #[must_use]
    pub fn name(&self) -> &str {
        match self {
            Self::BuiltIn(name) | Self::Exec(name) => name,
        }
    }
}

/// One implementation's entry.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Entry {
    /// How the command line named it.
    pub subject: Subject,
    /// How it went.
    #[serde(flatten)]
    pub outcome: Outcome,
}

/// How an implementation's certification went.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Outcome {
    /// Certified: the report.
    Certified(Box<Report>),
    /// A child that could not be started or did not complete its handshake: a failure.
    FailedToStart {
        /// The command line.
        implementation: String,
        /// Why, with the end of its stderr.
        failed_to_start: String,
    },
    /// Not available on this machine, and why.
    Skipped {
        /// Its name.
        implementation: String,
        /// Why it was skipped.
        skipped: String,
    },
}

impl Entry {
    /// Whether it counts as passed: certified with no failing rule. One that was skipped
    /// certified nothing of what the run was asked, so it is no pass.
    #[must_use]
    pub fn passed(&self) -> bool {
        match &self.outcome {
            Outcome::Certified(report) => report.passed(),
            Outcome::FailedToStart { .. } | Outcome::Skipped { .. } => false,
        }
    }

    /// The report, where it was certified.
    #[must_use]
    pub fn report(&self) -> Option<&Report> {
        match &self.outcome {
            Outcome::Certified(report) => Some(report),
            _ => None,
        }
    }
}

impl Document {
    /// Reads a document written by `certify --json` or `merge --json`; `Err` says what to fix.
    pub fn load(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let value: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))?;
        match value.get("schema_version").and_then(serde_json::Value::as_u64) {
            Some(v) if v == u64::from(SCHEMA_VERSION) => {}
            Some(v) => {
                return Err(format!(
                    "{}: schema_version {v}, where this refrast reads {SCHEMA_VERSION}; certify again \
                     with this refrast",
                    path.display()
                ));
            }
            None => {
                return Err(format!(
                    "{}: no schema_version: not a report of `refrast certify --json` (or one from \
                     before schema 1); certify again with this refrast",
                    path.display()
                ));
            }
        }
        serde_json::from_value(value).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Writes the document as indented JSON.
    pub fn save(&self, path: &Path) -> Result<(), String> {
        let json = serde_json::to_string_pretty(self).map_err(|e| e.to_string())?;
        std::fs::write(path, json + "\n").map_err(|e| format!("could not write {}: {e}", path.display()))
    }
}

/// The command that runs `r` again on the same cases, quoted for a POSIX shell.
#[must_use]
pub fn reproduce(options: &RunOptions, subject: &Subject, r: &RuleReport) -> String {
    let mut words: Vec<String> = ["refrast", "certify"].into_iter().map(str::to_owned).collect();
    words.extend(subject.flag().map(str::to_owned));
    words.extend([
        "--rule".to_owned(),
        r.id.clone(),
        "--seed".to_owned(),
        r.seed.to_string(),
    ]);
    if r.planned > 0 {
        words.extend(["--cases".to_owned(), r.planned.to_string()]);
    }
    if let Some(budget) = options.budget {
        words.extend(["--budget".to_owned(), budget.to_string()]);
    }
    if (options.case_timeout - DEFAULT_CASE_TIMEOUT.as_secs_f64()).abs() > f64::EPSILON {
        words.extend(["--case-timeout".to_owned(), options.case_timeout.to_string()]);
    }
    shell_words::join(words)
}

/// The command that replays `r`'s counterexample alone on `subject` (`refrast replay`), when
/// its case was written.
#[must_use]
pub fn replay_command(subject: &Subject, r: &RuleReport) -> Option<String> {
    let path = r.case_path.as_ref()?;
    let mut words: Vec<String> = ["refrast", "replay"].into_iter().map(str::to_owned).collect();
    words.extend(subject.flag().map(str::to_owned));
    words.push(path.to_string_lossy().into_owned());
    Some(shell_words::join(words))
}

/// The time budget per rule of an `--exec` rasterizer unless `--budget` says otherwise: a
/// Python rasterizer gets through the catalogue in a few minutes.
pub const DEFAULT_EXEC_BUDGET: std::time::Duration = std::time::Duration::from_secs(10);

/// refrast's git revision, as the build script found it.
#[must_use]
pub fn git_revision() -> &'static str {
    option_env!("REFRAST_GIT_REVISION").unwrap_or("unknown")
}

/// `when` as RFC 3339 in UTC, `YYYY-MM-DDTHH:MM:SSZ`.
#[must_use]
pub fn rfc3339(when: SystemTime) -> String {
    let (date, time) = civil(when);
    format!("{date}T{time}Z")
}

/// `when` as (`YYYY-MM-DD`, `HH:MM:SS`) in UTC (days to a civil date: Howard Hinnant's algorithm).
#[must_use]
pub fn civil(when: SystemTime) -> (String, String) {
    let secs = when.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let z = days + 719_468;
    let era = z / 146_097;
    let doe = z % 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + u64::from(month <= 2);
    let (hour, minute, second) = (rest / 3600, rest % 3600 / 60, rest % 60);
    (
        format!("{year:04}-{month:02}-{day:02}"),
        format!("{hour:02}:{minute:02}:{second:02}"),
    )
}

/// The entity for a character that is markup in HTML and in XML alike (`&`, `<`, `>` and both
/// quotes), or `None`: the escaping the page and the JUnit file share (`&#39;`, not `&apos;`,
/// which HTML 4 lacks).
pub(crate) fn markup_entity(c: char) -> Option<&'static str> {
    match c {
        '&' => Some("&amp;"),
        '<' => Some("&lt;"),
        '>' => Some("&gt;"),
        '"' => Some("&quot;"),
        '\'' => Some("&#39;"),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::{civil, rfc3339};
    use std::time::{Duration, UNIX_EPOCH};

    #[test]
    fn dates_are_civil_utc() {
        assert_eq!(rfc3339(UNIX_EPOCH), "1970-01-01T00:00:00Z");
        assert_eq!(
            civil(UNIX_EPOCH + Duration::from_secs(951_827_696)),
            ("2000-02-29".to_owned(), "12:34:56".to_owned())
        );
        assert_eq!(
            rfc3339(UNIX_EPOCH + Duration::from_secs(1_735_689_599)),
            "2024-12-31T23:59:59Z"
        );
    }
}
