//! `meta.facing.from-winding` judges clipped triangles too: facing taken from the triangle's
//! vertices divided by `w`, even a negative one, is wrong once a vertex is behind the eye.

use refrast::{Draw, DrawError, Fragment, FrontFace, Profile, Rasterizer, Reference};
use refrast_conformance::{Options, Status, certify};

/// The reference, except that facing comes from the projected input vertices when one has
/// `w ≤ 0`: the visible part of a triangle with a vertex behind the eye gets the wrong facing.
/// (Everywhere else it keeps the reference's facing, so that a sliver snapping turns over does
/// not give it away first.)
struct FacingByDivision;

impl Rasterizer for FacingByDivision {
    fn profile(&self) -> Profile {
        Profile {
            name: "facing-by-division".into(),
            ..Reference::default().profile().triangles_only()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut fragments = Reference::default().rasterize(draw)?;
        for f in &mut fragments {
            let p = draw.triangles()[f.primitive as usize].map(|i| draw.positions[i as usize].map(f64::from));
            if p.iter().all(|v| v[3] > 0.0) {
                continue;
            }
            let [a, b, c] = p.map(|v| [v[0] / v[3], v[1] / v[3]]);
            // Positive in NDC (y up) is counter-clockwise on screen.
            let ccw = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0.0;
            f.front_facing = ccw == (draw.state.front_face == FrontFace::CounterClockwise);
        }
        Ok(fragments)
    }
}

#[test]
fn facing_of_a_triangle_reaching_behind_the_eye_is_judged() {
    let options = Options {
        rules: vec!["meta.facing.from-winding".into()],
        ..Options::default()
    };
    let report = certify(&mut FacingByDivision, &options, |_| {});
    let rule = &report.rules[0];
    assert_eq!(rule.status, Status::Fail, "{rule:#?}");
    let input = rule.counterexample.as_deref().unwrap_or("");
    // Position lines read `[x, y, z, w],`: one of them has w < 0, or w = 0 (on the eye's
    // plane, where dividing by w fails as badly), which crossing scenes make too.
    let behind = input
        .lines()
        .filter_map(|l| l.trim().strip_prefix('[')?.strip_suffix("],"))
        .filter_map(|l| l.rsplit(", ").next()?.parse::<f32>().ok())
        .any(|w| w <= 0.0);
    assert!(
        behind,
        "the counterexample has a vertex behind the eye or on its plane:\n{input}"
    );
    // The same rule passes the reference, whose clipped triangles take det[x y w]'s sign.
    let report = certify(&mut Reference::default(), &options, |_| {});
    assert!(report.passed(), "{report:#?}");
}

/// The reference, except that its points and lines report back-facing (`flip`) or vanish under
/// a cull mode (`cull_points`): what softpipe and a careless cull would do.
struct CarelessPoints {
    flip: bool,
    cull_points: bool,
}

impl Rasterizer for CarelessPoints {
    fn profile(&self) -> Profile {
        Reference::default().profile()
    }
    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        let mut out = Reference::default().rasterize(draw)?;
        if !draw.topology.is_triangles() {
            if self.cull_points && draw.state.cull != refrast::CullMode::None {
                out.clear();
            }
            for f in &mut out {
                f.front_facing ^= self.flip;
            }
        }
        Ok(out)
    }
}

#[test]
fn lines_and_points_face_front_under_every_cull_mode() {
    let status = |r: &mut dyn Rasterizer| {
        let options = Options {
            rules: vec!["meta.facing.lines-points-front".into()],
            ..Options::default()
        };
        certify(r, &options, |_| {}).rules[0].status
    };
    assert_eq!(status(&mut Reference::default()), Status::Pass);
    for (flip, cull_points) in [(true, false), (false, true)] {
        assert_eq!(
            status(&mut CarelessPoints { flip, cull_points }),
            Status::Fail,
            "flip {flip}, cull {cull_points}"
        );
    }
}
