// Translucent world-space triangles (split planes, cells' faces) in one colour each, unlit:
// one instance per `ColorTriangle`, three vertices each.

struct View {
    view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    // width, height, 1 / width, 1 / height, in pixels
    viewport: vec4<f32>,
    mesh_color: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
}

@vertex
fn vs_triangle(
    @builtin(vertex_index) corner: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
    @location(2) c: vec3<f32>,
    @location(3) color: vec4<f32>,
) -> Varyings {
    var position = a;
    if corner == 1u {
        position = b;
    } else if corner == 2u {
        position = c;
    }
    var out: Varyings;
    out.clip = view.view_proj * vec4<f32>(position, 1.0);
    out.color = color;
    return out;
}

@fragment
fn fs_triangle(in: Varyings) -> @location(0) vec4<f32> {
    return in.color;
}
