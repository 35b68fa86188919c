//! Every mutant fails `certify`, on a rule of the family its documentation names, with a small
//! counterexample; the suite keeps passing the reference.

use std::time::Instant;

use refrast_conformance::{Family, Options, Status, certify_with};
use refrast_zoo::mutant::{Bug, Mutant};

/// One copy of a rasterizer per core, for [`certify_with`] to run that many rules at once.
fn copies<R>(make: impl Fn() -> R) -> Vec<R> {
    let n = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    (0..n).map(|_| make()).collect()
}

#[test]
fn every_mutant_is_caught_by_its_family_with_a_small_counterexample() {
    let mut table = Vec::new();
    let mut problems = Vec::new();
    for bug in Bug::ALL {
        let start = Instant::now();
        let options = Options {
            cases: Some(300),
            ..Options::default()
        };
        let report = certify_with(&mut copies(|| Mutant::new(bug)), &options, |_| {});
        let failed: Vec<_> = report.rules.iter().filter(|r| r.status == Status::Fail).collect();
        let family = bug.caught_by();
        let triangles_of = |input: &str| {
            input
                .lines()
                .find(|l| l.trim_start().starts_with("triangles:"))
                .map_or(0, |l| l.matches('[').count() - 1)
        };
        // The family's failing rule with the smallest counterexample: the one to read first.
        let by_family = failed
            .iter()
            .filter(|r| r.family.name() == family)
            .min_by_key(|r| triangles_of(r.counterexample.as_deref().unwrap_or("")));
        let Some(rule) = by_family else {
            let ids: Vec<_> = failed.iter().map(|r| r.id.as_str()).collect();
            problems.push(format!(
                "mutant {} not caught by a {} rule; failed: {ids:?}",
                bug.name(),
                family
            ));
            continue;
        };
        let input = rule.counterexample.as_deref().unwrap_or("");
        let triangles = triangles_of(input);
        if triangles > 3 {
            problems.push(format!(
                "mutant {}: {} shrunk to {triangles} triangles:\n{input}",
                bug.name(),
                rule.id
            ));
        }
        table.push((
            bug.name(),
            rule.id.clone(),
            triangles,
            failed.len(),
            start.elapsed().as_secs_f64(),
        ));
    }
    println!("| mutant | caught by | triangles | rules failed | certify time |");
    for (name, rule, n, failed, secs) in &table {
        println!("| `mutant:{name}` | `{rule}` | {n} | {failed} | {secs:.1} s |");
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Each mutant names a family the catalogue has, and its primitive bugs (lines, points, samples)
/// are exactly those of the three families the mutant then declares.
#[test]
fn every_mutant_names_a_family_of_the_catalogue() {
    let families: Vec<&str> = refrast_conformance::catalogue()
        .iter()
        .map(|r| r.family.name())
        .collect();
    for bug in Bug::ALL {
        assert!(
            families.contains(&bug.caught_by()),
            "mutant {} names the family `{}`, which no rule of the catalogue has",
            bug.name(),
            bug.caught_by()
        );
        let primitive = [Family::Line, Family::Point, Family::Msaa]
            .iter()
            .any(|f| f.name() == bug.caught_by());
        assert_eq!(bug.is_primitive(), primitive, "mutant {}", bug.name());
    }
}

#[test]
fn a_consistent_but_misdeclared_convention_fails_only_exact_rules() {
    let options = Options {
        cases: Some(300),
        ..Options::default()
    };
    let report = certify_with(
        &mut copies(|| Mutant::new(Bug::BottomRightAsTopLeft)),
        &options,
        |_| {},
    );
    let failed: Vec<_> = report.rules.iter().filter(|r| r.status == Status::Fail).collect();
    assert!(!failed.is_empty());
    for r in failed {
        assert_eq!(
            r.kind,
            refrast_conformance::Kind::Exact,
            "{} failed: the suite called watertight coverage wrong",
            r.id
        );
    }
}

#[test]
fn a_correct_rasterizer_declaring_another_convention_passes_everything() {
    for fill in [
        refrast::FillConvention::BottomRight,
        refrast::FillConvention::TopRight,
    ] {
        let config = refrast::ReferenceConfig {
            fill,
            ..refrast::ReferenceConfig::default()
        };
        let mut others = copies(|| refrast_zoo::Named::new("other-convention", config));
        let options = Options {
            cases: Some(300),
            ..Options::default()
        };
        let report = certify_with(&mut others, &options, |_| {});
        let failed: Vec<_> = report
            .rules
            .iter()
            .filter(|r| r.status == Status::Fail)
            .map(|r| &r.id)
            .collect();
        assert!(failed.is_empty(), "{fill:?}: {failed:?}");
    }
}
