// What the vertex stage hands the fragment stage, interpolated once a pixel at its centroid
// (several samples per pixel, centroid interpolation): prepended to `shaders.wgsl` by
// `Pipelines::get` for the centroid capture.
struct Varyings {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(perspective, centroid) perspective: vec3<f32>,
    @location(1) @interpolate(linear, centroid) screen: vec3<f32>,
    @location(2) @interpolate(flat) primitive: u32,
    @location(3) @interpolate(flat) vertex: u32,
}
