// The vertex stage of a draw with clip distances: `shaders.wgsl`'s, each vertex's eight clip
// distances (those the draw lacks at 1, inside) written to `clip_distances`, which only a vertex
// stage may write. A module of its own, paired with the fragment stage of any pass, so its
// outputs are `Varyings`' locations, interpolated alike: `Pipelines::get` puts for PERSPECTIVE
// and LINEAR what `varyings.wgsl` or `varyings_sample.wgsl` has (WGSL's default for an input
// without an attribute is `perspective, center`).
enable clip_distances;

struct ClipVaryings {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(PERSPECTIVE) perspective: vec3<f32>,
    @location(1) @interpolate(LINEAR) screen: vec3<f32>,
    @location(2) @interpolate(flat) primitive: u32,
    @location(3) @interpolate(flat) vertex: u32,
    @builtin(clip_distances) clip: array<f32, 8>,
}

override corners: u32 = 3u;
override strip: bool = false;

@vertex
fn vertex(
    @location(0) position: vec4<f32>,
    @location(1) low: vec4<f32>,
    @location(2) high: vec4<f32>,
    @builtin(vertex_index) index: u32,
) -> ClipVaryings {
    let corner = index % corners;
    let unit = vec3<f32>(f32(corner == 0u), f32(corner == 1u), f32(corner == 2u));
    var out: ClipVaryings;
    out.position = position;
    out.perspective = unit;
    out.screen = unit;
    out.primitive = select(index / corners, index, strip);
    out.vertex = index;
    out.clip = array<f32, 8>(low.x, low.y, low.z, low.w, high.x, high.y, high.z, high.w);
    return out;
}
