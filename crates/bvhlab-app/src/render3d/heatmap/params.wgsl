// The heat map's per-dispatch parameters (`gpu.rs`: `Params`, the same 128 bytes).
struct Params {
    // The eye, and the eye moved by the query's slack up (+) and down (−) on every axis: the
    // core's `PreparedRay::origin_near` / `origin_far` for each sign of the direction.
    origin: vec4<f32>,
    origin_plus: vec4<f32>,
    origin_minus: vec4<f32>,
    // `RayFrame`: direction = corner + step_x · (x + ½) + step_y · (y + ½).
    corner: vec4<f32>,
    step_x: vec4<f32>,
    step_y: vec4<f32>,
    size: vec2<u32>,
    // 0: nodes visited, 1: primitive tests.
    metric: u32,
    // The colour scale's top, or 0 for the image's largest count.
    fixed_max: u32,
    // +∞ (WGSL has no infinite constant), the core's GROW = 1 + SLACK, and a zero the
    // compiler cannot see (`rounded`).
    inf: f32,
    grow: f32,
    zero: u32,
    node_count: u32,
}

struct Trace {
    nodes: u32,
    prims: u32,
    // The hit's input index, or 0xffffffff for none.
    hit: u32,
    // The hit's t (f32 bits).
    t: u32,
}
