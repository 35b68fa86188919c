// refrast's wgpu adapter: the draw's clip-space positions go straight to the rasterizer; the
// fragment shaders only report what the driver computed. `varyings.wgsl` or
// `varyings_sample.wgsl` comes first.

// The vertices a primitive has (3, 2 or 1), and whether the list is a strip: vertex `i` of a
// list is corner `i % corners` of primitive `i / corners`; of a strip, it starts segment or
// triangle `i` (flat values come from a primitive's first vertex, or its last on OpenGL ES) as
// corner `i % corners`, so the three vertices of any strip triangle have distinct corners.
override corners: u32 = 3u;
override strip: bool = false;

@vertex
fn vertex(@location(0) position: vec4<f32>, @builtin(vertex_index) index: u32) -> Varyings {
    let corner = index % corners;
    let unit = vec3<f32>(f32(corner == 0u), f32(corner == 1u), f32(corner == 2u));
    var out: Varyings;
    out.position = position;
    out.perspective = unit;
    out.screen = unit;
    out.primitive = select(index / corners, index, strip);
    out.vertex = index;
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
