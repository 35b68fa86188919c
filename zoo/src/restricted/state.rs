//! Restrictions of the draw state beyond [`Features`]: each leaves one part of
//! [`StateSupport`] out of the default reference's declaration, or restricts its values.

use refrast::{
    BiasSupport, Features, PolygonMode, ProvokingVertex, ReferenceConfig, Spec, StateSupport, Supported,
};

use super::{Restriction, restriction};

/// The default reference declaring only `state` of the state beyond [`Features`].
fn stateful(name: &str, description: &str, state: StateSupport) -> Restriction {
    restriction(
        name,
        description,
        ReferenceConfig::default(),
        |_: &mut Features| {},
        state,
        Spec::Refrast,
    )
}

/// Every restriction of [`StateSupport`]: each part left out, each provoking-vertex mode
/// alone, depth ranges in order only, and line mode without point mode.
pub(super) fn restrictions() -> Vec<Restriction> {
    let all = StateSupport::ALL;
    let flat = |flat| StateSupport { flat, ..all };
    vec![
        stateful(
            "scissor=none",
            "no scissor",
            StateSupport {
                scissor: false,
                ..all
            },
        ),
        stateful(
            "sample-mask=none",
            "no sample mask",
            StateSupport {
                sample_mask: false,
                ..all
            },
        ),
        stateful(
            "centroid=none",
            "no centroid interpolation",
            StateSupport {
                centroid: false,
                ..all
            },
        ),
        stateful(
            "conservative=none",
            "no conservative rasterization",
            StateSupport {
                conservative: None,
                ..all
            },
        ),
        stateful(
            "conservative=over-only",
            "conservative overestimation alone, with no extra size",
            StateSupport {
                conservative: Some(refrast::ConservativeSupport {
                    max_extra: 0.0,
                    underestimate: false,
                    ..refrast::ConservativeSupport::REFERENCE
                }),
                ..all
            },
        ),
        stateful(
            "conservative=coarse",
            "conservative overestimation growing every triangle by its declared 1/2 px more",
            StateSupport {
                conservative: Some(refrast::ConservativeSupport {
                    overestimation_size: 0.5,
                    ..refrast::ConservativeSupport::REFERENCE
                }),
                ..all
            },
        ),
        stateful(
            "cull=one-face",
            "culls one face or none, never both",
            StateSupport {
                cull_both: false,
                ..all
            },
        ),
        stateful(
            "topology=lists",
            "triangle lists only: no strips or fans",
            StateSupport {
                triangle_strips: false,
                triangle_fans: false,
                ..all
            },
        ),
        stateful(
            "fans=none",
            "strips but no fans, as D3D11 and WebGPU",
            StateSupport {
                triangle_fans: false,
                ..all
            },
        ),
        stateful("flat=none", "no flat values reported", flat(Supported::NONE)),
        stateful(
            "provoking=first",
            "flat values from the first vertex only, as D3D11",
            flat(Supported::only(&[ProvokingVertex::First])),
        ),
        stateful(
            "provoking=last",
            "flat values from the last vertex only, as OpenGL ES",
            flat(Supported::only(&[ProvokingVertex::Last])),
        ),
        stateful(
            "viewport-depth=none",
            "depth always in [0, 1]: no viewport depth range",
            StateSupport {
                viewport_depth: false,
                inverted_depth: false,
                ..all
            },
        ),
        stateful(
            "viewport-depth=ordered",
            "depth ranges with minDepth ≤ maxDepth only, as D3D11 and wgpu",
            StateSupport {
                inverted_depth: false,
                ..all
            },
        ),
        stateful(
            "depth-clip=on",
            "depth always clipped: no depth clamping",
            StateSupport {
                unclipped_depth: false,
                ..all
            },
        ),
        stateful(
            "depth-bias=none",
            "no depth bias",
            StateSupport {
                depth_bias: None,
                ..all
            },
        ),
        stateful(
            "bias-clamp=off",
            "depth bias without its clamp, as wgpu's OpenGL ES backend",
            StateSupport {
                depth_bias: all.depth_bias.map(|b| BiasSupport { clamp: false, ..b }),
                ..all
            },
        ),
        stateful(
            "polygon-mode=fill",
            "triangles filled only: no line or point mode",
            StateSupport {
                polygon_modes: Supported::NONE,
                ..all
            },
        ),
        stateful(
            "polygon-mode=line",
            "line mode but no point mode, as D3D11's wireframe",
            StateSupport {
                polygon_modes: Supported::only(&[PolygonMode::Line]),
                ..all
            },
        ),
        stateful(
            "clip-distances=none",
            "cull distances but no clip distances",
            StateSupport {
                clip_distances: 0,
                ..all
            },
        ),
        stateful(
            "cull-distances=none",
            "clip distances but no cull distances, as WebGPU's clip-distances feature",
            StateSupport {
                cull_distances: 0,
                ..all
            },
        ),
    ]
}
