//! Criterion medians of issue 7's workload on the AABB tree over ogre.obj (124k triangles):
//! the binned SAH build, ray first hit on coherent and incoherent rays, closest point, each
//! unobserved (the fast walks) and, for rays, observed with the no-op observer (the walk the
//! lab steps through); the collapse to the 4-wide tree (`Bvh4`) and its queries; any hit (`t_max` infinite) in
//! both trees on the same rays. Skipped, with a message, when the shared meshes are absent.
//!
//! Run: `cargo bench -p bvhlab --bench speed`.

#[path = "workload/mod.rs"]
mod workload;

use std::hint::black_box;

use bvhlab::RangeShape;
use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::Bvh4;
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use workload::{camera_rays, random_points, random_rays, shared_mesh};

fn speed(c: &mut Criterion) {
    let Some(mesh) = shared_mesh("ogre.obj") else {
        return;
    };
    let tris = mesh.triangles();
    let mut group = c.benchmark_group("ogre");
    group.sample_size(10);
    group.throughput(Throughput::Elements(tris.len() as u64));
    group.bench_function("build binned SAH", |b| {
        b.iter(|| AabbTree3::build(black_box(tris)));
    });
    let tree = AabbTree3::build(tris);
    group.bench_function("collapse to 4-wide", |b| {
        b.iter(|| Bvh4::from_bvh(black_box(&tree)));
    });
    let wide = Bvh4::from_bvh(&tree);
    let bounds = mesh.bounds();
    for (name, rays) in [
        ("coherent", camera_rays(&bounds)),
        ("incoherent", random_rays(&bounds, 300_000)),
    ] {
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function(format!("ray first hit, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|ray| tree.ray_first_hit(black_box(ray), f32::INFINITY).is_some())
                    .count()
            });
        });
        group.bench_function(format!("ray first hit 4-wide, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|ray| wide.ray_first_hit(black_box(ray), f32::INFINITY).is_some())
                    .count()
            });
        });
        group.bench_function(format!("ray any hit, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|ray| tree.ray_any_hit(black_box(ray), f32::INFINITY).is_some())
                    .count()
            });
        });
        group.bench_function(format!("ray any hit 4-wide, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|ray| wide.ray_any_hit(black_box(ray), f32::INFINITY).is_some())
                    .count()
            });
        });
        group.bench_function(format!("ray all hits, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .map(|ray| tree.ray_all_hits(black_box(ray), f32::INFINITY).len())
                    .sum::<usize>()
            });
        });
        group.bench_function(format!("ray all hits 4-wide, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .map(|ray| wide.ray_all_hits(black_box(ray), f32::INFINITY).len())
                    .sum::<usize>()
            });
        });
        group.bench_function(format!("ray first hit observed, {name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|ray| {
                        tree.ray_first_hit_observed(black_box(ray), f32::INFINITY, &mut ())
                            .answer
                            .is_some()
                    })
                    .count()
            });
        });
    }
    let points = random_points(&bounds, 100_000);
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("closest point", |b| {
        b.iter(|| {
            points
                .iter()
                .filter_map(|&p| tree.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    group.bench_function("closest point 4-wide", |b| {
        b.iter(|| {
            points
                .iter()
                .filter_map(|&p| wide.closest_point(black_box(p)))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    near_queries(&mut group, &tree, &wide, &points, &bounds);
    group.finish();
}

/// The 8 nearest and a ball around each point (its radius a hundredth of the box's
/// diagonal), in both trees.
fn near_queries(
    group: &mut BenchmarkGroup<'_, WallTime>,
    tree: &AabbTree3,
    wide: &Bvh4<Triangle3>,
    points: &[Vec3],
    bounds: &Aabb3,
) {
    let radius = (bounds.max - bounds.min).length() * 0.01;
    group.bench_function("8 nearest", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|&p| tree.k_nearest(black_box(p), 8).len())
                .sum::<usize>()
        });
    });
    group.bench_function("8 nearest 4-wide", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|&p| wide.k_nearest(black_box(p), 8).len())
                .sum::<usize>()
        });
    });
    let balls: Vec<RangeShape<_>> = points
        .iter()
        .map(|&p| RangeShape::Ball(Sphere3::new(p, radius)))
        .collect();
    group.bench_function("range ball", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|s| tree.range(black_box(s)).len())
                .sum::<usize>()
        });
    });
    group.bench_function("range ball 4-wide", |b| {
        b.iter(|| {
            balls
                .iter()
                .map(|s| wide.range(black_box(s)).len())
                .sum::<usize>()
        });
    });
}

criterion_group!(benches, speed);
criterion_main!(benches);
