//! Probes: what a driver should declare where nothing reports it (Vulkan names no tie rule, no
//! snapping rounding, no guard band, no interpolation precision), decided by drawing a few
//! triangles on the driver's own grid. Every position is exact on that grid (w = 1 or a power
//! of two) unless a probe is about rounding.

use refrast::{ClipMode, Fragment, Rasterizer};
use refrast_conformance::oracle::raster::sample_ndc;
use refrast_conformance::oracle::ray_cast::ray_cast;
use refrast_wgpu::{Driver, Gpu};

use super::{apart, at, bits_of, clip_of, draw, exact_barycentrics, reference};

pub fn run(d: Driver, gpu: &mut Gpu) {
    let bits = bits_of(gpu);
    let name = d.name();
    tie_rule(name, gpu, bits);
    let (tried, wrong, worst) = near_ties(gpu, bits);
    println!(
        "{name}: snapping, {tried} vertices within 8 f32 ulps of a {bits}-bit tie: {wrong} on the \
         grid point farther from x/w (the farthest {worst:.2e} steps from the tie)"
    );
    // SwiftShader computes x·(1/w)·scale + offset in f32 and rounds that: not x/w rounded.
    if d == Driver::Swiftshader {
        assert!(wrong > 0, "swiftshader: snapping near ties");
    }
    let rounding = ties(gpu, bits);
    println!("{name}: exact ties (w = 1) in x and y, left and right half: {rounding:?}");
    assert!(rounding.iter().all(|r| *r == "to even"), "{name}: ties");
    guard_band(name, gpu, bits);
    let (slivers, far) = precision(name, gpu, bits);
    // The 8 bits the profiles claim hold on unclipped slivers; SwiftShader's f32 planes,
    // anchored at the vertex of largest w, lose them far from it (finding 5).
    assert!(slivers < 0.5f64.powi(8), "{name}: sliver precision");
    if d == Driver::Swiftshader {
        assert!(far > 0.5f64.powi(8), "swiftshader: precision far from the anchor");
    }
}

/// Which triangle owns a sample exactly on an edge they share (16 directions, each edge drawn
/// with either triangle first), or on a vertex six triangles share: exactly one must, and the
/// reference on the same grid says which the top-left rule picks.
fn tie_rule(name: &str, gpu: &mut Gpu, bits: u8) {
    let s = [8.5, 8.5];
    let p = |q: [f64; 2]| clip_of(16, 16, q[0], q[1], 0.5, 1.0);
    let mut draws = Vec::new();
    for (dx, dy) in [(1, 0), (0, 1), (1, 1), (1, -1), (2, 1), (1, 2), (2, -1), (1, -2)] {
        for sign in [1.0, -1.0] {
            let (dx, dy) = (sign * f64::from(dx), sign * f64::from(dy));
            let a = [s[0] - 2.0 * dx, s[1] - 2.0 * dy];
            let b = [s[0] + 2.0 * dx, s[1] + 2.0 * dy];
            let c1 = [s[0] - 3.0 * dy, s[1] + 3.0 * dx];
            let c2 = [s[0] + 3.0 * dy, s[1] - 3.0 * dx];
            draws.push(draw(16, 16, vec![p(a), p(b), p(c1), p(b), p(a), p(c2)]));
        }
    }
    let ring = [
        [3.0, 0.0],
        [1.0, 3.0],
        [-2.0, 2.0],
        [-3.0, -1.0],
        [-1.0, -3.0],
        [2.0, -2.0],
    ];
    let mut fan = Vec::new();
    for i in 0..6 {
        let (o, n) = (ring[i], ring[(i + 1) % 6]);
        fan.extend([p(s), p([s[0] + o[0], s[1] + o[1]]), p([s[0] + n[0], s[1] + n[1]])]);
    }
    draws.push(draw(16, 16, fan));
    let owners = |f: &[Fragment]| {
        let mut o: Vec<u32> = at(f, 8, 8).iter().map(|f| f.primitive).collect();
        o.sort_unstable();
        o
    };
    let (mut once, mut top_left) = (0, 0);
    for d in &draws {
        let got = owners(&gpu.rasterize(d).expect("the driver draws"));
        let want = owners(&reference(bits, ClipMode::GuardBand, d));
        assert_eq!(want.len(), 1);
        once += usize::from(got.len() == 1);
        top_left += usize::from(got == want);
    }
    println!(
        "{name}: tie rule, {} samples on shared edges or a shared vertex: covered exactly once {once} \
         times, by the triangle the top-left rule picks {top_left} times",
        draws.len()
    );
    assert_eq!(
        (once, top_left),
        (draws.len(), draws.len()),
        "{name}: the top-left rule"
    );
}

