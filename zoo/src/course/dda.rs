//! Seed 004's lines and seed 002's points as the labs draw them: a DDA from the pixel holding
//! one end to the pixel holding the other, both drawn, and a point in the pixel `floor` names.
//!
//! The lab's algorithm, `refrast::stage::rasterize_line` and `rasterize_point`, on ends clipped
//! in clip space and projected but not snapped. Declared as diamond-exit lines, which is what a
//! student would claim (Bresenham's algorithm), so that `certify` says where it differs:
//! - both end pixels are drawn, where the rule leaves out the last end's diamond, so a strip
//!   draws each joint twice (`line.diamond-exit.exact`, `line.strip.shared-end-once`);
//! - the pixels run between the pixels holding the ends, not along the segment itself, so a
//!   segment whose ends lie near pixel edges steps a row early or late;
//! - a point on a pixel corner lands below and to the right (`floor`), where the square's
//!   top-left rule puts it above and to the left (`point.square.exact`).
//!
//! Triangles are drawn by the reference, at one sample: only the line and point rules judge it.

use glam::{DVec3, DVec4};
use refrast::stage::{ClipVertex, LineVertex, clip_planes, clip_segment, rasterize_line, rasterize_point};
use refrast::{
    ClipMode, Draw, DrawError, Fragment, LineRule, Profile, Rasterizer, Reference, Topology, Viewport,
};

/// The labs' line and point drawing over the reference's triangles.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dda;

impl Rasterizer for Dda {
    fn profile(&self) -> Profile {
        Profile {
            name: "lab004-dda".into(),
            lines: Some(LineRule::DiamondExit),
            points: true,
            ..Reference::default().profile().triangles_only()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        draw.validate()?;
        if draw.samples != 1 {
            return Err(DrawError::Unsupported(draw.describe()));
        }
        let vp = draw.viewport;
        let state = &draw.state;
        let mut out = Vec::new();
        let mut emit = |primitive: usize, x: u32, y: u32, depth: f64, t: f64| {
            out.push(Fragment {
                x,
                y,
                sample: 0,
                primitive: primitive as u32,
                depth: depth.clamp(0.0, 1.0) as f32,
                barycentric: [(1.0 - t) as f32, t as f32, 0.0],
                flat: None,
                screen_barycentric: Some([(1.0 - t) as f32, t as f32, 0.0]),
                front_facing: true,
            });
        };
        match draw.topology {
            Topology::TriangleList | Topology::TriangleStrip | Topology::TriangleFan => {
                return Reference::default().rasterize(draw);
            }
            Topology::PointList => {
                let planes = clip_planes(ClipMode::Full, vp, state.depth_clip());
                for (i, &index) in draw.indices.iter().enumerate() {
                    let p = DVec4::from(draw.positions[index as usize].map(f64::from));
                    if !p.is_finite() || p.w <= 0.0 || planes.iter().any(|plane| plane.distance(p) < 0.0) {
                        continue;
                    }
                    if let Some(f) = rasterize_point(end(vp, p, state.depth_range), vp) {
                        emit(i, f.x, f.y, f.depth, 0.0);
                    }
                }
            }
            Topology::LineList | Topology::LineStrip => {
                let planes = clip_planes(ClipMode::GuardBand, vp, state.depth_clip());
                for i in 0..draw.primitive_count() {
                    let Some(&[a, b]) = draw.primitive(i).as_deref() else {
                        continue;
                    };
                    let clip = |v: u32, barycentric| ClipVertex {
                        position: DVec4::from(draw.positions[v as usize].map(f64::from)),
                        barycentric,
                    };
                    let (ca, cb) = (clip(a, DVec3::X), clip(b, DVec3::Y));
                    if !(ca.position.is_finite() && cb.position.is_finite()) {
                        continue;
                    }
                    let Some((ca, cb)) = clip_segment(ca, cb, &planes, &[]) else {
                        continue;
                    };
                    let (ua, ub) = (ca.barycentric.y, cb.barycentric.y);
                    rasterize_line(
                        end(vp, ca.position, state.depth_range),
                        end(vp, cb.position, state.depth_range),
                        vp,
                        |f| emit(i, f.x, f.y, f.depth, ua + (ub - ua) * f.t),
                    );
                }
            }
        }
        Ok(out)
    }
}

/// A clip-space point on screen, unsnapped, with its window depth.
fn end(vp: Viewport, p: DVec4, range: refrast::DepthRange) -> LineVertex {
    let (x, y) = vp.to_raster(p.x / p.w, p.y / p.w);
    LineVertex {
        x,
        y,
        depth: range.window_depth(p.z, p.w),
    }
}
