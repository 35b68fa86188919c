//! `lab002-scanline`: the polygon fill of seed 002 (DH2323 Lab 3, "Rasterization"), built as its
//! sections 4–6 build it.
//!
//! What the seed does, and what this module therefore does:
//!
//! - **VertexShader**: `zinv = 1/z` with `z` the camera-space depth (clip `w`), then
//!   `x = int(f · X · zinv) + W/2`, `y = int(f · Y · zinv) + H/2` with y down: each vertex is
//!   truncated to a whole pixel *toward the screen centre* (C++ `int()`), and `W/2`, `H/2` are
//!   integer divisions. There is no clipping, so vertices behind the eye come out mirrored.
//! - **Interpolate**: `N` values from `a` to `b`, a float `current` advanced by
//!   `step = (b − a)/max(N − 1, 1)` and truncated to integer positions ([`interpolate`]).
//! - **ComputePolygonRows**: one row per y from the smallest to the largest vertex y; each edge is
//!   drawn as a line of `max(|Δx|, |Δy|) + 1` pixels, and each row keeps its smallest x as the
//!   left pixel and its largest as the right ([`compute_polygon_rows`]).
//! - **DrawPolygonRows**: every pixel from left to right inclusive, interpolated the same way.
//! - **Depth**: `zinv` is interpolated linearly along the edges and rows; the depth buffer is
//!   cleared to `0` (infinitely far) and keeps a pixel whose `zinv` is larger
//!   ([`Rasterizer::resolve`]).
//! - **Perspective-correct quantities** (section 6.2): a quantity `q` is interpolated as `q · zinv`
//!   and divided by `zinv` afterwards. The barycentrics are such a quantity here.
//!
//! Where the lab would index out of its arrays, this module stops instead: pixels outside the
//! screen are skipped (as `PutPixelSDL` does), and a triangle with a vertex farther than
//! [`COORD_LIMIT`] pixels from the centre is discarded, because its rows would not fit in memory.

use refrast::{
    COORD_LIMIT, CullMode, DepthConvention, DepthRange, Draw, DrawError, Features, Fragment, Profile,
    Rasterizer, Resolved, SnapAccuracy, Snapping, Spec, Supported, Winding,
};

/// Seed 002's rasterizer: whole-pixel vertices, left/right rows from interpolated edges, 1/z depth.
#[derive(Clone, Copy, Debug, Default)]
pub struct Lab002;

/// The lab's `Pixel`: integer position, inverse depth, and the barycentrics times `zinv` it carries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pixel {
    /// Column.
    pub x: i32,
    /// Row.
    pub y: i32,
    /// Inverse camera-space depth `1/z`, linear in screen space.
    pub zinv: f32,
    /// Barycentrics in the input triangle times `zinv`, also linear in screen space.
    pub bary_over_z: [f32; 3],
}

impl Pixel {
    /// A pixel carrying nothing but its position, as the lab's first `ivec2` version has.
    #[must_use]
    pub fn at(x: i32, y: i32) -> Self {
        Self {
            x,
            y,
            zinv: 0.0,
            bary_over_z: [0.0; 3],
        }
    }

    /// The interpolated quantities as floats, in the lab's `vec` arithmetic.
    fn floats(self) -> [f32; 6] {
        let [b0, b1, b2] = self.bary_over_z;
        [self.x as f32, self.y as f32, self.zinv, b0, b1, b2]
    }

    /// Back from floats: positions truncated toward zero, as assigning a `vec2` to an `ivec2` does.
    fn from_floats(v: [f32; 6]) -> Self {
        Self {
            x: v[0] as i32,
            y: v[1] as i32,
            zinv: v[2],
            bary_over_z: [v[3], v[4], v[5]],
        }
    }
}

