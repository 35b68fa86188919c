//! The protocol's words and records, read and written.

use super::*;

fn parsed(lines: &[&str]) -> Result<Profile, String> {
    let lines: Vec<String> = lines.iter().map(|&l| l.to_owned()).collect();
    parse_profile(&lines, "child", 1).map(|d| d.profile)
}

/// Three NaN screen-barycentric words say "none" (a triangle with a vertex at w ≤ 0);
/// one NaN among finite words stays a value, which the rules judge.
#[test]
fn three_nan_screen_words_say_none() {
    let record = |screen: [f32; 3]| {
        let mut words: Vec<u32> = vec![1, 2, 0, 1];
        words.extend([0.5f32, 1.0, 0.0, 0.0].map(f32::to_bits));
        words.extend(screen.map(f32::to_bits));
        words.push(0);
        words.iter().flat_map(|w| w.to_le_bytes()).collect::<Vec<u8>>()
    };
    let none = fragment(&record([f32::NAN; 3]), true, 1).expect("a record");
    assert_eq!(none.screen_barycentric, None);
    let one = fragment(&record([f32::NAN, 0.5, 0.5]), true, 1).expect("a record");
    assert!(one.screen_barycentric.is_some_and(|s| s[0].is_nan()));
    let undeclared = fragment(&record([0.2, 0.3, 0.5]), false, 1).expect("a record");
    assert_eq!(undeclared.screen_barycentric, None);
    assert_eq!(
        fragment(&record([0.2, 0.3, 0.5]), true, 1)
            .expect("a record")
            .screen_barycentric,
        Some([0.2, 0.3, 0.5])
    );
}

/// `snap`, `clipping` and `point-clipping` read their words; a wrong one names the choices.
#[test]
fn the_new_profile_words_are_read() {
    let p = parsed(&["snapping grid 6", "snap toward-zero", "clipping none"]).expect("a profile");
    assert_eq!(p.features.snap, SnapAccuracy::TowardZero);
    assert!(!p.features.clips_in_3d);
    assert_eq!(
        parsed(&["snap floor"]).expect("floor").features.snap,
        SnapAccuracy::Floor
    );
    let why = parsed(&["clipping sometimes"]).expect_err("a bad word");
    assert!(why.contains("homogeneous or none"), "{why}");
    let why = parsed(&["snap truncate"]).expect_err("a bad word");
    assert!(why.contains("toward-zero"), "{why}");
    let lines: Vec<String> = [
        "topology triangle-list point-list",
        "point-clipping user-clip-planes-only",
    ]
    .iter()
    .map(|&l| l.to_owned())
    .collect();
    let declared = parse_profile(&lines, "child", 2).expect("version 2");
    assert_eq!(declared.profile.point_clipping, PointClipping::UserClipPlanesOnly);
    assert_eq!(parsed(&["spec opengles"]).expect("ES").spec, Spec::OpenGlEs);
}

/// The guard band is a line with its reach, or the feature word alone for the reach the rule
/// drew before it had a size; saying both is an error that names the fix.
#[test]
fn the_guard_band_is_declared_with_its_reach() {
    assert_eq!(parsed(&[]).unwrap().features.guard_band, 0);
    assert_eq!(parsed(&["guard-band 8192"]).unwrap().features.guard_band, 8192);
    assert_eq!(
        parsed(&["guard-band unbounded"]).unwrap().features.guard_band,
        u32::MAX
    );
    let word = parsed(&["features depth-test guard-band"]).unwrap().features;
    assert_eq!((word.guard_band, word.depth_test), (LEGACY_GUARD_BAND, true));
    let both = parsed(&["features guard-band", "guard-band 8192"]).unwrap_err();
    assert!(both.contains("keep the line `guard-band PIXELS`"), "{both}");
    let far = parsed(&["guard-band 40000"]).unwrap_err();
    assert!(far.contains("0 to 32768"), "{far}");
}

