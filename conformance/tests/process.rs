//! `Process` against children that misbehave on purpose: each bad child is a failed draw with a
//! message that says which, never a panic or a hang, and the child is restarted for the next.
//!
//! The children are this test binary again: with `REFRAST_FAKE_CHILD=MODE` it speaks the
//! protocol (docs/protocol.md) over the reference, misbehaving as MODE says. With
//! `REFRAST_AS_TESTS=1` it is an outside crate's `run_as_tests` over such a child.

use std::io::{BufRead, Read, Write};
use std::time::{Duration, Instant};

use libtest_mimic::{Arguments, Failed, Trial};
use refrast::{
    CompareOp, CullMode, DepthRange, Draw, DrawError, FrontFace, Rasterizer, Reference, Topology, Viewport,
};
use refrast_conformance::{Options, Status, certify};
use refrast_pipe::wire::{self, Word};
use refrast_pipe::{Process, ProcessError};

mod support;

use support::{gone, resident};

const MODE: &str = "REFRAST_FAKE_CHILD";

fn main() {
    if let Ok(mode) = std::env::var(MODE) {
        fake_child(&mode);
        return;
    }
    if std::env::var_os("REFRAST_AS_TESTS").is_some() {
        refrast_conformance::run_as_tests(|| Process::spawn(&child("good")));
    }
    let trials = vec![
        trial(
            "a_good_child_draws_what_the_reference_draws",
            a_good_child_draws_what_the_reference_draws,
        ),
        trial(
            "a_crash_fails_the_draw_with_its_signal_and_stderr_and_the_child_restarts",
            crash,
        ),
        trial("a_hang_fails_the_draw_at_the_timeout", hang),
        trial("a_malformed_reply_is_named", malformed),
        trial("a_truncated_reply_is_named", truncated),
        trial("a_count_too_high_is_named", count_too_high),
        trial("a_count_too_low_is_named", count_too_low),
        trial("a_fragment_outside_the_viewport_is_named", outside),
        trial("a_fragment_naming_no_primitive_is_named", bad_primitive),
        trial("a_resolve_of_the_wrong_size_is_named", wrong_size),
        trial("a_refusal_is_an_error_and_no_restart", refusal),
        trial("a_version_mismatch_says_both_versions", version_mismatch),
        trial(
            "a_version_2_child_draws_what_the_reference_draws",
            a_version_2_child_draws_what_the_reference_draws,
        ),
        trial(
            "a_sample_the_draw_lacks_is_named",
            a_sample_the_draw_lacks_is_named,
        ),
        trial(
            "a_version_2_child_draws_lines_points_and_samples",
            a_version_2_child_draws_lines_points_and_samples,
        ),
        trial(
            "a_version_3_child_reports_flat_values_in_its_mode_only",
            a_version_3_child_reports_flat_values,
        ),
        trial("a_bad_profile_line_is_named", bad_profile),
        trial("a_child_that_dies_at_start_shows_its_stderr", dies_at_start),
        trial("a_missing_program_is_a_start_error", missing_program),
        trial("spawn_never_fails_and_every_draw_says_why", spawn_never_fails),
        trial(
            "certify_fails_rules_of_a_crashing_child_and_goes_on",
            certify_crashing,
        ),
        trial("a_hanging_child_is_a_timeout_of_its_rule", certify_hanging),
        trial(
            "the_budget_stops_a_slow_child_and_says_how_many_cases_ran",
            budget,
        ),
        trial("run_as_tests_certifies_a_child", run_as_tests_child),
        trial(
            "a_child_flooding_stdout_costs_refrast_no_memory_and_is_named",
            flood,
        ),
        trial(
            "a_child_that_closes_stdin_and_runs_on_fails_at_the_timeout",
            closes_stdin,
        ),
        trial("a_grandchild_does_not_outlive_the_child_that_exited", grandchild),
        trial(
            "a_child_over_its_memory_limit_fails_the_draw_saying_so",
            memory_limit,
        ),
        trial(
            "the_exchange_in_protocol_md_is_what_refrast_sends_and_the_reference_draws",
            protocol_md_example,
        ),
    ];
    libtest_mimic::run(&Arguments::from_args(), trials).exit()
}

