//! The traversal-cost heat map: the CPU map is the core's per-ray cost, and the compute
//! shader gives the same counts, hits and colours pixel for pixel (on lavapipe here; set
//! `BVHLAB_REQUIRE_GPU=1` to fail instead of skipping when no adapter exists).
#![expect(
    clippy::print_stdout,
    reason = "skips, agreements and measurements are reported to the person running the tests"
)]

use std::future::Future;
use std::path::PathBuf;
use std::pin::pin;
use std::task::{Context, Poll, Waker};

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::QueryCost;
use bvhlab::structure::bvh::{NodeVolume, PreparedRay};
use bvhlab::{Mesh, Ray3, Triangle3};
use bvhlab_app::model::orbit_camera::{OrbitCamera, RayFrame};
use bvhlab_app::render3d::heatmap::colormap::{self, RAMP};
use bvhlab_app::render3d::heatmap::gpu::{colorize_shader_source, trace_shader_source};
use bvhlab_app::render3d::heatmap::{CpuHeatMap, GpuHeatMap, Metric, gpu_heatmap_supported};
use eframe::wgpu;
use wgpu::util::DeviceExt;

// ---------- a headless device, private to this file ----------

fn block_on<F: Future>(future: F) -> F::Output {
    let mut future = pin!(future);
    let mut cx = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(value) = future.as_mut().poll(&mut cx) {
            return value;
        }
        std::thread::yield_now();
    }
}

struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
}

/// The machine's adapter (lavapipe here), or `None` (with a message) when there is none and
/// `BVHLAB_REQUIRE_GPU` is not 1.
fn gpu(test: &str) -> Option<Gpu> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let found = block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .ok()
        .and_then(|adapter| {
            assert!(
                gpu_heatmap_supported(&adapter.get_downlevel_capabilities(), &adapter.limits()),
                "a native adapter runs compute shaders"
            );
            block_on(adapter.request_device(&wgpu::DeviceDescriptor::default())).ok()
        });
    match found {
        Some((device, queue)) => Some(Gpu { device, queue }),
        None if std::env::var("BVHLAB_REQUIRE_GPU").as_deref() == Ok("1") => {
            panic!("{test}: no GPU adapter, and BVHLAB_REQUIRE_GPU=1")
        }
        None => {
            println!("{test}: skipped, no GPU adapter (install mesa-vulkan-drivers for lavapipe)");
            None
        }
    }
}

// ---------- scenes and cameras ----------

/// A procedural scene with the hard cases: a flat grid on y = 0 with dyadic vertices (rays
/// through its vertices and edges, rays in its plane), an axis-aligned cube, a bumpy sphere,
/// degenerate triangles and a sliver.
fn procedural_mesh() -> Vec<Triangle3> {
    let mut tris = Vec::new();
    let step = 0.5;
    for i in 0..8 {
        for j in 0..8 {
            let (x, z) = (-2.0 + step * i as f32, -2.0 + step * j as f32);
            let p = |dx: f32, dz: f32| Vec3::new(x + dx, 0.0, z + dz);
            tris.push(Triangle3::new(p(0.0, 0.0), p(step, 0.0), p(step, step)));
            tris.push(Triangle3::new(p(0.0, 0.0), p(step, step), p(0.0, step)));
        }
    }
    let corners: Vec<Vec3> = (0..8)
        .map(|k| {
            Vec3::new(
                if k & 1 == 0 { -0.5 } else { 0.5 },
                if k & 2 == 0 { 0.5 } else { 1.5 },
                if k & 4 == 0 { -0.5 } else { 0.5 },
            )
        })
        .collect();
    for [a, b, c, d] in [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ] {
        tris.push(Triangle3::new(corners[a], corners[b], corners[c]));
        tris.push(Triangle3::new(corners[a], corners[c], corners[d]));
    }
    let centre = Vec3::new(1.0, 1.0, -1.0);
    let (rings, segments) = (16, 24);
    let point = |r: usize, s: usize| {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        let phi = std::f32::consts::TAU * s as f32 / segments as f32;
        let bump = 0.7 + 0.08 * (3.0 * phi).sin() * (2.0 * theta).sin();
        centre
            + bump
                * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                )
    };
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (point(r, s), point(r + 1, s));
            let (c, d) = (point(r + 1, s + 1), point(r, s + 1));
            tris.push(Triangle3::new(a, b, c));
            tris.push(Triangle3::new(a, c, d));
        }
    }
    tris.push(Triangle3::new(
        Vec3::new(0.0, 0.7, 0.0),
        Vec3::new(1.0, 0.7, 0.0),
        Vec3::new(2.0, 0.7, 0.0),
    ));
    tris.push(Triangle3::new(
        Vec3::splat(0.3),
        Vec3::splat(0.3),
        Vec3::new(0.3, 2.0, 0.3),
    ));
    tris.push(Triangle3::new(
        Vec3::new(-1.5, 0.25, 1.0),
        Vec3::new(1.5, 0.25, 1.0),
        Vec3::new(0.0, 0.25 + 1e-6, 1.0 + 1e-6),
    ));
    tris
}

