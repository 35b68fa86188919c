//! Certifies euc with every rule in a child process (this binary again), as `refrast certify`
//! does, and checks each rule's verdict against what the hand checks found (README,
//! "Certified implementations"). Also checks the crash on its own: a vertex at x = 10¹⁰·w makes
//! euc panic (debug builds: its own assertion or an overflow) or write out of bounds and die
//! (release builds).

use std::process::Command;
use std::time::Duration;

use refrast::{Draw, Rasterizer, Viewport};
use refrast_conformance::isolate::{certify_isolated, serve_rule};
use refrast_conformance::{Options, Status};
use refrast_euc::Euc;

const RULE_ENV: &str = "EUC_CERTIFY_RULE";
const CRASH_ENV: &str = "EUC_CERTIFY_CRASH";

/// The verdicts the hand checks confirm, at the cases below.
const FAIL: &str = "fill.mesh.exactly-once fill.fan.exactly-once fill.projected-mesh.exactly-once \
    bary.perspective.matches-raycast \
    depth.screen-linear.matches-raycast clip.behind-eye.empty clip.interior.matches-raycast \
    clip.mesh.watertight clip.crossing-quad.watertight meta.reversal.flips-facing meta.facing.from-winding meta.degenerate.empty \
    robust.non-finite.discarded robust.bit-patterns.sane-output robust.output.well-formed \
    bary.range.unit meta.cull.by-facing";
// The last two failed once crossing scenes reached w = 0 vertices (issue 12): euc panics
// there in debug builds (findings.rs, finding 6).
const PASS: &str = "fill.rotated-quad.exactly-once fill.interior.matches-raycast bary.sum.one \
    bary.vertex.one depth.range.vertices meta.rotation.same-coverage \
    depth.order.independent depth.resolve.matches-fragments meta.translate.whole-pixels \
    meta.translate.one-subpixel \
    meta.viewport.neutral meta.batch.independent robust.bad-index.error";
const NOT_APPLICABLE: &str = "fill.top-left.exact fill.guard-band.exact fill.brute-force.exact \
    bary.screen.reconstructs-sample bary.equal-w.affine clip.far.respected clip.gl-range.matches-raycast";

fn options() -> Options {
    Options {
        cases: Some(300),
        case_timeout: Duration::from_secs(60),
        ..Options::default()
    }
}

fn main() {
    if let Ok(id) = std::env::var(RULE_ENV) {
        let served = serve_rule(&id, || Ok(Box::new(Euc)), &options());
        std::process::exit(if served { 0 } else { 2 });
    }
    if std::env::var_os(CRASH_ENV).is_some() {
        let far = Draw::new(
            Viewport::new(16, 16).expect("a valid viewport"),
            vec![
                [0.5, 0.5, 0.5, 1.0],
                [-0.5, 0.5, 0.5, 1.0],
                [1e10, -0.5, 0.5, 1.0],
            ],
            vec![[0, 1, 2]],
        );
        let mut draw = far;
        draw.state = Euc.profile().fit(draw.state);
        let fragments = Euc.rasterize(&draw);
        println!("survived with {:?} fragments", fragments.map(|f| f.len()));
        std::process::exit(0);
    }
    let exe = std::env::current_exe().expect("this test binary");

    // The crash: a child that draws one triangle with a vertex at x = 1e10 must not survive it.
    let output = Command::new(&exe)
        .env(CRASH_ENV, "1")
        .output()
        .expect("the child starts");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success(),
        "euc survived a vertex at 1e10: {output:?}"
    );
    assert!(
        stderr.contains("triangles.rs") || output.status.code().is_none(),
        "a panic inside euc's rasterizer, or a signal: {output:?}"
    );

    // The whole catalogue.
    let command = |rule: &refrast_conformance::Rule| {
        let mut c = Command::new(&exe);
        c.env(RULE_ENV, rule.id);
        c
    };
    let report = certify_isolated(&command, &options(), |_| {}).expect("euc builds anywhere");
    let (pass, fail, na) = report.tally();
    println!("euc: {pass} passed, {fail} failed, {na} not applicable (300 cases per rule)");
    let mut wrong = Vec::new();
    for (ids, status) in [
        (FAIL, Status::Fail),
        (PASS, Status::Pass),
        (NOT_APPLICABLE, Status::NotApplicable),
    ] {
        for id in ids.split_whitespace() {
            let got = report.rules.iter().find(|r| r.id == id).map(|r| r.status);
            if got != Some(status) {
                let message = report
                    .rules
                    .iter()
                    .find(|r| r.id == id)
                    .and_then(|r| r.message.clone());
                wrong.push(format!(
                    "{id}: expected {}, got {got:?} ({message:?})",
                    status.label()
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "euc's verdicts moved:\n{}", wrong.join("\n"));
    let listed = [FAIL, PASS, NOT_APPLICABLE]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .count();
    assert_eq!(listed, report.rules.len(), "every rule has an expected verdict");
    println!("euc: every verdict as the hand checks found");
}
