//! The 4-wide tree's ray walks ([`Bvh4`]) on the comparison's workload, on the bunny and the
//! dragon (or a 100k-triangle torus when the shared meshes are absent): first hit for every
//! ray kind, and any hit on the shadow rays (an occlusion query: the goal is for it to be
//! clearly faster than the first hit on the same rays). Throughput is per ray.
//!
//! Run: `taskset -c 1 cargo bench -p bvhlab-bench --bench wide_rays`.

use std::hint::black_box;

use bvhlab::structure::bvh::Bvh4;
use bvhlab::{Ray3, Triangle3};
use bvhlab_bench::torus_with;
use bvhlab_bench::workload::{RayKind, SceneId, Workload, WorkloadSize};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// Fewer rays than the comparison: criterion repeats each batch many times.
const SIZE: WorkloadSize = WorkloadSize {
    width: 320,
    height: 240,
    viewpoints: 1,
    random_rays: 50_000,
    points: 0,
};

/// A scene's triangles, or the torus when its mesh file is absent.
fn scene(id: SceneId) -> (String, Vec<Triangle3>) {
    match id.triangles() {
        Ok(tris) => (id.name().to_owned(), tris),
        Err(e) => {
            eprintln!("{e}: using a 100k-triangle torus instead");
            ("torus-100k".to_owned(), torus_with(100_000))
        }
    }
}

fn wide_rays(c: &mut Criterion) {
    for id in [SceneId::Bunny, SceneId::Dragon] {
        let (name, tris) = scene(id);
        let work = Workload::generate(&tris, &SIZE);
        let tree = Bvh4::build(&tris);
        let mut group = c.benchmark_group(format!("wide/{name}"));
        group.sample_size(20);
        for kind in RayKind::ALL {
            let rays: Vec<(Ray3, f32)> = work
                .rays_of(kind)
                .iter()
                .filter_map(|r| Ray3::new(r.origin, r.dir).ok().map(|ray| (ray, r.t_max)))
                .collect();
            group.throughput(Throughput::Elements(rays.len() as u64));
            group.bench_function(format!("first hit/{}", kind.name()), |b| {
                b.iter(|| {
                    black_box(&rays)
                        .iter()
                        .filter_map(|(ray, t_max)| tree.ray_first_hit(ray, *t_max))
                        .map(|hit| hit.t)
                        .sum::<f32>()
                });
            });
            if kind == RayKind::Shadow {
                group.bench_function(format!("any hit/{}", kind.name()), |b| {
                    b.iter(|| {
                        black_box(&rays)
                            .iter()
                            .filter(|(ray, t_max)| tree.ray_any_hit(ray, *t_max).is_some())
                            .count()
                    });
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, wide_rays);
criterion_main!(benches);
