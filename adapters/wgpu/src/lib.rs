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
//! # The profile is measured on the driver, never assumed from another
//!
//! wgpu cannot ask for a fill rule or a subpixel precision, and reports neither, so each
//! driver's profile is measured when it is opened ([`Gpu::new`]), and [`Rasterizer::about`] says
//! what was chosen and why (`refrast certify` prints it as "reports itself as"):
//!
//! - **Grid.** A Vulkan driver's is the `subPixelPrecisionBits` it reports, read from
//!   `vulkaninfo` run with the driver's environment (`reported.rs`: the device whose name and
//!   IDs are the adapter's); the grid probe checks it. `vulkaninfo` missing makes the driver
//!   unavailable (`apt-get install vulkan-tools`). OpenGL reports nothing through wgpu: the
//!   probe measures the finest vertex move that changes coverage, and a driver moved by every
//!   step down to 2^-16 px (softpipe) has no grid (`Snapping::Float`, its band from how far
//!   from an edge a sample was decided against exact arithmetic).
//! - **Tie rule.** Which single edges own a sample exactly on them, over 262 tie samples: the
//!   convention that fits every one, else none. Shared edges covered twice are reported as the
//!   bug they are (Vulkan and OpenGL require exactly one), never read as a declaration.
//! - **Snapping.** A vertex a few f32 ulps from a snap tie landing on the farther grid point
//!   declares `SnapAccuracy::WithinOneStep` (Vulkan computes the viewport transform in floating
//!   point); exact ties all going to the even grid point declare `ties_to_even`.
//! - **Guard band.** 0 when a tie sample on an edge leaving the viewport flips (the driver clips
//!   x/y at the viewport and snaps the cut); else the largest reach tried that flips none.
//! - **Precision.** The bits kept on 1206 unclipped slivers and triangles, less
//!   [`measured::MARGIN`]: Vulkan and OpenGL hold a clipped polygon's values only to being a
//!   convex combination, and the suite judges them so (docs/levels.md).
//!
//! - **Lines, points and samples** (`probe/primitives.rs`). The line rule no probe segment
//!   disagrees with, else the nearest (the `line.` rules judge within each specification's
//!   allowance); points, and the grid they snap to when coarser than the triangles' (softpipe's
//!   quarter pixel); the 4 sample positions, read off coverage, when the driver runs fragment
//!   shaders per sample. Lines and points draw through wgpu's line-list, line-strip and
//!   point-list pipelines; at 4 samples a shader run per sample (`multisample.wgsl`) captures
//!   each covered sample, and the resolve's multisampled targets are read back by a pass that
//!   loads each sample (`unpack.wgsl`). A strip's primitive ids are measured too: OpenGL ES
//!   takes flat values from a segment's last vertex, Vulkan from its first.
//! - **Depth bias slope** (`probe/bias.rs`): whether the bias's `m` is the depth gradient's
//!   length or its largest component, read off the depth buffer (every driver here: the max).
//!
//! Every probe is a few batched draws read back by primitive id (`probe/`, well under a second
//! a process); the result is kept per driver and version under the target folder (`cache.rs`),
//! so each rule's child process reads it instead. `tests/measured.rs` pins every choice on this
//! project's machine: lavapipe 8 bits, top-left, within one step, ties to even, no guard band,
//! 7 bits of precision (measured 9.4); llvmpipe the same with 8 (10.1); softpipe no grid, no tie
//! rule, 7 (9.3); SwiftShader 4 bits (reported and measured), top-left, within one step, ties
//! to even, no guard band, 12 (14.9). What stays declared, not measured: depth is z/w
//! interpolated linearly on screen (Vulkan, Basic Polygon Rasterization), zero area is not decided before clipping
//! (Mesa and SwiftShader clip first), and the draw states WebGPU allows: it clips depth to
//! `0 ≤ z ≤ w` (far clipping cannot be switched off alone: `unclipped_depth`, declared where the
//! adapter reports `DEPTH_CLIP_CONTROL`, drops both planes and clamps) and has no `−w ≤ z`
//! range, so the suite sends no such draw; its viewport depth ranges are `set_viewport`'s,
//! `minDepth ≤ maxDepth` only. Vulkan asks only
//! that a sample on an edge shared by two polygons be covered by exactly one of them (Basic Polygon Rasterization);
//! the `fill.*.exactly-once` rules judge that whatever the profile says.
//!
//! One device per process and driver is created, on first use ([`device::context`]). A driver
//! that is missing, or an adapter that is not the one asked for, makes the built-in
//! unavailable, with the reason; it never quietly falls back to another driver.
#![forbid(unsafe_code)]

