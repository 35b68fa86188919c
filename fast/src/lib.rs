//! refrast-fast: a rasterizer with the reference's exact coverage and its own f32
//! interpolation, binned, tiled, blocked, in SIMD lanes chosen at run time, and threaded.
//!
//! [`Fast`] covers exactly the samples [`Reference::default`] covers, with the same primitive
//! ids and facing (the same snapped integer edge functions, fill rule and clipping decisions);
//! its depth and barycentrics are its own, within 2^-[`PRECISION_BITS`] of the exact values,
//! the precision its profile declares. Its resolved buffers differ from the reference's only
//! where two primitives' depths tie within that precision.
//!
//! # How
//!
//! - **Front end**: each triangle goes through the reference's own stages ([`refrast::stage`]:
//!   assemble, snap before clipping, clip, project, fan, facing, cull, bounding box); nothing
//!   that decides coverage is copied. What depends on one vertex alone (finiteness, clip
//!   outcode, projection and snapping) is computed once per mesh vertex. Triangles are set up
//!   in batches, split among threads.
//! - **Binning**: each triangle's box is binned into 64×64 tiles; a row of tiles is a band, a
//!   contiguous run of rows of every buffer, so threads own bands and need no locks.
//! - **Back end**: per tile, triangles in primitive order; per triangle, 8×8 blocks rejected
//!   or accepted whole from their corners (Abrash, *Rasterization on Larrabee*), each block row
//!   tested as eight SIMD lanes of exact edge values: `i32` when the triangle's box is small,
//!   `f64` (exact below 2^53) otherwise; a part of a tile at most 8 pixels wide goes row by row,
//!   without blocks. A clipped polygon's fan goes through the reference's own `traverse` on the
//!   tile's part of its box.
//! - **Warming**: before a tile's triangles are drawn, one value per cache line of the
//!   buffers under it and a few of each triangle's record are read, independently, so that
//!   their misses overlap instead of stalling the first samples drawn one at a time.
//! - **Hidden blocks**: under `Less`, `LessOrEqual`, `Greater` or `GreaterOrEqual`, a block of
//!   a triangle whose box holds four blocks' worth of pixels is skipped when a bound of its
//!   depths fails against a bound of the depths stored there (Greene's hierarchical z,
//!   `hiz.rs`): the samples skipped are exactly ones that would fail, so no output changes.
//! - **Interpolation**: depth and barycentrics as f32 planes over the exact edge values, set up
//!   once per triangle; depth for eight lanes at once, no division per sample; a fragment's
//!   perspective correction takes one reciprocal.
//! - **SIMD**: [`fearless_simd`], its level ([`SimdLevel`]) detected at run time; every level
//!   and the scalar fallback give the same bits (no fused multiply-add).
//!
//! # Order of fragments
//!
//! [`rasterize`](Rasterizer::rasterize) returns fragments by band of 64 rows, top to bottom;
//! within a band by batch of 16 384 primitives, then tile left to right, then primitive, then
//! 8×8 block row by row, then sample row-major (a triangle whose part of the tile is at most 8
//! pixels wide: row by row). Compare with the reference as sorted sets.
#![forbid(unsafe_code)]

mod back;
pub mod contract;
mod drive;
mod front;
mod hiz;
mod plane;
mod simd;
mod sink;
mod tiles;

use std::sync::Arc;

use rayon::ThreadPool;
use refrast::{
    BiasSupport, Draw, DrawError, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, Resolved,
    StateSupport,
};

pub use crate::plane::PRECISION_BITS;
pub use crate::simd::SimdLevel;

use crate::drive::Buffers;
use crate::hiz::HiZ;
use crate::sink::{ResolveBand, ShadeBand};
use crate::tiles::{BandRows, TILE};

/// The fast rasterizer's knobs: the reference's configuration it reproduces, and threads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FastConfig {
    /// Snapping, fill rule and clipping, as the reference it matches has them.
    pub reference: ReferenceConfig,
    /// Threads to draw with; 1 draws on the calling thread without rayon.
    pub threads: usize,
    /// The SIMD level of the back end; [`SimdLevel::Best`] detects it. The output is the same
    /// at every level.
    pub simd: SimdLevel,
}

impl Default for FastConfig {
    /// The reference's defaults, one thread per available core.
    fn default() -> Self {
        Self {
            reference: ReferenceConfig::default(),
            threads: std::thread::available_parallelism().map_or(1, usize::from),
            simd: SimdLevel::Best,
        }
    }
}

/// The fast rasterizer: the reference's output, drawn in tiles by several threads.
#[derive(Clone, Debug)]
pub struct Fast {
    config: FastConfig,
    pool: Option<Arc<ThreadPool>>,
    buffers: Buffers,
}

impl Default for Fast {
    fn default() -> Self {
        Self::new(FastConfig::default())
    }
}

