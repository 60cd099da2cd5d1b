//! Build times: every structure on generated tori of 10k, 100k and 1M triangles (O(n log n)
//! shows as time per triangle growing like log n), and on the 124k-triangle ogre when the
//! shared meshes are present.
//!
//! Then the parallel builds of the AABB tree and of `Bvh4` (bvhlab's `parallel` feature, which
//! this crate's benches turn on) beside their serial builds on the comparison's scenes
//! (`build-parallel/<scene>`: the bunny, dragon and ogre, the 420k torus, the 2M displaced
//! sphere), both timed in this one process.
//!
//! Run: `cargo bench -p bvhlab-bench --bench build`, or only the parallel rows:
//! `cargo bench -p bvhlab-bench --bench build -- build-parallel`.

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

/// The AABB tree and `Bvh4`, built serially and on every core (the same trees), on each scene
/// of the comparison that loads.
fn parallel_build(c: &mut Criterion) {
    use bvhlab::{AabbTree3, Bvh4};
    use bvhlab_bench::workload::SceneId;
    for id in SceneId::ALL {
        let tris = match id.triangles() {
            Ok(tris) => tris,
            Err(e) => {
                eprintln!("skipping {}: {e}", id.name());
                continue;
            }
        };
        let mut group = c.benchmark_group(format!("build-parallel/{}", id.name()));
        group.sample_size(10);
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_function("AABB tree serial", |b| {
            b.iter(|| AabbTree3::build(black_box(&tris)).nodes().len());
        });
        group.bench_function("AABB tree parallel", |b| {
            b.iter(|| AabbTree3::build_parallel(black_box(&tris)).nodes().len());
        });
        group.bench_function("Bvh4 serial", |b| {
            b.iter(|| Bvh4::build(black_box(&tris)).nodes().len());
        });
        group.bench_function("Bvh4 parallel", |b| {
            b.iter(|| Bvh4::build_parallel(black_box(&tris)).nodes().len());
        });
        group.finish();
    }
}

criterion_group!(benches, build, parallel_build);
criterion_main!(benches);
