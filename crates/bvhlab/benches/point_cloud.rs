//! A point cloud's nearest neighbours: 200k points uniform in the unit cube (seeded) and
//! 20k query points in the same cube, the k-d tree built with its defaults
//! ([`KdTree::build`]) beside the 4-wide AABB tree ([`Bvh4::build`]), the uniform grid and
//! the octree (their defaults too): their builds and their closest points. Throughput is
//! per point (per query).
//!
//! Run: `cargo bench -p bvhlab --bench point_cloud`.

use std::hint::black_box;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::kdtree::KdTree;
use bvhlab::{Grid, Orthtree};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn cube_points(n: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
        .collect()
}

/// The build and the closest points of one structure.
fn bench<S: SpatialIndex<Prim = Vec3>>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    points: &[Vec3],
    queries: &[Vec3],
) {
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function(format!("build {name}"), |b| {
        b.iter(|| S::build(black_box(points)).stats().nodes);
    });
    let index = S::build(points);
    group.throughput(Throughput::Elements(queries.len() as u64));
    group.bench_function(format!("closest point {name}"), |b| {
        b.iter(|| {
            queries
                .iter()
                .filter_map(|&p| index.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
}

fn point_cloud(c: &mut Criterion) {
    let points = cube_points(200_000, 5);
    let queries = cube_points(20_000, 6);
    let mut group = c.benchmark_group("point cloud 200k");
    group.sample_size(10);
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("build 4-wide", |b| {
        b.iter(|| Bvh4::build(black_box(&points)).len());
    });
    let wide = Bvh4::build(&points);
    group.throughput(Throughput::Elements(queries.len() as u64));
    group.bench_function("closest point 4-wide", |b| {
        b.iter(|| {
            queries
                .iter()
                .filter_map(|&p| wide.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    bench::<KdTree<Vec3>>(&mut group, "k-d tree", &points, &queries);
    bench::<Grid<Vec3>>(&mut group, "grid", &points, &queries);
    bench::<Orthtree<Vec3>>(&mut group, "octree", &points, &queries);
    group.finish();
}

criterion_group!(benches, point_cloud);
criterion_main!(benches);
