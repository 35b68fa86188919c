// Capturing one triangle per pass into two float targets, for drivers whose fragment shaders
// cannot write storage buffers: appended to `shaders.wgsl` by `Pipelines::new`.

struct Targets {
    // Perspective-correct barycentrics, then window depth.
    @location(0) perspective: vec4<f32>,
    // Screen-space barycentrics, then 1 for a front face and 2 for a back face (0: uncovered),
    // plus 4 times the provoking vertex's position in the vertex stream (exact in f32 below
    // 2^22 vertices; its parity tells a strip's two triangles apart).
    @location(1) screen: vec4<f32>,
}

// Every covered sample of the one triangle drawn: no depth test runs, and a triangle covers a
// sample at most once.
@fragment
fn capture_targets(in: Varyings, @builtin(front_facing) front_facing: bool) -> Targets {
    return Targets(
        vec4<f32>(in.perspective, in.position.z),
        vec4<f32>(in.screen, select(2.0, 1.0, front_facing) + 4.0 * f32(in.vertex)),
    );
}
