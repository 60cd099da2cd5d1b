// Copies the 3D view's finished image into egui's render pass, pixel for pixel.
//
// egui sets the viewport to the part of the view's rectangle that is on screen; `blit` says
// which part of the image that is (in 0..1 texture coordinates), so a view pushed partly off
// the window is cut, not squeezed. Texels are fetched, not filtered: the image has exactly
// the viewport's pixels.

struct Blit {
    uv_min: vec2<f32>,
    uv_max: vec2<f32>,
}

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var<uniform> blit: Blit;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

// One triangle covering the viewport: corners (-1, -1), (3, -1), (-1, 3).
@vertex
fn vs_blit(@builtin(vertex_index) vertex: u32) -> Varyings {
    let x = f32(vertex & 1u) * 4.0 - 1.0;
    let y = f32(vertex >> 1u) * 4.0 - 1.0;
    var out: Varyings;
    out.clip = vec4<f32>(x, y, 0.0, 1.0);
    let screen_uv = vec2<f32>(x + 1.0, 1.0 - y) * 0.5;
    out.uv = mix(blit.uv_min, blit.uv_max, screen_uv);
    return out;
}

fn fetch(uv: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(image));
    let texel = clamp(vec2<i32>(floor(uv * vec2<f32>(size))), vec2<i32>(0), size - 1);
    return textureLoad(image, texel, 0);
}

// For targets that store sRGB-encoded values as they are (Rgba8Unorm, Bgra8Unorm).
@fragment
fn fs_gamma(in: Varyings) -> @location(0) vec4<f32> {
    return fetch(in.uv);
}

// For *Srgb targets, which encode on write: hand them linear values.
@fragment
fn fs_linear(in: Varyings) -> @location(0) vec4<f32> {
    let color = fetch(in.uv);
    let c = color.rgb;
    let lower = c / 12.92;
    let higher = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(higher, lower, c <= vec3<f32>(0.04045)), color.a);
}
