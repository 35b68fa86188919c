//! A rasterizer that hangs, aborts or prints to stdout, run as `certify` runs rules: in a child
//! process. The hang and the abort fail the rule with a message naming what happened and the
//! case it happened on; the noise does no harm; a profile the suite cannot judge is refused by
//! the child before the rule runs, in a child as in this process. (This file is its own
//! harness: started with `ISOLATION_CHILD` set, it is the child.)

use std::process::Command;
use std::time::{Duration, Instant};

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Supported};
use refrast_conformance::isolate::{Outcome, run_rule_isolated, serve_rule};
use refrast_conformance::{Options, Status, catalogue, certify};

/// The reference, misbehaving on any draw with a vertex far outside the view (|x| > 1000·|w|).
struct Misbehaving(&'static str);

impl Rasterizer for Misbehaving {
    fn profile(&self) -> Profile {
        let mut profile = Profile {
            name: format!("misbehaving-{}", self.0),
            ..Reference::default().profile()
        };
        if self.0 == "unjudgeable" {
            profile.features.cull_modes = Supported::only(&[]);
        }
        profile
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let far = draw.positions.iter().any(|p| p[0].abs() > 1000.0 * p[3].abs());
        match self.0 {
            "hang" if far => loop {
                std::thread::sleep(Duration::from_secs(1));
            },
            "abort" if far => {
                eprintln!("about to abort on purpose");
                std::process::abort();
            }
            "noise" => println!("a line the rasterizer prints on its own"),
            _ => {}
        }
        Reference::default().rasterize(draw)
    }
}

const RULE: &str = "clip.interior.matches-raycast";

fn options() -> Options {
    Options {
        cases: Some(300),
        case_timeout: Duration::from_secs(3),
        ..Options::default()
    }
}

fn main() {
    if let Ok(kind) = std::env::var("ISOLATION_CHILD") {
        let kind: &'static str = Box::leak(kind.into_boxed_str());
        let served = serve_rule(RULE, || Ok(Box::new(Misbehaving(kind))), &options());
        std::process::exit(if served { 0 } else { 2 });
    }
    let rule = catalogue()
        .into_iter()
        .find(|r| r.id == RULE)
        .expect("the rule exists");
    let run = |kind: &'static str| {
        let mut child = Command::new(std::env::current_exe().expect("this test binary"));
        child.env("ISOLATION_CHILD", kind);
        let start = Instant::now();
        let Outcome::Ran(report, _) = run_rule_isolated(&rule, child, &options()) else {
            panic!("the misbehaving rasterizer builds anywhere");
        };
        (*report, start.elapsed())
    };

    let (hang, took) = run("hang");
    assert_eq!(hang.status, Status::Timeout, "{hang:#?}");
    let message = hang.message.clone().unwrap_or_default();
    assert!(message.contains("no answer within 3 s"), "{message}");
    let case = hang.counterexample.clone().unwrap_or_default();
    assert!(case.contains("positions"), "the hung case is named: {case}");
    assert!(
        took < Duration::from_secs(60),
        "the hung child was stopped, after {took:?}"
    );

    let (abort, _) = run("abort");
    assert_eq!(abort.status, Status::Crash, "{abort:#?}");
    let message = abort.message.clone().unwrap_or_default();
    assert!(message.contains("SIGABRT"), "{message}");
    assert!(
        message.contains("about to abort on purpose"),
        "stderr is shown: {message}"
    );
    assert!(abort.counterexample.is_some(), "the case it aborted on is named");

    let (noise, _) = run("noise");
    assert_eq!(noise.status, Status::Pass, "{noise:#?}");

    // No cull mode at all: refused in the child, before the rule, and in this process alike.
    let mut child = Command::new(std::env::current_exe().expect("this test binary"));
    child.env("ISOLATION_CHILD", "unjudgeable");
    let Outcome::Refused(why, profile) = run_rule_isolated(&rule, child, &options()) else {
        panic!("a profile with no cull mode is refused");
    };
    assert!(why.contains("no value of cull_modes"), "{why}");
    assert_eq!(
        profile.map(|p| p.name).as_deref(),
        Some("misbehaving-unjudgeable")
    );
    let report = certify(&mut Misbehaving("unjudgeable"), &options(), |_| {
        panic!("no rule runs")
    });
    assert!(report.rules.is_empty() && !report.passed(), "{report:#?}");
    assert!(
        report
            .refused
            .unwrap_or_default()
            .contains("at least one of None, Back, Front")
    );

    println!(
        "isolation: a hang timed out and an abort crashed its rule, each with a message; noise did no harm; an \
         unjudgeable profile was refused"
    );
}