fn trial(name: &'static str, test: fn() -> Result<(), String>) -> Trial {
    Trial::test(name, move || test().map_err(Failed::from))
}

/// The command line that starts this binary as a fake child in `mode`.
fn child(mode: &str) -> String {
    let exe = std::env::current_exe().expect("the test binary has a path");
    format!("env {MODE}={mode} '{}'", exe.display())
}

fn spawn(mode: &str, timeout: f64) -> Process {
    Process::try_spawn_with(&child(mode), Duration::from_secs_f64(timeout))
        .unwrap_or_else(|e| panic!("the {mode} child should start: {e}"))
}

/// A draw of `n` triangles on an 8×8 target.
fn draw(n: usize) -> Draw {
    let viewport = Viewport::new(8, 8).expect("valid");
    let positions = vec![
        [-1.0, 1.0, 0.5, 1.0],
        [1.0, 1.0, 0.5, 1.0],
        [-1.0, -1.0, 0.5, 1.0],
        [1.0, -1.0, 0.25, 1.0],
    ];
    let triangles = [[0, 1, 2], [2, 1, 3]].into_iter().cycle().take(n).collect();
    Draw::new(viewport, positions, triangles)
}

/// `Err` unless `result` is a `Misbehaved` error whose message contains every one of `words`.
fn misbehaved<T: std::fmt::Debug>(result: Result<T, DrawError>, words: &[&str]) -> Result<(), String> {
    match result {
        Err(DrawError::Misbehaved(message)) => match words.iter().find(|w| !message.contains(*w)) {
            Some(w) => Err(format!("the message lacks `{w}`: {message}")),
            None => Ok(()),
        },
        other => Err(format!("expected a misbehaviour, got {other:?}")),
    }
}

fn a_good_child_draws_what_the_reference_draws() -> Result<(), String> {
    a_child_draws_what_the_reference_draws("good")
}

/// Version 2 draws as version 1 does: the same fragments and buffers, the reserved words sent.
fn a_version_2_child_draws_what_the_reference_draws() -> Result<(), String> {
    a_child_draws_what_the_reference_draws("v2")
}

/// A version 2 child declaring lines, points and 4 samples is sent them, and draws and resolves
/// them as the reference does; a version 1 child is never sent them (refused here, unasked).
fn a_version_2_child_draws_lines_points_and_samples() -> Result<(), String> {
    let mut p = spawn("v2", 10.0);
    let declared = p.profile();
    if declared.lines != Some(refrast::LineRule::DiamondExit)
        || !declared.points
        || declared.sample_counts() != [1, 4]
    {
        return Err(format!("the child's declaration reads as {declared:?}"));
    }
    let mut reference = Reference::default();
    let d = draw(2);
    let strip = Draw::of(
        d.viewport,
        d.positions.clone(),
        Topology::LineStrip,
        vec![0, 1, 3, 2],
    );
    let draws = [
        Draw::of(
            d.viewport,
            d.positions.clone(),
            Topology::LineList,
            vec![0, 3, 1, 2],
        ),
        strip.clone(),
        Draw::of(
            d.viewport,
            d.positions.clone(),
            Topology::PointList,
            vec![0, 1, 2, 3],
        ),
        d.clone().at_samples(4),
        strip.at_samples(4),
    ];
    for d in &draws {
        let what = d.describe();
        let got = p.rasterize(d).map_err(|e| format!("{what}: {e}"))?;
        if got != without_flat(reference.rasterize(d).map_err(|e| e.to_string())?) {
            return Err(format!("{what}: fragments differ"));
        }
        if p.resolve(d).map_err(|e| e.to_string())? != reference.resolve(d).map_err(|e| e.to_string())? {
            return Err(format!("{what}: resolve differs"));
        }
    }
    let mut v1 = spawn("good", 10.0);
    match v1.rasterize(&draws[0]) {
        Err(DrawError::Unsupported(why)) if why.contains("does not declare") => Ok(()),
        other => Err(format!("a version 1 child was sent a line list: {other:?}")),
    }
}