mod cache;
pub mod device;
mod draw;
pub mod measured;
mod pipelines;
pub mod probe;
pub mod reported;
mod resources;
mod targets;
mod unpack;

use std::sync::{Arc, Mutex};

use refrast::{
    BiasSupport, CompareOp, DepthConvention, DepthFormat, DepthRange, Draw, DrawError, Features, Fragment,
    PolygonMode, Profile, ProvokingVertex, Rasterizer, Resolved, StateSupport, Supported, Unavailable,
};

pub use device::Driver;
use device::{Context, context, describe};
use measured::Measured;
use pipelines::{Method, Pipelines};
use probe::Probes;
use reported::Reported;

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
    measured: Arc<Measured>,
}

impl Gpu {
    /// The driver asked for, on this process's device for it, with its profile measured (once
    /// per process, and kept on disk per driver and version: see `cache.rs`); why not, when
    /// there is none, when it is a Vulkan driver and `vulkaninfo` is missing, or when measuring
    /// fails.
    pub fn new(driver: Driver) -> Result<Self, Unavailable> {
        let context = context(driver)?;
        if let Some(why) = reported::missing(driver) {
            return Err(why);
        }
        let mut pipelines = Pipelines::new(&context.device);
        let measured = cache::measured(driver, &context, || {
            let (reported, probes) = probe_now(driver, &context, &mut pipelines)?;
            Ok(measured::choose(driver.spec(), reported.as_ref(), &probes))
        })?;
        Ok(Self {
            driver,
            context,
            pipelines: Mutex::new(pipelines),
            measured,
        })
    }

    /// What the driver reports and what the probes see, read and run now (not from the file
    /// [`Gpu::new`] may have read its profile from): the tests pin these.
    pub fn probe(&mut self) -> Result<(Option<Reported>, Probes), Unavailable> {
        let mut pipelines = self.pipelines();
        probe_now(self.driver, &self.context, &mut pipelines)
    }

    /// The profile's measured declarations, with why.
    #[must_use]
    pub fn measured(&self) -> &Measured {
        &self.measured
    }

    /// [`Rasterizer::resolve`], with how long the device took to draw and how long reading
    /// the targets back took, apart (the side-by-side benchmark reports both).
    pub fn resolve_timed(&mut self, draw: &Draw) -> Result<(Resolved, Timings), DrawError> {
        self.check(draw)?;
        let r = draw::resolve(&self.context, &mut self.pipelines(), draw)?;
        let mut resolved = Resolved {
            viewport: draw.viewport,
            samples: draw.samples,
            depth: r.depth,
            primitive: r.primitive,
        };
        // Without a depth copy (OpenGL ES), the depth read back is the passing fragment's
        // FragCoord.z, which the buffer itself holds clamped: to the range where depth clipping
        // is off, and to [0, 1] where a bias may carry it out ("Fragment depth values are
        // clamped even when the depth buffer uses a floating-point representation", OpenGL ES
        // 3.2 §13.7.2; FragCoord.z "already has a polygon offset added in", unclamped).
        let biased = draw.state.depth_bias.is_some() && draw.topology.is_triangles();
        if !self.context.copies_depth && (!draw.state.clip_near || biased) {
            let range = draw.state.viewport_depth;
            for (depth, primitive) in resolved.depth.iter_mut().zip(&resolved.primitive) {
                if primitive.is_some() && draw.state.depth.write {
                    *depth = depth.clamp(0.0, 1.0);
                    if !draw.state.clip_near {
                        *depth = range.fragment_depth(f64::from(*depth));
                    }
                }
            }
        }
        Ok((resolved, r.timings))
    }

    /// The adapter drawing, as wgpu reports it.
    #[must_use]
    pub fn adapter(&self) -> &wgpu::AdapterInfo {
        &self.context.info
    }

