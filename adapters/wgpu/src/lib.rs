//! Real GPU drivers behind refrast's [`Rasterizer`] trait, through wgpu: Mesa's lavapipe
//! (Vulkan), llvmpipe and softpipe (OpenGL ES over EGL), Google's SwiftShader (Vulkan), or any
//! Vulkan adapter.
//!
//! The draw's clip-space positions go straight to the vertex stage, so the driver does its own
//! clipping, snapping, fill rule and depth test; that is what gets certified. Two passes read
//! back what it did:
//!
//! - **capture**: no depth test, a fragment shader appending every covered sample to a storage
//!   buffer with an atomic counter: pixel, primitive, window depth (`@builtin(position).z`),
//!   the barycentric unit vectors interpolated perspective-correctly and `@interpolate(linear)`,
//!   and `@builtin(front_facing)`. A driver whose fragment shaders cannot write storage buffers
//!   (softpipe's OpenGL ES) draws one triangle per pass into two `Rgba32Float` targets instead
//!   (`targets.rs`); a triangle covers a sample at most once, so nothing is lost;
//! - **resolve**: the driver's depth test against a `Depth32Float` attachment cleared to the
//!   draw's value, with the primitive id in an `R32Uint` target. The depth buffer is copied
//!   back; OpenGL ES cannot copy depth textures, so there the passing fragment also writes its
//!   depth's bits to a second `R32Uint` target, which with writes on is what the depth buffer
//!   holds (with writes off the buffer keeps its clear value, and a driver writing it anyway
//!   would show in the ids).
//!
//! # What the driver promises, and what the profile says
//!
//! wgpu cannot ask for a fill rule or a subpixel precision, so the profile states what the
//! driver documents, and the suite measures whether it holds:
//!
//! - Mesa's llvmpipe (lavapipe's rasterizer) reports `subPixelPrecisionBits = 8` and
//!   `standardSampleLocations` (`vulkaninfo` on Mesa 22.3.6); its setup code (`lp_setup_tri.c`)
//!   breaks ties with D3D's top-left rule in a y-down framebuffer. Declared: an 8-bit grid,
//!   top-left; `fill.top-left.exact` and `fill.brute-force.exact` pass 20 000 cases each.
//! - OpenGL names no tie rule, and softpipe keeps none (it covers a sample on a vertex where
//!   two right edges meet): declared an 8-bit grid and no tie rule.
//! - SwiftShader as Chromium builds it (`SWIFTSHADER_LEGACY_PRECISION`) reports
//!   `subPixelPrecisionBits = 4`; its setup (`SetupRoutine::edge`) walks edges in exact integers
//!   with ceiling divisions, spans `[left, right)` and rows from the top vertex's inclusive:
//!   the top-left rule. It clips x/y at the viewport (`Clipper.cpp`) and rounds with
//!   `cvtps2dq`, ties to even. Declared: lavapipe's profile on a 4-bit grid. Measured
//!   (`tests/swiftshader.rs`): the tie rule, exact ties and no guard band hold; it snaps
//!   `x·(1/w)·scale + offset` computed in f32, not `x/w` rounded, so a vertex within a few f32
//!   ulps of a tie (`2.5·10⁻⁶` px on a 64-px target) may land one step from the reference's
//!   (on a 2.8-px triangle with w from 0.1 to 3.3 that moved a weight by 0.46); and its f32
//!   plane equations, anchored at the vertex of largest w, keep 13 bits on slivers but as few
//!   as 3.6 on triangles reaching 10⁵ px. Lavapipe does not round x/w either (the same probe), on a grid
//!   16 times finer.
//! - Measured, against what a first profile assumed: Mesa clips x/y against the viewport (a
//!   tie on an edge leaving it flips), so no guard band is declared; and its f32 interpolation
//!   keeps 8 bits on slivers with very unequal w, so `precision_bits` is 8. Both are checked
//!   in `tests/drivers.rs`.
//! - Vulkan asks only that a sample on an edge shared by two polygons be covered by exactly one
//!   of them (§28.7.1); the `fill.*.exactly-once` rules judge that whatever the profile says.
//! - WebGPU clips depth to `0 ≤ z ≤ w` always (far clipping cannot be switched off without a
//!   feature that also drops near clipping) and has no `−w ≤ z` range: those are declared
//!   unsupported, and the suite sends no such draw.
//!
//! One device per process and driver is created, on first use ([`device::context`]). A driver
//! that is missing, or an adapter that is not the one asked for, makes the built-in
//! unavailable, with the reason; it never quietly falls back to another driver.
#![forbid(unsafe_code)]

