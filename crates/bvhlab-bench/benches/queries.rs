//! bvhlab alone on one mid-size mesh (the Stanford bunny, or a 100k-triangle torus when the
//! shared meshes are absent), with the comparison's workload: the AABB tree's build, ray first
//! hit for each ray kind and closest point, so speed work on the core can be tracked without
//! the peers. Throughput is per ray (per query point). Any hit runs on the same rays with
//! their own `t_max` (for shadow rays, the light's distance).
//!
//! Run: `cargo bench -p bvhlab-bench --bench queries`.

use bvhlab::{PointQuery, RayCast};
use std::hint::black_box;

use bvhlab::{AabbTree3, Ray3, SpatialIndex};
use bvhlab_bench::torus_with;
use bvhlab_bench::workload::{SceneId, Workload, WorkloadSize};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// Fewer rays than the comparison: criterion repeats each batch many times.
const SIZE: WorkloadSize = WorkloadSize {
    width: 320,
    height: 240,
    viewpoints: 1,
    random_rays: 50_000,
    points: 50_000,
};

fn queries(c: &mut Criterion) {
    let (name, tris) = match SceneId::Bunny.triangles() {
        Ok(tris) => ("bunny", tris),
        Err(e) => {
            eprintln!("{e}: using a 100k-triangle torus instead");
            ("torus-100k", torus_with(100_000))
        }
    };
    let work = Workload::generate(&tris, &SIZE);
    let tree = AabbTree3::build(&tris);

    let mut group = c.benchmark_group(format!("queries/{name}"));
    group.sample_size(10);
    group.throughput(Throughput::Elements(tris.len() as u64));
    group.bench_function("build", |b| {
        b.iter(|| AabbTree3::build(black_box(&tris)).stats().nodes);
    });
    for (kind, rays) in &work.rays {
        let rays: Vec<(Ray3, f32)> = rays
            .iter()
            .filter_map(|r| Ray3::new(r.origin, r.dir).ok().map(|ray| (ray, r.t_max)))
            .collect();
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function(format!("first hit/{}", kind.name()), |b| {
            b.iter(|| {
                rays.iter()
                    .filter_map(|(ray, t_max)| tree.ray_first_hit(ray, *t_max))
                    .map(|hit| hit.t)
                    .sum::<f32>()
            });
        });
        group.bench_function(format!("any hit/{}", kind.name()), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|(ray, t_max)| tree.ray_any_hit(ray, *t_max).is_some())
                    .count()
            });
        });
    }
    group.throughput(Throughput::Elements(work.points.len() as u64));
    group.bench_function("closest point", |b| {
        b.iter(|| {
            work.points
                .iter()
                .filter_map(|&p| tree.closest_point(p))
                .map(|n| n.distance)
                .sum::<f32>()
        });
    });
    group.finish();
}

criterion_group!(benches, queries);
criterion_main!(benches);
