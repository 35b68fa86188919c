// What the vertex stage hands the fragment stage, interpolated at each covered sample (several
// samples per pixel): a `sample` input runs the fragment shader once per sample, as the
// per-sample capture needs. Prepended to `shaders.wgsl` by `Pipelines::multisample`.
struct Varyings {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(perspective, sample) perspective: vec3<f32>,
    @location(1) @interpolate(linear, sample) screen: vec3<f32>,
    @location(2) @interpolate(flat) primitive: u32,
    @location(3) @interpolate(flat) vertex: u32,
}
