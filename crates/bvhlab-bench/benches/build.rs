//! Build times: every structure on generated tori of 10k, 100k and 1M triangles (O(n log n)
//! shows as time per triangle growing like log n), and on the 124k-triangle ogre when the
//! shared meshes are present.
//!
//! Run: `cargo bench -p bvhlab-bench --bench build`.

use bvhlab::{SpatialIndex, Triangle3};
use bvhlab_bench::{shared_mesh, torus_with};
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

const SIZES: [usize; 3] = [10_000, 100_000, 1_000_000];

fn bench_build<S: SpatialIndex<Prim = Triangle3>>(c: &mut Criterion, name: &str) {
    let mut group = c.benchmark_group(format!("build/{name}"));
    group.sample_size(10);
    for n in SIZES {
        let tris = torus_with(n);
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(tris.len()), &tris, |b, tris| {
            b.iter(|| S::build(black_box(tris)).stats().nodes);
        });
    }
    group.finish();
}

fn bench_ogre<S: SpatialIndex<Prim = Triangle3>>(
    c: &mut Criterion,
    name: &str,
    tris: &[Triangle3],
) {
    let mut group = c.benchmark_group("build/ogre");
    group.sample_size(10);
    group.bench_function(name, |b| b.iter(|| S::build(black_box(tris)).stats().nodes));
    group.finish();
}

/// Calls `$f::<S>(c, label, args..)` for every 3D structure.
macro_rules! for_each_structure {
    ($f:ident, $c:expr $(, $arg:expr)*) => {
        $f::<bvhlab::AabbTree3>($c, "AABB tree SAH" $(, $arg)*);
        $f::<bvhlab::SphereTree3>($c, "sphere tree SAH" $(, $arg)*);
        $f::<bvhlab::ObbTree3>($c, "OBB tree SAH" $(, $arg)*);
        $f::<bvhlab::KdTree3>($c, "kd-tree SAH" $(, $arg)*);
        $f::<bvhlab::Grid3>($c, "grid" $(, $arg)*);
        $f::<bvhlab::Octree3>($c, "octree" $(, $arg)*);
        $f::<bvhlab::Bsp3>($c, "bsp" $(, $arg)*);
    };
}

fn build(c: &mut Criterion) {
    for_each_structure!(bench_build, c);
    match shared_mesh("ogre.obj") {
        Some(path) => {
            let bytes = std::fs::read(path).expect("the shared meshes are readable");
            let ogre = bvhlab::Mesh::from_obj(&bytes).expect("ogre.obj loads");
            for_each_structure!(bench_ogre, c, ogre.triangles());
        }
        None => eprintln!(
            "skipping the ogre builds: ../shared/data/meshes is not beside the repository"
        ),
    }
}

criterion_group!(benches, build);
criterion_main!(benches);
