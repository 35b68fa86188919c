//! The tile grid: 64×64-pixel tiles (Larrabee's and llvmpipe's size), a row of them a band.
//!
//! A tile's depth and colour (32 KB) stay in the first-level cache while its triangles are
//! drawn; a band is a contiguous run of rows of every row-major buffer, so threads own bands
//! and write to them with no locks.

use refrast::Viewport;

use crate::back::Lanes;

/// The side of a tile in pixels.
pub(crate) const TILE: u32 = 64;

/// The viewport cut into tiles, numbered row-major.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TileGrid {
    width: u32,
    height: u32,
    columns: u32,
    rows: u32,
}

impl TileGrid {
    /// The tiles of `viewport`; those on the right and bottom may be cut short.
    pub fn new(viewport: Viewport) -> Self {
        let (width, height) = (viewport.width(), viewport.height());
        Self {
            width,
            height,
            columns: width.div_ceil(TILE),
            rows: height.div_ceil(TILE),
        }
    }

    /// How many tiles there are.
    pub fn tiles(&self) -> usize {
        (self.columns * self.rows) as usize
    }

    /// How many bands (rows of tiles) there are.
    pub fn bands(&self) -> usize {
        self.rows as usize
    }

    /// The tiles of band `band`, left to right.
    pub fn band_tiles(&self, band: usize) -> std::ops::Range<usize> {
        let first = band * self.columns as usize;
        first..first + self.columns as usize
    }

    /// The pixels of `tile`: `[x0, x1, y0, y1]`, half-open.
    pub fn tile_rect(&self, tile: usize) -> [u32; 4] {
        let (column, row) = (tile as u32 % self.columns, tile as u32 / self.columns);
        let (x0, y0) = (column * TILE, row * TILE);
        [x0, (x0 + TILE).min(self.width), y0, (y0 + TILE).min(self.height)]
    }

    /// Calls `f` with every tile that `rect` (`[x0, x1, y0, y1]`, inside the viewport, non-empty)
    /// touches, row-major.
    #[inline]
    pub fn for_each_tile(&self, rect: [u32; 4], mut f: impl FnMut(usize)) {
        let [x0, x1, y0, y1] = rect;
        for row in y0 / TILE..=(y1 - 1) / TILE {
            for column in x0 / TILE..=(x1 - 1) / TILE {
                f((row * self.columns + column) as usize);
            }
        }
    }
}

/// The rows of a band in a row-major buffer: where pixel `(x, y)` lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BandRows {
    /// The band's first row.
    pub y0: u32,
    /// The buffer's width.
    pub width: u32,
}

impl BandRows {
    /// Where pixel `(x, y)`, a pixel of the band, lies in the band's slice.
    #[inline(always)]
    pub fn index(self, x: u32, y: u32) -> usize {
        (y - self.y0) as usize * self.width as usize + x as usize
    }

    /// The range of the band's slice that `row`'s lanes occupy.
    #[inline(always)]
    pub fn lanes(self, row: &Lanes) -> std::ops::Range<usize> {
        let start = self.index(row.x0, row.y);
        start..start + row.n as usize
    }
}

/// The overlap of two rectangles `[x0, x1, y0, y1]`, or `None` when it is empty.
#[inline]
pub(crate) fn intersect(a: [u32; 4], b: [u32; 4]) -> Option<[u32; 4]> {
    let r = [a[0].max(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].min(b[3])];
    (r[0] < r[1] && r[2] < r[3]).then_some(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 130×70 viewport has 3×2 tiles, the last column 2 px wide and the last row 6 px tall;
    /// a box across the first tiles' corner touches four tiles, row-major.
    #[test]
    fn tiles_cover_the_viewport_and_a_box_finds_its_tiles() {
        let grid = TileGrid::new(Viewport::new(130, 70).unwrap());
        assert_eq!((grid.tiles(), grid.bands()), (6, 2));
        assert_eq!(grid.band_tiles(1), 3..6);
        assert_eq!(grid.tile_rect(5), [128, 130, 64, 70]);
        let mut touched = Vec::new();
        grid.for_each_tile([60, 70, 63, 65], |t| touched.push(t));
        assert_eq!(touched, [0, 1, 3, 4]);
        assert_eq!(intersect([0, 10, 0, 10], [10, 20, 0, 10]), None);
        assert_eq!(intersect([0, 10, 0, 10], [5, 20, 2, 3]), Some([5, 10, 2, 3]));
    }
}
