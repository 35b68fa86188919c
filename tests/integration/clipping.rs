//! Clipping: behind the eye, across the near plane, across all six planes, and shared edges.

use refrast::stage::{ClipOutcome, ClipPlane, ClipVertex, clip_planes, clip_polygon, clip_triangle};
use refrast::{ClipMode, DepthRange, Draw, Rasterizer, Reference, ReferenceConfig, Viewport};
use refrast_conformance::oracle::ray_cast::ray_cast;
use refrast_conformance::oracle::{brute_force, raster};

fn viewport(size: u32) -> Viewport {
    Viewport::new(size, size).unwrap()
}

fn covered(reference: &mut Reference, draw: &Draw) -> Vec<(u32, u32)> {
    let mut out: Vec<_> = reference
        .rasterize(draw)
        .unwrap()
        .iter()
        .map(|f| (f.x, f.y))
        .collect();
    out.sort_unstable_by_key(|&(x, y)| (y, x));
    out
}

#[test]
fn wholly_behind_the_eye_draws_nothing() {
    // Dividing these by w < 0 would land them on screen; they must not appear.
    let behind = vec![
        [0.5, 0.5, 0.5, -1.0],
        [-0.5, 0.5, 0.5, -1.0],
        [0.0, -0.5, 0.5, -1.0],
    ];
    // In front of the eye but before the near plane (z < 0).
    let before_near = vec![
        [0.5, 0.5, -0.1, 1.0],
        [-0.5, 0.5, -0.2, 1.0],
        [0.0, -0.5, -0.1, 1.0],
    ];
    for positions in [behind, before_near] {
        for clip in [ClipMode::GuardBand, ClipMode::Full] {
            let draw = Draw::new(viewport(32), positions.clone(), vec![[0, 1, 2]]);
            let reference = Reference::new(ReferenceConfig {
                clip,
                ..Default::default()
            });
            let stats = reference.draw(&draw, |f| panic!("drew {f:?}")).unwrap();
            assert_eq!(stats.clipped_away, 1);
        }
    }
}

#[test]
fn crossing_the_near_plane_keeps_exactly_the_part_in_front() {
    // w = 1 and z = x: the near plane z = 0 is the screen line x = 32 of a 64-px viewport, and the
    // clipped vertices land exactly on it, so coverage is the unclipped triangle's right of x = 32.
    let positions = vec![
        [-1.0, -1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0, 1.0],
        [1.0, 1.0, 1.0, 1.0],
    ];
    let draw = Draw::new(viewport(64), positions, vec![[0, 1, 2]]);
    let mut reference = Reference::default();
    let got = covered(&mut reference, &draw);
    let s = 256;
    let triangle = [(0, 64 * s), (64 * s, 64 * s), (64 * s, 0)];
    let want: Vec<_> = brute_force::coverage(triangle, 64, 64, 8, refrast::FillConvention::TopLeft)
        .into_iter()
        .filter(|&(x, _)| x >= 32)
        .collect();
    assert_eq!(got, want);
    for f in reference.rasterize(&draw).unwrap() {
        // Depth is z/w = x_ndc at the sample, linear in screen space.
        let [x_ndc, _] = raster::sample_ndc(64, 64, f.x, f.y);
        assert!((f64::from(f.depth) - x_ndc).abs() < 1e-6, "{f:?}");
    }
}

#[test]
fn crossing_all_six_planes_leaves_the_slab_between_near_and_far() {
    // A triangle holding the whole viewport, with z = ½ + x: near (z = 0) and far (z = 1) cut
    // it at x = −½ and x = ½, raster columns 16 and 48 of 64. Every plane clips it.
    let z = |x: f32| 0.5 + x;
    let positions = vec![
        [-4.0, -4.0, z(-4.0), 1.0],
        [4.0, -4.0, z(4.0), 1.0],
        [0.0, 6.0, z(0.0), 1.0],
    ];
    let mut draw = Draw::new(viewport(64), positions, vec![[0, 1, 2]]);
    draw.state.clip_far = true;
    let want: Vec<_> = (0..64).flat_map(|y| (16..48).map(move |x| (x, y))).collect();
    for clip in [ClipMode::Full, ClipMode::GuardBand] {
        let mut reference = Reference::new(ReferenceConfig {
            clip,
            ..Default::default()
        });
        assert_eq!(covered(&mut reference, &draw), want, "{clip:?}");
    }
    // The clipper itself: every vertex it leaves is inside all six planes, its barycentrics convex.
    let tri = [0, 1, 2].map(|i| ClipVertex::corner(draw.positions[i], i));
    let planes = clip_planes(ClipMode::Full, draw.viewport, draw.state.depth_clip());
    let (mut polygon, mut scratch) = (Vec::new(), Vec::new());
    assert_eq!(
        clip_triangle(&tri, &planes, &[], &mut polygon, &mut scratch),
        ClipOutcome::Clipped
    );
    for v in &polygon {
        for plane in &planes {
            assert!(plane.distance(v.position) >= -1e-12, "{v:?} outside {plane:?}");
        }
        // Barycentrics stay a convex combination.
        assert!((v.barycentric.element_sum() - 1.0).abs() < 1e-12);
        assert!(v.barycentric.min_element() >= -1e-12);
    }
}

