//! The refrast command line: certify rasterizers, list the rules, render built-in scenes, view
//! them in a window.

mod certify;
mod listing;
mod options;
mod render;
mod replay;
mod results;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// refrast: a reference triangle rasterizer and conformance suite.
#[derive(Parser, Debug)]
#[command(name = "refrast", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Certify rasterizers against the rule catalogue.
    Certify(certify::CertifyArgs),
    /// List the rules: ID, kind, family, source, sentence.
    Rules {
        /// Print the table of docs/rules.md instead: `| rule | kind | sentence |`.
        #[arg(long, conflicts_with = "levels")]
        markdown: bool,
        /// Print what Vulkan, OpenGL and D3D11.3 each require of every rule (docs/levels.md).
        #[arg(long, conflicts_with = "json")]
        levels: bool,
        /// Print the rules as JSON: an array of {id, kind, family, source, sentence, default_cases}.
        #[arg(long, conflicts_with = "markdown")]
        json: bool,
        /// Print the spec map instead: each normative statement of Vulkan, D3D11.3 and OpenGL,
        /// the seed labs' results and refrast's conventions, with the rules that check it
        /// (with --json as JSON, with --markdown as docs/spec.md).
        #[arg(long, conflicts_with = "levels")]
        spec: bool,
        /// With --spec: only the statements this rule checks.
        #[arg(long, requires = "spec", value_name = "RULE")]
        rule: Option<String>,
    },
    /// Replay one counterexample (the .case.json that certify writes beside a failure) on a
    /// rasterizer in any language or a built-in: the rule's message, hint and picture for that
    /// case alone; exit 0 when it passes, 1 when it fails.
    Replay(replay::ReplayArgs),
    /// List the built-in implementations and their profiles.
    Impls {
        /// Print them as JSON: an array of {name, origin, description, available, unavailable,
        /// profile}.
        #[arg(long)]
        json: bool,
        /// Only this one, built in this process (what the listing runs for a third party).
        #[arg(long, value_name = "NAME", hide = true)]
        only: Option<String>,
    },
    /// Compare two `certify --json` reports: per implementation, the rules that regressed, got
    /// fixed or changed status; exit 1 on a regression.
    Compare(results::compare::CompareArgs),
    /// Join the `certify --json` reports of a run's shards (`--shard I/N`) into one report:
    /// text, JSON, HTML and JUnit, as the run would have made in one piece.
    Merge(results::merge::MergeArgs),
    /// Render a built-in scene or a mesh file (PLY, OBJ) to a PNG, in any mode, through any rasterizer.
    #[command(allow_negative_numbers = true)]
    Render(render::RenderArgs),
    /// List the built-in scenes.
    Scenes,
    /// Open a window on a scene or mesh file, drawn every frame: fly the camera, switch the
    /// mode with 1-7 and the implementation with I, save with P.
    #[command(allow_negative_numbers = true)]
    View(view::ViewArgs),
    /// Run one rule for `certify` and speak to it on stdout (not for people).
    #[command(hide = true)]
    RunRule(certify::RunRuleArgs),
}

fn main() -> ExitCode {
    // The children refrast starts lead process groups of their own, which a terminal's Ctrl-C
    // does not reach: on an interrupt (or SIGTERM), end them, and whatever they started, first.
    // Exit status 130, a shell's for an interrupted command.
    if let Err(e) = ctrlc::set_handler(|| {
        refrast_pipe::contain::end_all();
        std::process::exit(130);
    }) {
        eprintln!("warning: no interrupt handler ({e}): an interrupted run may leave its children running");
    }
    let cli = Cli::parse();
    match cli.command {
        Command::Certify(args) => certify::run(&args),
        Command::RunRule(args) => certify::run_rule(&args),
        Command::Rules {
            spec: true,
            markdown,
            json,
            rule,
            ..
        } => listing::spec(markdown, json, rule.as_deref()),
        Command::Rules { markdown: true, .. } => {
            say(&refrast_conformance::markdown_table());
            ExitCode::SUCCESS
        }
        Command::Rules { levels: true, .. } => {
            say(refrast_conformance::levels_markdown().trim_end());
            ExitCode::SUCCESS
        }
        Command::Rules { json, .. } => listing::rules(json),
        Command::Impls { json, only } => listing::impls(json, only.as_deref()),
        Command::Compare(args) => results::compare::run(&args),
        Command::Merge(args) => results::merge::run(&args),
        Command::Scenes => {
            for scene in refrast_render::scene::scenes() {
                say(&format!("{:<14} {}", scene.name, scene.description));
            }
            ExitCode::SUCCESS
        }
        Command::Render(args) => render::run(&args),
        Command::Replay(args) => replay::run(&args),
        Command::View(args) => view::run(&args),
    }
}

/// Prints a line; when stdout is closed (`refrast rules | head`), stops quietly instead of panicking.
pub(crate) fn say(line: &str) {
    use std::io::Write;
    if writeln!(std::io::stdout().lock(), "{line}").is_err() {
        std::process::exit(0);
    }
}