    /// Refuses a draw the driver cannot do as asked, rather than draw something else: lines,
    /// points or samples its measured profile does not declare, and what
    /// [`Gpu::check_target`] refuses. The profile it checked against, built once a draw.
    fn check(&self, draw: &Draw) -> Result<Profile, DrawError> {
        draw.validate()?;
        let profile = self.profile();
        if !profile.draws(draw.topology, draw.samples) {
            return Err(DrawError::Unsupported(format!(
                "{} draws no {} (measured: {})",
                self.driver.name(),
                draw.describe(),
                self.measured.summary()
            )));
        }
        self.check_target(&profile, draw.viewport, &draw.state)?;
        let d = &draw.distances;
        if d.clip > profile.state.clip_distances || d.cull > profile.state.cull_distances {
            return Err(DrawError::Unsupported(format!(
                "{} clip and {} cull distances per vertex: {} takes {} clip distances (wgpu's CLIP_DISTANCES) and no cull distances (WGSL has none)",
                d.clip,
                d.cull,
                self.driver.name(),
                profile.state.clip_distances
            )));
        }
        if let Some(b) = draw.state.depth_bias.filter(|_| draw.topology.is_triangles()) {
            // `as` saturates: a constant that reads back unchanged is a whole i32.
            if f64::from(b.constant as i32) != f64::from(b.constant) {
                return Err(DrawError::Unsupported(format!(
                    "wgpu takes a depth bias constant as an i32 (DepthBiasState::constant), not {}",
                    b.constant
                )));
            }
        }
        Ok(profile)
    }

