//! Single-threaded speed of the AABB tree on a shared mesh (issue 7's workload): binned SAH
//! build time and SAH cost, ray first hit on coherent and incoherent rays, closest point;
//! then the same queries on its 4-wide copy (`Bvh4`), and the collapse's own time.
//! Medians of several runs; the scene and rays are fixed (seeded).
//!
//! Run: `cargo run -p bvhlab --release --example speed -- [MESH.obj] [runs]` (default: the
//! shared ogre.obj beside the repository, 5 runs). `BVHLAB_SPEED_ONLY=build|coherent|incoherent|closest`
//! runs one part only (for instruction counts: `none` only loads the mesh and builds the tree),
//! and `BVHLAB_SPEED_TREE=binary|wide` queries one tree only.
#![expect(
    clippy::print_stdout,
    reason = "an example that prints its measurements"
)]
#![expect(
    clippy::expect_used,
    reason = "an example: a missing mesh ends it with a message"
)]

use std::hint::black_box;
use std::time::Instant;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::Bvh4;

#[path = "../benches/workload/mod.rs"]
mod workload;

use workload::{camera_rays, random_points, random_rays};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "../shared/data/meshes/ogre.obj".into());
    let runs: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(5);
    let only = std::env::var("BVHLAB_SPEED_ONLY").unwrap_or_default();
    let want = |part: &str| only.is_empty() || only == part;
    let tree_only = std::env::var("BVHLAB_SPEED_TREE").unwrap_or_default();
    let (binary_queries, wide_queries) = (tree_only != "wide", tree_only != "binary");

    let bytes = std::fs::read(&path).expect("the mesh file is readable");
    let mesh = Mesh::from_obj(&bytes).expect("the mesh loads");
    let tris = mesh.triangles();
    println!("{path}: {} triangles", tris.len());

    if want("build") {
        let ms = median(runs, || {
            let t = Instant::now();
            black_box(AabbTree3::build(black_box(tris)));
            t.elapsed().as_secs_f64() * 1e3
        });
        let wide_ms = median(runs, || {
            let t = Instant::now();
            black_box(Bvh4::build(black_box(tris)));
            t.elapsed().as_secs_f64() * 1e3
        });
        let tree = AabbTree3::build(tris);
        let stats = tree.stats();
        println!(
            "build: {ms:.1} ms, SAH cost {:.2}, {} nodes; Bvh4::build {wide_ms:.1} ms",
            stats.sah_cost.unwrap_or(f32::NAN),
            stats.nodes
        );
    }
    let tree = AabbTree3::build(tris);
    let collapse_ms = median(runs, || {
        let t = Instant::now();
        black_box(Bvh4::from_bvh(black_box(&tree)));
        t.elapsed().as_secs_f64() * 1e3
    });
    let wide = Bvh4::from_bvh(&tree);
    if want("build") {
        println!(
            "collapse to 4-wide: {collapse_ms:.1} ms, {} wide nodes ({} bytes, {:.2} lanes used \
             per node, {} levels), {:.1} bytes per triangle in all",
            wide.nodes().len(),
            wide.node_bytes(),
            wide.mean_fill(),
            wide.depth(),
            wide.memory_bytes() as f64 / tris.len() as f64
        );
    }
    let bounds = mesh.bounds();
    let (coherent, incoherent) = (camera_rays(&bounds), random_rays(&bounds, 300_000));
    let tree_runs = |queried: bool| if queried { runs } else { 0 };
    for (name, rays) in [("coherent", &coherent), ("incoherent", &incoherent)] {
        if !want(name) {
            continue;
        }
        let (secs, hits) = ray_speed(tree_runs(binary_queries), rays, |ray| {
            tree.ray_first_hit(ray, f32::INFINITY).is_some()
        });
        println!(
            "{name}: {:.2} Mrays/s ({} rays, {hits} hits)",
            rays.len() as f64 / secs / 1e6,
            rays.len()
        );
        let (secs, wide_hits) = ray_speed(tree_runs(wide_queries), rays, |ray| {
            wide.ray_first_hit(ray, f32::INFINITY).is_some()
        });
        if binary_queries && wide_queries {
            assert_eq!(hits, wide_hits, "the wide tree answers as the binary one");
        }
        println!(
            "{name}, 4-wide: {:.2} Mrays/s",
            rays.len() as f64 / secs / 1e6
        );
    }
    if want("closest") {
        let points = random_points(&bounds, 100_000);
        let secs = closest_speed(tree_runs(binary_queries), &points, |p| {
            tree.closest_point(p).map(|n| n.distance)
        });
        println!(
            "closest point: {:.1} k queries/s",
            points.len() as f64 / secs / 1e3
        );
        let secs = closest_speed(tree_runs(wide_queries), &points, |p| {
            wide.closest_point(p).map(|n| n.distance)
        });
        println!(
            "closest point, 4-wide: {:.1} k queries/s",
            points.len() as f64 / secs / 1e3
        );
    }
}

/// Seconds for the first hits of `rays` (the median or least of `runs`), and how many hit.
fn ray_speed(runs: usize, rays: &[Ray3], first_hit: impl Fn(&Ray3) -> bool) -> (f64, usize) {
    let mut hits = 0;
    let secs = median(runs, || {
        let t = Instant::now();
        hits = rays.iter().filter(|ray| first_hit(ray)).count();
        t.elapsed().as_secs_f64()
    });
    (secs, hits)
}

/// Seconds for the closest points to `points` (the median or least of `runs`).
fn closest_speed(runs: usize, points: &[Vec3], distance: impl Fn(Vec3) -> Option<f32>) -> f64 {
    median(runs, || {
        let t = Instant::now();
        let sum: f32 = points.iter().filter_map(|&p| distance(p)).sum();
        black_box(sum);
        t.elapsed().as_secs_f64()
    })
}

/// The median of `runs` measurements, or with `BVHLAB_SPEED_BEST` set the least (on a busy
/// machine the least is the run that was disturbed least); NaN for no run (a tree left out).
fn median(runs: usize, mut measure: impl FnMut() -> f64) -> f64 {
    if runs == 0 {
        return f64::NAN;
    }
    let mut samples: Vec<f64> = (0..runs).map(|_| measure()).collect();
    samples.sort_by(f64::total_cmp);
    if std::env::var_os("BVHLAB_SPEED_BEST").is_some() {
        samples[0]
    } else {
        samples[samples.len() / 2]
    }
}
