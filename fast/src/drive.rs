//! The driver: batches of primitives set up in parallel chunks, then bands of tiles drawn in
//! parallel, each tile's triangles in primitive order.
//!
//! Order of work, and so of fragments: for each batch of [`BATCH`] primitives, every band; in
//! a band, tile by tile left to right; in a tile, primitive order; in a triangle, 8×8 blocks
//! row by row, samples row-major within a block. Each pixel sees its primitives in draw order,
//! so a depth test in the bands gives the reference's result.

use rayon::ThreadPool;
use rayon::prelude::*;
use refrast::stage::{PixelRect, ViewportTransform, clip_planes, traverse};
use refrast::{Draw, DrawError, FixedPoint, ReferenceConfig};

use crate::front::{Chunk, DrawSetup, Prepared};
use crate::sink::{Corners, Sink};
use crate::tiles::{TileGrid, intersect};

/// Primitives set up and binned before their tiles are drawn: enough to share the work among
/// threads, few enough that what they keep stays in the last-level cache.
pub(crate) const BATCH: usize = 1 << 14;

/// Runs `f` on every item, spread over `pool`'s threads when there is one.
fn for_each<T: Send>(pool: Option<&ThreadPool>, items: &mut [T], f: impl Fn(usize, &mut T) + Sync) {
    match pool {
        Some(pool) => pool.install(|| items.par_iter_mut().enumerate().for_each(|(i, t)| f(i, t))),
        None => items.iter_mut().enumerate().for_each(|(i, t)| f(i, t)),
    }
}

/// Draws `draw` into `sinks`, one per band of the viewport's tile grid, setting triangles up
/// in `chunks` (one per thread, reused from draw to draw).
pub(crate) fn run<S: Sink>(
    config: ReferenceConfig,
    pool: Option<&ThreadPool>,
    chunks: &mut Vec<Chunk>,
    draw: &Draw,
    sinks: &mut [S],
) -> Result<(), DrawError> {
    draw.validate()?;
    let setup = DrawSetup {
        draw,
        planes: clip_planes(
            config.clip,
            draw.viewport,
            draw.state.clip_far,
            draw.state.depth_range,
        ),
        transform: ViewportTransform {
            viewport: draw.viewport,
            bits: config.subpixel_bits,
            depth_range: draw.state.depth_range,
        },
        fill: config.fill,
    };
    let grid = TileGrid::new(draw.viewport);
    debug_assert_eq!(sinks.len(), grid.bands());
    let threads = pool.map_or(1, ThreadPool::current_num_threads);
    chunks.resize_with(threads, Chunk::default);
    let count = draw.triangles.len();
    for start in (0..count).step_by(BATCH) {
        let end = (start + BATCH).min(count);
        let per_chunk = (end - start).div_ceil(threads);
        for_each(pool, chunks, |i, chunk| {
            let first = (start + i * per_chunk).min(end);
            chunk.prepare(&setup, &grid, first..(first + per_chunk).min(end));
        });
        for_each(pool, sinks, |band, sink| {
            for tile in grid.band_tiles(band) {
                let rect = grid.tile_rect(tile);
                for chunk in chunks.iter() {
                    for &t in &chunk.bins[tile] {
                        draw_in_tile(&setup.transform, chunk, &chunk.triangles[t as usize], rect, sink);
                    }
                }
            }
        });
    }
    Ok(())
}

/// Draws the part of triangle `t` inside `tile` into `sink`.
#[inline]
fn draw_in_tile<S: Sink>(
    transform: &ViewportTransform,
    chunk: &Chunk,
    t: &Prepared,
    tile: [u32; 4],
    sink: &mut S,
) {
    let Some(rect) = intersect(t.rect, tile) else {
        return;
    };
    if let Some(single) = &t.single {
        let corners = Corners::single(t.primitive, t.front_facing, single);
        single
            .steps
            .traverse(rect, |x, y, values| sink.covered(&corners.sample(x, y, values)));
        return;
    }
    let fans = &chunk.fans[t.fans.start as usize..t.fans.end as usize];
    let raster = &chunk.raster[t.raster.start as usize..t.raster.end as usize];
    // A clipped polygon's fan (or a lone triangle turned over by snapping): the reference's
    // own traversal, on this tile's part of the box.
    let bits = transform.bits;
    let [x0, x1, y0, y1] = rect.map(i64::from);
    let corners = [(x0, y0), (x1 - 1, y1 - 1)]
        .map(|(x, y)| FixedPoint::sample(x, y, bits).expect("a viewport's pixels have samples"));
    let rect = PixelRect::bounding(corners, bits, transform.viewport).expect("a non-empty box");
    let mut row = Vec::new();
    traverse(fans, t.winding, rect, bits, &mut row, |hit| {
        let corners = Corners::new(t.primitive, t.front_facing, &fans[hit.triangle], raster);
        sink.covered(&corners.sample(hit.x, hit.y, hit.values));
    });
}
