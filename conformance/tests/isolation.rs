//! A rasterizer that hangs, aborts (always, or once), prints to stdout, allocates without bound, floods stdout
//! without a newline or leaves a grandchild behind, run as `certify` runs rules: in a child
//! process. The hang and the abort fail the rule with a message naming what happened and the
//! case it happened on (found again by a second run; an abort that run does not repeat is
//! said to be so); the noise does no harm; the allocation meets the memory limit and
//! fails its rule saying so; the flood costs refrast no memory; the grandchild does not outlive
//! the rule; a profile the suite cannot judge is refused by the child before the rule runs, in
//! a child as in this process. (This file is its own harness: started with `ISOLATION_CHILD`
//! set, it is the child; with `ISOLATION_GRANDCHILD` set, the grandchild.)

use std::process::Command;
use std::time::{Duration, Instant};

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference, Supported};
use refrast_conformance::isolate::{ChildRun, run_rule_isolated, serve_rule};
use refrast_conformance::{Options, Status, catalogue, certify};

mod support;

use support::{gone, resident};

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
            "flaky" if far => {
                // Aborts in the first process only: a second run goes past the case.
                let marker = std::env::var_os("ISOLATION_FLAKY_FILE").unwrap_or_default();
                if std::fs::exists(&marker).is_ok_and(|there| !there) {
                    let _ = std::fs::write(&marker, "aborted once");
                    std::process::abort();
                }
            }
            "noise" => println!("a line the rasterizer prints on its own"),
            "hog" if far => hog(),
            "flood" if far => flood(),
            "fork" if far => {
                // A grandchild that sleeps for an hour, then this child hangs.
                let _ = Command::new(std::env::current_exe().expect("this test binary"))
                    .env(
                        "ISOLATION_GRANDCHILD",
                        std::env::var_os("ISOLATION_PID_FILE").unwrap_or_default(),
                    )
                    .spawn();
                loop {
                    std::thread::sleep(Duration::from_secs(1));
                }
            }
            _ => {}
        }
        Reference::default().rasterize(draw)
    }
}

/// Allocates and touches 16 MiB at a time, up to 2 GiB: far past the limit the test sets.
fn hog() {
    let mut kept: Vec<Vec<u8>> = Vec::new();
    for _ in 0..128 {
        kept.push(vec![1; 16 << 20]);
    }
    eprintln!("allocated {} MiB without meeting a limit", kept.len() * 16);
}

/// Writes 4 GiB to stdout without a newline, then hangs.
fn flood() {
    use std::io::Write;
    let chunk = vec![b'x'; 1 << 20];
    let mut out = std::io::stdout().lock();
    for _ in 0..4096 {
        if out.write_all(&chunk).is_err() {
            break;
        }
    }
    loop {
        std::thread::sleep(Duration::from_secs(1));
    }
}

/// The file whose absence makes the flaky rasterizer abort (and which it then writes).
fn flaky_file() -> std::path::PathBuf {
    std::env::temp_dir().join(format!("refrast-isolation-flaky-{}", std::process::id()))
}

/// Where the grandchild writes its process ID (named by the test's process, passed down).
fn grandchild_file() -> std::path::PathBuf {
    std::env::temp_dir().join(format!("refrast-isolation-grandchild-{}", std::process::id()))
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
    if let Some(file) = std::env::var_os("ISOLATION_GRANDCHILD") {
        let _ = std::fs::write(file, std::process::id().to_string());
        std::thread::sleep(Duration::from_secs(3600));
        return;
    }
    if let Ok(kind) = std::env::var("ISOLATION_CHILD") {
        let kind: &'static str = Box::leak(kind.into_boxed_str());
        let served = serve_rule(RULE, || Ok(Box::new(Misbehaving(kind))), &options());
        std::process::exit(if served { 0 } else { 2 });
    }
    let rule = catalogue()
        .into_iter()
        .find(|r| r.id == RULE)
        .expect("the rule exists");
    let run_with = |kind: &'static str, options: &Options| {
        let mut child = Command::new(std::env::current_exe().expect("this test binary"));
        child
            .env("ISOLATION_CHILD", kind)
            .env("ISOLATION_PID_FILE", grandchild_file())
            .env("ISOLATION_FLAKY_FILE", flaky_file());
        let start = Instant::now();
        let ChildRun::Ran(report, _) = run_rule_isolated(&rule, child, options) else {
            panic!("the misbehaving rasterizer builds anywhere");
        };
        (*report, start.elapsed())
    };
    let run = |kind: &'static str| run_with(kind, &options());

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
    let case = abort.counterexample.clone().unwrap_or_default();
    assert!(
        case.contains("positions"),
        "the case it aborted on is named: {case}"
    );

    // An abort a second run does not repeat: the case goes unnamed, and the message says why.
    let _ = std::fs::remove_file(flaky_file());
    let (flaky, _) = run("flaky");
    let _ = std::fs::remove_file(flaky_file());
    assert_eq!(flaky.status, Status::Crash, "{flaky:#?}");
    let message = flaky.message.clone().unwrap_or_default();
    assert!(message.contains("SIGABRT"), "{message}");
    assert!(
        message.contains("a second run, to name that input, did not stop on it"),
        "{message}"
    );
    assert_eq!(flaky.counterexample, None);

    let (noise, _) = run("noise");
    assert_eq!(noise.status, Status::Pass, "{noise:#?}");

    // 256 MiB for the rule's process: the allocation fails there, and the rule says why.
    let limited = Options {
        memory_limit: Some(256 << 20),
        ..options()
    };
    let (hog, took) = run_with("hog", &limited);
    assert_eq!(hog.status, Status::Crash, "{hog:#?}");
    let message = hog.message.clone().unwrap_or_default();
    assert!(message.contains("limited to 256 MiB"), "{message}");
    assert!(message.contains("memory allocation of"), "{message}");
    assert!(took < Duration::from_secs(60), "after {took:?}");

    // 4 GiB of stdout without a newline: refrast reads it all (else the child blocks and
    // times out, as it does after) and keeps at most one cut line of it.
    let before = resident();
    let (flood, _) = run("flood");
    assert_eq!(flood.status, Status::Timeout, "{flood:#?}");
    if let (Some(before), Some(after)) = (before, resident()) {
        let grew = after.saturating_sub(before);
        assert!(
            grew < 128 << 20,
            "refrast grew by {} MiB reading the flood",
            grew >> 20
        );
    }

    // A grandchild left asleep: gone once the rule is over (its process group is killed).
    let _ = std::fs::remove_file(grandchild_file());
    let (fork, _) = run("fork");
    assert_eq!(fork.status, Status::Timeout, "{fork:#?}");
    let pid: u32 = std::fs::read_to_string(grandchild_file())
        .expect("the grandchild wrote its process ID")
        .trim()
        .parse()
        .expect("a process ID");
    let _ = std::fs::remove_file(grandchild_file());
    let deadline = Instant::now() + Duration::from_secs(5);
    while !gone(pid) && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(gone(pid), "the grandchild {pid} outlived its rule");

    // No cull mode at all: refused in the child, before the rule, and in this process alike.
    let mut child = Command::new(std::env::current_exe().expect("this test binary"));
    child.env("ISOLATION_CHILD", "unjudgeable");
    let ChildRun::Refused(why, profile) = run_rule_isolated(&rule, child, &options()) else {
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
        "isolation: a hang timed out and an abort crashed its rule, each with a message and its case (an abort \
         a second run did not repeat, without); noise did no harm; an \
         allocation without bound met the memory limit; a flood cost no memory; a grandchild did not outlive its \
         rule; an unjudgeable profile was refused"
    );
}