impl Fast {
    /// A fast rasterizer with `config`; with `threads > 1` it starts its own thread pool.
    ///
    /// Should the pool fail to start, it draws on the calling thread: same output, slower.
    /// Should the CPU lack `config.simd`, it draws at the best level it has: same output.
    #[must_use]
    pub fn new(config: FastConfig) -> Self {
        let pool = (config.threads > 1)
            .then(|| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(config.threads)
                    .build()
                    .ok()
            })
            .flatten()
            .map(Arc::new);
        Self {
            config,
            pool,
            buffers: Buffers::default(),
        }
    }

    /// One with the reference's defaults and `threads` threads.
    #[must_use]
    pub fn with_threads(threads: usize) -> Self {
        Self::new(FastConfig {
            threads,
            ..FastConfig::default()
        })
    }

    /// Its configuration.
    #[must_use]
    pub fn config(&self) -> FastConfig {
        self.config
    }

    /// The SIMD level it draws at: the configured one, or the best the CPU has when it lacks it.
    #[must_use]
    pub fn simd(&self) -> SimdLevel {
        SimdLevel::of(self.level())
    }

    /// Calls `f` on every item of `items`, spread over this rasterizer's threads (on the
    /// calling thread with one): for work that follows a draw at its thread count, such as
    /// shading a visibility buffer band by band.
    pub fn for_each<T: Send>(&self, items: &mut [T], f: impl Fn(&mut T) + Sync) {
        drive::for_each(self.pool.as_deref(), items, |_, item| f(item));
    }

    /// Draws `draw` into `sinks`, one per band of tiles, with this rasterizer's configuration,
    /// SIMD level, threads and buffers.
    fn drive<K: sink::Sink>(&mut self, draw: &Draw, sinks: &mut [K]) -> Result<(), DrawError> {
        drive::run(
            self.config.reference,
            self.level(),
            self.pool.as_deref(),
            &mut self.buffers,
            draw,
            sinks,
        )
    }

    /// The level handed to the back end.
    fn level(&self) -> fearless_simd::Level {
        self.config.simd.level().unwrap_or_else(fearless_simd::Level::new)
    }

    /// Draws `draw` into row-major `depth` and `color` buffers of its viewport's size, in the
    /// order of work of `refrast::pipeline::Renderer::draw_mesh`: early depth test on the
    /// sample's depth, then `shade` on its fragment (`None` discards), then the writes.
    pub fn render<C, F>(
        &mut self,
        draw: &Draw,
        depth: &mut [f32],
        color: &mut [C],
        shade: F,
    ) -> Result<(), DrawError>
    where
        C: Send,
        F: Fn(&Fragment) -> Option<C> + Sync,
    {
        let (pixels, width) = (draw.viewport.pixel_count(), draw.viewport.width());
        if depth.len() != pixels || color.len() != pixels {
            return Err(DrawError::Unsupported(format!(
                "buffers of {} and {} pixels for a viewport of {pixels}",
                depth.len(),
                color.len()
            )));
        }
        let band = (width * TILE) as usize;
        let mut sinks: Vec<_> = depth
            .chunks_mut(band)
            .zip(color.chunks_mut(band))
            .enumerate()
            .map(|(i, (depth, color))| {
                let rows = BandRows {
                    y0: i as u32 * TILE,
                    width,
                };
                ShadeBand {
                    rows,
                    compare: draw.state.depth.compare,
                    write: draw.state.depth.write,
                    hiz: HiZ::new(draw.state.depth.compare, width, TILE),
                    depth,
                    color,
                    shade: &shade,
                }
            })
            .collect();
        self.drive(draw, &mut sinks)
    }
}

impl Rasterizer for Fast {
    fn profile(&self) -> Profile {
        let triangles = Reference::new(self.config.reference).profile().triangles_only();
        Profile {
            name: "fast".into(),
            precision_bits: PRECISION_BITS,
            // Triangles at one sample, lists, strips and fans (the front end reads every
            // triangle through `Draw::triangles`): fast draws nothing else. The reference's
            // front end also gives it depth clipping off, the depth range and depth bias; its planes
            // offset and clamp.
            state: StateSupport {
                // At one sample, the mask's bit 0 (drive::run).
                sample_mask: true,
                triangle_strips: true,
                triangle_fans: true,
                viewport_depth: true,
                inverted_depth: true,
                unclipped_depth: true,
                // The front end's offset, added to each plane's depth.
                depth_bias: Some(BiasSupport::REFERENCE),
                ..triangles.state
            },
            ..triangles
        }
    }

    fn about(&self) -> String {
        format!(
            "refrast-fast {}, {} thread(s), SIMD {}",
            env!("CARGO_PKG_VERSION"),
            self.config.threads,
            self.simd().name()
        )
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let bands = draw.viewport.height().div_ceil(TILE) as usize;
        let mut sinks: Vec<Vec<Fragment>> = vec![Vec::new(); bands];
        self.drive(draw, &mut sinks)?;
        Ok(sinks.concat())
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let (viewport, state) = (draw.viewport, draw.state.depth);
        let mut depth = vec![state.clear; viewport.pixel_count()];
        let mut primitive = vec![None; viewport.pixel_count()];
        let band = (viewport.width() * TILE) as usize;
        let mut sinks: Vec<_> = depth
            .chunks_mut(band)
            .zip(primitive.chunks_mut(band))
            .enumerate()
            .map(|(i, (depth, primitive))| {
                let rows = BandRows {
                    y0: i as u32 * TILE,
                    width: viewport.width(),
                };
                ResolveBand {
                    rows,
                    state,
                    hiz: HiZ::new(state.compare, viewport.width(), TILE),
                    depth,
                    primitive,
                }
            })
            .collect();
        self.drive(draw, &mut sinks)?;
        Ok(Resolved {
            viewport,
            samples: 1,
            depth,
            primitive,
        })
    }
}