/// A version 3 child declaring the last provoking vertex is sent only that mode, whatever a draw
/// asks; its flat vertices come back under it, and are none for a draw asking the first.
fn a_version_3_child_reports_flat_values() -> Result<(), String> {
    let mut p = spawn("v3", 10.0);
    let mut reference = Reference::default();
    let mut d = Draw::of(
        draw(2).viewport,
        draw(2).positions,
        Topology::TriangleStrip,
        vec![0, 1, 2, 3],
    );
    let first = p.rasterize(&d).map_err(|e| e.to_string())?;
    if first.is_empty() || first.iter().any(|f| f.flat.is_some()) {
        return Err(format!("under the undeclared first mode: {first:?}"));
    }
    d.state.provoking_vertex = refrast::ProvokingVertex::Last;
    let last = p.rasterize(&d).map_err(|e| e.to_string())?;
    if last != reference.rasterize(&d).map_err(|e| e.to_string())? || last.iter().any(|f| f.flat.is_none()) {
        return Err(format!("under the last mode, fragments differ: {last:?}"));
    }
    Ok(())
}

/// Version 2's sample word names a sample the draw has: only 0 at one sample a pixel.
fn a_sample_the_draw_lacks_is_named() -> Result<(), String> {
    misbehaved(
        spawn("v2-bad-sample", 10.0).rasterize(&draw(1)),
        &["fragment 0 of", "names sample 1", "1 sample a pixel"],
    )
}

fn a_child_draws_what_the_reference_draws(mode: &str) -> Result<(), String> {
    let mut p = spawn(mode, 10.0);
    let mut reference = Reference::default();
    for n in [1, 2, 7] {
        let d = draw(n);
        let got = p.rasterize(&d).map_err(|e| e.to_string())?;
        if got != without_flat(reference.rasterize(&d).map_err(|e| e.to_string())?) {
            return Err(format!("{n} triangles: fragments differ"));
        }
        if p.resolve(&d).map_err(|e| e.to_string())? != reference.resolve(&d).map_err(|e| e.to_string())? {
            return Err(format!("{n} triangles: resolve differs"));
        }
    }
    assert_eq!(p.profile().name, format!("fake-{mode}"));
    assert!(p.about().contains("fake child"), "{}", p.about());
    Ok(())
}

fn crash() -> Result<(), String> {
    let mut p = spawn("crash", 10.0);
    p.rasterize(&draw(1)).map_err(|e| e.to_string())?;
    misbehaved(
        p.rasterize(&draw(2)),
        &["stdout closed", "SIGABRT", "about to crash"],
    )?;
    p.rasterize(&draw(1))
        .map_err(|e| format!("the restarted child should draw: {e}"))?;
    if p.starts() == 2 {
        Ok(())
    } else {
        Err(format!("{} starts, not 2", p.starts()))
    }
}

fn hang() -> Result<(), String> {
    let mut p = spawn("hang", 1.0);
    let start = Instant::now();
    misbehaved(
        p.rasterize(&draw(2)),
        &["no reply within 1 s", "hangs", "thinking"],
    )?;
    if start.elapsed() > Duration::from_secs(5) {
        return Err(format!("took {:?}", start.elapsed()));
    }
    p.rasterize(&draw(1))
        .map_err(|e| format!("the restarted child should draw: {e}"))?;
    Ok(())
}

/// After a good reply, the child writes well-formed replies (`fragments 0`, `end`) without
/// end, up to 4 GiB: refrast reads ahead at most 1 MiB of it, and the next draw names it.
fn flood() -> Result<(), String> {
    let mut p = spawn("flood", 2.0);
    let before = resident();
    p.rasterize(&draw(2)).map_err(|e| e.to_string())?;
    std::thread::sleep(Duration::from_millis(500));
    if let (Some(before), Some(after)) = (before, resident()) {
        // Other trials run in this process at the same time; they use a few MB.
        if after.saturating_sub(before) > 64 << 20 {
            return Err(format!("refrast grew by {} MiB", (after - before) >> 20));
        }
    }
    misbehaved(p.rasterize(&draw(2)), &["after its last reply's `end`"])
}

