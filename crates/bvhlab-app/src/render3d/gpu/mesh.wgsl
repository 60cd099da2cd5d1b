// The mesh, flat-shaded with a headlight, and the highlighted triangles drawn over it.
//
// The mesh's vertex buffer holds positions only: each fragment takes its face's normal from
// the screen-space derivatives of its world position (the triangle's plane), so no normals
// are stored and every face is flat. Colours arrive sRGB-encoded (as egui's are); lighting is
// done on linear values and the result is encoded again for the Rgba8Unorm target.

struct View {
    view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    // width, height, 1 / width, 1 / height, in pixels
    viewport: vec4<f32>,
    mesh_color: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;

// Light that reaches faces seen edge-on; faces seen head-on get all of it (so the colour
// asked for is the colour seen there).
const AMBIENT: f32 = 0.25;
// Back faces (seen from inside a cut or open mesh) are drawn in a warmer, darker shade.
const BACK_TINT: vec3<f32> = vec3<f32>(1.0, 0.5, 0.45);

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) color: vec4<f32>,
}

@vertex
fn vs_mesh(@location(0) position: vec3<f32>) -> Varyings {
    var out: Varyings;
    out.clip = view.view_proj * vec4<f32>(position, 1.0);
    out.world = position;
    out.color = view.mesh_color;
    return out;
}

// One instance per highlighted triangle (a `ColorTriangle`), three vertices each.
@vertex
fn vs_highlight(
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
    out.world = position;
    out.color = color;
    return out;
}

fn linear_from_gamma(srgb: vec3<f32>) -> vec3<f32> {
    let c = clamp(srgb, vec3<f32>(0.0), vec3<f32>(1.0));
    let lower = c / 12.92;
    let higher = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(higher, lower, c <= vec3<f32>(0.04045));
}

fn gamma_from_linear(rgb: vec3<f32>) -> vec3<f32> {
    let c = clamp(rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    let lower = c * 12.92;
    let higher = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(higher, lower, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_lit(in: Varyings, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    // The face's normal (unnormalised; either sign) from the plane the derivatives span.
    let normal = cross(dpdx(in.world), dpdy(in.world));
    let to_eye = normalize(view.eye.xyz - in.world);
    let length_n = length(normal);
    var facing = 1.0;
    if length_n > 0.0 {
        facing = abs(dot(normal, to_eye)) / length_n;
    }
    var base = linear_from_gamma(in.color.rgb);
    if !front {
        base = base * BACK_TINT;
    }
    let lit = base * (AMBIENT + (1.0 - AMBIENT) * facing);
    return vec4<f32>(gamma_from_linear(lit), in.color.a);
}