/// The lab's `Interpolate(a, b, result)` with `result.size() == n`: `n` pixels from `a` towards
/// `b`, accumulated step by step in `f32`, because that is how the lab produces edges and rows.
pub fn interpolate(a: Pixel, b: Pixel, n: usize) -> impl Iterator<Item = Pixel> {
    let (fa, fb) = (a.floats(), b.floats());
    let divisor = n.saturating_sub(1).max(1) as f32;
    let step: [f32; 6] = std::array::from_fn(|k| (fb[k] - fa[k]) / divisor);
    let mut current = fa;
    (0..n).map(move |_| {
        let pixel = Pixel::from_floats(current);
        for (c, s) in current.iter_mut().zip(step) {
            *c += s;
        }
        pixel
    })
}

/// The lab's `ComputePolygonRows`: for each row from the top vertex to the bottom one, the
/// leftmost and rightmost pixel of the polygon's edges, drawn as lines with [`interpolate`].
///
/// A row no edge reaches keeps `x = i32::MAX` on the left and `i32::MIN` on the right. It
/// allocates one entry per row, so callers keep vertices within [`COORD_LIMIT`] as the lab's do.
#[must_use]
pub fn compute_polygon_rows(vertices: &[Pixel]) -> (Vec<Pixel>, Vec<Pixel>) {
    let (Some(top), Some(bottom)) = (
        vertices.iter().map(|v| v.y).min(),
        vertices.iter().map(|v| v.y).max(),
    ) else {
        return (Vec::new(), Vec::new());
    };
    let rows = (i64::from(bottom) - i64::from(top) + 1) as usize;
    let unset = |x: i32, row: usize| Pixel::at(x, top + row as i32);
    let mut left: Vec<Pixel> = (0..rows).map(|r| unset(i32::MAX, r)).collect();
    let mut right: Vec<Pixel> = (0..rows).map(|r| unset(i32::MIN, r)).collect();
    for (i, &a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        let delta = (a.x.abs_diff(b.x), a.y.abs_diff(b.y));
        let pixels = delta.0.max(delta.1) as usize + 1;
        for p in interpolate(a, b, pixels) {
            let Some(row) = usize::try_from(i64::from(p.y) - i64::from(top))
                .ok()
                .filter(|&r| r < rows)
            else {
                continue;
            };
            if left[row].x > p.x {
                left[row] = p;
            }
            if right[row].x < p.x {
                right[row] = p;
            }
        }
    }
    (left, right)
}

/// Maps the lab's `zinv` decreasingly into `[0, 1]`, because fragments must carry depth there:
/// `1/(1 + zinv) = z/(z + 1)`; `zinv ≤ 0`, which never beats the cleared buffer, maps to 1.
#[must_use]
pub fn window_depth(zinv: f32) -> f32 {
    if zinv > 0.0 {
        (1.0 / (1.0 + f64::from(zinv))) as f32
    } else {
        1.0
    }
}

/// The lab's `VertexShader` for vertex `k` of a triangle; `None` off the valid range or for a
/// non-finite coordinate (clip `z` included, though the lab ignores it).
fn vertex_shader(p: [f32; 4], k: usize, width: u32, height: u32) -> Option<Pixel> {
    if !p.iter().all(|c| c.is_finite()) {
        return None;
    }
    let [x, y, _, w] = p;
    let zinv = 1.0 / w;
    // The focal length in pixels is W/2 across (H/2 down) for the clip-space x (y) range ±w.
    let fx = (width as f32 / 2.0) * x * zinv;
    let fy = (height as f32 / 2.0) * -y * zinv;
    let in_range = |c: f32| c.is_finite() && f64::from(c).abs() <= COORD_LIMIT;
    if !(in_range(fx) && in_range(fy) && zinv.is_finite()) {
        return None;
    }
    let mut bary_over_z = [0.0; 3];
    bary_over_z[k] = zinv;
    Some(Pixel {
        x: fx as i32 + (width / 2) as i32,
        y: fy as i32 + (height / 2) as i32,
        zinv,
        bary_over_z,
    })
}

