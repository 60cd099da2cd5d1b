// Thick world-space segments as screen-space quads: one instance per `Line3d`, six vertices
// (two triangles) each. The quad is the segment widened by `width_px` on screen and lengthened
// by half that at both ends (square caps, so a box's edges meet without notches). Depth comes
// from the segment itself, so depth-tested lines hide behind the mesh like geometry.

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

// A clip-space position outside the depth range: the whole quad collapses there and is
// clipped away.
const CULLED: vec4<f32> = vec4<f32>(0.0, 0.0, -2.0, 1.0);

@vertex
fn vs_line(
    @builtin(vertex_index) vertex: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) width_px: f32,
) -> Varyings {
    var out: Varyings;
    out.color = color;
    var pa = view.view_proj * vec4<f32>(a, 1.0);
    var pb = view.view_proj * vec4<f32>(b, 1.0);
    // Cut the segment at the near plane (clip z = 0 there) so the part in front of the eye
    // projects sensibly; a segment wholly behind it is dropped.
    if pa.z < 0.0 && pb.z < 0.0 {
        out.clip = CULLED;
        return out;
    }
    if pa.z < 0.0 {
        pa = mix(pa, pb, pa.z / (pa.z - pb.z));
    } else if pb.z < 0.0 {
        pb = mix(pb, pa, pb.z / (pb.z - pa.z));
    }
    let half_viewport = view.viewport.xy * 0.5;
    let sa = pa.xy / pa.w * half_viewport;
    let sb = pb.xy / pb.w * half_viewport;
    let span = sb - sa;
    let span_length = length(span);
    var along = vec2<f32>(1.0, 0.0);
    if span_length > 1e-6 {
        along = span / span_length;
    }
    let across = vec2<f32>(-along.y, along.x);
    // Corners of the two triangles: (which end, which side).
    var ends = array<f32, 6>(0.0, 1.0, 1.0, 0.0, 1.0, 0.0);
    var sides = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let end = ends[vertex % 6u];
    let side = sides[vertex % 6u];
    let half_width = width_px * 0.5;
    let offset_px = across * side * half_width + along * (end * 2.0 - 1.0) * half_width;
    let at = mix(pa, pb, end);
    out.clip = at + vec4<f32>(offset_px / half_viewport * at.w, 0.0, 0.0);
    return out;
}

@fragment
fn fs_line(in: Varyings) -> @location(0) vec4<f32> {
    return in.color;
}
