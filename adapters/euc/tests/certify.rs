//! Certifies euc with every rule in a child process (this binary again), as `refrast certify`
//! does, and checks each rule's verdict against `expectations/euc.txt`, what the hand checks
//! found (docs/certified.md, "Certified implementations"). Also checks the crash on its own: a vertex at
//! x = 10¹⁰·w makes euc panic (debug builds: its own assertion or an overflow) or write out of
//! bounds and die (release builds).

use std::process::Command;
use std::time::Duration;

use refrast::{Draw, Rasterizer, Viewport};
use refrast_conformance::Options;
use refrast_conformance::expect::Expectations;
use refrast_conformance::isolate::{certify_isolated, serve_rule};
use refrast_euc::Euc;

const RULE_ENV: &str = "EUC_CERTIFY_RULE";
const CRASH_ENV: &str = "EUC_CERTIFY_CRASH";

/// The verdicts the hand checks confirm, with why each is what it is, and which ones differ
/// between a debug and a release build of euc (its `debug_assert!`s).
const EXPECTATIONS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../expectations/euc.txt");

/// At 300 cases a rule, as `expectations/euc.txt` was taken.
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
    let expect = Expectations::load(&[EXPECTATIONS.into()]).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        expect.section("euc").is_some(),
        "{EXPECTATIONS} has a section [euc]"
    );
    let moved: Vec<String> = expect
        .check("euc", &report)
        .iter()
        .map(ToString::to_string)
        .collect();
    assert!(
        moved.is_empty(),
        "euc's verdicts moved (a fix in euc, or a change in refrast? check by hand, then update \
         {EXPECTATIONS}):\n{}",
        moved.join("\n")
    );
    println!("euc: every verdict as expected");
}