pub mod device;
mod draw;
mod pipelines;
pub mod probe;
pub mod reported;
mod targets;

use std::sync::{Arc, Mutex};

use refrast::{
    CompareOp, DepthConvention, DepthRange, Draw, DrawError, Features, FillConvention, Fragment, Profile,
    Rasterizer, Resolved, SnapAccuracy, Snapping, Spec, Supported,
};
use refrast_conformance::{BuiltIn, Origin, Unavailable};

pub use device::Driver;
use device::{Context, context, describe};
use pipelines::{Method, Pipelines};

/// How long a resolve took on the device.
#[derive(Clone, Copy, Debug)]
pub struct Timings {
    /// From submitting the draw to the device finishing it.
    pub drawing: std::time::Duration,
    /// Copying the depth and id targets to buffers and mapping them.
    pub reading: std::time::Duration,
}

/// A driver behind wgpu, as a [`Rasterizer`].
pub struct Gpu {
    driver: Driver,
    context: Arc<Context>,
    pipelines: Mutex<Pipelines>,
}

impl Gpu {
    /// The driver asked for, on this process's device for it; why not, when there is none.
    pub fn new(driver: Driver) -> Result<Self, Unavailable> {
        let context = context(driver)?;
        let pipelines = Mutex::new(Pipelines::new(&context.device));
        Ok(Self {
            driver,
            context,
            pipelines,
        })
    }

    /// [`Rasterizer::resolve`], with how long the device took to draw and how long reading
    /// the targets back took, apart (the side-by-side benchmark reports both).
    pub fn resolve_timed(&mut self, draw: &Draw) -> Result<(Resolved, Timings), DrawError> {
        self.check(draw)?;
        let r = draw::resolve(&self.context, &mut self.pipelines(), draw)?;
        let resolved = Resolved {
            viewport: draw.viewport,
            depth: r.depth,
            primitive: r.primitive,
        };
        Ok((resolved, r.timings))
    }

    /// The adapter drawing, as wgpu reports it.
    #[must_use]
    pub fn adapter(&self) -> &wgpu::AdapterInfo {
        &self.context.info
    }

    /// Refuses a draw the driver cannot do as asked, rather than draw something else.
    fn check(&self, draw: &Draw) -> Result<(), DrawError> {
        draw.validate()?;
        let profile = self.profile();
        if !profile.supports(&draw.state) {
            return Err(DrawError::Unsupported(format!(
                "{} cannot draw with {:?}: far clipping is always on and z runs 0 ≤ z ≤ w",
                profile.name, draw.state
            )));
        }
        let side = self.context.max_side;
        if draw.viewport.width() > side || draw.viewport.height() > side {
            return Err(DrawError::Unsupported(format!(
                "a {}×{} target is beyond this device's {side}-pixel limit",
                draw.viewport.width(),
                draw.viewport.height()
            )));
        }
        Ok(())
    }

