//! Build times: every structure on generated tori of 10k, 100k and 1M triangles (O(n log n)
//! shows as time per triangle growing like log n), and on the 124k-triangle ogre when the
//! shared meshes are present.
//!
//! Run: `cargo bench -p bvhlab-bench --bench build`.

use bvhlab::{SpatialIndex, Triangle3};
use bvhlab_bench::torus_with;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

fn bench_build<S: SpatialIndex<Prim = Triangle3>>(c: &mut Criterion, name: &str, sizes: &[usize]) {
    let mut group = c.benchmark_group(format!("build/{name}"));
    group.sample_size(10);
    for &n in sizes {
        let tris = torus_with(n);
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(tris.len()), &tris, |b, tris| {
            b.iter(|| S::build(black_box(tris)).stats().nodes);
        });
    }
    group.finish();
}

fn build(c: &mut Criterion) {
    bench_build::<bvhlab::structure::BruteForce<Triangle3>>(c, "brute force (copy)", &[10_000, 100_000, 1_000_000]);
}

criterion_group!(benches, build);
criterion_main!(benches);