/// The child closes its stdin (a shell does it before starting it) and sleeps: its draw
/// times out and it is killed, not left running.
fn closes_stdin() -> Result<(), String> {
    let exe = std::env::current_exe().expect("the test binary has a path");
    let line = format!("sh -c 'exec 0<&- env {MODE}=sleeper \"$0\"' '{}'", exe.display());
    let mut p = Process::try_spawn_with(&line, Duration::from_secs(1)).map_err(|e| e.to_string())?;
    let start = Instant::now();
    misbehaved(p.rasterize(&draw(2)), &["hangs"])?;
    if start.elapsed() > Duration::from_secs(5) {
        return Err(format!("took {:?}", start.elapsed()));
    }
    Ok(())
}

/// The child starts a grandchild that keeps its stdout open and sleeps for an hour, then
/// exits without replying: the draw fails at the timeout and the grandchild is gone with it.
fn grandchild() -> Result<(), String> {
    let file = std::env::temp_dir().join(format!("refrast-process-grandchild-{}", std::process::id()));
    let _ = std::fs::remove_file(&file);
    let exe = std::env::current_exe().expect("the test binary has a path");
    let line = format!(
        "env {MODE}=fork-exit REFRAST_PID_FILE='{}' '{}'",
        file.display(),
        exe.display()
    );
    let mut p = Process::try_spawn_with(&line, Duration::from_secs(1)).map_err(|e| e.to_string())?;
    let start = Instant::now();
    misbehaved(p.rasterize(&draw(2)), &["hangs"])?;
    if start.elapsed() > Duration::from_secs(5) {
        return Err(format!("took {:?}", start.elapsed()));
    }
    let pid: u32 = std::fs::read_to_string(&file)
        .map_err(|e| format!("the grandchild wrote no process ID: {e}"))?
        .trim()
        .parse()
        .map_err(|e| format!("{e}"))?;
    let _ = std::fs::remove_file(&file);
    let deadline = Instant::now() + Duration::from_secs(5);
    while !gone(pid) && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    if gone(pid) {
        Ok(())
    } else {
        Err(format!("the grandchild {pid} outlived the draw"))
    }
}

/// A child limited to 128 MiB that allocates 2 GiB on a draw: the draw fails as a death whose
/// message names the limit.
fn memory_limit() -> Result<(), String> {
    let mut p = Process::try_spawn_limited(&child("hog"), Duration::from_secs(10), Some(128 << 20))
        .map_err(|e| e.to_string())?;
    misbehaved(
        p.rasterize(&draw(2)),
        &["limited to 128 MiB", "memory allocation of"],
    )
}

fn malformed() -> Result<(), String> {
    misbehaved(
        spawn("malformed", 10.0).rasterize(&draw(1)),
        &["malformed reply", "`hello there`", "stderr"],
    )
}

fn truncated() -> Result<(), String> {
    misbehaved(
        spawn("truncated", 10.0).rasterize(&draw(1)),
        &["truncated reply", "exit code 0"],
    )
}

fn count_too_high() -> Result<(), String> {
    misbehaved(
        spawn("count-high", 1.0).rasterize(&draw(1)),
        &["is the count right?"],
    )
}

fn count_too_low() -> Result<(), String> {
    misbehaved(
        spawn("count-low", 10.0).rasterize(&draw(1)),
        &["wrong count", "`end`"],
    )
}

fn outside() -> Result<(), String> {
    misbehaved(
        spawn("outside", 10.0).rasterize(&draw(1)),
        &["lies at (8, 0), outside the 8×8 viewport"],
    )
}

fn bad_primitive() -> Result<(), String> {
    misbehaved(
        spawn("bad-primitive", 10.0).rasterize(&draw(1)),
        &["names primitive 1", "1 triangles"],
    )
}