    fn pipelines(&self) -> std::sync::MutexGuard<'_, Pipelines> {
        self.pipelines
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl Rasterizer for Gpu {
    fn profile(&self) -> Profile {
        Profile {
            name: self.driver.name().into(),
            // llvmpipe's subPixelPrecisionBits and its setup's top-left rule (see the crate docs);
            // OpenGL names no tie rule, and softpipe keeps none: it covers a sample on a vertex
            // where two right edges meet (tests/drivers.rs).
            snapping: match self.driver {
                // SwiftShader as Chromium builds it (`SWIFTSHADER_LEGACY_PRECISION`) reports
                // `subPixelPrecisionBits = 4` and snaps to sixteenths (`vk::SUBPIXEL_PRECISION_BITS`).
                Driver::Swiftshader => Snapping::Grid(4),
                _ => Snapping::Grid(8),
            },
            fill: match self.driver {
                Driver::Softpipe => None,
                _ => Some(FillConvention::TopLeft),
            },
            // Window depth is z/w, interpolated linearly on screen (Vulkan §28.7.5).
            depth: DepthConvention::ScreenLinearZOverW,
            // Snapping moves an edge by up to √2/2 subpixel from where the float input puts it.
            tolerance_subpixels: 1,
            // Neither Vulkan nor Mesa bounds interpolation. Measured, not assumed: Mesa's f32
            // plane equations keep about 14 bits on ordinary triangles, but on a 0.008-px sliver
            // with a 30:1 w ratio lavapipe's weight at a vertex is 0.99744 (2^-8.6 off;
            // tests/drivers.rs). 8 bits is what they keep on every case the suite draws.
            // SwiftShader keeps 13 on slivers but as few as 3.6 on triangles reaching 10⁵ px
            // (tests/swiftshader.rs): no claim would hold there, so it claims 8 and fails those.
            precision_bits: 8,
            features: Features {
                perspective_barycentrics: true,
                screen_barycentrics: true,
                cull_modes: Supported::ALL,
                front_faces: Supported::ALL,
                depth_test: true,
                compare_ops: Supported::<CompareOp>::ALL,
                depth_writes: Supported::ALL,
                far_clipping: Supported::only(&[true]),
                depth_ranges: Supported::only(&[DepthRange::ZeroToOne]),
                // Mesa and SwiftShader clip x/y against the viewport for a triangle reaching
                // outside it: a tie sample on an edge crossing the boundary can flip
                // (tests/drivers.rs, tests/swiftshader.rs).
                guard_band: 0,
                // Mesa's setup snaps with `util_iround`, to nearest under the CPU's default
                // rounding: ties to even. Checked on lavapipe and llvmpipe (tests/drivers.rs, a
                // tie found by `mutant:half-up-snap`; both exact rules at 20000 cases with ties);
                // softpipe keeps no tie rule, so its exact rules do not apply either way.
                // SwiftShader rounds with `cvtps2dq` (tests/swiftshader.rs: exact ties in x and
                // y go to even).
                ties_to_even: self.driver != Driver::Softpipe,
                // Mesa's setup snaps the f32 viewport transform's result to nearest; no claim
                // about zero-area triangles cut by the near plane (Mesa clips first).
                snap: SnapAccuracy::Nearest,
                zero_area_before_clipping: false,
            },
            spec: match self.driver {
                Driver::Lavapipe | Driver::Swiftshader | Driver::Vulkan => Spec::Vulkan,
                Driver::Llvmpipe | Driver::Softpipe => Spec::OpenGl,
            },
        }
    }

    fn about(&self) -> String {
        let how = match self.pipelines().method {
            Method::StorageBuffer => "",
            Method::FloatTargets => {
                "; no storage buffers in fragment shaders, so captured one triangle per pass"
            }
        };
        format!("{}{how}", describe(&self.context.info))
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        self.check(draw)?;
        draw::capture(&self.context, &mut self.pipelines(), draw)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        self.resolve_timed(draw).map(|(resolved, _)| resolved)
    }
}

/// Every driver as a built-in: `refrast certify --impl lavapipe`, and so on.
#[must_use]
pub fn builtins() -> Vec<BuiltIn> {
    Driver::ALL
        .iter()
        .map(|&driver| {
            let description = match driver {
                Driver::Lavapipe => "Mesa's lavapipe (Vulkan on the CPU) through wgpu",
                Driver::Llvmpipe => "Mesa's llvmpipe through wgpu's OpenGL ES backend (EGL)",
                Driver::Softpipe => {
                    "Mesa's softpipe (GALLIUM_DRIVER=softpipe) through wgpu's OpenGL ES backend"
                }
                Driver::Swiftshader => {
                    "Google's SwiftShader (Vulkan on the CPU, as Chromium ships it) through wgpu"
                }
                Driver::Vulkan => "whatever Vulkan adapter this machine has (a GPU first) through wgpu",
            };
            let mut b = BuiltIn::fallible(driver.name(), description, Origin::ThirdParty, move || {
                Ok(Box::new(Gpu::new(driver)?) as Box<dyn Rasterizer>)
            });
            for (name, value) in driver.env() {
                b = b.with_env(name, value);
            }
            b
        })
        .collect()
}
