//! `refrast replay`: one counterexample, read from its JSON, run again through a rasterizer in
//! any language or a built-in, with the same message, hint and picture as in `certify`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use refrast::{Rasterizer, Topology};
use refrast_conformance::{Case, CaseFile, Options, PrimitiveScene, RuleReport, Status};
use refrast_pipe::{Process, contain};

use crate::certify::{plural, positive_seconds, reach, rule_lines, this_program};
use crate::say;

/// Arguments of `refrast replay`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("rasterizer").required(true).args(["exec", "implementation"])))]
pub struct ReplayArgs {
    /// The case: a `.case.json` file that `certify` wrote beside a failure's picture, or a
    /// `certify --json` report (then --rule says which failure).
    case: PathBuf,
    /// The rasterizer to replay it on: the command that starts it, speaking docs/protocol.md.
    #[arg(long = "exec", value_name = "CMD")]
    exec: Option<String>,
    /// A built-in to replay it on (see `refrast impls`), run in this process.
    #[arg(long = "impl", value_name = "NAME")]
    implementation: Option<String>,
    /// With a `certify --json` report: the rule whose counterexample to replay (of the first
    /// implementation that failed it).
    #[arg(long, value_name = "RULE")]
    rule: Option<String>,
    /// Folder for the picture (what was drawn against what is required) and the case again.
    #[arg(long, value_name = "DIR", default_value = "refrast-replay")]
    report: PathBuf,
    /// Also print every fragment the rasterizer draws for the case's draw: x, y, primitive,
    /// sample, facing, depth and barycentrics.
    #[arg(long)]
    fragments: bool,
    /// Print the rule's report as JSON (docs/json.md, a rule's entry) instead of text.
    #[arg(long)]
    json: bool,
    /// Seconds the draw may take before the child counts as hung.
    #[arg(long, value_name = "SECONDS", default_value_t = refrast_conformance::DEFAULT_CASE_TIMEOUT.as_secs_f64(),
          value_parser = positive_seconds)]
    case_timeout: f64,
    /// The most memory, in MiB, the --exec child may allocate (0 sets no limit).
    #[arg(long, value_name = "MIB", default_value_t = contain::DEFAULT_MEMORY_LIMIT >> 20)]
    memory_limit: u64,
}

/// Runs `refrast replay`: 0 when the case passes (or fails only beyond the specification the
/// profile claims), 1 when it fails, crashes or hangs, 2 when the file, the rule or the
/// rasterizer cannot be had.
pub fn run(args: &ReplayArgs) -> ExitCode {
    if let Some(code) = in_its_environment(args) {
        return code;
    }
    match replay(args) {
        Ok(report) => {
            if report.status.is_failure() {
                ExitCode::FAILURE
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The exit code of this same replay run in a child with the environment a built-in needs set
/// before its process starts (softpipe's `GALLIUM_DRIVER`), as `certify` runs it; `None` when
/// this process has that environment already, or the rasterizer needs none.
fn in_its_environment(args: &ReplayArgs) -> Option<ExitCode> {
    let name = args.implementation.as_ref().filter(|_| args.exec.is_none())?;
    let builtin = refrast_registry::find(name).ok()?;
    let set = |(k, v): &(String, String)| std::env::var(k).is_ok_and(|now| now == *v);
    if builtin.env.iter().all(set) {
        return None;
    }
    let status = this_program()
        .args(std::env::args_os().skip(1))
        .envs(builtin.env.iter().map(|(k, v)| (k, v)))
        .status();
    Some(match status {
        Ok(status) => match status.code() {
            Some(code) => ExitCode::from(u8::try_from(code).unwrap_or(1)),
            // A signal: the rasterizer took the process down with it, before any verdict.
            None => {
                eprintln!(
                    "error: the replay on {name} ended without a verdict ({}): the rasterizer crashed it",
                    refrast_pipe::status_words(status)
                );
                ExitCode::FAILURE
            }
        },
        Err(e) => {
            eprintln!(
                "error: could not start a child to replay on {name} with {:?} set: {e}",
                builtin.env
            );
            ExitCode::from(2)
        }
    })
}

/// Reads the case, builds the rasterizer, replays, prints.
fn replay(args: &ReplayArgs) -> Result<RuleReport, String> {
    let case = read_case(&args.case, args.rule.as_deref())?;
    let (mut rasterizer, name, is_exec): (Box<dyn Rasterizer>, String, bool) =
        match (&args.exec, &args.implementation) {
            (Some(command), _) => {
                let limit = (args.memory_limit > 0).then(|| args.memory_limit.saturating_mul(1 << 20));
                let process =
                    Process::try_spawn_limited(command, Duration::from_secs_f64(args.case_timeout), limit)
                        .map_err(|e| format!("--exec {command}: the child did not start: {e}"))?;
                (Box::new(process), command.clone(), true)
            }
            (None, Some(name)) => {
                let builtin = refrast_registry::find(name)?;
                let built = builtin
                    .build()
                    .map_err(|why| format!("{name} is unavailable on this machine: {why}"))?;
                (built, name.clone(), false)
            }
            (None, None) => return Err("give --exec CMD or --impl NAME: the rasterizer to replay on".into()),
        };
    let mut report = refrast_conformance::replay(&case, rasterizer.as_mut(), &Options::default())?;
    if let Err(why) = report.save_exhibit(&args.report) {
        eprintln!("warning: {why}");
    }
    if args.json {
        let text = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
        say(&text);
        return Ok(report);
    }
    say(&format!(
        "replay of {} (the case {} failed{}) on {name}",
        case.rule,
        if case.implementation.is_empty() {
            "an implementation"
        } else {
            &case.implementation
        },
        if case.seed == 0 {
            String::new()
        } else {
            format!(" with seed {}", case.seed)
        },
    ));
    say(&format!("the draw: {}", describe(&case)));
    // The case is the file given: its text is not printed again.
    let shown = RuleReport {
        counterexample: None,
        case_file: None,
        case_path: None,
        ..report.clone()
    };
    for line in rule_lines(&shown, &reach(&name, is_exec)) {
        say(&line);
    }
    if report.status == Status::Pass {
        say("      the case passes: what it checks is drawn as required");
    }
    if args.fragments {
        print_fragments(rasterizer.as_mut(), &case)?;
    }
    Ok(report)
}

/// The case in `path`: a case file, or the counterexample of `rule` in a `certify --json`
/// report.
fn read_case(path: &Path, rule: Option<&str>) -> Result<CaseFile, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let value: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))?;
    let case = match value.get("implementations") {
        Some(implementations) => from_report(implementations, rule, path)?,
        None => value,
    };
    serde_json::from_value(case).map_err(|e| {
        format!(
            "{}: not a case file ({e}); give a .case.json that certify wrote, or a certify --json report with --rule",
            path.display()
        )
    })
}

/// The counterexample of `rule` in a report's implementations: the first one that has it.
fn from_report(
    implementations: &serde_json::Value,
    rule: Option<&str>,
    path: &Path,
) -> Result<serde_json::Value, String> {
    let cases: Vec<(&str, &serde_json::Value)> = implementations
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|i| i.get("rules")?.as_array())
        .flatten()
        .filter_map(|r| Some((r.get("id")?.as_str()?, r.get("case")?)))
        .collect();
    let ids = || {
        let mut ids: Vec<&str> = cases.iter().map(|(id, _)| *id).collect();
        ids.dedup();
        ids.join(", ")
    };
    match rule {
        Some(rule) => cases
            .iter()
            .find(|(id, _)| *id == rule)
            .map(|(_, case)| (*case).clone())
            .ok_or_else(|| match cases.len() {
                0 => format!("{}: no failure in this report has a case", path.display()),
                _ => format!(
                    "{}: no case of {rule}; the cases are of {}",
                    path.display(),
                    ids()
                ),
            }),
        None => match cases.as_slice() {
            [(_, case)] => Ok((*case).clone()),
            [] => Err(format!(
                "{}: no failure in this report has a case",
                path.display()
            )),
            _ => Err(format!(
                "{}: several failures have cases; say which with --rule (one of {})",
                path.display(),
                ids()
            )),
        },
    }
}

