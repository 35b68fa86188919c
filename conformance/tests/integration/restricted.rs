//! The restricted-profile matrix: the reference restricted to each setting's values (and a few
//! combinations), using only those whatever a draw asks, passes or is `n/a` on every rule, and
//! the rules that go `n/a` under each restriction are the ones `docs/profiles.md` lists.
//!
//! A few cases a rule here (`REFRAST_MATRIX_CASES`, default 24); the long-run form is
//! `refrast certify --impl 'restricted:*'` at every rule's default cases.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use refrast_conformance::{Options, Status, certify};
use refrast_zoo::restricted::restrictions;

/// Cases per rule: few, since the matrix is wide; the nightly run takes each rule's default.
fn cases() -> u32 {
    std::env::var("REFRAST_MATRIX_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(24)
}

/// The docs table: one row per restriction, the rules it leaves `n/a` and why.
fn not_applicable_table(rows: &BTreeMap<String, Vec<(String, String)>>) -> String {
    let mut table = String::from("| restriction | n/a | rules not applicable, and why |\n|---|---|---|");
    for (name, na) in rows {
        let why: Vec<String> = na
            .iter()
            .map(|(id, reason)| format!("`{id}` ({reason})"))
            .collect();
        let listed = if why.is_empty() {
            "none".to_owned()
        } else {
            why.join("; ")
        };
        let _ = write!(table, "\n| `restricted:{name}` | {} | {listed} |", na.len());
    }
    table
}

#[test]
fn every_restricted_reference_passes_or_is_not_applicable() {
    let options = Options {
        cases: Some(cases()),
        ..Options::default()
    };
    let mut failures = Vec::new();
    let mut rows = BTreeMap::new();
    for restriction in restrictions() {
        let mut r = (restriction.make)();
        let report = certify(&mut r, &options, |_| {});
        assert_eq!(
            report.refused, None,
            "restricted:{} was refused",
            restriction.name
        );
        for rule in &report.rules {
            if rule.status == Status::Fail {
                failures.push(format!(
                    "restricted:{} fails {}: {}\n{}",
                    restriction.name,
                    rule.id,
                    rule.message.as_deref().unwrap_or(""),
                    rule.counterexample.as_deref().unwrap_or("")
                ));
            }
        }
        let na: Vec<(String, String)> = report
            .rules
            .iter()
            .filter(|r| r.status == Status::NotApplicable)
            .map(|r| (r.id.clone(), r.message.clone().unwrap_or_default()))
            .collect();
        rows.insert(restriction.name.clone(), na);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    let table = not_applicable_table(&rows);
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/profiles.md"))
        .unwrap_or_default();
    assert!(
        docs.contains(&table),
        "docs/profiles.md does not hold the n/a table the matrix measured; put this in it:\n\n{table}\n"
    );
}

/// The reference snapping down (within one grid step of x/w), by name.
fn snapping_down() -> refrast_zoo::restricted::Restricted {
    let r = restrictions()
        .into_iter()
        .find(|r| r.name == "snap=floor")
        .expect("listed");
    (r.make)()
}

/// Regressions of the full matrix (`certify --impl 'restricted:*'`): with snapping within one
/// step an edge moves up to √2 grid steps, not √2/2, and the band of one step failed the floor
/// reference on a sample that close to an edge (fill.interior.matches-raycast at case 2563,
/// clip.far.respected at 2546, clip.gl-range.matches-raycast at 1521). The band is two steps
/// for such a profile now (`Profile::band_px`).
#[test]
fn snapping_within_one_step_is_judged_outside_two_steps_of_an_edge() {
    use refrast::{CompareOp, CullMode, DepthRange, DepthState, Distances, DrawState, FrontFace};
    use refrast_conformance::Scene;
    use refrast_conformance::rules::fill::check_exactly_once;
    let state = |range, clip_far| DrawState {
        cull: CullMode::None,
        front_face: FrontFace::CounterClockwise,
        depth: DepthState {
            compare: CompareOp::Less,
            write: true,
            clear: 1.0,
        },
        depth_range: range,
        clip_far,
        scissor: None,
        ..refrast::DrawState::default()
    };
    let scenes = [
        (
            32,
            32,
            [
                [-0.036305554, -0.08583549, 0.0, 0.1],
                [0.0, 0.0, 0.0, 0.1],
                [0.05969065, -0.014887135, 0.0, 0.1],
            ],
            state(DepthRange::ZeroToOne, false),
        ),
        (
            64,
            80,
            [
                [0.0, 0.0, 0.0, 0.1],
                [0.021248478, 0.030762175, 0.0, 0.1],
                [-0.11996859, -0.10734619, 0.0, 0.1],
            ],
            state(DepthRange::ZeroToOne, true),
        ),
        (
            32,
            32,
            [
                [0.0077443034, -0.020770863, -0.14216962, 0.1],
                [0.0, 0.0, 0.0, 0.1],
                [-0.12880902, -0.046137314, 0.118317924, 0.1],
            ],
            state(DepthRange::NegativeOneToOne, false),
        ),
    ];
    let mut floor = snapping_down();
    for (width, height, positions, state) in scenes {
        let scene = Scene {
            width,
            height,
            positions: positions.to_vec(),
            triangles: vec![[0, 1, 2]],
            state,
            distances: Distances::default(),
        };
        check_exactly_once(&mut floor, &scene).unwrap_or_else(|v| panic!("{v}\n{scene:?}"));
    }
}
