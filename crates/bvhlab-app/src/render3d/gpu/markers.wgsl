// Screen-facing discs with a darker rim, on top of everything: one instance per `Marker`,
// six vertices (a square one pixel larger than the disc) each. The edge is antialiased by
// coverage, so markers look round without multisampling.

struct View {
    view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    // width, height, 1 / width, 1 / height, in pixels
    viewport: vec4<f32>,
    mesh_color: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;

// The rim's width in pixels, and how dark it is relative to the fill.
const RIM_PX: f32 = 1.5;
const RIM_SHADE: f32 = 0.3;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    // This fragment's offset from the centre, in pixels.
    @location(0) offset_px: vec2<f32>,
    @location(1) radius_px: f32,
    @location(2) color: vec4<f32>,
}

@vertex
fn vs_marker(
    @builtin(vertex_index) vertex: u32,
    @location(0) pos: vec3<f32>,
    @location(1) radius_px: f32,
    @location(2) color: vec4<f32>,
) -> Varyings {
    var out: Varyings;
    out.radius_px = radius_px;
    out.color = color;
    let centre = view.view_proj * vec4<f32>(pos, 1.0);
    if centre.z < 0.0 {
        // In front of the near plane (or behind the eye): not shown.
        out.clip = vec4<f32>(0.0, 0.0, -2.0, 1.0);
        out.offset_px = vec2<f32>(0.0);
        return out;
    }
    var xs = array<f32, 6>(-1.0, 1.0, 1.0, -1.0, 1.0, -1.0);
    var ys = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let reach = radius_px + 1.0;
    let offset = vec2<f32>(xs[vertex % 6u], ys[vertex % 6u]) * reach;
    let ndc = centre.xy / centre.w + offset * 2.0 * view.viewport.zw;
    // Depth 0: markers are drawn without a depth test, and must not be cut by the far plane.
    out.clip = vec4<f32>(ndc, 0.0, 1.0);
    out.offset_px = offset;
    return out;
}

@fragment
fn fs_marker(in: Varyings) -> @location(0) vec4<f32> {
    let distance = length(in.offset_px);
    let coverage = clamp(in.radius_px + 0.5 - distance, 0.0, 1.0);
    if coverage <= 0.0 {
        discard;
    }
    let rim = clamp(distance - (in.radius_px - RIM_PX) + 0.5, 0.0, 1.0);
    let rgb = mix(in.color.rgb, in.color.rgb * RIM_SHADE, rim);
    return vec4<f32>(rgb, in.color.a * coverage);
}
