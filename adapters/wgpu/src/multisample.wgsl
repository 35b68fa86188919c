// Capturing every covered sample at several samples per pixel: appended to
// `varyings_sample.wgsl`, `shaders.wgsl` and `record.wgsl` by `Pipelines::multisample`. The
// `sample` inputs run this once per covered sample, at the sample's position. The depth it
// records is `@builtin(position).z` (FragCoord.z), which Vulkan and OpenGL tie to no sample:
// a driver may give the pixel centre's, so msaa.depth.per-sample requires only the resolve's
// depth buffer of them, and msaa.resolve.per-sample replays at each sample's own depth.

// Every covered sample of every primitive, overlapped ones included: no depth test runs.
@fragment
fn capture_samples(
    in: Varyings,
    @builtin(front_facing) front_facing: bool,
    @builtin(sample_index) sample: u32,
) {
    append(in, front_facing, sample);
}
