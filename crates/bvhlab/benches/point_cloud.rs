//! A point cloud's nearest neighbours: 200k points uniform in the unit cube (seeded) and
//! 20k query points in the same cube, the k-d tree built with its defaults
//! ([`KdTree::build`]) beside the 4-wide AABB tree ([`Bvh4::build`]): their builds and
//! their closest points. Throughput is per point (per query).
//!
//! Run: `cargo bench -p bvhlab --bench point_cloud`.

use std::hint::black_box;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::kdtree::KdTree;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn cube_points(n: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
        .collect()
}

fn point_cloud(c: &mut Criterion) {
    let points = cube_points(200_000, 5);
    let queries = cube_points(20_000, 6);
    let mut group = c.benchmark_group("point cloud 200k");
    group.sample_size(10);
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("build k-d tree", |b| {
        b.iter(|| KdTree::build(black_box(&points)).nodes().len());
    });
    group.bench_function("build 4-wide", |b| {
        b.iter(|| Bvh4::build(black_box(&points)).len());
    });
    let kd = KdTree::build(&points);
    let wide = Bvh4::build(&points);
    group.throughput(Throughput::Elements(queries.len() as u64));
    group.bench_function("closest point k-d tree", |b| {
        b.iter(|| {
            queries
                .iter()
                .filter_map(|&p| kd.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    group.bench_function("closest point 4-wide", |b| {
        b.iter(|| {
            queries
                .iter()
                .filter_map(|&p| wide.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    group.finish();
}

criterion_group!(benches, point_cloud);
criterion_main!(benches);
