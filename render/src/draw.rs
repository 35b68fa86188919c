//! A picture through any [`Rasterizer`]: its fragments, depth-tested by its own test where it
//! declares one (else in API order), coloured by the mode and the shading.

use glam::{Mat4, Vec3, Vec3A, Vec4};
use refrast::pipeline::{Framebuffer, Mesh, Renderer, to_rgba8};

use refrast::{Draw, DrawError, DrawState, Fragment, Profile, Rasterizer, Reference, Resolved};

use crate::geometry::{edges, face_normal};
use crate::mode::{Mode, depth_greys, normal_color, overdraw_color};
use crate::shade::{Light, Shading};
use crate::texture::{Sampling, Texture};

/// Everything a picture needs besides the rasterizer and the target.
#[derive(Clone, Copy, Debug)]
pub struct Job<'a> {
    /// The triangles, in world space.
    pub mesh: &'a Mesh,
    /// World to clip space.
    pub view_projection: Mat4,
    /// Where the eye is, for specular highlights and two-sided lighting.
    pub eye: Vec3,
    /// Culling, facing, depth test and clipping.
    pub state: DrawState,
    /// What to show.
    pub mode: Mode,
    /// Where lighting is evaluated (fill mode only).
    pub shading: Shading,
    /// The light.
    pub light: Light,
    /// A texture multiplied into the vertex colour at the fragment's uv (fill mode only).
    pub texture: Option<&'a Texture>,
    /// How the texture is sampled.
    pub sampling: Sampling,
    /// The background.
    pub clear: [u8; 4],
}

/// What a picture took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Triangles (or, in points mode, vertices; in wire mode, edges) sent.
    pub primitives: usize,
    /// Fragments the rasterizer returned (before the depth test), or pixels of points and lines.
    pub fragments: usize,
    /// Fragments written: those that passed the depth test, or, for an implementation with its
    /// own depth test, those of the primitive its resolve kept at their pixel.
    pub written: usize,
}

/// Clears `target` and draws `job` into it with `rasterizer`.
///
/// Triangles go through `rasterizer`; points and lines through refrast's own line rasterizer,
/// since the [`Rasterizer`] contract draws triangles only. Fragments outside the target or of
/// a primitive the draw does not have (a misbehaving implementation) are skipped.
pub fn render(
    rasterizer: &mut dyn Rasterizer,
    job: &Job<'_>,
    target: &mut Framebuffer,
) -> Result<Stats, DrawError> {
    target.clear(job.clear, job.state.depth.clear);
    if let Some(stats) = draw_lines(job, target) {
        return Ok(stats);
    }
    let draw = triangle_draw(&rasterizer.profile(), job, target)?;
    let (mesh, viewport) = (job.mesh, target.viewport());
    let mut fragments = rasterizer.rasterize(&draw)?;
    // API order, as `Resolved::from_fragments` replays them: stable, so each primitive keeps its own.
    fragments.sort_by_key(|f| f.primitive);
    let fragments: Vec<Fragment> = fragments
        .into_iter()
        .filter(|f| {
            f.x < viewport.width() && f.y < viewport.height() && (f.primitive as usize) < mesh.triangles.len()
        })
        .collect();
    let mut stats = Stats {
        primitives: mesh.triangles.len(),
        fragments: fragments.len(),
        written: 0,
    };
    if job.mode == Mode::Overdraw {
        let mut counts = vec![0u32; viewport.pixel_count()];
        for f in &fragments {
            counts[viewport.index(f.x, f.y)] += 1;
        }
        for (pixel, &count) in target.color_mut().iter_mut().zip(&counts) {
            if let Some(c) = overdraw_color(count) {
                *pixel = c;
                stats.written += 1;
            }
        }
        return Ok(stats);
    }
    let shader = Shader::new(job);
    if rasterizer.profile().features.depth_test {
        // Its own depth test, as certification judges it: a painter's order or a scanline
        // z-buffer shows what it gets wrong, where replaying its fragments would hide it.
        // It costs a second pass: `resolve` gives no barycentrics to shade with.
        let resolved = rasterizer.resolve(&draw)?;
        let pixels = viewport.pixel_count();
        if resolved.viewport != viewport
            || resolved.depth.len() != pixels
            || resolved.primitive.len() != pixels
        {
            return Err(DrawError::Misbehaved(format!(
                "resolve gave {} depths and {} primitives for a {}×{} target",
                resolved.depth.len(),
                resolved.primitive.len(),
                viewport.width(),
                viewport.height()
            )));
        }
        stats.written = own_depth_test(&resolved, &fragments, &shader, target);
    } else {
        for f in &fragments {
            let i = viewport.index(f.x, f.y);
            if job
                .state
                .depth
                .test_and_write(f.depth, &mut target.depth_mut()[i])
            {
                target.color_mut()[i] = to_rgba8(shader.color(f.primitive, f.barycentric));
                stats.written += 1;
            }
        }
    }
    if job.mode == Mode::Depth {
        let greys = depth_greys(target.depth(), job.state.depth.clear);
        for (pixel, grey) in target.color_mut().iter_mut().zip(greys) {
            if let Some(g) = grey {
                *pixel = [g, g, g, 255];
            }
        }
    }
    Ok(stats)
}

