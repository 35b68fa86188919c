//! How `refrast certify` runs: the options of one run, typed once as clap arguments and turned
//! here, and only here, into the suite's [`Options`] and the JSON document's [`RunOptions`].

use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::time::Duration;

use refrast_conformance::{Options, Shard};

use super::positive_seconds;
use crate::results::RunOptions;

/// The options of one run of the catalogue.
#[derive(clap::Args, Clone, Debug)]
pub struct RunArgs {
    /// Seconds of wall time per rule after which no new case starts; the report says how many
    /// ran [default: 10 for --exec, none for built-ins].
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub budget: Option<f64>,
    /// Cases per rule [default: PROPTEST_CASES, else each rule's own].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub cases: Option<u32>,
    /// Multiply the cases per rule by N (nightly runs use 10).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub scale: u32,
    /// Seed of the case generator.
    #[arg(long, value_name = "S", default_value_t = refrast_conformance::DEFAULT_SEED)]
    pub seed: u64,
    /// Only rules matching this glob (`fill.*`, `*.exact`); without `*`, a prefix (repeatable:
    /// rules matching any).
    #[arg(long, value_name = "PATTERN")]
    pub rule: Vec<String>,
    /// Only part I of N of the selected rules (every N-th in catalogue order, from the I-th),
    /// for a run split across machines; `refrast merge` joins the parts' --json reports.
    #[arg(long, value_name = "I/N", value_parser = |s: &str| s.parse::<Shard>())]
    pub shard: Option<Shard>,
    /// Seconds one case may take before the rule fails as hung (for --exec: one draw).
    #[arg(long, value_name = "SECONDS", default_value_t = refrast_conformance::DEFAULT_CASE_TIMEOUT.as_secs_f64(),
          value_parser = positive_seconds)]
    pub case_timeout: f64,
    /// The most memory, in MiB, each rule's child process and each --exec child may allocate
    /// (its data: heap and private mappings; 0 sets no limit). A child over it fails its rule
    /// as a crash that says so.
    #[arg(long, value_name = "MIB", default_value_t = refrast_pipe::contain::DEFAULT_MEMORY_LIMIT >> 20)]
    pub memory_limit: u64,
    /// Stop at the first failing rule: no rule starts after it, and the rules and implementations
    /// after it are listed as not run (results of later rules already running are dropped).
    #[arg(long)]
    pub fail_fast: bool,
    /// Rules run at once: each built-in's rule in its child process, across implementations
    /// too, and for --exec one rule at a time in each of N children started from CMD (a child
    /// that cannot run beside a copy of itself wants 1); verdicts, order and output are those
    /// of --jobs 1 but for times. --in-process runs one rule at a time whatever this says
    /// [default: the available parallelism].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,
    /// Run the rules in this process, one at a time, instead of one child process each (for a
    /// debugger or a profiler; a rasterizer that hangs or aborts then stops the whole run).
    #[arg(long)]
    pub in_process: bool,
}

impl RunArgs {
    /// The suite's options for this run.
    #[must_use]
    pub fn options(&self) -> Options {
        Options {
            cases: self.cases,
            scale: self.scale,
            seed: self.seed,
            rules: self.rule.clone(),
            shard: self.shard,
            case_timeout: Duration::from_secs_f64(self.case_timeout),
            budget: self.budget.map(Duration::from_secs_f64),
            fail_fast: self.fail_fast,
            memory_limit: (self.memory_limit > 0).then(|| self.memory_limit.saturating_mul(1 << 20)),
            ..Options::default()
        }
    }

    /// Rules run at once: `--jobs`, else the available parallelism.
    #[must_use]
    pub fn jobs(&self) -> usize {
        self.jobs.map_or_else(
            || std::thread::available_parallelism().map_or(1, NonZeroUsize::get),
            usize::from,
        )
    }

    /// The options as the JSON document records them, with the `expect` files judged.
    #[must_use]
    pub fn recorded(&self, expect: &[PathBuf]) -> RunOptions {
        RunOptions {
            cases: self.cases,
            proptest_cases: std::env::var("PROPTEST_CASES")
                .ok()
                .filter(|_| self.cases.is_none()),
            scale: self.scale,
            seed: self.seed,
            rules: self.rule.clone(),
            shard: self.shard,
            budget: self.budget,
            case_timeout: self.case_timeout,
            fail_fast: self.fail_fast,
            jobs: self.jobs(),
            in_process: self.in_process,
            memory_limit_mib: (self.memory_limit > 0).then_some(self.memory_limit),
            expect: expect.to_vec(),
        }
    }
}