fn shared_mesh(name: &str) -> Option<Vec<Triangle3>> {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let path = [
        "../../../shared/data/meshes",
        "../../../../shared/data/meshes",
    ]
    .iter()
    .map(|dir| manifest.join(dir).join(name))
    .find(|p| p.exists());
    let Some(path) = path else {
        println!("{name}: skipped, the shared meshes folder is absent");
        return None;
    };
    let bytes = std::fs::read(&path).expect("readable mesh");
    Some(
        Mesh::from_obj(&bytes)
            .expect("valid OBJ")
            .triangles()
            .to_vec(),
    )
}

/// A frame looking along `forward` (a unit axis) from `origin`, whose pixel directions are
/// dyadic: the middle column and row have direction components of exactly 0 (the slab test's
/// infinite inverse), and the pixel where they cross is the axis itself.
fn axis_frame(origin: Vec3, forward: Vec3, right: Vec3, up: Vec3, size: u32) -> RayFrame {
    let step = 2.0 / size as f32;
    // corner + step · (x + ½) is 0 at x = size/2 − 1: corner = −step · (size/2 − ½).
    let half = step * (size as f32 / 2.0 - 0.5);
    RayFrame {
        origin,
        corner: forward - right * half + up * half,
        step_x: right * step,
        step_y: -up * step,
        width: size,
        height: size,
    }
}

/// Cameras on a scene with bounds `b`: framing it, inside it, grazing it horizontally and
/// nearly vertically, and axis-aligned frames from outside and from the centre.
fn frames(b: &Aabb3, size: u32) -> Vec<(&'static str, RayFrame)> {
    let centre = (b.min + b.max) * 0.5;
    let extent = (b.max - b.min).max_element();
    let framing = OrbitCamera::framing(b);
    let inside = OrbitCamera {
        target: centre,
        distance: extent * 0.15,
        yaw: 2.0,
        pitch: -0.3,
        ..framing
    };
    let level = OrbitCamera {
        target: Vec3::new(centre.x, b.min.y + (b.max.y - b.min.y) * 0.25, centre.z),
        pitch: 0.0,
        yaw: 0.0,
        ..framing
    };
    let steep = OrbitCamera {
        pitch: 1.5,
        ..framing
    };
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    vec![
        ("framing", framing.ray_frame(size, size * 3 / 4)),
        ("inside", inside.ray_frame(size, size)),
        ("level", level.ray_frame(size, size / 2)),
        ("steep", steep.ray_frame(size, size)),
        (
            "down the y axis",
            axis_frame(centre + y * extent, -y, x, -z, size),
        ),
        (
            "along x from outside",
            axis_frame(centre - x * extent, x, -z, y, size),
        ),
        ("along z from the centre", axis_frame(centre, z, x, y, size)),
    ]
}

// ---------- the comparison ----------

/// Per pixel, what the core says: the cost and the hit of the pixel's first-hit query.
fn cpu_traces(tree: &AabbTree3, frame: &RayFrame) -> Vec<(QueryCost, Option<(u32, f32)>)> {
    (0..frame.height)
        .flat_map(|y| (0..frame.width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = frame.ray(x, y).expect("finite camera");
            let traced = tree.ray_first_hit_observed(&ray, f32::INFINITY, &mut ());
            (traced.cost, traced.answer.map(|h| (h.prim as u32, h.t)))
        })
        .collect()
}

/// Dispatches the frame for `metric` and waits.
fn run(gpu: &Gpu, map: &mut GpuHeatMap, frame: &RayFrame, metric: Metric, top: Option<u32>) {
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    map.dispatch(&gpu.device, &gpu.queue, &mut encoder, frame, metric, top)
        .expect("dispatch");
    gpu.queue.submit([encoder.finish()]);
}

