//! The observer costs nothing when unused: `ray_first_hit` (the plain call, which passes the
//! no-op observer `()`; except in the AABB tree, whose plain first hit takes a walk of its own,
//! `structure/bvh/walk/fast_ray.rs`), `ray_first_hit_observed(.., &mut ())` spelled out, and,
//! for contrast, an observer that does a little work per event (counts them), on the same
//! rays.
//!
//! Run: `cargo bench -p bvhlab-bench --bench observer`.

use bvhlab::glam::Vec3;
use bvhlab::structure::{Event, Observer};
use bvhlab::{SpatialIndex, Triangle3};
use bvhlab_bench::{camera_rays, torus_with};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// Counts events: the cheapest observer that does something.
struct Counter(u64);

impl Observer<Vec3> for Counter {
    fn on(&mut self, _event: Event<Vec3>) {
        self.0 += 1;
    }
}

fn bench_structure<S: SpatialIndex<Prim = Triangle3>>(
    c: &mut Criterion,
    name: &str,
    tris: &[Triangle3],
) {
    let structure = S::build(tris);
    let rays = camera_rays(Vec3::new(0.0, -4.0, 2.0), Vec3::ZERO, 64, 48);
    let mut group = c.benchmark_group(format!("observer/{name}"));
    group.bench_function("plain", |b| {
        b.iter(|| {
            rays.iter()
                .filter_map(|r| structure.ray_first_hit(black_box(r), f32::INFINITY))
                .count()
        });
    });
    group.bench_function("no-op observer", |b| {
        b.iter(|| {
            rays.iter()
                .filter_map(|r| {
                    structure
                        .ray_first_hit_observed(black_box(r), f32::INFINITY, &mut ())
                        .answer
                })
                .count()
        });
    });
    group.bench_function("counting observer", |b| {
        b.iter(|| {
            let mut counter = Counter(0);
            let hits = rays
                .iter()
                .filter_map(|r| {
                    structure
                        .ray_first_hit_observed(black_box(r), f32::INFINITY, &mut counter)
                        .answer
                })
                .count();
            (hits, counter.0)
        });
    });
    group.finish();
}

fn observer(c: &mut Criterion) {
    let tris = torus_with(20_000);
    bench_structure::<bvhlab::structure::BruteForce<Triangle3>>(
        c,
        "brute force (2k tris)",
        &tris[..2_000],
    );
    bench_structure::<bvhlab::AabbTree3>(c, "AABB tree (20k tris)", &tris);
    bench_structure::<bvhlab::KdTree3>(c, "kd-tree (20k tris)", &tris);
    bench_structure::<bvhlab::Grid3>(c, "grid (20k tris)", &tris);
}

criterion_group!(benches, observer);
criterion_main!(benches);