/// Left edges at x = x_c/w for x_c up to 8 f32 ulps either side of the f32 nearest a tie
/// between two grid points, at ten values of w: the sample half a step left of the tie is
/// covered exactly when the edge snapped onto it. Returns the vertices tried, those snapped to
/// the grid point farther from x/w (covered when they should not be, or not when they should),
/// and the largest distance from the tie, in grid steps, at which that happened.
fn near_ties(gpu: &mut Gpu, bits: u8) -> (usize, usize, f64) {
    let step = 0.5f64.powi(i32::from(bits));
    let (mut tried, mut wrong, mut worst) = (0, 0, 0.0f64);
    for px in [21u32, 40] {
        let sample = f64::from(px) + 0.5;
        let tie = sample + step / 2.0;
        for w in [0.3f32, 0.7, 1.3, 1.7, 2.9, 3.3, 5.1, 7.7, 0.55, 11.3] {
            let nearest = clip_of(64, 68, tie, 0.0, 0.5, w)[0];
            let mut positions = Vec::new();
            let mut xs = Vec::new();
            for k in -8i32..=8 {
                let mut x = nearest;
                for _ in 0..k.abs() {
                    x = if k > 0 { x.next_up() } else { x.next_down() };
                }
                let row = 4.0 * f64::from(k + 8);
                let at_row = |y: f64| clip_of(64, 68, tie, y, 0.5, w)[1];
                let right = clip_of(64, 68, tie + 4.0, row + 1.75, 0.5, w);
                positions.extend([
                    [x, at_row(row + 0.25), 0.5 * w, w],
                    [x, at_row(row + 3.25), 0.5 * w, w],
                    right,
                ]);
                xs.push(x);
            }
            let frags = gpu.rasterize(&draw(64, 68, positions)).expect("the driver draws");
            for (i, &x) in xs.iter().enumerate() {
                let row = 4 * u32::try_from(i).expect("17 rows") + 1;
                let covered = !at(&frags, px, row).is_empty();
                let x_f = (f64::from(x) / f64::from(w) + 1.0) * 32.0;
                let snapped = (x_f / step).round_ties_even() * step;
                tried += 1;
                if covered != (snapped <= sample) {
                    wrong += 1;
                    worst = worst.max(((x_f - tie) / step).abs());
                }
            }
        }
    }
    (tried, wrong, worst)
}