/// GPU against CPU on every camera: counts of both metrics, hits, and the coloured images.
fn compare(gpu: &Gpu, name: &str, tris: &[Triangle3], size: u32) {
    let tree = AabbTree3::build(tris);
    let mut map = GpuHeatMap::new(&gpu.device);
    map.upload(&gpu.device, &tree).expect("upload");
    let mut zero_dirs = 0;
    for (view, frame) in frames(&bounds(tris), size) {
        let want = cpu_traces(&tree, &frame);
        run(gpu, &mut map, &frame, Metric::Nodes, None);
        let got = map.read_traces(&gpu.device, &gpu.queue).expect("read-back");
        assert_eq!(got.len(), want.len());
        let mut wrong = Vec::new();
        for (i, (g, (cost, hit))) in got.iter().zip(&want).enumerate() {
            let g_hit = (g[2] != u32::MAX).then(|| (g[2], f32::from_bits(g[3])));
            if u64::from(g[0]) != cost.nodes_visited
                || u64::from(g[1]) != cost.prim_tests
                || g_hit != *hit
            {
                wrong.push((i, *g, *cost, *hit));
            }
        }
        assert!(
            wrong.is_empty(),
            "{name}, {view}: {} of {} pixels differ, e.g. {:?}",
            wrong.len(),
            got.len(),
            &wrong[..wrong.len().min(4)]
        );
        zero_dirs += (0..frame.height)
            .flat_map(|y| (0..frame.width).map(move |x| (x, y)))
            .filter(|&(x, y)| frame.direction(x, y).to_array().contains(&0.0))
            .count();
        for metric in [Metric::Nodes, Metric::PrimitiveTests] {
            let counts: Vec<u32> = want.iter().map(|(c, _)| metric.count(c)).collect();
            for top in [None, Some(7)] {
                run(gpu, &mut map, &frame, metric, top);
                assert_eq!(
                    map.read_counts(&gpu.device, &gpu.queue).expect("counts"),
                    counts
                );
                // The largest count comes back asynchronously for the legend.
                map.after_submit();
                gpu.device
                    .poll(wgpu::PollType::wait_indefinitely())
                    .expect("poll");
                let largest = counts.iter().copied().max();
                assert_eq!(map.largest_count(), largest, "{name}, {view}, {metric:?}");
                let image = colormap::colour_image(
                    &counts,
                    frame.width as usize,
                    frame.height as usize,
                    top,
                );
                let gpu_image = map.read_image(&gpu.device, &gpu.queue).expect("image");
                let cpu_image: Vec<[u8; 4]> =
                    image.pixels.iter().map(egui::Color32::to_array).collect();
                assert!(
                    gpu_image == cpu_image,
                    "{name}, {view}, {metric:?}, {top:?}: colours differ"
                );
            }
        }
    }
    assert!(
        zero_dirs > 0,
        "the axis-aligned frames have zero direction components"
    );
    println!(
        "{name}: {} triangles, GPU = CPU on every camera",
        tris.len()
    );
}

fn bounds(tris: &[Triangle3]) -> Aabb3 {
    let corners: Vec<Vec3> = tris.iter().flat_map(|t| [t.a, t.b, t.c]).collect();
    Aabb3::from_points(&corners)
}

#[test]
fn gpu_equals_cpu_on_the_procedural_scene() {
    let Some(gpu) = gpu("gpu_equals_cpu_on_the_procedural_scene") else {
        return;
    };
    compare(&gpu, "procedural", &procedural_mesh(), 64);
}

#[test]
fn gpu_equals_cpu_on_the_shared_meshes() {
    let Some(gpu) = gpu("gpu_equals_cpu_on_the_shared_meshes") else {
        return;
    };
    for name in [
        "suzanne.obj",
        "spot.obj",
        "fandisk.obj",
        "stanford-bunny.obj",
    ] {
        if let Some(tris) = shared_mesh(name) {
            compare(&gpu, name, &tris, 64);
        }
    }
}

// ---------- the exact arithmetic, operation by operation ----------

/// `Params` with only what the helper functions read: +∞, GROW and the hidden zero.
fn test_params() -> [u32; 32] {
    let mut words = [0u32; 32];
    words[28] = f32::INFINITY.to_bits();
    words[29] = bvhlab::structure::bvh::volume::GROW.to_bits();
    words
}

/// A test kernel appended to the tracing shader, run on `input`, returning `out_words` u32
/// per input element.
fn run_kernel(
    gpu: &Gpu,
    kernel: &str,
    entry: &str,
    input: &[[f32; 4]],
    out_words: usize,
) -> Vec<u32> {
    let source = format!("{}\n{kernel}", trace_shader_source());
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(entry),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
    let init = |contents: &[u8], usage| {
        gpu.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents,
                usage,
            })
    };
    let params = init(
        bytemuck::cast_slice(&test_params()),
        wgpu::BufferUsages::UNIFORM,
    );
    let input_buffer = init(bytemuck::cast_slice(input), wgpu::BufferUsages::STORAGE);
    let size = (input.len() * out_words * 4) as u64;
    let output = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: params.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 10,
                resource: input_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 11,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(input.len().div_ceil(64) as u32, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, size);
    gpu.queue.submit([encoder.finish()]);
    staging.map_async(wgpu::MapMode::Read, .., |_| {});
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    bytemuck::cast_slice(&staging.get_mapped_range(..).expect("mapped")).to_vec()
}

