// One covered sample as the capture passes append it, and where: appended to `shaders.wgsl`
// before `capture.wgsl` or `multisample.wgsl`.

// One covered sample, as the capture pass appends it.
struct Sample {
    x: u32,
    y: u32,
    primitive: u32,
    front_facing: u32,
    depth: f32,
    perspective: array<f32, 3>,
    screen: array<f32, 3>,
    // Which of the pixel's samples (0 at one sample per pixel).
    sample: u32,
    // The provoking vertex's position in the vertex stream.
    vertex: u32,
}

@group(0) @binding(0) var<storage, read_write> count: atomic<u32>;
@group(0) @binding(1) var<storage, read_write> samples: array<Sample>;

// Appends one covered sample, `sample` of its pixel.
fn append(in: Varyings, front_facing: bool, sample: u32) {
    let i = atomicAdd(&count, 1u);
    if i < arrayLength(&samples) {
        samples[i] = Sample(
            // The sample position's bits: a conversion to u32 would clamp a fragment left of or
            // above the target to column or row 0, inside it.
            bitcast<u32>(in.position.x),
            bitcast<u32>(in.position.y),
            in.primitive,
            select(0u, 1u, front_facing),
            in.position.z,
            array<f32, 3>(in.perspective.x, in.perspective.y, in.perspective.z),
            array<f32, 3>(in.screen.x, in.screen.y, in.screen.z),
            sample,
            in.vertex,
        );
    }
}
