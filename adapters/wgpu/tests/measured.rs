//! Each driver's measured profile, every probe's choice pinned: a driver's profile is measured
//! on it (`refrast_wgpu::probe`, `refrast_wgpu::measured`), never assumed from another driver's.
//!
//! Each driver runs in a child process of its own, with the environment it needs. A driver that
//! is not installed is skipped with its reason printed; with `REFRAST_REQUIRE_DRIVERS=1` a
//! missing Mesa driver fails instead, and with `REFRAST_REQUIRE_SWIFTSHADER=1` a missing
//! SwiftShader. `vulkan` (whatever adapter is found) is measured and printed, not pinned.

use std::process::Command;
use std::time::Instant;

use refrast::{
    DepthSlope, FillConvention, LineRule, PointClipping, Profile, Rasterizer, SamplePattern, SnapAccuracy,
    Snapping,
};
use refrast_wgpu::measured::{Measured, choose};
use refrast_wgpu::{Driver, Gpu};

const CHILD_ENV: &str = "MEASURED_TEST_DRIVER";
/// The exit code of a child whose driver is missing.
const UNAVAILABLE: i32 = 3;

/// What each driver must declare on this project's machine (Debian 12: Mesa 22.3.6, Chromium
/// 148's SwiftShader 5.0.0); the fewest bits of precision its probe may measure; whether a
/// shared edge was covered twice (softpipe's bug, docs/certified.md, "Findings").
struct Pinned {
    declared: Measured,
    fewest_bits: f64,
    covered_twice: bool,
}

/// What a measurement declares about lines, points and samples, as a profile says it.
fn primitives(m: &Measured) -> Profile {
    Profile {
        lines: m.lines,
        points: m.points,
        point_snapping: m.point_snapping,
        endpoint_snapping: m.endpoint_snapping,
        multisample: m.multisample.clone(),
        point_clipping: m.point_clipping,
        ..Profile::default()
    }
}

fn pinned(d: Driver) -> Option<Pinned> {
    // Lines by the rule the probe fits (Vulkan's strictLines rectangles on lavapipe and
    // SwiftShader; OpenGL's diamond-exit rule on llvmpipe and softpipe), points, Vulkan's
    // standard 4 sample locations where the capture at 4 samples works, and softpipe's points on
    // a grid of their own (a quarter pixel, read one bit coarse).
    let primitives = match d {
        Driver::Lavapipe | Driver::Swiftshader | Driver::Vulkan => Profile {
            lines: Some(LineRule::Rectangle),
            points: true,
            multisample: SamplePattern::standard(4).into_iter().collect(),
            ..Profile::default()
        },
        // OpenGL ES clips points by the near and far planes only (§12.5).
        Driver::Llvmpipe => Profile {
            lines: Some(LineRule::DiamondExit),
            points: true,
            point_clipping: PointClipping::UserClipPlanesOnly,
            ..Profile::default()
        },
        Driver::Softpipe => Profile {
            lines: Some(LineRule::DiamondExit),
            points: true,
            point_snapping: Some(Snapping::Grid(1)),
            point_clipping: PointClipping::UserClipPlanesOnly,
            ..Profile::default()
        },
    };
    let pin = |snapping, fill, snap, ties_to_even, precision_bits, fewest_bits| Pinned {
        declared: Measured {
            snapping,
            fill,
            ties_to_even,
            snap,
            guard_band: 0,
            precision_bits,
            tolerance_subpixels: 1,
            lines: primitives.lines,
            points: primitives.points,
            point_snapping: primitives.point_snapping,
            endpoint_snapping: primitives.endpoint_snapping,
            multisample: primitives.multisample.clone(),
            point_clipping: primitives.point_clipping,
            // Each computes max(|∂z/∂x|, |∂z/∂y|) (Mesa's `lp_state_setup.c` and
            // `draw_pipe_offset.c`, SwiftShader's `SetupRoutine`), which the probe reads.
            bias_slope: DepthSlope::Max,
            reported: String::new(),
            why: String::new(),
        },
        fewest_bits,
        covered_twice: d == Driver::Softpipe,
    };
    let (top_left, within) = (Some(FillConvention::TopLeft), SnapAccuracy::WithinOneStep);
    match d {
        // Measured 9.4 bits (perspective weights on slivers with w 32:1).
        Driver::Lavapipe => Some(pin(Snapping::Grid(8), top_left, within, true, 7, 9.0)),
        // The same rasterizer through OpenGL ES: 10.1 bits.
        Driver::Llvmpipe => Some(pin(Snapping::Grid(8), top_left, within, true, 8, 10.0)),
        // Float edge walking: every move down to 2^-16 px changes coverage, and its rounding
        // decides some samples on edges (259 of 262 follow top-right); 9.3 bits.
        Driver::Softpipe => Some(pin(Snapping::Float, None, SnapAccuracy::Nearest, false, 7, 9.0)),
        // 14.9 bits on triangles drawn whole.
        Driver::Swiftshader => Some(pin(Snapping::Grid(4), top_left, within, true, 12, 14.0)),
        Driver::Vulkan => None,
    }
}