/// A small deterministic generator (xorshift64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// In [0, 1).
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    /// A random sign and significand at a random exponent in `[-spread, spread)`.
    fn scaled(&mut self, spread: i32) -> f32 {
        let e = (self.next() % (2 * spread as u64)) as i32 - spread;
        let s = if self.next() & 1 == 0 { 1.0 } else { -1.0 };
        s * (1.0 + self.unit()) * 2f32.powi(e)
    }
}

const EXACT_KERNEL: &str = r"
@group(0) @binding(10) var<storage, read> cases: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> results: array<vec4<u32>>;

// IEEE binary64 bits (high word, low word); zero as +0.
fn f64_bits(x: F64) -> vec2<u32> {
    if f64_is_zero(x) {
        return vec2<u32>(0u, 0u);
    }
    let hi = select(0u, 0x80000000u, x.neg) | (u32(x.e + 1023) << 20u) | ((x.m.x >> 11u) & 0xfffffu);
    return vec2<u32>(hi, (x.m.y >> 11u) | (x.m.x << 21u));
}

@compute @workgroup_size(64)
fn exact_ops(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&cases) {
        return;
    }
    _ = params.zero;
    let v = cases[i];
    let a = f64_from_f32(v.x);
    let b = f64_from_f32(v.y);
    let c = f64_from_f32(v.z);
    let d = f64_from_f32(v.w);
    let e = f64_sub(f64_mul(a, b), f64_mul(c, d));
    let s = f64_add(f64_mul(e, c), f64_mul(a, d));
    var q = f64_zero();
    if !f64_is_zero(e) {
        q = f64_div(s, e);
    }
    let t = f64_to_f32(q);
    let ab = f64_to_f32(f64_mul(a, b));
    let r = f32_div(v.x, v.y);
    results[3u * i] = vec4<u32>(f64_bits(e), f64_bits(s));
    results[3u * i + 1u] = vec4<u32>(f64_bits(q), t.bits, select(0u, 1u, t.finite));
    results[3u * i + 2u] = vec4<u32>(r.bits, select(0u, 1u, r.finite), ab.bits, select(0u, 1u, ab.finite));
}
";

/// Bits of an f64 with zero as +0 (the soft-float keeps no sign on zero).
fn bits64(x: f64) -> [u32; 2] {
    let b = if x == 0.0 { 0 } else { x.to_bits() };
    [(b >> 32) as u32, b as u32]
}

fn bits32(x: f32) -> u32 {
    if x == 0.0 { 0 } else { x.to_bits() }
}

/// Operands: random scales, near-cancelling products (a·b ≈ c·d), exact ties, and scales
/// whose products round to f32 subnormals, zero or infinity.
fn exact_cases(rng: &mut Rng) -> Vec<[f32; 4]> {
    let mut cases = Vec::new();
    for k in 0..20_000 {
        let (a, b) = (rng.scaled(20), rng.scaled(20));
        let case = match k % 5 {
            0 => [a, b, rng.scaled(20), rng.scaled(20)],
            1 => {
                let f = 1.0 + (rng.next() % 8) as f32 * f32::EPSILON;
                [a, b, a * f, b / f]
            }
            2 => [a, b, b, a],
            3 => [
                a * 2f32.powi(-55),
                b * 2f32.powi(-55),
                rng.scaled(4),
                rng.scaled(4),
            ],
            _ => [
                a * 2f32.powi(50),
                b * 2f32.powi(50),
                rng.scaled(30),
                rng.scaled(30),
            ],
        };
        cases.push(case);
    }
    cases
}

