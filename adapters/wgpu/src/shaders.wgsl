// refrast's wgpu adapter: the draw's clip-space positions go straight to the rasterizer; the
// fragment shaders only report what the driver computed.

struct Varyings {
    @builtin(position) position: vec4<f32>,
    // The vertex's barycentric unit vector, interpolated perspective-correctly (the default).
    @location(0) perspective: vec3<f32>,
    // The same, interpolated linearly in screen space.
    @location(1) @interpolate(linear) screen: vec3<f32>,
    @location(2) @interpolate(flat) primitive: u32,
}

@vertex
fn vertex(@location(0) position: vec4<f32>, @builtin(vertex_index) index: u32) -> Varyings {
    let corner = index % 3u;
    let unit = vec3<f32>(f32(corner == 0u), f32(corner == 1u), f32(corner == 2u));
    var out: Varyings;
    out.position = position;
    out.perspective = unit;
    out.screen = unit;
    out.primitive = index / 3u;
    return out;
}

// What the resolve pass writes for the fragment that passes the driver's depth test.
struct Resolved {
    // The primitive id, plus one (0 is "none").
    @location(0) id: u32,
    // The bits of its window depth, for backends that cannot copy a depth texture (OpenGL ES).
    @location(1) depth: u32,
}

@fragment
fn resolve(in: Varyings) -> Resolved {
    return Resolved(in.primitive + 1u, bitcast<u32>(in.position.z));
}