/// The specification claimed, how exactly snapping lands and the zero-area claim: refrast's
/// conventions, the nearest grid point and no claim unless said.
#[test]
fn spec_snap_and_zero_area_are_declared() {
    let plain = parsed(&[]).unwrap();
    assert_eq!(plain.spec, Spec::Refrast);
    assert_eq!(plain.features.snap, SnapAccuracy::Nearest);
    assert!(!plain.features.zero_area_before_clipping);
    let said = parsed(&[
        "spec vulkan",
        "snap within-one-step",
        "features zero-area-before-clipping",
    ])
    .unwrap();
    assert_eq!(said.spec, Spec::Vulkan);
    assert_eq!(said.features.snap, SnapAccuracy::WithinOneStep);
    assert!(said.features.zero_area_before_clipping);
    assert!(parsed(&["spec metal"]).unwrap_err().contains("vulkan"));
    assert!(parsed(&["snap exact"]).unwrap_err().contains("within-one-step"));
}

/// Ties round to even only when the child says so.
#[test]
fn ties_to_even_is_a_feature_word() {
    assert!(!parsed(&["snapping grid 8"]).unwrap().features.ties_to_even);
    let f = parsed(&["snapping grid 8", "features ties-to-even"])
        .unwrap()
        .features;
    assert!(f.ties_to_even && !f.depth_test);
    let bad = parsed(&["features ties-up"]).unwrap_err();
    assert!(bad.contains("ties-to-even"), "{bad}");
}