#[test]
fn the_shader_arithmetic_rounds_as_ieee_f64_and_f32_do() {
    let Some(gpu) = gpu("the_shader_arithmetic_rounds_as_ieee_f64_and_f32_do") else {
        return;
    };
    let cases = exact_cases(&mut Rng(0x9e37_79b9_7f4a_7c15));
    let out = run_kernel(&gpu, EXACT_KERNEL, "exact_ops", &cases, 12);
    let mut wrong = Vec::new();
    for (case, got) in cases.iter().zip(out.chunks(12)) {
        let [a, b, c, d] = case.map(f64::from);
        let e = a * b - c * d;
        let s = e * c + a * d;
        let q = if e == 0.0 { 0.0 } else { s / e };
        let t = q as f32;
        let r = case[0] / case[1];
        let ab = (a * b) as f32;
        let want = [
            bits64(e)[0],
            bits64(e)[1],
            bits64(s)[0],
            bits64(s)[1],
            bits64(q)[0],
            bits64(q)[1],
            bits32(t),
            u32::from(t.is_finite()),
            bits32(r),
            u32::from(r.is_finite()),
            bits32(ab),
            u32::from(ab.is_finite()),
        ];
        if got != want {
            wrong.push(format!("{case:?}: shader {got:x?}, IEEE {want:x?}"));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} of {} cases differ: {:?}",
        wrong.len(),
        cases.len(),
        &wrong[..wrong.len().min(3)]
    );
    let subnormal = cases
        .iter()
        .filter(|c| {
            let x = (f64::from(c[0]) * f64::from(c[1])) as f32;
            x != 0.0 && !x.is_normal()
        })
        .count();
    let overflow = cases
        .iter()
        .filter(|c| ((f64::from(c[0]) * f64::from(c[1])) as f32).is_infinite())
        .count();
    assert!(
        subnormal > 100 && overflow > 100,
        "{subnormal} subnormal, {overflow} overflowing"
    );
}

const RAY_KERNEL: &str = r"
@group(0) @binding(10) var<storage, read> cases: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> results: array<vec4<u32>>;

@compute @workgroup_size(64)
fn ray_cases(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= arrayLength(&cases) / 9u {
        return;
    }
    let k = 9u * i;
    let r = prepare_ray(cases[k].xyz, cases[k + 2u].xyz, cases[k + 3u].xyz, cases[k + 1u].xyz);
    let flags = select(0u, 1u, cases[k + 4u].w != 0.0);
    let tri = Tri(cases[k + 4u].xyz, 0u, cases[k + 5u].xyz, flags, cases[k + 6u].xyz, 0u);
    let h = ray_triangle(r, tri);
    let t = box_entry(r, cases[k + 7u].xyz, cases[k + 8u].xyz);
    results[i] = vec4<u32>(select(0u, 1u, h.hit), bitcast<u32>(h.t), bitcast<u32>(t), 0u);
}
";

/// A ray, a triangle and a box to test it against.
struct RayCase {
    origin: Vec3,
    dir: Vec3,
    tri: Triangle3,
    bounds: Aabb3,
}

/// Random rays aimed at random triangles; rays through the vertices and edges of a dyadic
/// grid (exactly zero edge functions); directions with zero components, of either sign;
/// boxes whose planes hold the ray's slack-moved origin (the slab test's 0 · ∞); rays in the
/// triangle's plane; degenerate triangles.
fn ray_cases(rng: &mut Rng) -> Vec<RayCase> {
    let mut cases = Vec::new();
    let v = |rng: &mut Rng, r: f32| {
        Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0 * r - Vec3::splat(r)
    };
    for k in 0..6000 {
        let tri = Triangle3::new(v(rng, 1.0), v(rng, 1.0), v(rng, 1.0));
        let origin = v(rng, 3.0);
        let (w1, w2) = (rng.unit(), rng.unit());
        let aim = tri.a + (tri.b - tri.a) * w1 + (tri.c - tri.a) * (w2 * (1.0 - w1));
        let mut case = RayCase {
            origin,
            dir: aim - origin,
            tri,
            bounds: tri.bounds(),
        };
        match k % 6 {
            1 => {
                // A dyadic grid cell, hit through a vertex, an edge midpoint or its inside.
                let q = |rng: &mut Rng| (rng.next() % 9) as f32 * 0.25 - 1.0;
                let a = Vec3::new(q(rng), q(rng), 0.0);
                let tri = Triangle3::new(a, a + Vec3::X * 0.5, a + Vec3::Y * 0.5);
                let targets = [
                    tri.a,
                    tri.b,
                    (tri.a + tri.b) * 0.5,
                    (tri.b + tri.c) * 0.5,
                    tri.a + Vec3::new(0.125, 0.125, 0.0),
                ];
                let aim = targets[(rng.next() % 5) as usize];
                let origin = Vec3::new(q(rng), q(rng), 1.0 + (rng.next() % 4) as f32);
                case = RayCase {
                    origin,
                    dir: aim - origin,
                    tri,
                    bounds: tri.bounds(),
                };
            }
            2 => {
                // Zero components, of either sign.
                for i in 0..3 {
                    if rng.next().is_multiple_of(2) {
                        case.dir[i] = if rng.next().is_multiple_of(2) {
                            0.0
                        } else {
                            -0.0
                        };
                    }
                }
                if case.dir == Vec3::ZERO {
                    case.dir.z = 1.0;
                }
            }
            3 => {
                // A box with a plane through the slack-moved origin on a flat axis.
                case.dir.x = if rng.next().is_multiple_of(2) {
                    0.0
                } else {
                    -0.0
                };
                let (up, down) = slack_origins(case.origin);
                case.bounds.min.x = if rng.next().is_multiple_of(2) {
                    up.x
                } else {
                    down.x
                };
                case.bounds.max.x = case.bounds.min.x.max(case.bounds.max.x);
                if rng.next().is_multiple_of(2) {
                    case.bounds.max.x = case.bounds.min.x;
                }
            }
            4 => {
                // In the plane of an axis-aligned triangle.
                case.tri = Triangle3::new(
                    Vec3::new(-1.0, -1.0, 0.5),
                    Vec3::new(1.0, -1.0, 0.5),
                    Vec3::new(0.0, 1.0, 0.5),
                );
                case.origin.z = 0.5;
                case.dir.z = 0.0;
                case.bounds = case.tri.bounds();
            }
            5 if k % 12 == 5 => {
                case.tri = Triangle3::new(tri.a, tri.b, tri.a + (tri.b - tri.a) * 2.0);
            }
            _ => {}
        }
        if case.dir != Vec3::ZERO {
            cases.push(case);
        }
    }
    cases
}

