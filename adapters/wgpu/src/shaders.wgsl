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

// One covered sample, as the capture pass appends it.
struct Sample {
    x: u32,
    y: u32,
    primitive: u32,
    front_facing: u32,
    depth: f32,
    perspective: array<f32, 3>,
    screen: array<f32, 3>,
    pad: u32,
}

@group(0) @binding(0) var<storage, read_write> count: atomic<u32>;
@group(0) @binding(1) var<storage, read_write> samples: array<Sample>;

// Every covered sample of every triangle, overlapped ones included: no depth test runs.
@fragment
fn capture(in: Varyings, @builtin(front_facing) front_facing: bool) {
    let i = atomicAdd(&count, 1u);
    if i < arrayLength(&samples) {
        samples[i] = Sample(
            u32(in.position.x),
            u32(in.position.y),
            in.primitive,
            select(0u, 1u, front_facing),
            in.position.z,
            array<f32, 3>(in.perspective.x, in.perspective.y, in.perspective.z),
            array<f32, 3>(in.screen.x, in.screen.y, in.screen.z),
            0u,
        );
    }
}

// The primitive id, plus one (0 is "none"), of the fragment that passes the driver's depth test.
@fragment
fn resolve(in: Varyings) -> @location(0) u32 {
    return in.primitive + 1u;
}
