//! The driver: batches of primitives set up in parallel chunks, then bands of tiles drawn in
//! parallel, each tile's triangles in primitive order.
//!
//! Order of work, and so of fragments: for each batch of [`BATCH`] primitives, every band; in
//! a band, tile by tile left to right; in a tile, primitive order; in a triangle, 8×8 blocks
//! row by row, samples row-major within a block (where its part of the tile is at most 8
//! pixels wide, rows top to bottom, no blocks). Each pixel sees its primitives in draw order,
//! so a depth test in the bands gives the reference's result.

use fearless_simd::{Level, Simd, dispatch};
use rayon::ThreadPool;
use rayon::prelude::*;
use refrast::stage::{Corner, FrontSetup, PixelRect, ViewportTransform, traverse};
use refrast::{Draw, DrawError, FixedPoint, ReferenceConfig, Traversal};

use crate::back::{BLOCK, Lanes};
use crate::front::{Chunk, DrawSetup, Prepared};
use crate::sink::Sink;
use crate::tiles::{TileGrid, intersect};

/// Primitives set up and binned before their tiles are drawn: enough to share the work among
/// threads, few enough that what they keep stays in the last-level cache.
pub(crate) const BATCH: usize = 1 << 14;

/// Runs `f` on every item, spread over `pool`'s threads when there is one.
pub(crate) fn for_each<T: Send>(
    pool: Option<&ThreadPool>,
    items: &mut [T],
    f: impl Fn(usize, &mut T) + Sync,
) {
    match pool {
        Some(pool) => pool.install(|| items.par_iter_mut().enumerate().for_each(|(i, t)| f(i, t))),
        None => items.iter_mut().enumerate().for_each(|(i, t)| f(i, t)),
    }
}

/// What a draw keeps between draws: its positions' setups and one chunk per thread.
#[derive(Clone, Debug, Default)]
pub(crate) struct Buffers {
    /// Every position of the draw as a triangle's corner, set up once.
    pub vertices: Vec<Corner>,
    /// One per thread.
    pub chunks: Vec<Chunk>,
}

/// Positions set up by one thread at a time.
const VERTEX_RUN: usize = 1 << 12;

/// Draws `draw` into `sinks`, one per band of the viewport's tile grid, setting its positions
/// up once and its triangles in `buffers`' chunks, the back end at SIMD level `level`.
pub(crate) fn run<K: Sink>(
    config: ReferenceConfig,
    level: Level,
    pool: Option<&ThreadPool>,
    buffers: &mut Buffers,
    draw: &Draw,
    sinks: &mut [K],
) -> Result<(), DrawError> {
    draw.validate()?;
    if !draw.is_triangles_at_one_sample() {
        return Err(DrawError::Unsupported(format!(
            "{}: fast draws triangles at one sample",
            draw.describe()
        )));
    }
    // The sample mask test at one sample: bit 0 keeps every fragment or none.
    if !draw.state.passes_sample_mask(0) {
        return Ok(());
    }
    // Both traversals give the same samples; the box is the one worth drawing.
    let front = FrontSetup::new(
        draw,
        ReferenceConfig {
            traversal: Traversal::BoundingBox,
            ..config
        },
    );
    let Buffers { vertices, chunks } = buffers;
    vertices.clear();
    vertices.resize(draw.positions.len(), Corner::default());
    let mut runs: Vec<_> = vertices
        .chunks_mut(VERTEX_RUN)
        .zip(draw.positions.chunks(VERTEX_RUN))
        .collect();
    for_each(pool, &mut runs, |_, (out, positions)| {
        for (v, p) in out.iter_mut().zip(positions.iter()) {
            *v = Corner::new(*p, &front.planes, &front.transform);
        }
    });
    let setup = DrawSetup { front, vertices };
    let grid = TileGrid::new(draw.viewport);
    debug_assert_eq!(sinks.len(), grid.bands());
    let threads = pool.map_or(1, ThreadPool::current_num_threads);
    chunks.resize_with(threads, Chunk::default);
    let count = setup.front.triangles.len();
    for start in (0..count).step_by(BATCH) {
        let end = (start + BATCH).min(count);
        let per_chunk = (end - start).div_ceil(threads);
        for_each(pool, chunks, |i, chunk| {
            let first = (start + i * per_chunk).min(end);
            chunk.prepare(&setup, &grid, first..(first + per_chunk).min(end));
        });
        for_each(pool, sinks, |band, sink| {
            dispatch!(level, simd => draw_band(simd, &setup.front.transform, &grid, chunks, band, sink));
        });
    }
    Ok(())
}