/// The origin moved up and down by the query's slack, from the core's own `PreparedRay`.
fn slack_origins(origin: Vec3) -> (Vec3, Vec3) {
    let up = PreparedRay::new(&Ray3::new(origin, Vec3::ONE).expect("ray"));
    let down = PreparedRay::new(&Ray3::new(origin, -Vec3::ONE).expect("ray"));
    (up.origin_near, down.origin_near)
}

#[test]
fn the_shader_triangle_and_slab_tests_are_the_cores() {
    let Some(gpu) = gpu("the_shader_triangle_and_slab_tests_are_the_cores") else {
        return;
    };
    let cases = ray_cases(&mut Rng(0x2545_f491_4f6c_dd1d));
    let input: Vec<[f32; 4]> = cases
        .iter()
        .flat_map(|c| {
            let (up, down) = slack_origins(c.origin);
            let flag = if c.tri.is_degenerate() { 1.0 } else { 0.0 };
            [
                c.origin.extend(0.0),
                c.dir.extend(0.0),
                up.extend(0.0),
                down.extend(0.0),
                c.tri.a.extend(flag),
                c.tri.b.extend(0.0),
                c.tri.c.extend(0.0),
                c.bounds.min.extend(0.0),
                c.bounds.max.extend(0.0),
            ]
            .map(|v| v.to_array())
        })
        .collect();
    let out = run_kernel(&gpu, RAY_KERNEL, "ray_cases", &input, 4);
    let (mut wrong, mut hits, mut box_hits, mut flat_hits) = (Vec::new(), 0, 0, 0);
    for (c, got) in cases.iter().zip(out.chunks(4)) {
        let ray = Ray3::new(c.origin, c.dir).expect("valid ray");
        let hit = c.tri.ray_hit(&ray);
        let entry = c.bounds.ray_entry(&PreparedRay::new(&ray));
        let got_hit = (got[0] == 1).then(|| f32::from_bits(got[1]));
        let want_entry = entry.map_or(-1.0f32, |(t, _)| t);
        if got_hit != hit || got[2] != want_entry.to_bits() {
            wrong.push(format!(
                "{:?} {:?} {:?} {:?}: shader {got:x?}, core {hit:?} {entry:?}",
                c.origin, c.dir, c.tri, c.bounds
            ));
        }
        hits += usize::from(hit.is_some());
        box_hits += usize::from(entry.is_some());
        flat_hits += usize::from(entry.is_some() && c.dir.to_array().contains(&0.0));
    }
    assert!(
        wrong.is_empty(),
        "{} of {} differ: {:#?}",
        wrong.len(),
        cases.len(),
        &wrong[..wrong.len().min(3)]
    );
    assert!(
        hits > cases.len() / 3 && box_hits > cases.len() / 2 && flat_hits > 200,
        "{hits} hits, {box_hits} box hits, {flat_hits} with zero components"
    );
}

// ---------- the CPU map, the colour scale, the shaders' validity ----------