fn main() {
    if let Ok(name) = std::env::var(CHILD_ENV) {
        let d = Driver::ALL
            .into_iter()
            .find(|d| d.name() == name)
            .expect("a driver name");
        child(d);
        return;
    }
    let exe = std::env::current_exe().expect("this test binary");
    let mut moved = Vec::new();
    for d in Driver::ALL {
        let mut c = Command::new(&exe);
        for (name, value) in d.env() {
            c.env(name, value);
        }
        let output = c.env(CHILD_ENV, d.name()).output().expect("the child starts");
        let stdout = String::from_utf8_lossy(&output.stdout);
        if output.status.code() == Some(UNAVAILABLE) {
            let required = match d {
                Driver::Swiftshader => "REFRAST_REQUIRE_SWIFTSHADER",
                Driver::Vulkan => "",
                _ => "REFRAST_REQUIRE_DRIVERS",
            };
            assert!(
                required.is_empty() || std::env::var(required).as_deref() != Ok("1"),
                "{}: {required} is set, but {stdout}",
                d.name()
            );
            println!("{}: SKIPPED: {stdout}", d.name());
            continue;
        }
        print!("{stdout}");
        if !output.status.success() {
            let stderr = String::from_utf8_lossy(&output.stderr);
            let why = stderr
                .lines()
                .take_while(|l| !l.starts_with("stack backtrace"))
                .collect::<Vec<_>>();
            moved.push(format!("{}: {}", d.name(), why.join("\n")));
        }
    }
    assert!(moved.is_empty(), "measured choices moved:\n{}", moved.join("\n"));
}

/// Measures `d` in this process: twice afresh (the same both times), against the profile
/// `Gpu::new` gave (from the file or measured), against the pinned choices.
fn child(d: Driver) {
    let start = Instant::now();
    let mut gpu = match Gpu::new(d) {
        Ok(gpu) => gpu,
        Err(why) => {
            println!("{why}");
            std::process::exit(UNAVAILABLE);
        }
    };
    let opened = start.elapsed();
    let start = Instant::now();
    let (reported, probes) = gpu.probe().expect("the probes run");
    let probing = start.elapsed();
    let again = gpu.probe().expect("the probes run again");
    assert_eq!(
        again,
        (reported.clone(), probes.clone()),
        "{}: the probes are deterministic",
        d.name()
    );
    let fresh = choose(d.spec(), reported.as_ref(), &probes);
    println!(
        "{}: {} (opened and profiled in {:.2} s, probes alone {:.2} s)\n  {}",
        d.name(),
        fresh.summary(),
        opened.as_secs_f64(),
        probing.as_secs_f64(),
        gpu.about()
    );
    assert_eq!(
        gpu.measured(),
        &fresh,
        "{}: the profile in use is the one measured now",
        d.name()
    );
    let profile = gpu.profile();
    assert_eq!(profile.snapping, fresh.snapping);
    assert_eq!(profile.precision_bits, fresh.precision_bits);
    let Some(Pinned {
        declared: want,
        fewest_bits,
        covered_twice,
    }) = pinned(d)
    else {
        return;
    };
    let name = d.name();
    assert_eq!(
        fresh.snapping,
        want.snapping,
        "{name}: grid: {}",
        probes.grid.describe()
    );
    if let Some(r) = &reported {
        assert_eq!(
            fresh.snapping.grid_bits(),
            r.subpixel_bits,
            "{name}: the reported grid"
        );
        assert_eq!(
            probes.grid.bits(),
            r.subpixel_bits,
            "{name}: the probe agrees with it"
        );
    }
    let ties = probes.tie_rule.describe();
    assert_eq!(fresh.fill, want.fill, "{name}: {ties}");
    assert_eq!(probes.tie_rule.twice > 0, covered_twice, "{name}: {ties}");
    assert_eq!(fresh.snap, want.snap, "{name}: {}", probes.snap.describe());
    assert_eq!(
        fresh.ties_to_even,
        want.ties_to_even,
        "{name}: {}",
        probes.rounding.describe()
    );
    assert_eq!(
        fresh.guard_band,
        want.guard_band,
        "{name}: {}",
        probes.band.describe()
    );
    assert_eq!(
        fresh.tolerance_subpixels,
        want.tolerance_subpixels,
        "{name}: {}",
        probes.coverage.describe()
    );
    assert!(
        probes.precision.bits() >= fewest_bits && fresh.precision_bits == want.precision_bits,
        "{name}: {}",
        probes.precision.describe()
    );
    assert_eq!(
        primitives(&fresh),
        primitives(&want),
        "{name}: {}",
        probes.primitives.describe()
    );
    let declared = gpu.profile();
    assert_eq!(
        (
            declared.lines,
            declared.points,
            declared.point_snapping,
            declared.endpoint_snapping
        ),
        (
            fresh.lines,
            fresh.points,
            fresh.point_snapping,
            fresh.endpoint_snapping
        ),
        "{name}: the profile declares it"
    );
    assert_eq!(
        (&declared.multisample, declared.point_clipping),
        (&fresh.multisample, fresh.point_clipping),
        "{name}: the profile declares it"
    );
    println!("{name}: every measured choice is the pinned one");
}
