//! A point cloud's nearest neighbours: 200k points uniform in the unit cube (seeded) and
//! 20k query points in the same cube, the k-d tree built with its defaults
//! ([`KdTree::build`]) beside the 4-wide AABB tree ([`Bvh4::build`]), the uniform grid and
//! the octree (their defaults too): their builds and their closest points. Throughput is
//! per point (per query).
//!
//! A second group is a newcomer's case (issue 33): balls over the same 200k points, each of
//! radius 0.165 wholly inside the cube (centres in `[r, 1 - r]^3`), so that each holds
//! about 3,770 points (4/3 π r³ × 200k = 3,763); [`Bvh4::range`] beside a plain scan of
//! every point with the same test, and beside a count of squared distances; and
//! [`Bvh4::range_count`], which counts without the list.
//!
//! Run: `cargo bench -p bvhlab --bench point_cloud` (the balls alone: `-- "large balls"`).

use std::hint::black_box;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::kdtree::KdTree;
use bvhlab::{Grid, Orthtree, RangeShape, Sphere};
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

/// The radius of the large balls: 3,770 of 200k uniform points in the unit cube.
const LARGE_RADIUS: f32 = 0.165;

/// `n` centres of large balls, each ball wholly inside the unit cube.
fn inner_centres(n: usize, seed: u64) -> Vec<Vec3> {
    let r = LARGE_RADIUS;
    cube_points(n, seed)
        .into_iter()
        .map(|p| Vec3::splat(r) + p * (1.0 - 2.0 * r))
        .collect()
}

/// Range queries with large balls (issue 33): the 4-wide tree against a plain scan.
fn large_balls(c: &mut Criterion) {
    let points = cube_points(200_000, 5);
    let balls: Vec<RangeShape<Vec3>> = inner_centres(200, 7)
        .into_iter()
        .map(|centre| RangeShape::Ball(Sphere::new(centre, LARGE_RADIUS)))
        .collect();
    let wide = Bvh4::build(&points);
    let found: usize = balls.iter().map(|ball| wide.range(ball).len()).sum();
    eprintln!(
        "large balls: {:.0} points per ball",
        found as f64 / balls.len() as f64
    );
    let mut group = c.benchmark_group("large balls 200k");
    group.sample_size(10);
    group.throughput(Throughput::Elements(balls.len() as u64));
    group.bench_function("range 4-wide", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|ball| wide.range(black_box(ball)).len())
                .sum::<usize>()
        });
    });
    group.bench_function("range count 4-wide", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|ball| wide.range_count(black_box(ball)))
                .sum::<usize>()
        });
    });
    group.bench_function("plain scan", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|ball| {
                    let ball = black_box(ball);
                    let found: Vec<usize> = points
                        .iter()
                        .enumerate()
                        .filter(|(_, p)| ball.overlaps_primitive(*p))
                        .map(|(i, _)| i)
                        .collect();
                    found.len()
                })
                .sum::<usize>()
        });
    });
    // What a newcomer writes first: a count of squared distances, which the compiler turns
    // into vector instructions (it may differ from the exact test by a point on the surface).
    group.bench_function("plain scan, squared count", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|ball| {
                    let RangeShape::Ball(s) = black_box(ball) else {
                        return 0;
                    };
                    let r2 = s.radius * s.radius;
                    points
                        .iter()
                        .filter(|p| p.distance_squared(s.center) <= r2)
                        .count()
                })
                .sum::<usize>()
        });
    });
    group.finish();
}

criterion_group!(benches, point_cloud, large_balls);
criterion_main!(benches);