/// What the CPU map asks of a structure.
type CostOf<'a> = dyn FnMut(&Ray3) -> QueryCost + 'a;

#[test]
fn the_cpu_map_is_the_cores_cost_of_every_pixel_for_any_structure() {
    let tris = procedural_mesh();
    let aabb = AabbTree3::build(&tris);
    let spheres = SphereTree3::build(&tris);
    let frame = OrbitCamera::framing(&bounds(&tris)).ray_frame(41, 29);
    for metric in [Metric::Nodes, Metric::PrimitiveTests] {
        let mut cost_of_aabb =
            |r: &Ray3| aabb.ray_first_hit_observed(r, f32::INFINITY, &mut ()).cost;
        let mut cost_of_spheres = |r: &Ray3| {
            spheres
                .ray_first_hit_observed(r, f32::INFINITY, &mut ())
                .cost
        };
        let structures: [(&str, &mut CostOf); 2] = [
            ("AABB tree", &mut cost_of_aabb),
            ("sphere tree", &mut cost_of_spheres),
        ];
        for (name, cost_of) in structures {
            let mut map = CpuHeatMap::new(frame, metric);
            let mut last = map.fraction();
            assert_eq!(last, 0.0);
            while !map.is_done() {
                map.step(cost_of, 37);
                assert!(map.fraction() > last, "progress on every step");
                last = map.fraction();
                // Pixels not done yet are transparent; done ones have the scale's colour.
                let image = map.image(None);
                let done = (last * (41.0 * 29.0)).round() as usize;
                assert!(
                    image.pixels[done..]
                        .iter()
                        .all(|c| *c == egui::Color32::TRANSPARENT)
                );
            }
            assert_eq!(last, 1.0);
            let mut want = Vec::new();
            for y in 0..frame.height {
                for x in 0..frame.width {
                    let dir = frame.corner
                        + frame.step_x * (x as f32 + 0.5)
                        + frame.step_y * (y as f32 + 0.5);
                    let ray = Ray3::new(frame.origin, dir).expect("ray");
                    let cost = cost_of(&ray);
                    want.push(match metric {
                        Metric::Nodes => cost.nodes_visited,
                        Metric::PrimitiveTests => cost.prim_tests,
                    } as u32);
                }
            }
            assert_eq!(map.counts(), want, "{name}, {metric:?}");
            let top = *want.iter().max().expect("pixels");
            assert!(top > 1, "{name}: the scene costs something");
            assert_eq!(map.max_count(), top);
            let image = map.image(None);
            for (pixel, &count) in image.pixels.iter().zip(&want) {
                let [r, g, b] = colormap::colour(count, top);
                assert_eq!(*pixel, egui::Color32::from_rgb(r, g, b));
            }
        }
    }
}

#[test]
fn the_colour_scale_passes_its_control_points_and_brightens_with_the_count() {
    let top = 9 * 40;
    for (k, point) in RAMP.iter().enumerate() {
        assert_eq!(
            colormap::colour(k as u32 * 40, top),
            *point,
            "control point {k}"
        );
    }
    assert_eq!(
        colormap::colour(top * 3, top),
        RAMP[9],
        "above the top: the top colour"
    );
    assert_eq!(
        colormap::colour(5, 0),
        RAMP[0],
        "an empty scale: the bottom colour"
    );
    let luma =
        |[r, g, b]: [u8; 3]| 0.2126 * f32::from(r) + 0.7152 * f32::from(g) + 0.0722 * f32::from(b);
    let mut last = -1.0;
    for count in 0..=1000 {
        let l = luma(colormap::colour(count, 1000));
        assert!(
            l >= last - 0.5,
            "lightness falls at {count}: {l} after {last}"
        );
        last = l;
    }
    assert!(luma(RAMP[9]) - luma(RAMP[0]) > 150.0);
}

fn validate_wgsl(name: &str, source: &str) {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {e:?}"));
}

#[test]
fn the_legend_draws_the_bar_and_its_numbers() {
    let ctx = egui::Context::default();
    let mut output = ctx.run_ui(egui::RawInput::default(), |ui| {
        colormap::legend(ui, 144, Metric::Nodes);
    });
    output.textures_delta.clear();
    let shapes = format!("{:?}", output.shapes);
    for text in ["nodes visited per ray", "\"0\"", "\"72\"", "\"144\""] {
        assert!(shapes.contains(text), "{text} missing from the legend");
    }
    let bottom = egui::Color32::from_rgb(RAMP[0][0], RAMP[0][1], RAMP[0][2]);
    let top = egui::Color32::from_rgb(RAMP[9][0], RAMP[9][1], RAMP[9][2]);
    let meshes: Vec<_> = output
        .shapes
        .iter()
        .filter_map(|c| match &c.shape {
            egui::Shape::Mesh(m) => Some(m.clone()),
            _ => None,
        })
        .collect();
    let colours: Vec<egui::Color32> = meshes
        .iter()
        .flat_map(|m| m.vertices.iter().map(|v| v.color))
        .collect();
    assert!(
        colours.contains(&bottom) && colours.contains(&top),
        "the bar runs the whole ramp"
    );
}