#[test]
fn intersections_do_not_depend_on_walking_direction() {
    // Edge a–b crosses the near plane; c is inside. Two triangles walk a–b in opposite directions.
    let v = |x, y, z, w, i: usize| ClipVertex {
        position: glam::DVec4::new(x, y, z, w),
        barycentric: glam::DVec3::AXES[i],
    };
    let (a, b, c) = (
        v(0.3, -0.7, 0.4, 1.3, 0),
        v(-0.9, 0.2, -0.8, 0.6, 1),
        v(0.1, 0.1, 0.9, 1.1, 2),
    );
    let plane = ClipPlane::Near(DepthRange::ZeroToOne);
    let (mut forward, mut backward) = (Vec::new(), Vec::new());
    clip_polygon(&[a, b, c], plane, &mut forward);
    clip_polygon(&[c, b, a], plane, &mut backward);
    let new_point = |poly: &[ClipVertex]| {
        let on_ab: Vec<_> = poly
            .iter()
            .filter(|p| p.barycentric.z == 0.0 && p.position != a.position)
            .collect();
        assert_eq!(on_ab.len(), 1, "{poly:?}");
        on_ab[0].position
    };
    // Bit-identical, not merely close.
    assert_eq!(new_point(&forward), new_point(&backward));
}

#[test]
fn shared_edges_crossing_the_near_plane_stay_watertight() {
    // A quad (two triangles) from in front of the eye to behind it. Behind the eye (w < 0) x is
    // mirrored, so the back vertices are listed right-to-left to keep the quad unfolded; listed
    // the other way it folds over itself and 12 samples are rightly covered twice.
    let positions = vec![
        [-0.8, -0.8, 0.5, 1.0],
        [0.8, -0.8, 0.5, 1.0],
        [0.4, 0.5, -1.0, -0.5],
        [-0.4, 0.5, -1.0, -0.5],
    ];
    for (first, second) in [([0, 1, 2], [0, 2, 3]), ([0, 1, 3], [1, 2, 3])] {
        for clip in [ClipMode::GuardBand, ClipMode::Full] {
            let draw = Draw::new(viewport(64), positions.clone(), vec![first, second]);
            let mut reference = Reference::new(ReferenceConfig {
                clip,
                ..Default::default()
            });
            let mut got = covered(&mut reference, &draw);
            let n = got.len();
            got.dedup();
            assert_eq!(n, got.len(), "double coverage with {clip:?}");
            // The ray cast sees 180 samples, none on both triangles (or on an edge, where it could not tell).
            assert_eq!(n, ray_cast_count(&draw), "{clip:?}");
            // No hole: each covered row is one contiguous run (the visible quad is convex).
            for y in 0..64 {
                let row: Vec<u32> = got.iter().filter(|p| p.1 == y).map(|p| p.0).collect();
                if let (Some(first), Some(last)) = (row.first(), row.last()) {
                    assert_eq!(
                        row.len() as u32,
                        last - first + 1,
                        "hole in row {y} with {clip:?}"
                    );
                }
            }
        }
    }
}

/// Samples whose ray hits a triangle of the draw, checked to be hit by at most one.
fn ray_cast_count(draw: &Draw) -> usize {
    let (w, h) = (draw.viewport.width(), draw.viewport.height());
    let tris: Vec<[[f64; 4]; 3]> = draw
        .triangles()
        .iter()
        .map(|t| t.map(|i| draw.positions[i as usize].map(f64::from)))
        .collect();
    let mut count = 0;
    for y in 0..h {
        for x in 0..w {
            let [nx, ny] = raster::sample_ndc(w, h, x, y);
            let hits = tris
                .iter()
                .filter(|t| ray_cast(t, nx, ny, &draw.state).is_some())
                .count();
            assert!(
                hits <= 1,
                "sample ({x}, {y}) is on both triangles: the quad folds"
            );
            count += hits;
        }
    }
    assert_eq!(count, 180);
    count
}
