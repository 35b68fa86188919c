//! Any built-in implementation (`refrast impls`: the reference variants, the mutants, the course
//! rasterizers, `fast`; not the third parties, which `refrast-registry` leaves out here so that
//! wgpu is not built under the sanitizers) under any target's check but `pipeline`, chosen by
//! the environment:
//! `REFRAST_FUZZ_IMPL` (default `reference`) and `REFRAST_FUZZ_TARGET` (default `watertight`).
//! Bytes decode exactly as that target's own `fuzz_target!` decodes them, so corpora are shared.
//!
//! `REFRAST_FUZZ_EXEC="python3 my_raster.py"` fuzzes a rasterizer in any language instead,
//! through the pipe protocol (docs/protocol.md): one child, started once and restarted after it
//! misbehaves, whose crash, hang or garbled answer is a finding like any other.
#![no_main]

use std::sync::{Mutex, OnceLock};

use libfuzzer_sys::fuzz_target;
use refrast_conformance::fuzz::{Checked, Target};
use refrast_pipe::Process;
use refrast_registry::BuiltIn;

/// The child named by `REFRAST_FUZZ_EXEC`, if any; exits 2 saying why when it cannot start.
fn process() -> Option<&'static Mutex<Process>> {
    static PROCESS: OnceLock<Option<Mutex<Process>>> = OnceLock::new();
    PROCESS
        .get_or_init(|| {
            let command = std::env::var("REFRAST_FUZZ_EXEC").ok()?;
            match Process::try_spawn(&command) {
                Ok(p) => Some(Mutex::new(p)),
                Err(why) => {
                    eprintln!("REFRAST_FUZZ_EXEC={command}: {why}");
                    std::process::exit(2);
                }
            }
        })
        .as_ref()
}

/// The target and implementation named by the environment; exits 2 naming the choices if unknown.
fn chosen() -> &'static (Target, BuiltIn) {
    static CHOSEN: OnceLock<(Target, BuiltIn)> = OnceLock::new();
    CHOSEN.get_or_init(|| {
        let var = |name: &str, default: &str| std::env::var(name).unwrap_or_else(|_| default.into());
        let (impl_name, target_name) = (
            var("REFRAST_FUZZ_IMPL", "reference"),
            var("REFRAST_FUZZ_TARGET", "watertight"),
        );
        let all = refrast_registry::all();
        let names: Vec<String> = all.iter().map(|b| b.name.clone()).collect();
        let Some(built_in) = all.into_iter().find(|b| b.name == impl_name) else {
            eprintln!(
                "REFRAST_FUZZ_IMPL={impl_name} is not a built-in; choose one of: {}",
                names.join(", ")
            );
            std::process::exit(2);
        };
        if let Err(why) = built_in.build() {
            eprintln!("REFRAST_FUZZ_IMPL={impl_name} cannot be built on this machine: {why}");
            std::process::exit(2);
        }
        let Some(target) = Target::from_name(&target_name).filter(|t| t.judges_rasterizer()) else {
            let targets: Vec<&str> = Target::ALL
                .iter()
                .filter(|t| t.judges_rasterizer())
                .map(|t| t.name())
                .collect();
            eprintln!(
                "REFRAST_FUZZ_TARGET={target_name} is not a target for any rasterizer; choose one of: {}",
                targets.join(", ")
            );
            std::process::exit(2);
        };
        (target, built_in)
    })
}

fuzz_target!(
    init: {
        let (target, built_in) = chosen();
        match process() {
            Some(p) => eprintln!("fuzzing `{}` with the {} target", p.lock().map(|p| p.command().to_owned()).unwrap_or_default(), target.name()),
            None => eprintln!("fuzzing {} with the {} target", built_in.name, target.name()),
        }
    },
    |data: &[u8]| {
        let (target, built_in) = chosen();
        if let Some(p) = process() {
            let mut p = p.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            if let Checked::Failed(failure) = target.run(&mut *p, data) {
                panic!("`{}` fails the {} target: {failure}", p.command(), target.name());
            }
            return;
        }
        // Checked buildable in `chosen`; a build failing later is itself worth a crash report.
        let mut rasterizer = built_in.build().unwrap_or_else(|why| panic!("{} stopped building: {why}", built_in.name));
        if let Checked::Failed(failure) = target.run(&mut *rasterizer, data) {
            panic!("{} fails the {} target: {failure}", built_in.name, target.name());
        }
    }
);