/// The case's draw in a line: size, topology, how many primitives and vertices, its state.
fn describe(case: &CaseFile) -> String {
    let d = &case.case.draw;
    let primitives = Topology::from_name(&d.topology)
        .and_then(|t| t.primitive_count(d.indices.len()).ok())
        .unwrap_or(0);
    let mut text = format!(
        "{}x{} pixels at {}, {} of {} over {}; cull {}, front-face {}, depth-compare {}, depth-write {}, depth-range {}, far-clipping {}",
        d.width,
        d.height,
        plural(usize::from(d.samples), "sample"),
        d.topology,
        plural(primitives, "primitive"),
        plural(d.positions.len(), "vertex"),
        d.cull,
        d.front_face,
        d.depth_compare,
        d.depth_write,
        d.depth_range,
        d.far_clipping
    );
    if let Some([x, y, w, h]) = d.scissor {
        text.push_str(&format!(
            "; scissor x {x}..{}, y {y}..{}",
            u64::from(x) + u64::from(w),
            u64::from(y) + u64::from(h)
        ));
    }
    if let Some(mask) = d.sample_mask {
        text.push_str(&format!("; sample mask {mask:#x}"));
    }
    if let Some(sampling) = &d.interpolation {
        text.push_str(&format!("; {sampling} interpolation"));
    }
    if let Some(mode) = &d.conservative {
        text.push_str(&format!("; conservative {mode}"));
    }
    if let Some(mode) = &d.provoking_vertex {
        text.push_str(&format!("; provoking-vertex {mode}"));
    }
    if let Some([constant, slope, clamp]) = d.depth_bias {
        text.push_str(&format!(
            "; depth bias constant {} slope {} clamp {}",
            constant.0, slope.0, clamp.0
        ));
    }
    if let Some([dx, dy]) = case.case.translate {
        text.push_str(&format!("; drawn again moved by ({dx}, {dy}) pixels"));
    }
    if let Some(p) = case.case.poison {
        text.push_str(&format!(
            "; drawn again with component {} of triangle 0's vertex {} set to {}",
            p.component, p.vertex, p.value.0
        ));
    }
    text
}

/// Prints every fragment `r` draws for the case's draw, one a line.
fn print_fragments(r: &mut dyn Rasterizer, case: &CaseFile) -> Result<(), String> {
    // The case's data was read once already, so its viewport is in range.
    let draw = PrimitiveScene::from_data(&case.case)?.draw();
    match r.rasterize(&draw) {
        Ok(fragments) => {
            say(&format!(
                "fragments drawn for the draw ({}): x y primitive sample front-facing depth barycentric flat",
                fragments.len()
            ));
            for f in &fragments {
                let b = f.barycentric;
                let flat = f.flat.map_or("-".to_owned(), |v| v.to_string());
                say(&format!(
                    "  {} {} {} {} {} {:?} [{:?}, {:?}, {:?}] {flat}",
                    f.x, f.y, f.primitive, f.sample, f.front_facing, f.depth, b[0], b[1], b[2]
                ));
            }
        }
        Err(e) => say(&format!("the draw returned an error: {e}")),
    }
    Ok(())
}
