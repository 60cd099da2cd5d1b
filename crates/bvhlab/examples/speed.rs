//! Single-threaded speed of the AABB tree on a shared mesh (issue 7's workload): binned SAH
//! build time and SAH cost, ray first hit on coherent and incoherent rays, closest point.
//! Medians of several runs; the scene and rays are fixed (seeded).
//!
//! Run: `cargo run -p bvhlab --release --example speed -- [MESH.obj] [runs]` (default: the
//! shared ogre.obj beside the repository, 5 runs). `BVHLAB_SPEED_ONLY=build|coherent|incoherent|closest`
//! runs one part only (for instruction counts: `none` only loads the mesh and builds the tree).
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

use bvhlab::prelude::*;

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
        let tree = AabbTree3::build(tris);
        let stats = tree.stats();
        println!(
            "build: {ms:.1} ms, SAH cost {:.2}, {} nodes",
            stats.sah_cost.unwrap_or(f32::NAN),
            stats.nodes
        );
    }
    let tree = AabbTree3::build(tris);
    let bounds = mesh.bounds();
    let (coherent, incoherent) = (camera_rays(&bounds), random_rays(&bounds, 300_000));
    for (name, rays) in [("coherent", &coherent), ("incoherent", &incoherent)] {
        if !want(name) {
            continue;
        }
        let mut hits = 0;
        let secs = median(runs, || {
            let t = Instant::now();
            hits = rays
                .iter()
                .filter(|ray| tree.ray_first_hit(ray, f32::INFINITY).is_some())
                .count();
            t.elapsed().as_secs_f64()
        });
        println!(
            "{name}: {:.2} Mrays/s ({} rays, {hits} hits)",
            rays.len() as f64 / secs / 1e6,
            rays.len()
        );
    }
    if want("closest") {
        let points = random_points(&bounds, 100_000);
        let secs = median(runs, || {
            let t = Instant::now();
            let sum: f32 = points
                .iter()
                .filter_map(|&p| tree.closest_point(p))
                .map(|n| n.distance)
                .sum();
            black_box(sum);
            t.elapsed().as_secs_f64()
        });
        println!(
            "closest point: {:.1} k queries/s",
            points.len() as f64 / secs / 1e3
        );
    }
}

/// The median of `runs` measurements, or with `BVHLAB_SPEED_BEST` set the least (on a busy
/// machine the least is the run that was disturbed least).
fn median(runs: usize, mut measure: impl FnMut() -> f64) -> f64 {
    let mut samples: Vec<f64> = (0..runs.max(1)).map(|_| measure()).collect();
    samples.sort_by(f64::total_cmp);
    if std::env::var_os("BVHLAB_SPEED_BEST").is_some() {
        samples[0]
    } else {
        samples[samples.len() / 2]
    }
}