impl Lab002 {
    /// Every fragment of the draw with its `zinv`, in primitive order.
    fn fragments(draw: &Draw) -> Result<Vec<(Fragment, f32)>, DrawError> {
        draw.validate()?;
        let (width, height) = (draw.viewport.width(), draw.viewport.height());
        let mut out = Vec::new();
        for (t, indices) in draw.triangles().iter().enumerate() {
            let mut vertices = [Pixel::at(0, 0); 3];
            let mut ok = true;
            for (k, &i) in indices.iter().enumerate() {
                match vertex_shader(draw.positions[i as usize], k, width, height) {
                    Some(v) => vertices[k] = v,
                    None => ok = false,
                }
            }
            if !ok {
                continue;
            }
            let [a, b, c] = vertices.map(|v| (i64::from(v.x), i64::from(v.y)));
            let area2 = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
            let front_facing = draw
                .state
                .front_face
                .is_front(Winding::from_area2(area2))
                .unwrap_or(false);
            let (left, right) = compute_polygon_rows(&vertices);
            for (l, r) in left.into_iter().zip(right) {
                if l.x > r.x || l.y < 0 || l.y >= height as i32 {
                    continue;
                }
                let n = (i64::from(r.x) - i64::from(l.x) + 1) as usize;
                let visible = interpolate(l, r, n)
                    .take_while(|p| p.x < width as i32)
                    .filter(|p| p.x >= 0);
                for p in visible {
                    let barycentric = p.bary_over_z.map(|q| q / p.zinv);
                    if barycentric.iter().any(|b| !b.is_finite()) {
                        continue;
                    }
                    let fragment = Fragment {
                        x: p.x as u32,
                        y: p.y as u32,
                        sample: 0,
                        primitive: t as u32,
                        depth: window_depth(p.zinv),
                        barycentric,
                        flat: None,
                        screen_barycentric: None,
                        front_facing,
                    };
                    out.push((fragment, p.zinv));
                }
            }
        }
        Ok(out)
    }
}

impl Rasterizer for Lab002 {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab002-scanline".into(),
            // The VertexShader truncates every vertex to a whole pixel: a grid of 2^0 pixel.
            snapping: Snapping::Grid(0),
            // Both row ends are drawn: no tie rule.
            fill: None,
            // 1/z interpolated linearly, not z/w.
            depth: DepthConvention::Other,
            tolerance_subpixels: 1,
            // Held to the reference's precision: the labs compute in f32 or f64 from exact inputs.
            precision_bits: 18,
            features: Features {
                // Section 6.2: q·zinv interpolated, then divided by zinv.
                perspective_barycentrics: true,
                screen_barycentrics: false,
                cull_modes: Supported::only(&[CullMode::None]),
                front_faces: Supported::ALL,
                // Only `zinv >` against a cleared 0: no compare ops, no write mask.
                depth_test: false,
                compare_ops: Supported::ALL,
                depth_writes: Supported::ALL,
                far_clipping: Supported::only(&[false]),
                depth_ranges: Supported::only(&[DepthRange::ZeroToOne]),
                // No x/y clipping at all, so none can move an edge.
                guard_band: u32::MAX,
                // It truncates to its grid: a tie rounds down, not to even.
                ties_to_even: false,
                // Truncation lands on the grid point at or below the exact position: within
                // one step of it, not the nearest.
                snap: SnapAccuracy::WithinOneStep,
                zero_area_before_clipping: false,
                clips_in_3d: true,
                z_rewritten_in_f32: false,
            },
            spec: Spec::Refrast,
            ..Profile::default()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        Ok(Self::fragments(draw)?.into_iter().map(|(f, _)| f).collect())
    }

    /// The lab's own depth buffer: cleared to `zinv = 0`, a pixel kept when its `zinv` is larger.
    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        let viewport = draw.viewport;
        let mut zinv = vec![0.0f32; viewport.pixel_count()];
        let mut primitive = vec![None; viewport.pixel_count()];
        for (f, z) in Self::fragments(draw)? {
            let i = viewport.index(f.x, f.y);
            if z > zinv[i] {
                zinv[i] = z;
                primitive[i] = Some(f.primitive);
            }
        }
        Ok(Resolved {
            viewport,
            samples: 1,
            depth: zinv.into_iter().map(window_depth).collect(),
            primitive,
        })
    }
}