    /// Refuses a state WebGPU cannot set (far clipping off, `−w ≤ z`) and a target beyond the
    /// device's largest side.
    fn check_target(
        &self,
        profile: &Profile,
        viewport: refrast::Viewport,
        state: &refrast::DrawState,
    ) -> Result<(), DrawError> {
        if !profile.supports(state) {
            return Err(DrawError::Unsupported(format!(
                "{} cannot draw with {state:?}: far clipping is on unless depth clipping is off \
                 altogether, z runs 0 ≤ z ≤ w, depth ranges run up, and wgpu culls one face or \
                 none (the nearest it draws: {:?})",
                profile.name,
                profile.fit(*state)
            )));
        }
        let side = self.context.max_side;
        if viewport.width() > side || viewport.height() > side {
            return Err(DrawError::Unsupported(format!(
                "a {}×{} target is beyond this device's {side}-pixel limit",
                viewport.width(),
                viewport.height()
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

/// Reads `vulkaninfo` (Vulkan drivers) and runs every probe through the capture pass.
fn probe_now(
    driver: Driver,
    ctx: &Context,
    pipelines: &mut Pipelines,
) -> Result<(Option<Reported>, Probes), Unavailable> {
    let reported = if driver.spec() == refrast::Spec::Vulkan {
        Some(reported::read(driver, &ctx.info)?)
    } else {
        None
    };
    let bits = reported.as_ref().and_then(|r| r.subpixel_bits);
    let multisampling = ctx.no_multisampling.clone().map_or(Ok(()), Err);
    let failed = |e: DrawError| Unavailable(format!("measuring {}'s profile failed: {e}", driver.name()));
    let mut probes =
        probe::measure(&mut |d| draw::capture(ctx, pipelines, d), bits, multisampling).map_err(failed)?;
    probes.slope = probe::bias::probe(&mut |d| {
        draw::resolve(ctx, pipelines, d).map(|r| Resolved {
            viewport: d.viewport,
            samples: d.samples,
            depth: r.depth,
            primitive: r.primitive,
        })
    })
    .map_err(failed)?;
    Ok((reported, probes))
}

impl Rasterizer for Gpu {
    fn profile(&self) -> Profile {
        let m = &self.measured;
        Profile {
            name: self.driver.name().into(),
            snapping: m.snapping,
            fill: m.fill,
            // Window depth is z/w, interpolated linearly on screen (Vulkan, Basic Polygon Rasterization).
            depth: DepthConvention::ScreenLinearZOverW,
            tolerance_subpixels: m.tolerance_subpixels,
            precision_bits: m.precision_bits,
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
                guard_band: m.guard_band,
                ties_to_even: m.ties_to_even,
                snap: m.snap,
                // Mesa and SwiftShader clip first; no probe shows the reference's order.
                zero_area_before_clipping: false,
                clips_in_3d: true,
                // wgpu's GL backend writes `gl_Position.z = 2z − w` in the vertex shader (naga's
                // ADJUST_COORDINATE_SPACE, always on in wgpu-hal's GLES device).
                z_rewritten_in_f32: self.driver.backends() == wgpu::Backends::GL,
            },
            spec: self.driver.spec(),
            // What the probes measured: the line rule, points, and the 4 samples' positions.
            lines: m.lines,
            points: m.points,
            endpoint_snapping: m.endpoint_snapping,
            point_snapping: m.point_snapping,
            multisample: m.multisample.clone(),
            point_clipping: m.point_clipping,
            // The scissor test is core in Vulkan, OpenGL and OpenGL ES, and wgpu sets it on
            // every backend (`set_scissor_rect`, in raster space on each); its `Face` has no
            // value for both faces, and its `PrimitiveTopology` no triangle fan, so neither is
            // declared (their rules are n/a). Triangle strips are core everywhere. Flat values
            // (WGSL `@interpolate(flat)`) come from the mode the API fixes, as wgpu sets no
            // other: Vulkan's default, the first vertex; OpenGL ES's only one, the last (§12.4,
            // Table 12.3); the rule checks each driver against it. The viewport's depth range is
            // `set_viewport`'s, which rejects `min_depth > max_depth`. Depth clipping off is
            // `unclipped_depth` where the adapter reports DEPTH_CLIP_CONTROL. The sample mask is
            // WebGPU's `multisample.mask`.
            state: StateSupport {
                scissor: true,
                // `MultisampleState::mask`, core in WebGPU, which wgpu-hal 30 passes on to
                // Vulkan as `pSampleMask` (both words, at every count) but never reads in its
                // GLES backend (no `SampleMaski`): declared there, it would blame the driver
                // for what wgpu drops.
                sample_mask: self.driver.backends() == wgpu::Backends::VULKAN,
                // WGSL's `@interpolate(perspective, centroid)` at pixel rate, with the
                // `sample_mask` input naming the covered samples (`centroid.wgsl`); declared
                // with the mask, on Vulkan only, the one backend whose multisampled captures
                // the drivers here run.
                centroid: self.driver.backends() == wgpu::Backends::VULKAN,
                // `PrimitiveState::conservative`: overestimation of filled triangles, no extra
                // size. wgpu reports neither `primitiveOverestimationSize` nor
                // `degenerateTrianglesRasterized`: half a pixel is assumed (D3D12's Tier 1
                // bound; NVIDIA reports 1/256), and either degenerate outcome accepted.
                conservative: self.context.conservative.then_some(refrast::ConservativeSupport {
                    overestimation_size: 0.5,
                    max_extra: 0.0,
                    extra_granularity: 0.0,
                    underestimate: false,
                    degenerate_triangles: None,
                }),
                cull_both: false,
                triangle_strips: true,
                triangle_fans: false,
                flat: Supported::only(&[if self.driver.backends() == wgpu::Backends::GL {
                    ProvokingVertex::Last
                } else {
                    ProvokingVertex::First
                }]),
                viewport_depth: true,
                inverted_depth: false,
                unclipped_depth: self.context.unclipped_depth,
                // The attachment is Depth32Float; the slope measure is the probe's.
                depth_bias: Some(BiasSupport {
                    format: DepthFormat::Float32,
                    slope: m.bias_slope,
                    clamp: self.context.bias_clamp,
                }),
                // wgpu's `PolygonMode` where the device has it: line mode by the measured line
                // rule, point mode with the measured points.
                polygon_modes: Supported::only(
                    &self
                        .context
                        .polygon_modes
                        .values()
                        .filter(|&mode| match mode {
                            PolygonMode::Line => m.lines.is_some(),
                            _ => m.points,
                        })
                        .collect::<Vec<_>>(),
                ),
                // WGSL's `clip_distances` (an array of at most 8) where the device has wgpu's
                // CLIP_DISTANCES; WGSL has no cull distances.
                clip_distances: if self.context.clip_distances { 8 } else { 0 },
                cull_distances: 0,
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
        let m = &self.measured;
        let reported = if m.reported.is_empty() {
            String::new()
        } else {
            format!("; vulkaninfo: {}", m.reported)
        };
        format!(
            "{}{how}{reported}; measured: {}",
            describe(&self.context.info),
            m.why
        )
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let profile = self.check(draw)?;
        let mut fragments = draw::capture(&self.context, &mut self.pipelines(), draw)?;
        // The capture reads FragCoord.z, which no specification clamps (Vulkan clamps z_f on its
        // way to the depth test, D3D11.3 §16.3.1 leaves the shader's input unclamped): the
        // depth a fragment tests, the contract's, is it clamped to the range where depth
        // clipping is off or a bias may carry it out (OpenGL's FragCoord.z "already has a
        // polygon offset added in"). The depth buffer `resolve` reads shows the driver's own
        // clamp.
        let biased = draw.state.depth_bias.is_some() && draw.topology.is_triangles();
        if !draw.state.clip_near || biased {
            let range = draw.state.viewport_depth;
            for f in &mut fragments {
                f.depth = range.fragment_depth(f64::from(f.depth));
            }
        }
        // Flat values come in the backend's one mode: under another, none is reported.
        if !profile.state.flat.contains(draw.state.provoking_vertex) {
            fragments.iter_mut().for_each(|f| f.flat = None);
        }
        Ok(fragments)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        self.resolve_timed(draw).map(|(resolved, _)| resolved)
    }
}
