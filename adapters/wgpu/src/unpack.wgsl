// Reading a multisampled resolve back: a texture copy cannot read a multisampled texture, so
// one triangle over the whole target loads each pixel's samples (up to 4) into the channels of
// two integer targets, which copy back as usual.

@group(0) @binding(0) var ids: texture_multisampled_2d<u32>;
@group(0) @binding(1) var depths: texture_depth_multisampled_2d;

// The samples' primitive ids (plus one, 0 for none) and their depths' bits, by sample index.
struct Unpacked {
    @location(0) ids: vec4<u32>,
    @location(1) depths: vec4<u32>,
}

// A triangle covering the whole target.
@vertex
fn cover(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let x = f32((index << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(index & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn unpack(@builtin(position) position: vec4<f32>) -> Unpacked {
    let pixel = vec2<i32>(position.xy);
    let count = i32(textureNumSamples(ids));
    var out = Unpacked(vec4<u32>(0u), vec4<u32>(0u));
    for (var k = 0; k < min(count, 4); k++) {
        out.ids[k] = textureLoad(ids, pixel, k).x;
        out.depths[k] = bitcast<u32>(textureLoad(depths, pixel, k));
    }
    return out;
}
