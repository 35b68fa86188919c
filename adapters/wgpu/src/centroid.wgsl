// Capturing a centroid-interpolated draw at several samples per pixel: appended to
// `varyings_centroid.wgsl`, `shaders.wgsl` and `record.wgsl` by `Pipelines::get`. The shader
// runs once a pixel (no `sample` input, no `sample_index`), its inputs at the driver's
// centroid; `sample_mask` holds the pixel's covered samples the mask keeps (WebGPU: every
// covered sample at pixel rate), and each becomes a fragment carrying the pixel's one set of
// barycentrics. The depth is `@builtin(position).z` at the pixel, as the per-sample capture's
// may be.

// Every covered sample of every primitive, overlapped ones included: no depth test runs.
@fragment
fn capture_centroid(
    in: Varyings,
    @builtin(front_facing) front_facing: bool,
    @builtin(sample_mask) covered: u32,
) {
    for (var sample = 0u; sample < 32u; sample++) {
        if ((covered >> sample) & 1u) == 1u {
            append(in, front_facing, sample);
        }
    }
}
