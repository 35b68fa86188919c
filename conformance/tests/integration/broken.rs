//! The suite catches a classic bug: inclusive edges everywhere (`E ≥ 0`, no fill rule).

use refrast::{
    Draw, DrawError, FixedPoint, Fragment, Profile, Rasterizer, Reference, SubpixelBits, orient2d,
};
use refrast_conformance::{CaseFile, Options, Status, certify, replay};

/// Covers a sample when every edge function is `≥ 0`: samples on shared edges go to both sides.
struct InclusiveEdges;

impl Rasterizer for InclusiveEdges {
    fn profile(&self) -> Profile {
        Profile {
            name: "inclusive-edges".into(),
            ..Reference::default().profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        draw.validate()?;
        let bits = SubpixelBits::DEFAULT;
        let vp = draw.viewport;
        let mut out = Vec::new();
        for (primitive, t) in draw.triangles().iter().enumerate() {
            let clip = t.map(|i| draw.positions[i as usize]);
            // No clipping: only triangles wholly in front of the eye are drawn.
            if clip
                .iter()
                .any(|p| p[3].is_nan() || p[3] <= 0.0 || p.iter().any(|c| !c.is_finite()))
            {
                continue;
            }
            let snapped = clip.map(|p| {
                let (x, y) = vp.to_raster(f64::from(p[0] / p[3]), f64::from(p[1] / p[3]));
                FixedPoint::snap(x, y, bits)
            });
            let [Some(a), Some(b), Some(c)] = snapped else {
                continue;
            };
            let area = orient2d(a, b, c);
            if area == 0 {
                continue;
            }
            for y in 0..vp.height() {
                for x in 0..vp.width() {
                    let Some(s) = FixedPoint::sample(i64::from(x), i64::from(y), bits) else {
                        continue;
                    };
                    let e =
                        [orient2d(b, c, s), orient2d(c, a, s), orient2d(a, b, s)].map(|e| e * area.signum());
                    if e.iter().all(|&e| e >= 0) {
                        let w = e.map(|e| e as f32 / area.abs() as f32);
                        let depth = (0..3)
                            .map(|k| w[k] * clip[k][2] / clip[k][3])
                            .sum::<f32>()
                            .clamp(0.0, 1.0);
                        out.push(Fragment {
                            x,
                            y,
                            sample: 0,
                            primitive: primitive as u32,
                            depth,
                            barycentric: w,
                            screen_barycentric: Some(w),
                            front_facing: area < 0,
                            flat: None,
                        });
                    }
                }
            }
        }
        Ok(out)
    }
}

#[test]
fn inclusive_edges_fail_the_fill_rules_with_a_small_counterexample_and_a_picture() {
    let dir = std::env::temp_dir().join("refrast-broken-test");
    let options = Options {
        rules: vec!["fill.*".into()],
        ..Options::default()
    };
    let report = certify(&mut InclusiveEdges, &options, |r| r.save_exhibit(&dir).unwrap());
    let failed: Vec<_> = report.rules.iter().filter(|r| r.status == Status::Fail).collect();
    for id in [
        "fill.mesh.exactly-once",
        "fill.fan.exactly-once",
        "fill.top-left.exact",
        "fill.brute-force.exact",
    ] {
        assert!(failed.iter().any(|r| r.id == id), "{id} should fail: {report:#?}");
    }
    let mesh = failed.iter().find(|r| r.id == "fill.mesh.exactly-once").unwrap();
    let message = mesh.message.as_deref().unwrap_or("");
    // On the grid the samples lie exactly on the shared edge: the tie rule is named, not the
    // rounding of an edge function (a distance in doubles once said 1.6e-16 px and blamed it).
    assert!(
        message.contains("lies exactly on the edge") && message.contains("tie rule"),
        "{message}"
    );
    assert!(
        !mesh.details.iter().any(|d| d.contains("antisymmetric")),
        "{:#?}",
        mesh.details
    );
    let counts = mesh.counts.expect("coverage failures carry counts");
    assert!(
        counts.double > 0,
        "inclusive edges double-cover shared edges: {counts:?}"
    );
    let input = mesh.counterexample.as_deref().unwrap();
    let triangles = input
        .lines()
        .find(|l| l.trim_start().starts_with("triangles:"))
        .unwrap();
    let n = triangles.matches('[').count() - 1;
    assert!(n <= 2, "shrunk to {n} triangles:\n{input}");
    let picture = mesh.picture.as_ref().expect("a picture is written");
    let image = image::open(picture).expect("the picture is a PNG").to_rgba8();
    // Double-covered samples are drawn blue.
    assert!(
        image.pixels().any(|p| p.0 == [40, 90, 255, 255]),
        "no blue sample in {}",
        picture.display()
    );
}

/// Judging writes no file: a failure's picture and case come back as its exhibit, and are
/// written only where the runner saves them (issue 44: the runner owns every output).
#[test]
fn judging_writes_nothing_until_the_runner_saves_the_exhibit() {
    let options = Options {
        rules: vec!["fill.mesh.exactly-once".into()],
        ..Options::default()
    };
    let mut report = certify(&mut InclusiveEdges, &options, |_| {});
    let failed = &mut report.rules[0];
    assert_eq!(failed.status, Status::Fail, "{failed:#?}");
    assert_eq!((&failed.picture, &failed.case_path), (&None, &None));
    let exhibit = failed.exhibit.as_ref().expect("a failure keeps its exhibit");
    assert!(
        exhibit.stem.ends_with("__fill.mesh.exactly-once"),
        "{}",
        exhibit.stem
    );
    assert!(exhibit.picture.is_some() && !exhibit.caption.is_empty());
    let dir = std::env::temp_dir().join(format!("refrast-exhibit-{}", std::process::id()));
    failed.save_exhibit(&dir).expect("the files are written");
    for path in [&failed.picture, &failed.case_path] {
        let path = path.as_ref().expect("each path is recorded");
        assert!(path.starts_with(&dir) && path.is_file(), "{}", path.display());
    }
    // A folder that cannot be made is an error that names the file, not a panic.
    let blocked = dir.join(failed.picture.as_ref().unwrap().file_name().unwrap());
    let why = failed
        .save_exhibit(&blocked)
        .expect_err("a file stands where the folder goes");
    assert!(why.contains("could not write"), "{why}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_reference_passes_what_the_broken_one_fails() {
    let options = Options {
        rules: vec!["fill.*".into()],
        cases: Some(64),
        ..Options::default()
    };
    let report = certify(&mut Reference::default(), &options, |_| {});
    assert!(report.passed(), "{report:#?}");
}

/// A counterexample read back from its JSON replays alone: the same failure on the rasterizer
/// that failed it, a pass on the reference, and a clear error for a case of another rule.
#[test]
fn a_counterexample_replays_from_its_json() {
    let dir = std::env::temp_dir().join("refrast-replay-test");
    let options = Options {
        rules: vec!["fill.mesh.exactly-once".into()],
        ..Options::default()
    };
    let report = certify(&mut InclusiveEdges, &options, |r| r.save_exhibit(&dir).unwrap());
    let failed = &report.rules[0];
    assert_eq!(failed.status, Status::Fail, "{failed:#?}");
    let path = failed
        .case_path
        .as_ref()
        .expect("the case is written beside the picture");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        text.contains("\"rule\": \"fill.mesh.exactly-once\"")
            && text.contains("\"topology\": \"triangle-list\""),
        "{text}"
    );
    let case: CaseFile = serde_json::from_str(&text).unwrap();
    assert_eq!(Some(&case), failed.case_file.as_ref());

    let again = replay(&case, &mut InclusiveEdges, &Options::default()).unwrap();
    assert_eq!((again.status, again.cases), (Status::Fail, 1));
    assert_eq!(again.message, failed.message);
    assert_eq!(again.counterexample, failed.counterexample);
    let reference = replay(&case, &mut Reference::default(), &Options::default()).unwrap();
    assert_eq!(reference.status, Status::Pass, "{reference:#?}");

    let translated = CaseFile {
        rule: "meta.translate.whole-pixels".into(),
        ..case.clone()
    };
    let err = replay(&translated, &mut InclusiveEdges, &Options::default()).unwrap_err();
    assert!(err.contains("no translate"), "{err}");
    let unknown = CaseFile {
        rule: "fill.nothing".into(),
        ..case
    };
    let err = replay(&unknown, &mut InclusiveEdges, &Options::default()).unwrap_err();
    assert!(err.contains("no rule is called 'fill.nothing'"), "{err}");
}