fn wrong_size() -> Result<(), String> {
    misbehaved(
        spawn("wrong-size", 10.0).resolve(&draw(1)),
        &["wrong count", "resolved 8 8"],
    )
}

fn refusal() -> Result<(), String> {
    let mut p = spawn("good", 10.0);
    let mut d = draw(1);
    d.indices.extend([0, 9, 1]);
    match p.rasterize(&d) {
        Err(DrawError::Backend(why)) if why.contains("vertex 9") => {}
        other => return Err(format!("expected the child's refusal, got {other:?}")),
    }
    p.rasterize(&draw(1)).map_err(|e| e.to_string())?;
    if p.starts() == 1 {
        Ok(())
    } else {
        Err("a refusal restarted the child".into())
    }
}

fn start_error(mode: &str) -> String {
    match Process::try_spawn_with(&child(mode), Duration::from_secs(5)) {
        Err(ProcessError::Handshake(why)) => why,
        other => panic!("expected a handshake error, got {other:?}"),
    }
}

fn version_mismatch() -> Result<(), String> {
    let why = start_error("version-4");
    if why.contains("version 4") && why.contains("speaks versions 1, 2 and 3") {
        Ok(())
    } else {
        Err(why)
    }
}

fn bad_profile() -> Result<(), String> {
    let why = start_error("bad-profile");
    if why.contains("unknown key `colour`") {
        Ok(())
    } else {
        Err(why)
    }
}

fn dies_at_start() -> Result<(), String> {
    let why = start_error("die-at-start");
    if why.contains("exit code 3") && why.contains("no module named numpy") {
        Ok(())
    } else {
        Err(why)
    }
}

fn missing_program() -> Result<(), String> {
    match Process::try_spawn("./no-such-rasterizer --fast") {
        Err(ProcessError::Start(why)) if why.contains("no-such-rasterizer") => Ok(()),
        other => Err(format!("{other:?}")),
    }
}

fn spawn_never_fails() -> Result<(), String> {
    let mut p = Process::spawn(&child("version-4"));
    if p.start_error().is_none() {
        return Err("no start error".into());
    }
    misbehaved(p.rasterize(&draw(1)), &["version 4"])
}

fn certify_crashing() -> Result<(), String> {
    let mut p = spawn("crash", 10.0);
    let options = Options {
        cases: Some(5),
        rules: vec!["fill.mesh".into()],
        ..Options::default()
    };
    let report = certify(&mut p, &options, |_| {});
    let rule = &report.rules[0];
    let message = rule.message.as_deref().unwrap_or("");
    if rule.status == Status::Crash && message.contains("SIGABRT") && message.contains("about to crash") {
        Ok(())
    } else {
        Err(format!("{:?}: {message}", rule.status))
    }
}

/// A child that hangs on a draw makes its rule a `timeout`, not a `fail`.
fn certify_hanging() -> Result<(), String> {
    let mut p = spawn("hang", 1.0);
    let options = Options {
        cases: Some(5),
        rules: vec!["fill.mesh".into()],
        budget: Some(Duration::from_secs(4)),
        ..Options::default()
    };
    let report = certify(&mut p, &options, |_| {});
    let rule = &report.rules[0];
    let message = rule.message.as_deref().unwrap_or("");
    if rule.status == Status::Timeout && message.contains("hangs") {
        Ok(())
    } else {
        Err(format!("{:?}: {message}", rule.status))
    }
}

fn budget() -> Result<(), String> {
    let mut p = spawn("slow", 10.0);
    let options = Options {
        rules: vec!["fill.top-left.exact".into()],
        budget: Some(Duration::from_millis(600)),
        ..Options::default()
    };
    let start = Instant::now();
    let report = certify(&mut p, &options, |_| {});
    let rule = &report.rules[0];
    let ok = rule.status == Status::Pass && rule.budget_spent && rule.cases > 0 && rule.cases < rule.planned;
    if ok && start.elapsed() < Duration::from_secs(5) {
        Ok(())
    } else {
        Err(format!("{rule:?} in {:?}", start.elapsed()))
    }
}