/// Draws band `band`'s tiles into `sink`: tile by tile, each tile's triangles in order.
#[inline(always)]
fn draw_band<S: Simd, K: Sink>(
    simd: S,
    transform: &ViewportTransform,
    grid: &TileGrid,
    chunks: &[Chunk],
    band: usize,
    sink: &mut K,
) {
    simd.vectorize(
        #[inline(always)]
        || {
            for tile in grid.band_tiles(band) {
                let rect = grid.tile_rect(tile);
                warm_tile(chunks, tile, rect, sink);
                for chunk in chunks {
                    for &t in &chunk.bins[tile] {
                        draw_in_tile(transform, chunk, &chunk.triangles[t as usize], rect, sink);
                    }
                }
            }
        },
    );
}

/// The most records of one tile's triangles [`warm_tile`] reads in: about 150 KB, within
/// every second-level cache `fast` runs on, so that the first are not evicted by the last.
const WARMED: usize = 512;

/// Reads in, before drawing tile `tile` (`rect`, in pixels), what drawing it reads first: the
/// band's buffers under it and its triangles' records, when it has triangles.
///
/// A tile's triangles are spread over a batch's records, and its rows over a band's; read
/// while drawing, each waits on its own cache miss (on the small scene, the stored depth and
/// the records each a fifth to a tenth of the frame). Read here, independently, the misses
/// overlap. Nothing is computed from what is read.
#[inline(always)]
fn warm_tile<K: Sink>(chunks: &[Chunk], tile: usize, rect: [u32; 4], sink: &mut K) {
    if chunks.iter().all(|c| c.bins[tile].is_empty()) {
        return;
    }
    sink.warm(rect);
    let mut seen = 0;
    let mut left = WARMED;
    for chunk in chunks {
        let bin = &chunk.bins[tile];
        for &t in &bin[..bin.len().min(left)] {
            seen ^= chunk.triangles[t as usize].warm();
        }
        left -= bin.len().min(left);
    }
    std::hint::black_box(seen);
}

/// Whether a triangle with box `rect` is worth testing block by block against what is stored
/// ([`Sink::take_block`]): one whose box holds four blocks' worth of pixels. A smaller one
/// covers few samples of each block it touches, so the test (a bound from four corners) would
/// cost about what it could save.
#[inline(always)]
fn occludable(rect: [u32; 4]) -> bool {
    (rect[1] - rect[0]) * (rect[3] - rect[2]) >= 4 * 64
}

/// Draws the part of triangle `t` inside `tile` into `sink`.
#[inline(always)]
fn draw_in_tile<K: Sink>(
    transform: &ViewportTransform,
    chunk: &Chunk,
    t: &Prepared,
    tile: [u32; 4],
    sink: &mut K,
) {
    let Some(rect) = intersect(t.rect, tile) else {
        return;
    };
    if let Some(single) = &t.single {
        let planes = &single.planes;
        if occludable(t.rect) {
            single.steps.traverse::<true>(
                rect,
                #[inline(always)]
                |block| sink.take_block(planes, block),
            );
        } else if rect[1] - rect[0] <= BLOCK {
            single.steps.rows(
                rect,
                #[inline(always)]
                |row| sink.take(planes, row),
            );
        } else {
            single.steps.traverse::<false>(
                rect,
                #[inline(always)]
                |block| {
                    block.rows(
                        #[inline(always)]
                        |row| sink.take(planes, row),
                    )
                },
            );
        }
        return;
    }
    draw_fan(transform, chunk, t, rect, sink);
}

/// Draws the part of a clipped polygon's fan (or of a lone triangle turned over by snapping)
/// inside `rect` into `sink`: the reference's own traversal, on this part of the box, with
/// `fast`'s interpolation.
#[inline(never)]
fn draw_fan<K: Sink>(
    transform: &ViewportTransform,
    chunk: &Chunk,
    t: &Prepared,
    rect: [u32; 4],
    sink: &mut K,
) {
    let fans = &chunk.fans[t.fans.start as usize..t.fans.end as usize];
    let planes = &chunk.fan_planes[t.fans.start as usize..t.fans.end as usize];
    let bits = transform.bits;
    let [x0, x1, y0, y1] = rect.map(i64::from);
    let corners = [(x0, y0), (x1 - 1, y1 - 1)]
        .map(|(x, y)| FixedPoint::sample(x, y, bits).expect("a viewport's pixels have samples"));
    let rect = PixelRect::bounding(corners, bits, transform.viewport).expect("a non-empty box");
    let mut row = Vec::new();
    traverse(fans, t.winding, rect, bits, &mut row, |hit| {
        sink.take(&planes[hit.triangle], &Lanes::one(hit.x, hit.y, hit.values));
    });
}
