//! A driver's verdicts pinned rule by rule: which rules fail, which fail only beyond the
//! specification the profile claims, which do not apply; every other rule passes.

use refrast_conformance::{Report, Status};

/// Space-separated rule IDs per status other than pass.
pub struct Pinned {
    /// Failures of conformance to the claimed specification.
    pub fail: &'static str,
    /// Failures on what the claimed specification leaves open (`beyond-spec`).
    pub beyond: &'static str,
    /// Rules that do not apply to the profile.
    pub not_applicable: &'static str,
}

impl Pinned {
    /// The status pinned for rule `id`.
    pub fn status(&self, id: &str) -> Status {
        let listed = |list: &str| list.split_whitespace().any(|r| r == id);
        if listed(self.fail) {
            Status::Fail
        } else if listed(self.beyond) {
            Status::BeyondSpec
        } else if listed(self.not_applicable) {
            Status::NotApplicable
        } else {
            Status::Pass
        }
    }

    /// Every rule of `report` whose status is not the pinned one, with its message.
    pub fn moved(&self, report: &Report) -> Vec<String> {
        report
            .rules
            .iter()
            .filter(|r| r.status != self.status(&r.id))
            .map(|r| {
                format!(
                    "{}: expected {}, got {} ({:?})",
                    r.id,
                    self.status(&r.id).label(),
                    r.status.label(),
                    r.message
                )
            })
            .collect()
    }
}

/// The closing line of a pinned certification.
pub fn tally(name: &str, report: &Report, cases: u32) -> String {
    let (pass, fail, na) = report.tally();
    format!(
        "{name}: {pass} passed, {fail} failed, {} beyond the claimed specification, {na} not \
         applicable ({cases} cases per rule)",
        report.beyond_spec()
    )
}
