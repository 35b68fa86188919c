//! A driver's verdicts checked against its expectation file, `expectations/NAME.txt` (the file
//! `.ci/run` gives `refrast certify --expect`): a rule that fails, passes or changes status
//! against it is reported, with the line to change.

use std::path::PathBuf;

use refrast_conformance::Report;
use refrast_conformance::expect::Expectations;

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
