//! A driver test binary's whole run, shared by `tests/drivers.rs` and `tests/swiftshader.rs`:
//! each driver in child processes of its own (Mesa and the Vulkan loader read their choice of
//! driver from the environment when they load), its hand-checked findings first, then every
//! rule, its verdict checked against its expectation file, `expectations/NAME.txt` (the file
//! `.ci/run` gives `refrast certify --expect`): a rule that fails, passes or changes status
//! against it is reported, with the line to change.

use std::path::PathBuf;
use std::process::Command;

use refrast::Rasterizer;
use refrast_conformance::expect::Expectations;
use refrast_conformance::isolate::{certify_isolated_jobs, serve_rule};
use refrast_conformance::{Options, Report, Rule};
use refrast_wgpu::{Driver, Gpu};

/// Runs every check of `findings` through `run`, whatever the others do; each that panicked,
/// as `WHAT: its message`: a moved finding hides no other.
pub fn moved_findings<F: Copy>(findings: &[(&str, F)], mut run: impl FnMut(F)) -> Vec<String> {
    findings
        .iter()
        .filter_map(|&(what, check)| {
            let panicked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(check))).err()?;
            let why = panicked
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panicked.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                .unwrap_or_default();
            Some(format!("{what}: {why}"))
        })
        .collect()
}

/// The variable naming the rule a child certifies.
const RULE_ENV: &str = "REFRAST_DRIVER_TEST_RULE";
/// The variable naming the driver a child opens.
const DRIVER_ENV: &str = "REFRAST_DRIVER_TEST_DRIVER";
/// The variable asking a child for the driver's findings.
const FINDINGS_ENV: &str = "REFRAST_DRIVER_TEST_FINDINGS";
/// The exit code of a findings child whose driver is missing.
const UNAVAILABLE: i32 = 3;

/// What a driver test binary certifies, and how.
pub struct Certification {
    /// The drivers, in order.
    pub drivers: &'static [Driver],
    /// The variable that, set to 1, makes a driver that cannot be opened a failure, not a skip.
    pub required: &'static str,
    /// Cases per rule, for the closing line.
    pub cases: u32,
    /// The options of every rule's certification.
    pub options: fn() -> Options,
    /// The hand-checked findings, run in a child with the driver open; a moved one panics.
    pub findings: fn(Driver, &mut Gpu),
}

/// The test binary's `main`: a rule's or a findings child when the environment says so, else
/// the parent, which runs each driver's findings and then its rules in children, and fails on
/// a moved finding or verdict.
pub fn run(c: &Certification) {
    let driver = || {
        let name = std::env::var(DRIVER_ENV).expect("the child is told its driver");
        Driver::ALL
            .into_iter()
            .find(|d| d.name() == name)
            .expect("a driver name")
    };
    if let Ok(id) = std::env::var(RULE_ENV) {
        let d = driver();
        let served = serve_rule(
            &id,
            || Ok(Box::new(Gpu::new(d)?) as Box<dyn Rasterizer>),
            &(c.options)(),
        );
        std::process::exit(if served { 0 } else { 2 });
    }
    if std::env::var(FINDINGS_ENV).is_ok() {
        let d = driver();
        let mut gpu = match Gpu::new(d) {
            Ok(gpu) => gpu,
            Err(why) => {
                println!("{why}");
                std::process::exit(UNAVAILABLE);
            }
        };
        (c.findings)(d, &mut gpu);
        std::process::exit(0);
    }
    let required = std::env::var(c.required).as_deref() == Ok("1");
    let exe = std::env::current_exe().expect("this test binary");
    let with_env = |d: Driver| {
        let mut command = Command::new(&exe);
        for (name, value) in d.env() {
            command.env(name, value);
        }
        command.env(DRIVER_ENV, d.name());
        command
    };
    let mut moved = Vec::new();
    for &d in c.drivers {
        let output = with_env(d)
            .env(FINDINGS_ENV, "1")
            .output()
            .expect("the child starts");
        let stdout = String::from_utf8_lossy(&output.stdout);
        if output.status.code() == Some(UNAVAILABLE) {
            assert!(!required, "{}: {} is set, but {stdout}", d.name(), c.required);
            println!("{}: SKIPPED: {stdout}", d.name());
            continue;
        }
        assert!(
            output.status.success(),
            "{}: a hand-checked finding moved:\n{stdout}\n{}",
            d.name(),
            String::from_utf8_lossy(&output.stderr)
        );
        print!("{stdout}");
        let command = |rule: &Rule| {
            let mut command = with_env(d);
            command.env(RULE_ENV, rule.id);
            command
        };
        let report = certify_isolated_jobs(&command, &(c.options)(), jobs(), |_| {})
            .expect("the driver was there a moment ago");
        println!("{}", tally(d.name(), &report, c.cases));
        moved.extend(self::moved(d.name(), &report));
    }
    assert!(moved.is_empty(), "verdicts moved:\n{}", moved.join("\n"));
}

/// Rules certified at once, each in its child: one per core (each child's driver may use
/// threads of its own, but the oracles checking its output are single-threaded).
pub fn jobs() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// The expectation file of the implementation `name`.
pub fn file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../expectations")
        .join(format!("{name}.txt"))
}

/// Every rule of `report` whose status `expectations/NAME.txt` does not accept for `name`.
pub fn moved(name: &str, report: &Report) -> Vec<String> {
    let path = file(name);
    let expect = Expectations::load(std::slice::from_ref(&path)).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        expect.section(name).is_some(),
        "{} has no section [{name}]",
        path.display()
    );
    expect
        .check(name, report)
        .iter()
        .map(ToString::to_string)
        .collect()
}

/// The closing line of a certification checked against its expectations.
pub fn tally(name: &str, report: &Report, cases: u32) -> String {
    let (pass, fail, na) = report.tally();
    format!(
        "{name}: {pass} passed, {fail} failed, {} beyond the claimed specification, {na} not \
         applicable ({cases} cases per rule)",
        report.beyond_spec()
    )
}
