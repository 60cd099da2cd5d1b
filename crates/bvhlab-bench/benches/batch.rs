//! Batch queries against one call per query, on `Bvh4` over two meshes (the bunny and the
//! dragon, or tori when the shared meshes are absent): whether answering a batch of points in
//! Morton order pays, and (with both cores) what the `parallel` feature's split gives.
//!
//! Run: `cargo bench -p bvhlab-bench --bench batch` (pin with `taskset -c 1` for the
//! single-threaded rows; the parallel rows want both cores).

use std::hint::black_box;

use bvhlab::structure::bvh::Bvh4;
use bvhlab::{PointQuery, Triangle3};
use bvhlab_bench::torus_with;
use bvhlab_bench::workload::{SceneId, Workload, WorkloadSize};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// Query points only: the rays of the workload are not used here.
const SIZE: WorkloadSize = WorkloadSize {
    width: 8,
    height: 8,
    viewpoints: 1,
    random_rays: 8,
    points: 200_000,
};

/// The scenes: two real meshes, or tori of about their sizes.
fn scenes() -> Vec<(&'static str, Vec<Triangle3>)> {
    [(SceneId::Bunny, 70_000), (SceneId::Dragon, 100_000)]
        .into_iter()
        .map(|(id, fallback)| match id.triangles() {
            Ok(tris) => (id.name(), tris),
            Err(e) => {
                eprintln!("{e}: a torus instead");
                ("torus", torus_with(fallback))
            }
        })
        .collect()
}

fn batch(c: &mut Criterion) {
    for (name, tris) in scenes() {
        let work = Workload::generate(&tris, &SIZE);
        let tree = Bvh4::build(&tris);
        let points = &work.points;
        let mut group = c.benchmark_group(format!("batch/{name}"));
        group.sample_size(10);
        group.throughput(Throughput::Elements(points.len() as u64));
        group.bench_function("closest point/one call per point", |b| {
            b.iter(|| {
                let answers: Vec<_> = points.iter().map(|&p| tree.closest_point(p)).collect();
                black_box(answers)
            });
        });
        group.bench_function("closest point/batch (Morton order)", |b| {
            b.iter(|| black_box(tree.closest_points(points)));
        });
        group.finish();
    }
}

criterion_group!(benches, batch);
criterion_main!(benches);