/// Colours each pixel from the fragment of the primitive `resolved` (of the target's size) keeps
/// there and takes its depth buffer; returns how many fragments it coloured. A kept primitive without a fragment
/// at that pixel (a misbehaving implementation) leaves the pixel's colour as cleared.
fn own_depth_test(
    resolved: &Resolved,
    fragments: &[Fragment],
    shader: &Shader<'_>,
    target: &mut Framebuffer,
) -> usize {
    let viewport = target.viewport();
    for (stored, &depth) in target.depth_mut().iter_mut().zip(&resolved.depth) {
        *stored = depth;
    }
    let mut written = 0;
    for f in fragments {
        let i = viewport.index(f.x, f.y);
        if resolved.primitive.get(i) == Some(&Some(f.primitive)) {
            target.color_mut()[i] = to_rgba8(shader.color(f.primitive, f.barycentric));
            written += 1;
        }
    }
    written
}

/// The draw of `job`'s mesh on `target`, as every triangle mode sends it; `Err` for state
/// `profile` does not declare ([`undeclared_state`]) or a mesh the contract refuses.
pub(crate) fn triangle_draw(
    profile: &Profile,
    job: &Job<'_>,
    target: &Framebuffer,
) -> Result<Draw, DrawError> {
    undeclared_state(profile, job)?;
    let pipeline = Renderer {
        reference: Reference::default(),
        state: job.state,
    };
    let mut draw = pipeline.mesh_draw(target.viewport(), job.mesh, job.view_projection);
    // A picture uses no flat values: the provoking vertex is the rasterizer's own (OpenGL ES
    // drivers declare only the last).
    draw.state.provoking_vertex = profile.fit(draw.state).provoking_vertex;
    draw.validate()?;
    Ok(draw)
}

/// `Err(Unsupported)` when `job` asks for state `profile` does not declare ([`Profile::state`]:
/// a scissor, a sample mask, centroid interpolation, conservative rasterization, depth bias, a polygon mode, culling of both faces): such a draw is refused with what to do, never drawn as if
/// it had not been asked.
pub(crate) fn undeclared_state(profile: &Profile, job: &Job<'_>) -> Result<(), DrawError> {
    if job.state.scissor.is_some() && !profile.state.scissor {
        return Err(DrawError::Unsupported(
            "a scissor, which this rasterizer does not declare (the reference does)".to_owned(),
        ));
    }
    if job.state.sample_mask != refrast::DrawState::ALL_SAMPLES && !profile.state.sample_mask {
        return Err(DrawError::Unsupported(
            "a sample mask, which this rasterizer does not declare (the reference does)".to_owned(),
        ));
    }
    if job.state.interpolation != refrast::Interpolation::Sample && !profile.state.centroid {
        return Err(DrawError::Unsupported(
            "centroid interpolation, which this rasterizer does not declare (the reference does)".to_owned(),
        ));
    }
    match (job.state.conservative, profile.state.conservative) {
        (Some(_), None) => {
            return Err(DrawError::Unsupported(
                "conservative rasterization, which this rasterizer does not declare (the reference does)"
                    .to_owned(),
            ));
        }
        (Some(mode), Some(support)) if support.fit(mode) != Some(mode) => {
            return Err(DrawError::Unsupported(format!(
                "conservative {}, beyond what this rasterizer declares (extra sizes up to {} px{})",
                mode.words(),
                support.max_extra,
                if support.underestimate {
                    ", underestimation"
                } else {
                    ", no underestimation"
                }
            )));
        }
        _ => {}
    }
    if let Some(bias) = job.state.depth_bias {
        match profile.state.depth_bias {
            None => {
                return Err(DrawError::Unsupported(
                    "depth bias, which this rasterizer does not declare (the reference does)".to_owned(),
                ));
            }
            Some(support) if bias.clamp != 0.0 && !support.clamp => {
                return Err(DrawError::Unsupported(
                    "a depth bias clamp, which this rasterizer does not declare (the reference does)"
                        .to_owned(),
                ));
            }
            Some(_) => {}
        }
    }
    let mode = job.state.polygon_mode;
    if mode != refrast::PolygonMode::Fill && !profile.state.polygon_modes.contains(mode) {
        return Err(DrawError::Unsupported(format!(
            "polygon mode {}, which this rasterizer does not declare (the reference does)",
            mode.name()
        )));
    }
    if job.state.cull == refrast::CullMode::FrontAndBack && !profile.state.cull_both {
        return Err(DrawError::Unsupported(
            "culling of both faces, which this rasterizer does not declare (the reference does)".to_owned(),
        ));
    }
    Ok(())
}

