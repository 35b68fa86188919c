//! The refrast command line: render the built-in scenes (and, later, certify rasterizers).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use refrast::scenes::{self, DEFAULT_SIZE, SCENES};

/// refrast: a reference triangle rasterizer and conformance suite.
#[derive(Parser, Debug)]
#[command(name = "refrast", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a built-in scene to a PNG with the reference rasterizer.
    Render {
        /// The scene (see `refrast scenes`).
        scene: String,
        /// Where to write the PNG [default: SCENE.png].
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Width in pixels (1..=16384).
        #[arg(long, default_value_t = DEFAULT_SIZE.0)]
        width: u32,
        /// Height in pixels (1..=16384).
        #[arg(long, default_value_t = DEFAULT_SIZE.1)]
        height: u32,
    },
    /// List the built-in scenes.
    Scenes,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Scenes => {
            for scene in SCENES {
                println!("{:<14} {}", scene.name, scene.description);
            }
            ExitCode::SUCCESS
        }
        Command::Render {
            scene,
            output,
            width,
            height,
        } => {
            let output = output.unwrap_or_else(|| PathBuf::from(format!("{scene}.png")));
            let target = match scenes::render(&scene, width, height) {
                Ok(target) => target,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Err(e) = target.save_png(&output) {
                eprintln!("error: could not write {}: {e}", output.display());
                return ExitCode::FAILURE;
            }
            println!("wrote {} ({width}x{height}, scene {scene})", output.display());
            ExitCode::SUCCESS
        }
    }
}
