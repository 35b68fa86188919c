// Capturing into a storage buffer at one sample per pixel: appended to `shaders.wgsl` and
// `record.wgsl` by `Pipelines::new`.

// Every covered sample of every primitive, overlapped ones included: no depth test runs.
@fragment
fn capture(in: Varyings, @builtin(front_facing) front_facing: bool) {
    append(in, front_facing, 0u);
}
