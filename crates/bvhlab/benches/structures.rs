//! Every structure on one mesh, for the crate documentation's "which structure for which job"
//! table: the build, ray first hit on random rays and closest point on random points (in the
//! box of the Stanford bunny, 69k triangles; seeded), each structure built with its
//! defaults. Skipped, with a message, when the shared meshes are absent.
//!
//! Run: `cargo bench -p bvhlab --bench structures`.

#[path = "workload/mod.rs"]
mod workload;

use std::hint::black_box;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::Bvh4;
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use workload::{random_points, random_rays, shared_mesh};

/// The build, first hits and closest points of one structure.
fn bench<S: SpatialIndex<Prim = Triangle3>>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    tris: &[Triangle3],
    rays: &[Ray3],
    points: &[Vec3],
) {
    group.throughput(Throughput::Elements(tris.len() as u64));
    group.bench_function(format!("build {name}"), |b| {
        b.iter(|| S::build(black_box(tris)).stats().nodes);
    });
    let s = S::build(tris);
    group.throughput(Throughput::Elements(rays.len() as u64));
    group.bench_function(format!("first hit {name}"), |b| {
        b.iter(|| {
            rays.iter()
                .filter(|ray| s.ray_first_hit(black_box(ray), f32::INFINITY).is_some())
                .count()
        });
    });
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function(format!("closest point {name}"), |b| {
        b.iter(|| {
            points
                .iter()
                .filter_map(|&p| s.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
}

fn structures(c: &mut Criterion) {
    let Some(mesh) = shared_mesh("stanford-bunny.obj") else {
        return;
    };
    let tris = mesh.triangles();
    let bounds = mesh.bounds();
    let rays = random_rays(&bounds, 20_000);
    let points = random_points(&bounds, 5_000);
    let mut group = c.benchmark_group("bunny");
    group.sample_size(10);
    group.throughput(Throughput::Elements(tris.len() as u64));
    group.bench_function("build 4-wide", |b| {
        b.iter(|| Bvh4::build(black_box(tris)).len());
    });
    let wide = Bvh4::build(tris);
    group.throughput(Throughput::Elements(rays.len() as u64));
    group.bench_function("first hit 4-wide", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|ray| wide.ray_first_hit(black_box(ray), f32::INFINITY).is_some())
                .count()
        });
    });
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("closest point 4-wide", |b| {
        b.iter(|| {
            points
                .iter()
                .filter_map(|&p| wide.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    bench::<AabbTree3>(&mut group, "AABB tree", tris, &rays, &points);
    bench::<KdTree3>(&mut group, "k-d tree", tris, &rays, &points);
    bench::<Grid3>(&mut group, "grid", tris, &rays, &points);
    bench::<Octree3>(&mut group, "octree", tris, &rays, &points);
    bench::<Bsp3>(&mut group, "BSP tree", tris, &rays, &points);
    group.finish();
}

criterion_group!(benches, structures);
criterion_main!(benches);
