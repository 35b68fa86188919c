//! What certifying euc 0.5.3 found, each on its smallest input, checked against what the input
//! should give, worked out independently of euc (exact orientation, the ray cast). These are
//! the hand checks behind the findings of docs/certified.md, kept so that a change in euc or in the suite
//! shows. The crash is in `tests/crash.rs` (it needs a process of its own).

use refrast::{Draw, Fragment, FrontFace, Rasterizer, Viewport};
use refrast_conformance::oracle::raster::sample_ndc;
use refrast_conformance::oracle::ray_cast::ray_cast;
use refrast_conformance::{Scene, rules};
use refrast_euc::Euc;

/// A square draw in the state euc supports (the suite fits every draw the same way).
fn draw(side: u32, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Draw {
    fitted(Draw::new(
        Viewport::new(side, side).expect("a valid side"),
        positions,
        triangles,
    ))
}

fn fitted(mut draw: Draw) -> Draw {
    draw.state = Euc.profile().fit(draw.state);
    draw
}

/// A scene in the state euc supports.
fn scene(side: u32, positions: Vec<[f32; 4]>, triangles: Vec<[u32; 3]>) -> Scene {
    Scene::new(side, side, positions, triangles).fitted(&Euc.profile())
}

fn fragments(draw: &Draw) -> Vec<Fragment> {
    Euc.rasterize(draw)
        .expect("euc takes every draw with supported state")
}

/// Samples covered by two triangles.
fn doubles(frags: &[Fragment]) -> Vec<(u32, u32)> {
    let mut seen = std::collections::HashMap::new();
    for f in frags {
        *seen.entry((f.x, f.y)).or_insert(0) += 1;
    }
    let mut twice: Vec<_> = seen.into_iter().filter(|&(_, n)| n > 1).map(|(p, _)| p).collect();
    twice.sort_unstable_by_key(|&(x, y)| (y, x));
    twice
}

/// Finding 1. Two triangles sharing the diagonal of the viewport both cover the 16 samples
/// lying exactly on it (Vulkan, Basic Polygon Rasterization: exactly one of them must).
#[test]
fn a_shared_edge_is_covered_twice() {
    // The 16×16 viewport split on its diagonal from (0, 0) to (16, 16) in raster space, which
    // passes through the sample (i + ½, i + ½) of every pixel (i, i).
    let d = draw(
        16,
        vec![
            [-1.0, 1.0, 0.5, 1.0],
            [1.0, 1.0, 0.5, 1.0],
            [1.0, -1.0, 0.5, 1.0],
            [-1.0, -1.0, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let frags = fragments(&d);
    assert_eq!(doubles(&frags), (0..16).map(|i| (i, i)).collect::<Vec<_>>());
    assert_eq!(frags.len(), 256 + 16, "every sample once, the diagonal's twice");
}

/// Finding 2. A triangle wholly behind the eye (every w < 0) shows no sample (Vulkan, Primitive Clipping:
/// the view volume has −w ≤ x, y ≤ w, so w > 0); euc draws it, mirrored, with 32 fragments.
#[test]
fn a_triangle_behind_the_eye_is_drawn() {
    let d = draw(
        16,
        vec![
            [0.5, 0.5, 0.5, -1.0],
            [-0.5, 0.5, 0.5, -1.0],
            [0.0, -0.5, 0.5, -1.0],
        ],
        vec![[0, 1, 2]],
    );
    let tri = Scene::new(16, 16, d.positions.clone(), d.triangles().to_vec()).positions_of(0);
    let frags = fragments(&d);
    assert_eq!(frags.len(), 32);
    for f in &frags {
        let [nx, ny] = sample_ndc(16, 16, f.x, f.y);
        assert!(
            ray_cast(&tri, nx, ny, &d.state).is_none(),
            "no ray hits it in front of the eye"
        );
    }
}

/// Finding 2, before the near plane: every vertex at z = −½·w draws, at depth −½.
#[test]
fn a_triangle_before_the_near_plane_is_drawn() {
    let d = draw(
        16,
        vec![
            [0.5, 0.5, -0.5, 1.0],
            [-0.5, 0.5, -0.5, 1.0],
            [0.0, -0.5, -0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    let frags = fragments(&d);
    assert!(!frags.is_empty());
    assert!(
        frags.iter().all(|f| f.depth == -0.5),
        "outside [0, 1]: {:?}",
        frags[0]
    );
}

/// Finding 3. A zero-area triangle (a repeated vertex) covers a sample, with NaN depth and
/// barycentrics (Vulkan, Basic Polygon Rasterization: zero-area triangles are back-facing and cover nothing).
/// Nearly edge-on triangles do the same (the suite's rotation and reversal counterexamples).
#[test]
fn a_zero_area_triangle_draws_nan_fragments() {
    let d = draw(
        16,
        vec![
            [-1.0, 1.0, 0.5, 1.0],
            [-0.1875, 0.5625, 0.5, 1.0],
            [-1.0, 1.0, 0.5, 1.0],
        ],
        vec![[0, 1, 2]],
    );
    let frags = fragments(&d);
    assert_eq!(frags.len(), 1);
    assert_eq!((frags[0].x, frags[0].y), (6, 3));
    assert!(frags[0].depth.is_nan() && frags[0].barycentric.iter().all(|b| b.is_nan()));
}

/// Finding 4. The visible part of a triangle with a vertex behind the eye turns
/// counter-clockwise on screen (det[x y w] > 0), yet euc calls it back-facing: it decides on
/// the vertices divided by w, and dividing by a negative w mirrors one of them (Vulkan
/// Basic Polygon Rasterization: facing from the sign of the clipped polygon's area).
#[test]
fn facing_flips_when_a_vertex_is_behind_the_eye() {
    let positions = vec![
        [2745.8733, -1327.9667, 0.0, 0.2],
        [0.0, 611.8581, 0.0, -0.1],
        [0.0, 0.0, 0.0, 0.2],
    ];
    let d = draw(16, positions.clone(), vec![[0, 1, 2]]);
    // det[x y w] of the three clip-space vertices, exactly: a·(b_y c_w) for this input.
    let det = f64::from(positions[0][0]) * f64::from(positions[1][1]) * f64::from(positions[2][3]);
    assert!(det > 0.0, "counter-clockwise on screen");
    let frags = fragments(&d);
    assert!(frags.len() >= 16);
    assert!(frags.iter().all(|f| !f.front_facing), "euc says back-facing");
    // With culling of back faces, euc drops this visible, front-facing triangle.
    let mut culled = d.clone();
    culled.state.cull = refrast::CullMode::Back;
    assert!(fragments(&culled).is_empty());
    // The rule agrees with this reading, at every judged sample.
    let scene = scene(16, positions, vec![[0, 1, 2]]);
    assert!(rules::meta::check_facing(&mut Euc, &scene).is_err());
    assert_eq!(d.state.front_face, FrontFace::CounterClockwise);
}

/// Finding 5. f32 weights: at pixel (2, 1) of this triangle euc's perspective-correct
/// barycentrics are off by 1.2·10⁻³ from the exact ones (worked out in exact rationals:
/// 0.773157, 0.062797, 0.164046), twenty times the 2^-14 an f32 rasterizer keeps.
#[test]
fn barycentrics_are_off_by_a_thousandth() {
    let d = draw(
        16,
        vec![
            [0.0, -0.015234375, 0.0, 0.1],
            [-0.081250004, 0.1, 0.0, 0.1],
            [-2.5225985, 3.0515306, 0.0, 3.2048895],
        ],
        vec![[0, 1, 2]],
    );
    let exact = [0.7731570408577654, 0.06279682679569522, 0.16404613234653942];
    let tri = Scene::new(16, 16, d.positions.clone(), d.triangles().to_vec()).positions_of(0);
    let [nx, ny] = sample_ndc(16, 16, 2, 1);
    let hit = ray_cast(&tri, nx, ny, &d.state).expect("the sample is inside");
    for (got, want) in hit.barycentric.iter().zip(exact) {
        assert!((got - want).abs() < 1e-12, "the ray cast is exact here");
    }
    let f = fragments(&d)
        .into_iter()
        .find(|f| (f.x, f.y) == (2, 1))
        .expect("covered");
    let off = (0..3)
        .map(|k| (f64::from(f.barycentric[k]) - exact[k]).abs())
        .fold(0.0, f64::max);
    assert!(off > 1e-3 && off < 1.3e-3, "off by {off}");
}

/// Finding 5, depth: near an edge of a triangle whose vertices' w differ thirtyfold, euc's depth
/// at pixel (3, 0) is 0.889460, the exact z/w 0.878723 (worked out in exact rationals): off by
/// 1.07·10⁻², where an f32 rasterizer keeps 2^-14 ≈ 6·10⁻⁵.
#[test]
fn depth_is_off_by_a_hundredth_near_an_edge() {
    let d = fitted(Draw::new(
        Viewport::new(32, 16).expect("a valid viewport"),
        vec![
            [-0.07832032, -0.053320315, 0.0, 0.1],
            [-0.2707494, 0.10829976, 0.0, 0.34655923],
            [-2.3588076, 3.0192738, 2.918375, 3.0192738],
        ],
        vec![[0, 1, 2]],
    ));
    let f = fragments(&d)
        .into_iter()
        .find(|f| (f.x, f.y) == (3, 0))
        .expect("covered");
    let off = (f64::from(f.depth) - 0.8787225288466437).abs();
    assert!(off > 1.0e-2 && off < 1.1e-2, "off by {off}");
}

/// Whether euc panics drawing `d` (its debug assertions and overflow checks are on in tests).
#[cfg(debug_assertions)]
fn panics(d: &Draw) -> Option<String> {
    let caught = std::panic::catch_unwind(|| Euc.rasterize(d));
    caught.err().map(|p| {
        p.downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| (*s).to_string()))
            .unwrap_or_default()
    })
}

/// Finding 6. A vertex at w = 0 (valid input: clipping at the near plane removes it, Vulkan
/// Primitive Clipping) makes x/w infinite; euc casts it to i32, which saturates at `i32::MAX`, and the
/// bounding box's `e + 1` overflows (triangles.rs:129): a panic in debug builds, the same path
/// as the vertex at x = 10¹⁰·w that crashes release builds. Found by `bary.range.unit` and
/// `meta.cull.by-facing` once `crossing_scene` made vertices at w = 0.
#[test]
#[cfg(debug_assertions)] // The overflow check and the assertion exist only in debug builds.
fn a_vertex_at_w_zero_overflows_the_bounding_box() {
    let d = draw(
        16,
        vec![
            [1.3765194, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.2],
            [0.0, 0.0, 0.0, 0.2],
        ],
        vec![[0, 1, 2]],
    );
    let message = panics(&d).expect("euc panics in a debug build");
    assert!(message.contains("overflow"), "{message}");
}

/// Finding 7. A zero-area triangle whose coinciding vertices have different w: vertices 0 and
/// 2 both project to NDC (−1.15625, 0.9375), so det[x y w] = 0 while the normal of the
/// (x, y, w) plane is not zero; euc divides by that determinant and its debug assertion that
/// the weights are finite fires (triangles.rs:97). With equal w (finding 3) the normal is zero
/// and euc draws NaN fragments instead. Found by `meta.rotation.same-coverage` while a
/// version of `grid_offset` made sub-pixel (here zero) offsets.
#[test]
#[cfg(debug_assertions)]
fn a_zero_area_triangle_with_different_w_trips_an_assertion() {
    let d = Draw::new(
        Viewport::new(32, 16).expect("a valid viewport"),
        vec![
            [-1.131672, 0.9175719, 0.0, 0.9787434],
            [-4.1690516, -2.951541, 0.0, 3.1483104],
            [-0.115625, 0.09375, 0.0, 0.1],
        ],
        vec![[0, 1, 2]],
    );
    let p = [[-1.131672f64, 0.9175719, 0.9787434], [-0.115625, 0.09375, 0.1]];
    // The two vertices project to the same point (to f32 rounding of the inputs).
    assert!((p[0][0] / p[0][2] - p[1][0] / p[1][2]).abs() < 1e-6);
    assert!((p[0][1] / p[0][2] - p[1][1] / p[1][2]).abs() < 1e-6);
    let message = panics(&fitted(d)).expect("euc panics in a debug build");
    assert!(message.contains("is_finite"), "{message}");
}

/// Not a finding, a false positive fixed: a sample within 10⁻⁶ px of an edge goes in or out
/// depending on the vertex order in euc's f32 weights. Without a tie rule that is allowed, so
/// `meta.rotation.same-coverage` no longer judges the coverage of samples within the band of
/// an edge for a profile without exact coverage (it did, and failed euc on this triangle).
/// Its barycentrics move by 6·10⁻⁶ with the order, within the 2^-14 its profile claims.
#[test]
fn rotation_ignores_samples_on_an_edge_without_exact_coverage() {
    let positions = vec![
        [-0.09375, 0.056250002, 0.0, 0.1],
        [-0.08291016, 0.027294923, 0.0, 0.1],
        [-1.0780537, 1.1639342, 0.0, 2.0692165],
    ];
    let scene = scene(16, positions.clone(), vec![[0, 1, 2]]);
    let rotated = Scene {
        triangles: vec![[1, 2, 0]],
        ..scene.clone()
    };
    let covered = |s: &Scene| {
        let mut c: Vec<_> = fragments(&s.draw()).iter().map(|f| (f.x, f.y)).collect();
        c.sort_unstable();
        c
    };
    // euc's coverage does change with the order, on the row the edge from vertex 0 to 2 runs along.
    assert_ne!(covered(&scene), covered(&rotated));
    assert!(rules::meta::check_rotation(&mut Euc, &scene).is_ok());
}