#[test]
fn both_shaders_are_valid_wgsl() {
    validate_wgsl("trace", &trace_shader_source());
    validate_wgsl("colorize", &colorize_shader_source());
}

#[test]
fn a_tree_too_large_for_the_device_is_refused_with_a_clear_error() {
    let Some(gpu) = gpu("a_tree_too_large_for_the_device_is_refused_with_a_clear_error") else {
        return;
    };
    let mut map = GpuHeatMap::new(&gpu.device);
    let frame = OrbitCamera::default().ray_frame(8, 8);
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let before = map.dispatch(
        &gpu.device,
        &gpu.queue,
        &mut encoder,
        &frame,
        Metric::Nodes,
        None,
    );
    assert_eq!(
        before,
        Err(bvhlab_app::render3d::heatmap::HeatMapError::NoTree)
    );
    // 48 bytes per triangle: just over the binding limit.
    let limit = gpu.device.limits().max_storage_buffer_binding_size;
    let count = (limit / 48 + 1) as usize;
    let tri = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let tree = AabbTree3::build(&vec![tri; count]);
    let error = map.upload(&gpu.device, &tree).expect_err("too big");
    assert!(error.to_string().contains("triangles"), "{error}");
}

// ---------- measurements and the picture (cargo test -- --ignored --nocapture) ----------

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn measure_the_bunny_and_write_its_picture() {
    let Some(tris) = shared_mesh("stanford-bunny.obj") else {
        return;
    };
    let tree = AabbTree3::build(&tris);
    let framing = OrbitCamera::framing(&bounds(&tris));
    let frame = framing.ray_frame(640, 480);
    // A close-up whose every ray meets the bunny's root box, most of them the bunny.
    let close = OrbitCamera {
        distance: framing.distance * 0.3,
        ..framing
    }
    .ray_frame(640, 480);
    for (view, f) in [("framing", &frame), ("close-up", &close)] {
        let mut hits = 0usize;
        let start = std::time::Instant::now();
        for y in 0..f.height {
            for x in 0..f.width {
                let ray = f.ray(x, y).expect("ray");
                hits += usize::from(tree.ray_first_hit(&ray, f32::INFINITY).is_some());
            }
        }
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "CPU, {view}: {:.0} rays/s (one thread), {:.0}% of the pixels hit the bunny",
            f64::from(f.width * f.height) / seconds,
            100.0 * hits as f64 / f64::from(f.width * f.height)
        );
    }
    for metric in [Metric::Nodes, Metric::PrimitiveTests] {
        let mut map = CpuHeatMap::new(frame, metric);
        let start = std::time::Instant::now();
        map.step(
            &mut |r| tree.ray_first_hit_observed(r, f32::INFINITY, &mut ()).cost,
            usize::MAX,
        );
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "CPU, {metric:?}: {} rays in {seconds:.3} s = {:.0} rays/s (one thread), largest count {}",
            map.counts().len(),
            map.counts().len() as f64 / seconds,
            map.max_count()
        );
        let name = match metric {
            Metric::Nodes => "heatmap-bunny.png",
            Metric::PrimitiveTests => "heatmap-bunny-prims.png",
        };
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../target")
            .join(name);
        std::fs::create_dir_all(path.parent().expect("folder")).expect("target folder");
        let png = bvhlab_app::export::png_bytes(&map.image(None)).expect("png");
        std::fs::write(&path, png).expect("written");
        println!("wrote {}", path.display());
    }
    let Some(gpu) = gpu("measure_the_bunny_and_write_its_picture") else {
        return;
    };
    let mut map = GpuHeatMap::new(&gpu.device);
    map.upload(&gpu.device, &tree).expect("upload");
    for (view, f) in [("framing", &frame), ("close-up", &close)] {
        for round in 0..3 {
            let start = std::time::Instant::now();
            run(&gpu, &mut map, f, Metric::Nodes, None);
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .expect("poll");
            println!(
                "GPU (lavapipe), {view}, dispatch {round}: {:.3} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
    map.after_submit();
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    println!("GPU largest count read back: {:?}", map.largest_count());
}
