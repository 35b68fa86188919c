//! Expectation files read and written: the last matching line decides, a rule no line matches
//! is expected to pass, and a written file reads back to the verdicts it was written from.

use refrast_conformance::expect::{Expectations, MAY_FAIL, Taken, write};
use refrast_conformance::{ProfileReport, Report, RuleReport, Status, catalogue};

fn report(statuses: &[(&str, Status)]) -> Report {
    Report {
        implementation: "x".into(),
        profile: ProfileReport::unknown(),
        rules: statuses
            .iter()
            .map(|(id, status)| {
                let rule = catalogue()
                    .into_iter()
                    .find(|r| r.id == *id)
                    .expect("a rule of the catalogue");
                RuleReport {
                    status: *status,
                    cases: 1,
                    planned: 1,
                    message: Some("why it failed".into()),
                    ..RuleReport::new(&rule, 1, 1)
                }
            })
            .collect(),
        not_run: Vec::new(),
        refused: None,
    }
}

#[test]
fn the_last_matching_line_decides_and_unlisted_rules_pass() {
    let e = Expectations::parse(
        "taken cases=300 seed=5 scale=2 budget=20\n[x]\nfill.*  fail  # all\nfill.interior.matches-raycast  may-fail\n",
        "e.txt",
    )
    .expect("parses");
    assert_eq!(
        e.taken[0].1,
        Taken {
            cases: Some(300),
            seed: 5,
            scale: 2,
            budget: Some(20.0)
        }
    );
    let s = e.section("x").expect("a section");
    assert_eq!(s.expected("fill.mesh.exactly-once").0, vec![Status::Fail]);
    assert_eq!(s.expected("fill.interior.matches-raycast").0, MAY_FAIL.to_vec());
    assert_eq!(s.expected("bary.sum.one").0, vec![Status::Pass]);
    let r = report(&[
        ("fill.mesh.exactly-once", Status::Crash),
        ("fill.interior.matches-raycast", Status::Pass),
        ("bary.sum.one", Status::Pass),
    ]);
    let m = e.check("x", &r);
    assert_eq!(m.len(), 1, "{m:?}");
    assert_eq!(
        (m[0].rule.as_str(), m[0].got),
        ("fill.mesh.exactly-once", Status::Crash)
    );
}

#[test]
fn written_files_read_back_to_the_same_verdicts() {
    let r = report(&[
        ("fill.mesh.exactly-once", Status::Fail),
        ("clip.far.respected", Status::NotApplicable),
        ("bary.sum.one", Status::Pass),
        ("robust.output.well-formed", Status::Timeout),
    ]);
    let taken = Taken {
        cases: None,
        seed: 9,
        scale: 1,
        budget: None,
    };
    let text = write(&Expectations::default(), &taken, &[("x", &r)]);
    let back = Expectations::parse(&text, "written").expect("parses");
    assert!(back.check("x", &r).is_empty(), "{text}");
    assert_eq!(back.taken[0].1, taken);
    assert!(text.contains("# why it failed"), "{text}");
    assert!(!text.contains("bary.sum.one"), "passes are not written: {text}");
}
