//! The traversal-cost heat map: the CPU map is the core's per-ray cost, and the compute
//! shader gives the same counts, hits and colours pixel for pixel (on lavapipe here; set
//! `BVHLAB_REQUIRE_GPU=1` to fail instead of skipping when no adapter exists).

use std::future::Future;
use std::path::PathBuf;
use std::pin::pin;
use std::task::{Context, Poll, Waker};

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::QueryCost;
use bvhlab::structure::bvh::{NodeVolume, PreparedRay};
use bvhlab::{Mesh, Triangle3};
use bvhlab_app::view3d::camera::{OrbitCamera, RayFrame};
use bvhlab_app::view3d::heatmap::colormap::{self, RAMP};
use bvhlab_app::view3d::heatmap::gpu::{colorize_shader_source, trace_shader_source};
use bvhlab_app::view3d::heatmap::{CpuHeatMap, GpuHeatMap, Metric, gpu_heatmap_supported};
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
                let image = colormap::colour_image(
                    &counts,
                    frame.width as usize,
                    frame.height as usize,
                    top,
                );
                let gpu_image = map.read_image(&gpu.device, &gpu.queue).expect("image");
                let cpu_image: Vec<[u8; 4]> = image.pixels.iter().map(|c| c.to_array()).collect();
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