/// How exact ties round, in x and in y (the same draws transposed), left and right of the
/// centre: a vertex halfway between an even grid point and the odd one after it snaps to the
/// even one (config A) or not; halfway between an odd one and the even one after it snaps to
/// the odd one (config B) or not. Both decide between to even, half up, half down and to odd.
fn ties(gpu: &mut Gpu, bits: u8) -> Vec<&'static str> {
    let step = 0.5f64.powi(i32::from(bits));
    let mut found = Vec::new();
    for transpose in [false, true] {
        let p = |x: f64, y: f64| {
            let (x, y) = if transpose { (y, x) } else { (x, y) };
            clip_of(16, 16, x, y, 0.5, 1.0)
        };
        for px in [5u32, 10] {
            let c = f64::from(px) + 0.5;
            let s = (px, 7u32);
            // A: a vertical left edge halfway between c (even) and c + step; covered iff on c.
            let a = draw(
                16,
                16,
                vec![
                    p(c + step / 2.0, 3.25),
                    p(c + step / 2.0, 12.25),
                    p(c + 4.0, 7.75),
                ],
            );
            // B: an edge through the sample from (c − step, 6.5) to (c + step, 8.5), its top
            // vertex halfway between c − step (odd) and c; covered iff on c − step.
            let b = draw(
                16,
                16,
                vec![p(c - step / 2.0, 6.5), p(c + step, 8.5), p(c + 4.0, 7.5)],
            );
            let (sx, sy) = if transpose { (s.1, s.0) } else { s };
            // The reference rounds ties to even: the probe must read it so.
            let on = |f: &[Fragment]| !at(f, sx, sy).is_empty();
            let exact = |d| on(&reference(bits, ClipMode::GuardBand, d));
            assert!(
                exact(&a) && !exact(&b),
                "the ties probe reads the reference as to even"
            );
            let even = on(&gpu.rasterize(&a).expect("the driver draws"));
            let odd = on(&gpu.rasterize(&b).expect("the driver draws"));
            found.push(match (even, odd) {
                (true, false) => "to even",
                (false, false) => "half up",
                (true, true) => "half down",
                (false, true) => "to odd",
            });
        }
    }
    found
}

/// A sample exactly on an edge that leaves the viewport on the right (48 slopes, the third
/// vertex on either side): a driver with a guard band covers it as the top-left rule says; one
/// that clips x/y at the viewport snaps the cut vertex, which moves the edge off the sample.
/// The same triangles moved inside a 64×64 target are the control.
fn guard_band(name: &str, gpu: &mut Gpu, bits: u8) {
    let e = 0.125;
    let s = [11.5, 7.5];
    let (mut flips, mut control, mut tried) = (0, 0, 0);
    for p in [3.0f64, 5.0, 7.0, 9.0, 11.0, 13.0] {
        for q in [-7.0f64, -5.0, -3.0, -1.0, 1.0, 3.0, 5.0, 7.0] {
            for side in [1.0, -1.0] {
                let (ma, mb) = ((24.0 / p).ceil(), (52.0 / p).ceil());
                let a = [s[0] - ma * p * e, s[1] - ma * q * e];
                let b = [s[0] + mb * p * e, s[1] + mb * q * e];
                let c = [s[0] - side * 3.0 * q * e, s[1] + side * 3.0 * p * e];
                let tri = |w: u32, h: u32, dx: f64, dy: f64| {
                    let v = |q: [f64; 2]| clip_of(w, h, q[0] + dx, q[1] + dy, 0.5, 1.0);
                    draw(w, h, vec![v(a), v(b), v(c)])
                };
                let covers = |f: &[Fragment], x, y| !at(f, x, y).is_empty();
                let (leaving, inside) = (tri(16, 16, 0.0, 0.0), tri(64, 64, 16.0, 24.0));
                let got = covers(&gpu.rasterize(&leaving).expect("the driver draws"), 11, 7);
                flips += usize::from(got != covers(&reference(bits, ClipMode::GuardBand, &leaving), 11, 7));
                let got = covers(&gpu.rasterize(&inside).expect("the driver draws"), 27, 31);
                control += usize::from(got != covers(&reference(bits, ClipMode::GuardBand, &inside), 27, 31));
                tried += 1;
            }
        }
    }
    println!(
        "{name}: guard band, {tried} samples on an edge leaving the viewport: {flips} covered against \
         the top-left rule ({control} of the same moved inside)"
    );
    assert!(
        flips > 0 && control == 0,
        "{name}: no guard band, and the tie rule inside"
    );
}