/// The scissor and culling of both faces are declared apart (a feature word; a word in the
/// cull line), sent only when declared, and carried in the request's header.
#[test]
fn the_scissor_and_both_faces_are_declared_and_sent() {
    let plain = parsed(&["cull none back"]).unwrap();
    assert!(!plain.state.scissor && !plain.state.cull_both);
    let both = parsed(&["cull none front-and-back", "features scissor"]).unwrap();
    assert!(both.state.scissor && both.state.cull_both);
    assert!(both.features.cull_modes.contains(CullMode::None));
    assert!(!both.features.cull_modes.contains(CullMode::Back));
    assert!(parsed(&["cull front-and-sides"]).unwrap_err().contains("cull"));
    let alone = parsed(&["cull front-and-back"]).unwrap_err();
    assert!(alone.contains("needs one of none, front, back"), "{alone}");
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    let header = |draw: &Draw| {
        let bytes = request(Op::Rasterize, draw, 2);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    assert!(!header(&draw).contains("scissor"));
    draw.state.cull = CullMode::FrontAndBack;
    draw.state.scissor = Some(refrast::Scissor {
        x: 1,
        y: 2,
        width: 3,
        height: 0,
    });
    let text = header(&draw);
    assert!(
        text.contains(" cull=front-and-back ") && text.ends_with(" scissor=1,2,3,0"),
        "{text}"
    );
    assert_eq!(CullMode::parse("front-and-back"), Some(CullMode::FrontAndBack));
}

/// The sample mask is a feature word, sent last in the header only when it is not all ones,
/// and only to a child that declares it.
#[test]
fn the_sample_mask_is_declared_and_sent_last() {
    assert!(!parsed(&["features scissor"]).unwrap().state.sample_mask);
    let masking = parsed(&["features sample-mask depth-test"]).unwrap();
    assert!(masking.state.sample_mask && masking.features.depth_test);
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    )
    .at_samples(4);
    let header = |draw: &Draw| {
        let bytes = request(Op::Rasterize, draw, 3);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    assert!(!header(&draw).contains("sample-mask"));
    draw.state.sample_mask = 0b1010;
    draw.state.scissor = Some(refrast::Scissor::default());
    let text = header(&draw);
    assert!(text.ends_with(" scissor=0,0,0,0 sample-mask=10"), "{text}");
    // A child that does not declare it is sent every sample: the fit drops the mask.
    let plain = parsed(&["features scissor"]).unwrap();
    assert_eq!(plain.fit(draw.state).sample_mask, refrast::DrawState::ALL_SAMPLES);
    assert_eq!(masking.fit(draw.state).sample_mask, 0b1010);
}

/// Centroid interpolation is a feature word; `interpolation=centroid` ends a triangle draw's
/// header at several samples, and is never sent at one sample or to a child without it.
#[test]
fn centroid_is_declared_and_sent_after_the_mask() {
    let plain = parsed(&["features sample-mask"]).unwrap();
    let centroid = parsed(&["features sample-mask centroid"]).unwrap();
    assert!(!plain.state.centroid && centroid.state.centroid);
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    )
    .at_samples(4);
    let header = |draw: &Draw| {
        let bytes = request(Op::Rasterize, draw, 3);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    draw.state.sample_mask = 0b0110;
    draw.state.interpolation = refrast::Interpolation::Centroid;
    let text = header(&draw);
    assert!(text.ends_with(" sample-mask=6 interpolation=centroid"), "{text}");
    assert!(!header(&draw.clone().at_samples(1)).contains("interpolation"));
    assert_eq!(
        plain.fit(draw.state).interpolation,
        refrast::Interpolation::Sample
    );
    assert_eq!(
        centroid.fit(draw.state).interpolation,
        refrast::Interpolation::Centroid
    );
}

/// The depth range and depth clipping off are feature words (reversed ranges implying ranges)
/// and keys at the end of a request, sent only when the draw has them.
#[test]
fn the_depth_range_and_unclipped_depth_are_declared_and_sent() {
    let plain = parsed(&["features depth-test"]).unwrap();
    assert!(!plain.state.honours_viewport_depth() && !plain.state.unclipped_depth);
    let ordered = parsed(&["features viewport-depth unclipped-depth"]).unwrap();
    assert!(ordered.state.viewport_depth && !ordered.state.inverted_depth && ordered.state.unclipped_depth);
    let reversed = parsed(&["features inverted-depth"]).unwrap();
    assert!(reversed.state.viewport_depth && reversed.state.inverted_depth);
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    let header = |draw: &Draw| {
        let bytes = request(Op::Rasterize, draw, 1);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    let before = header(&draw);
    assert!(
        !before.contains("viewport-depth") && !before.contains("near-clipping"),
        "{before}"
    );
    draw.state.clip_near = false;
    draw.state.viewport_depth = refrast::ViewportDepth { min: 0.75, max: 0.1 };
    let text = header(&draw);
    assert!(
        text.contains(" far-clipping=off near-clipping=off viewport-depth=0.75,0.1"),
        "{text}"
    );
}

/// Depth bias is a profile line naming the format, the slope measure and the clamp, and a key
/// at the end of a triangle draw's request, never of a line or point draw's.
#[test]
fn depth_bias_is_declared_with_its_format_and_sent_with_triangles() {
    assert_eq!(parsed(&["features depth-test"]).unwrap().state.depth_bias, None);
    let declared = parsed(&["depth-bias float32 max clamp"])
        .unwrap()
        .state
        .depth_bias;
    assert_eq!(
        declared,
        Some(refrast::BiasSupport {
            format: refrast::DepthFormat::Float32,
            slope: refrast::DepthSlope::Max,
            clamp: true,
        })
    );
    let unclamped = parsed(&["depth-bias unorm24 either"]).unwrap().state.depth_bias;
    assert!(unclamped.is_some_and(|b| !b.clamp && b.format == refrast::DepthFormat::Unorm24));
    for bad in [
        "depth-bias float32",
        "depth-bias float64 max",
        "depth-bias float32 max clamped",
    ] {
        let why = parsed(&[bad]).unwrap_err();
        assert!(why.contains("FORMAT SLOPE"), "{bad}: {why}");
    }
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    draw.state.depth_bias = Some(refrast::DepthBias {
        constant: -4096.0,
        slope: 1.5,
        clamp: 0.001,
    });
    let header = |draw: &Draw| {
        let bytes = request(Op::Rasterize, draw, 2);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    assert!(
        header(&draw).ends_with(" depth-bias=-4096.0,1.5,0.001"),
        "{}",
        header(&draw)
    );
    draw.topology = Topology::PointList;
    draw.indices = vec![0, 1, 2];
    assert!(!header(&draw).contains("depth-bias"), "{}", header(&draw));
}

/// Strips and fans are declared in the topology line, each on its own, and a request sends
/// `T + 2` indices for `T` triangles, none for a strip too short to make one.
#[test]
fn strips_and_fans_are_declared_and_sent() {
    let declared = |line: &str| {
        parse_profile(&[line.to_owned()], "child", 2)
            .expect("version 2")
            .folded()
            .profile
    };
    let strips = declared("topology triangle-list triangle-strip");
    assert!(strips.state.triangle_strips && !strips.state.triangle_fans);
    assert!(strips.draws(Topology::TriangleStrip, 1) && !strips.draws(Topology::TriangleFan, 1));
    let fans = declared("topology triangle-list triangle-fan");
    assert!(fans.state.triangle_fans && !fans.state.triangle_strips);
    assert!(!declared("topology triangle-list").state.triangle_strips);
    let vp = refrast::Viewport::new(4, 4).unwrap();
    let body = |indices: Vec<u32>| {
        let draw = Draw::of(vp, vec![[0.0; 4]; 4], Topology::TriangleFan, indices);
        let bytes = request(Op::Rasterize, &draw, 2);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        let header = String::from_utf8(bytes[..end].to_vec()).unwrap();
        (header, bytes.len() - end - 1 - 4 * 16)
    };
    let (header, bytes) = body(vec![0, 1, 2, 3]);
    assert!(
        header.contains(" triangles=2 ") && header.contains(" topology=triangle-fan "),
        "{header}"
    );
    assert_eq!(bytes, 4 * 4);
    assert_eq!(body(vec![0, 1]).1, 0);
}

/// Version 3 declares the provoking modes, sends the draw's, and reads each fragment's flat
/// vertex from a thirteenth word (`0xFFFF_FFFF`: none); version 2 knows none of it.
#[test]
fn version_3_carries_the_provoking_vertex_and_the_flat_vertex() {
    let line = vec!["provoking-vertex last".to_owned()];
    let declared = parse_profile(&line, "child", 3).expect("version 3");
    assert!(declared.profile.state.flat.contains(ProvokingVertex::Last));
    assert!(!declared.profile.state.flat.contains(ProvokingVertex::First));
    let refused = parse_profile(&line, "child", 2).expect_err("version 2");
    assert!(refused.contains("unknown key `provoking-vertex`"), "{refused}");
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    draw.state.provoking_vertex = ProvokingVertex::Last;
    let header = |version| {
        let bytes = request(Op::Rasterize, &draw, version);
        let end = bytes.iter().position(|&b| b == b'\n').unwrap();
        String::from_utf8(bytes[..end].to_vec()).unwrap()
    };
    assert!(
        header(3).ends_with(" samples=1 provoking-vertex=last"),
        "{}",
        header(3)
    );
    assert!(!header(2).contains("provoking"));
    assert_eq!(
        (fragment_bytes(1), fragment_bytes(2), fragment_bytes(3)),
        (44, 48, 52)
    );
    let mut record = vec![0u8; 52];
    record[48..].copy_from_slice(&7u32.to_le_bytes());
    assert_eq!(fragment(&record, false, 1).unwrap().flat, Some(7));
    record[48..].copy_from_slice(&u32::MAX.to_le_bytes());
    assert_eq!(fragment(&record, false, 1).unwrap().flat, None);
    assert_eq!(fragment(&record[..48], false, 1).unwrap().flat, None);
    assert_eq!(version("refrast-protocol 3"), Ok(3));
    let why = version("refrast-protocol 9").unwrap_err();
    assert!(why.contains("speaks versions 1, 2 and 3"), "{why}");
}

/// Clip and cull distances are declared by count (at most 8 together) and sent with the key
/// `distances=CLIP,CULL`, their values after the indices, vertex by vertex, clip first.
#[test]
fn distances_are_declared_by_count_and_sent_after_the_indices() {
    let none = parsed(&["features depth-test"]).unwrap().state;
    assert_eq!((none.clip_distances, none.cull_distances), (0, 0));
    let both = parsed(&["clip-distances 6", "cull-distances 2"]).unwrap().state;
    assert_eq!((both.clip_distances, both.cull_distances), (6, 2));
    for bad in [
        "clip-distances nine",
        "clip-distances 9",
        "cull-distances",
        "clip-distances 1 2",
    ] {
        let why = parsed(&[bad]).unwrap_err();
        assert!(why.contains("0 to 8"), "{bad}: {why}");
    }
    let why = parsed(&["clip-distances 5", "cull-distances 4"]).unwrap_err();
    assert!(why.contains("at most 8 together"), "{why}");
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    let plain = request(Op::Rasterize, &draw, 2);
    draw.distances = refrast::Distances::new(1, 1, &[vec![0.5, -1.0], vec![2.0, 0.0], vec![-0.25, 1.0]]);
    let bytes = request(Op::Rasterize, &draw, 2);
    let end = bytes.iter().position(|&b| b == b'\n').unwrap();
    let header = String::from_utf8(bytes[..end].to_vec()).unwrap();
    assert!(header.ends_with(" distances=1,1"), "{header}");
    let tail: Vec<f32> = floats(&bytes[bytes.len() - 24..]);
    assert_eq!(tail, [0.5, -1.0, 2.0, 0.0, -0.25, 1.0]);
    assert_eq!(bytes.len(), plain.len() + " distances=1,1".len() + 24);
}

/// Conservative rasterization is a profile line of three sizes and words; its key ends a
/// filled triangle draw's header, and a malformed line says what to write.
#[test]
fn conservative_is_declared_by_its_line_and_sent_last() {
    let p = parsed(&["conservative 0.5 0.75 0.25 under degenerates-culled"]).unwrap();
    let c = p.state.conservative.expect("declared");
    assert_eq!(
        (c.overestimation_size, c.max_extra, c.extra_granularity),
        (0.5, 0.75, 0.25)
    );
    assert!(c.underestimate && c.degenerate_triangles == Some(false));
    assert!(
        parsed(&["features depth-test"])
            .unwrap()
            .state
            .conservative
            .is_none()
    );
    for bad in [
        "conservative 0.5",
        "conservative -1 0 0",
        "conservative 0 0 0 sideways",
    ] {
        let err = parsed(&[bad]).expect_err(bad);
        assert!(err.contains("OVERESTIMATION MAX_EXTRA GRANULARITY"), "{err}");
    }
    let mut draw = Draw::new(
        refrast::Viewport::new(4, 4).unwrap(),
        vec![[0.0; 4]; 3],
        vec![[0, 1, 2]],
    );
    draw.state.conservative = Some(refrast::Conservative::Overestimate { extra: 1.5 });
    let bytes = request(Op::Rasterize, &draw, 3);
    let end = bytes.iter().position(|&b| b == b'\n').unwrap();
    let text = String::from_utf8(bytes[..end].to_vec()).unwrap();
    assert!(text.ends_with(" conservative=over,1.5"), "{text}");
    // The fit clamps the extra size to the largest declared, and drops underestimation where
    // it is not declared.
    assert_eq!(
        p.fit(draw.state).conservative,
        Some(refrast::Conservative::Overestimate { extra: 0.75 })
    );
    draw.state.conservative = Some(refrast::Conservative::Underestimate);
    let over_only = parsed(&["conservative 0 0 0"]).unwrap();
    assert_eq!(over_only.fit(draw.state).conservative, None);
}
