// Colours the traced counts with the colour scale (`ramp`, generated from colormap.rs so that
// the CPU and the GPU share one table and one integer formula).

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> traces: array<Trace>;
@group(0) @binding(2) var<storage, read> maxima: array<u32, 2>;
@group(0) @binding(3) var image: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(8, 8)
fn colorize(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.size.x || gid.y >= params.size.y {
        return;
    }
    let trace = traces[gid.y * params.size.x + gid.x];
    let count = select(trace.nodes, trace.prims, params.metric == 1u);
    var top = maxima[min(params.metric, 1u)];
    if params.fixed_max != 0u {
        top = params.fixed_max;
    }
    // k / 255 converts back to the byte k exactly (unorm8 rounds to nearest).
    let rgb = vec3<f32>(ramp(count, top)) / 255.0;
    textureStore(image, vec2<i32>(gid.xy), vec4<f32>(rgb, 1.0));
}