/// Points and wire modes through refrast's line rasterizer: what they took, or `None` for a
/// mode of triangles.
pub(crate) fn draw_lines(job: &Job<'_>, target: &mut Framebuffer) -> Option<Stats> {
    let mesh = job.mesh;
    // The reference's pipeline: its line rasterizer.
    let pipeline = Renderer {
        reference: Reference::default(),
        state: job.state,
    };
    let (primitives, written) = match job.mode {
        Mode::Points => (
            mesh.vertices.len(),
            pipeline.draw_points(target, &mesh.vertices, job.view_projection),
        ),
        Mode::Wire => {
            let segments = edges(mesh);
            let written = pipeline.draw_lines(target, &mesh.vertices, &segments, job.view_projection);
            (segments.len(), written)
        }
        _ => return None,
    };
    Some(Stats {
        primitives,
        fragments: written,
        written,
    })
}

/// The colour of a fragment under a job's mode and shading, with what is computed once per
/// vertex or per triangle computed up front.
pub(crate) struct Shader<'a> {
    job: &'a Job<'a>,
    /// Per vertex (Gouraud) or per triangle (flat): the light as `(diffuse, specular)`.
    lit: Vec<(Vec3, Vec3)>,
    /// Per triangle (flat): the mean vertex colour.
    flat_albedo: Vec<Vec4>,
}

impl<'a> Shader<'a> {
    pub(crate) fn new(job: &'a Job<'a>) -> Self {
        let (mesh, light, eye) = (job.mesh, &job.light, job.eye);
        let (mut lit, mut flat_albedo) = (Vec::new(), Vec::new());
        if job.mode == Mode::Fill {
            match job.shading {
                Shading::Gouraud => {
                    lit = mesh
                        .vertices
                        .iter()
                        .map(|v| light.at(v.position, v.normal, eye))
                        .collect();
                }
                Shading::Flat => {
                    for &t in &mesh.triangles {
                        let [a, b, c] = t.map(|i| &mesh.vertices[i as usize]);
                        let centroid = (a.position + b.position + c.position) / 3.0;
                        lit.push(light.at(centroid, face_normal(mesh, t), eye));
                        flat_albedo.push((a.color + b.color + c.color) / 3.0);
                    }
                }
                Shading::None | Shading::Phong => {}
            }
        }
        Self {
            job,
            lit,
            flat_albedo,
        }
    }

    /// The linear colour of `f`.
    pub(crate) fn color(&self, primitive: u32, [wa, wb, wc]: [f32; 3]) -> Vec4 {
        let mesh = self.job.mesh;
        let t = mesh.triangles[primitive as usize];
        let [a, b, c] = t.map(|i| &mesh.vertices[i as usize]);
        let mix3 = |pa: Vec3, pb: Vec3, pc: Vec3| pa * wa + pb * wb + pc * wc;
        match self.job.mode {
            Mode::Barycentric => return Vec4::new(wa, wb, wc, 1.0),
            Mode::Normals => return normal_color(mix3(a.normal, b.normal, c.normal)),
            Mode::Depth => return Vec4::ONE,
            _ => {}
        }
        let mut albedo = if self.job.shading == Shading::Flat {
            self.flat_albedo[primitive as usize]
        } else {
            a.color * wa + b.color * wb + c.color * wc
        };
        if let Some(texture) = self.job.texture {
            let uv = a.uv * wa + b.uv * wb + c.uv * wc;
            albedo *= texture.sample(uv, self.job.sampling);
        }
        let (diffuse, specular) = match self.job.shading {
            Shading::None => return albedo,
            Shading::Flat => self.lit[primitive as usize],
            Shading::Gouraud => {
                let [la, lb, lc] = t.map(|i| self.lit[i as usize]);
                (mix3(la.0, lb.0, lc.0), mix3(la.1, lb.1, lc.1))
            }
            Shading::Phong => {
                // `mix3` in SIMD lanes: the same products and sums, lane by lane.
                let mix3a = |pa: Vec3, pb: Vec3, pc: Vec3| {
                    Vec3A::from(pa) * wa + Vec3A::from(pb) * wb + Vec3A::from(pc) * wc
                };
                let position = mix3a(a.position, b.position, c.position);
                let normal = mix3a(a.normal, b.normal, c.normal);
                let (diffuse, specular) = self.job.light.at_simd(position, normal, self.job.eye.into());
                (diffuse.into(), specular.into())
            }
        };
        (albedo.truncate() * diffuse + specular).extend(albedo.w)
    }
}