/// How close perspective and screen-space barycentrics come to exact on slivers with w ratios
/// up to 32:1 (every vertex on the grid, w a power of two, so snapping is exact), and on strips
/// reaching 160 000 px (clipped; the far vertex's snapping moves nothing measurable). Returns the
/// largest error on the slivers and on the strips.
fn precision(name: &str, gpu: &mut Gpu, bits: u8) -> (f64, f64) {
    let bits_of_error = |e: f64| -e.log2();
    let (mut persp, mut screen) = (0.0f64, 0.0f64);
    for delta in [1.0 / 16.0, 0.25, 1.0] {
        for (w0, w1) in [(4.0f32, 0.125f32), (0.125, 4.0), (1.0, 1.0)] {
            let p = [[1.5, 1.5], [30.5, 30.5 - delta], [30.5 - delta, 30.5]];
            let w = [w0, w1, w1];
            let positions = (0..3)
                .map(|i| clip_of(32, 32, p[i][0], p[i][1], 0.5, w[i]))
                .collect();
            for f in gpu.rasterize(&draw(32, 32, positions)).expect("the driver draws") {
                let s = [f64::from(f.x) + 0.5, f64::from(f.y) + 0.5];
                let (b, sb) = exact_barycentrics(p, w.map(f64::from), s);
                persp = persp.max(apart(f.barycentric, b));
                screen = screen.max(apart(f.screen_barycentric.expect("screen weights"), sb));
            }
        }
    }
    // 1000 random slivers: an apex anywhere, the far edge at most 8 grid steps long.
    let one = f64::from(1u32 << bits);
    let mut state = 0x1234_5678u64;
    let mut next = move |n: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % n
    };
    let ws = [0.125f32, 0.25, 0.5, 1.0, 2.0, 4.0];
    for _ in 0..1000 {
        let mut grid = |n: u64| next(n) as f64 / one;
        let (a, b) = (
            [grid(32 << bits), grid(32 << bits)],
            [grid(32 << bits), grid(32 << bits)],
        );
        let c = [
            (b[0] + grid(17) - 8.0 / one).clamp(0.0, 32.0),
            (b[1] + grid(17) - 8.0 / one).clamp(0.0, 32.0),
        ];
        let p = [a, b, c];
        let w = [(); 3].map(|()| ws[usize::try_from(next(6)).expect("small")]);
        let positions = (0..3)
            .map(|i| clip_of(32, 32, p[i][0], p[i][1], 0.5, w[i]))
            .collect();
        for f in gpu.rasterize(&draw(32, 32, positions)).expect("the driver draws") {
            let s = [f64::from(f.x) + 0.5, f64::from(f.y) + 0.5];
            let (b, sb) = exact_barycentrics(p, w.map(f64::from), s);
            persp = persp.max(apart(f.barycentric, b));
            screen = screen.max(apart(f.screen_barycentric.expect("screen weights"), sb));
        }
    }
    // A strip from the segment (2.5, 2.5)-(13.5, 13.5) towards a vertex 160 000 px away down it
    // (direction (1, 1 + ε)): weights change across the strip, and plane equations anchored at
    // the far vertex add terms of 10⁵ that cancel.
    let mut far = 0.0f64;
    for eps in [0.125f32, 0.25, 0.5] {
        for w2 in [0.25f32, 1.0, 4.0] {
            let t = 20_000.0;
            let tri = [
                clip_of(16, 16, 2.5, 2.5, 0.5, 1.0),
                clip_of(16, 16, 13.5, 13.5, 0.5, 1.0),
                [t * w2, -t * (1.0 + eps) * w2, 0.5 * w2, w2],
            ];
            let d = draw(16, 16, tri.to_vec());
            let tri64 = tri.map(|v| v.map(f64::from));
            for f in gpu.rasterize(&d).expect("the driver draws") {
                let [nx, ny] = sample_ndc(16, 16, f.x, f.y);
                if let Some(hit) = ray_cast(&tri64, nx, ny, &d.state) {
                    far = far.max(apart(f.barycentric, hit.barycentric));
                }
            }
        }
    }
    println!(
        "{name}: precision, slivers (9 wedges 29 px long, w 32:1, and 1000 random ones, w 1/8 to 4): \
         perspective within 2^-{:.1}, screen within 2^-{:.1}; strips to 160 000 px: perspective \
         within 2^-{:.1}",
        bits_of_error(persp),
        bits_of_error(screen),
        bits_of_error(far)
    );
    (persp.max(screen), far)
}