fn run_as_tests_child() -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = std::process::Command::new(exe)
        .args(["fill.top-left.exact", "--exact"])
        .env("REFRAST_AS_TESTS", "1")
        .env("PROPTEST_CASES", "20")
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout);
    if out.status.success() && text.contains("fill.top-left.exact ... ok") && text.contains(" 1 passed") {
        Ok(())
    } else {
        Err(format!(
            "{}\n{text}{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

fn protocol_md_example() -> Result<(), String> {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/protocol.md"))
        .map_err(|e| e.to_string())?;
    let viewport = Viewport::new(2, 2).expect("valid");
    let positions = vec![
        [-1.0, -1.0, 0.5, 1.0],
        [-1.0, 1.0, 0.5, 1.0],
        [1.0, -1.0, 0.5, 1.0],
        [1.0, 1.0, 0.5, 1.0],
    ];
    let mut d = Draw::of(viewport, positions, Topology::TriangleStrip, vec![0, 1, 2, 3]);
    d.state.provoking_vertex = refrast::ProvokingVertex::Last;
    let bytes = wire::request(wire::Op::Rasterize, &d, wire::VERSION);
    let header =
        String::from_utf8_lossy(&bytes[..bytes.iter().position(|&b| b == b'\n').unwrap_or(0)]).into_owned();
    if !doc.contains(&format!("→ {header}\n")) {
        return Err(format!("docs/protocol.md lacks the request line `{header}`"));
    }
    if bytes.len() != header.len() + 1 + 64 + 16 {
        return Err(format!("{} bytes", bytes.len()));
    }
    let fragments = Reference::default().rasterize(&d).map_err(|e| e.to_string())?;
    let seen: Vec<_> = fragments
        .iter()
        .map(|f| {
            (
                f.x,
                f.y,
                f.primitive,
                f.front_facing,
                f.depth,
                f.barycentric,
                f.flat,
            )
        })
        .collect();
    let shown = [
        (0, 1, 0, false, 0.5, [0.5, 0.25, 0.25], Some(2)),
        (0, 0, 1, false, 0.5, [0.75, 0.0, 0.25], Some(3)),
        (1, 0, 1, false, 0.5, [0.25, 0.5, 0.25], Some(3)),
        (1, 1, 1, false, 0.5, [0.25, 0.0, 0.75], Some(3)),
    ];
    if shown.iter().all(|f| seen.contains(f)) && seen.len() == shown.len() {
        Ok(())
    } else {
        Err(format!(
            "the example's fragments are not what docs/protocol.md shows: {seen:?}"
        ))
    }
}

// ---- the fake child ----------------------------------------------------------------------------

/// Speaks the protocol over the reference, misbehaving as `mode` says.
fn fake_child(mode: &str) {
    let mut out = std::io::stdout().lock();
    match mode {
        "version-4" => {
            let _ = writeln!(out, "refrast-protocol 4\nname future\nready");
            return;
        }
        "die-at-start" => {
            eprintln!("Traceback: no module named numpy");
            std::process::exit(3);
        }
        "grandchild" => {
            if let Some(file) = std::env::var_os("REFRAST_PID_FILE") {
                let _ = std::fs::write(file, std::process::id().to_string());
            }
            std::thread::sleep(Duration::from_secs(3600));
            return;
        }
        _ => {}
    }
    let colour = if mode == "bad-profile" {
        "colour blue\n"
    } else {
        ""
    };
    // Modes starting `v2` speak version 2: the reserved profile lines, a request's topology and
    // samples, a sample word in each fragment; `v3` also the last provoking vertex and a flat
    // word in each fragment.
    let version = if mode.starts_with("v3") {
        3
    } else if mode.starts_with("v2") {
        2
    } else {
        1
    };
    let reserved = match version {
        2 => "topology triangle-list line-list line-strip point-list\nsamples 1 4\nlines diamond-exit\n",
        3 => "topology triangle-list triangle-strip\nprovoking-vertex last\n",
        _ => "",
    };
    let _ = write!(
        out,
        "refrast-protocol {version}\nname fake-{mode}\nabout a fake child\nsnapping grid 8\nfill top-left\n\
         features perspective-barycentrics screen-barycentrics depth-test guard-band\n{reserved}{colour}ready\n"
    );
    let _ = out.flush();
    if mode == "sleeper" {
        std::thread::sleep(Duration::from_secs(3600));
        return;
    }
    let mut input = std::io::stdin().lock();
    let mut reference = Reference::default();
    loop {
        let mut header = String::new();
        if input.read_line(&mut header).unwrap_or(0) == 0 {
            return;
        }
        let Some((op, d)) = read_draw(&header, &mut input, version) else {
            return;
        };
        let mut reply = Vec::new();
        if op == "resolve" {
            let r = reference.resolve(&d).expect("valid");
            let (w, h) = (d.viewport.width(), d.viewport.height());
            let w = if mode == "wrong-size" { w + 1 } else { w };
            reply.extend(format!("resolved {w} {h}\n").bytes());
            r.depth.iter().for_each(|v| reply.extend(v.to_le_bytes()));
            r.primitive
                .iter()
                .for_each(|p| reply.extend(p.unwrap_or(u32::MAX).to_le_bytes()));
            reply.extend(b"end\n");
        } else {
            let fragments = match reference.rasterize(&d) {
                Ok(f) => f,
                Err(e) => {
                    let _ = writeln!(out, "error {e}");
                    let _ = out.flush();
                    continue;
                }
            };
            match (mode, d.primitive_count()) {
                ("crash", 2..) => {
                    eprintln!("about to crash");
                    std::process::abort();
                }
                ("hang", 2..) => {
                    eprintln!("thinking");
                    std::thread::sleep(Duration::from_secs(3600));
                }
                ("slow", _) => std::thread::sleep(Duration::from_millis(20)),
                ("fork-exit", _) => {
                    let exe = std::env::current_exe().expect("the test binary has a path");
                    let _ = std::process::Command::new(exe).env(MODE, "grandchild").spawn();
                    std::process::exit(0);
                }
                ("hog", _) => {
                    let kept: Vec<Vec<u8>> = (0..128).map(|_| vec![1; 16 << 20]).collect();
                    eprintln!("allocated {} MiB", kept.len() * 16);
                }
                ("malformed", _) => {
                    eprintln!("debugging output went to stdout");
                    let _ = writeln!(out, "hello there");
                    let _ = out.flush();
                    continue;
                }
                _ => {}
            }
            let mut records: Vec<Vec<u8>> = fragments.iter().map(|f| record(f, f.sample, version)).collect();
            match mode {
                "outside" => records[0][0..4].copy_from_slice(&d.viewport.width().to_le_bytes()),
                "bad-primitive" => records[0][8..12].copy_from_slice(&1u32.to_le_bytes()),
                "v2-bad-sample" => records[0][44..48].copy_from_slice(&1u32.to_le_bytes()),
                _ => {}
            }
            let claimed = match mode {
                "count-high" | "truncated" => records.len() + 1,
                "count-low" => records.len() - 1,
                _ => records.len(),
            };
            reply.extend(format!("fragments {claimed}\n").bytes());
            if mode == "truncated" {
                reply.extend(&records[0]);
                let _ = out.write_all(&reply);
                let _ = out.flush();
                std::process::exit(0);
            }
            records.iter().for_each(|r| reply.extend(r));
            reply.extend(b"end\n");
        }
        let _ = out.write_all(&reply);
        let _ = out.flush();
        if mode == "flood" {
            let lines = b"fragments 0\nend\n".repeat(1 << 16);
            for _ in 0..(4 << 30) / lines.len() {
                if out.write_all(&lines).is_err() {
                    return;
                }
            }
        }
    }
}

/// The reference's fragments as a child of version 1 or 2 reports them: with no flat vertex,
/// which those versions have no word for.
fn without_flat(fragments: Vec<refrast::Fragment>) -> Vec<refrast::Fragment> {
    fragments
        .into_iter()
        .map(|f| refrast::Fragment { flat: None, ..f })
        .collect()
}

/// A fragment as the protocol's record: 44 bytes, and version 2's sample word.
fn record(f: &refrast::Fragment, sample: u8, version: u32) -> Vec<u8> {
    let words = [
        f.x,
        f.y,
        f.primitive,
        u32::from(f.front_facing),
        f.depth.to_bits(),
        f.barycentric[0].to_bits(),
        f.barycentric[1].to_bits(),
        f.barycentric[2].to_bits(),
    ];
    let screen = f.screen_barycentric.unwrap_or_default().map(f32::to_bits);
    let extra = [u32::from(sample), f.flat.unwrap_or(u32::MAX)];
    let extra = match version {
        1 => &extra[..0],
        2 => &extra[..1],
        _ => &extra[..],
    };
    words
        .iter()
        .chain(&screen)
        .chain(extra)
        .flat_map(|w| w.to_le_bytes())
        .collect()
}

/// Parses a request as a child must: the header's `key=value` words, then the arrays; version 2
/// says the topology and the samples (version 1: a triangle list at one sample a pixel), and
/// `triangles=T` counts its primitives.
fn read_draw(header: &str, input: &mut impl Read, version: u32) -> Option<(String, Draw)> {
    let mut words = header.split_whitespace();
    let op = words.next()?.to_owned();
    let fields: std::collections::HashMap<&str, &str> = words.filter_map(|w| w.split_once('=')).collect();
    let given = (fields.get("topology").copied(), fields.get("samples").copied());
    let (topology, samples) = match (version, given) {
        (1, (None, None)) => (Topology::TriangleList, 1),
        (2 | 3, (Some(t), Some(n))) => (Topology::from_name(t)?, n.parse().ok()?),
        _ => {
            eprintln!("version {version} request with topology and samples {given:?}");
            return None;
        }
    };
    let number = |key: &str| fields.get(key).and_then(|v| v.parse::<u32>().ok());
    let viewport = Viewport::new(number("width")?, number("height")?).ok()?;
    let (vertices, primitives) = (number("vertices")? as usize, number("triangles")? as usize);
    let indices = match topology {
        Topology::TriangleList => 3 * primitives,
        Topology::LineList => 2 * primitives,
        Topology::LineStrip if primitives > 0 => primitives + 1,
        Topology::TriangleStrip | Topology::TriangleFan if primitives > 0 => primitives + 2,
        Topology::LineStrip | Topology::TriangleStrip | Topology::TriangleFan => 0,
        Topology::PointList => primitives,
    };
    let mut bytes = vec![0u8; vertices * 16 + indices * 4];
    input.read_exact(&mut bytes).ok()?;
    let positions = (0..vertices)
        .map(|v| std::array::from_fn(|k| wire::f32_at(&bytes, 4 * v + k)))
        .collect();
    let indices = (0..indices)
        .map(|i| wire::f32_at(&bytes[vertices * 16..], i).to_bits())
        .collect();
    let mut d = Draw::of(viewport, positions, topology, indices);
    d.samples = samples;
    let word = |key: &str| fields.get(key).copied().unwrap_or("");
    d.state.cull = CullMode::parse(word("cull"))?;
    d.state.front_face = FrontFace::parse(word("front-face"))?;
    d.state.depth.compare = CompareOp::parse(word("depth-compare"))?;
    d.state.depth.write = bool::parse(word("depth-write"))?;
    d.state.depth.clear = word("depth-clear").parse().ok()?;
    d.state.depth_range = DepthRange::parse(word("depth-range"))?;
    d.state.clip_far = bool::parse(word(wire::FAR_CLIPPING))?;
    if version >= 3 {
        d.state.provoking_vertex = refrast::ProvokingVertex::parse(word("provoking-vertex"))?;
    }
    Some((op, d))
}
