// What the vertex stage hands the fragment stage, interpolated at the pixel's centre (one
// sample per pixel): prepended to `shaders.wgsl` by `Pipelines::new`.
struct Varyings {
    @builtin(position) position: vec4<f32>,
    // The vertex's barycentric unit vector, interpolated perspective-correctly (the default).
    @location(0) perspective: vec3<f32>,
    // The same, interpolated linearly in screen space.
    @location(1) @interpolate(linear) screen: vec3<f32>,
    @location(2) @interpolate(flat) primitive: u32,
    // The provoking vertex's position in the vertex stream: whose flat values the fragment has.
    @location(3) @interpolate(flat) vertex: u32,
}
