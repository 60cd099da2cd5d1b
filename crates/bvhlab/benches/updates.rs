//! Criterion medians of updates against builds (issue 20): 10 000 triangles of the Stanford
//! bunny inserted one by one into an AABB tree against one binned SAH build; a hundredth of
//! them removed and put back; the reinsertion pass; and a uniform grid's moves against its
//! build. Skipped, with a message, when the shared meshes are absent.
//!
//! Run: `cargo bench -p bvhlab --bench updates`.

#[path = "workload/mod.rs"]
mod workload;

use std::hint::black_box;

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{BvhOptions, SplitMethod};
use criterion::measurement::WallTime;
use criterion::{BatchSize, BenchmarkGroup, Criterion, criterion_group, criterion_main};
use workload::shared_mesh;

/// How many triangles, spread over the whole mesh.
const TRIANGLES: usize = 10_000;

fn updates(c: &mut Criterion) {
    let Some(mesh) = shared_mesh("stanford-bunny.obj") else {
        return;
    };
    let all = mesh.triangles();
    let step = (all.len() / TRIANGLES).max(1);
    let tris: Vec<Triangle3> = all.iter().step_by(step).take(TRIANGLES).copied().collect();
    let extent = mesh.bounds().size().max_element();
    let mut group = c.benchmark_group(format!("bunny, {} triangles", tris.len()));
    group.sample_size(10);

    group.bench_function("AABB tree: build binned SAH", |b| {
        b.iter(|| AabbTree3::build(black_box(&tris)));
    });
    group.bench_function("AABB tree: insert one by one", |b| {
        b.iter(|| {
            let mut tree = AabbTree3::build(&[]);
            for &t in &tris {
                tree.insert(black_box(t));
            }
            tree
        });
    });
    let built = AabbTree3::build(&tris);
    let hundredth = tris.len() / 100;
    group.bench_function("AABB tree: remove and reinsert a hundredth", |b| {
        b.iter_batched(
            || built.clone(),
            |mut tree| {
                for _ in 0..hundredth {
                    let removed = tree.remove(0).expect("in range");
                    tree.insert(removed.prim);
                }
                tree
            },
            BatchSize::LargeInput,
        );
    });
    bvh4_updates(&mut group, &tris, hundredth);
    let shift = Vec3::splat(0.01 * extent);
    group.bench_function("AABB tree: move a hundredth (replace)", |b| {
        b.iter_batched(
            || built.clone(),
            |mut tree| {
                for i in 0..hundredth {
                    let t = tree.primitives()[i * 97 % tris.len()];
                    let moved = Triangle3::new(t.a + shift, t.b + shift, t.c + shift);
                    tree.replace(i * 97 % tris.len(), moved).expect("in range");
                }
                tree
            },
            BatchSize::LargeInput,
        );
    });
    let median = AabbTree3::build_with(&tris, &BvhOptions::with_method(SplitMethod::SpatialMedian));
    group.bench_function("AABB tree: 5 reinsertion passes on a median tree", |b| {
        b.iter_batched(
            || median.clone(),
            |mut tree| {
                tree.optimize_by_reinsertion(5);
                tree
            },
            BatchSize::LargeInput,
        );
    });

    group.bench_function("grid: build", |b| {
        b.iter(|| Grid3::build(black_box(&tris)));
    });
    let grid = Grid3::build(&tris);
    group.bench_function("grid: move a hundredth (replace)", |b| {
        b.iter_batched(
            || grid.clone(),
            |mut grid| {
                for i in 0..hundredth {
                    let t = grid.primitives()[i * 97 % tris.len()];
                    let moved = Triangle3::new(t.a + shift, t.b + shift, t.c + shift);
                    grid.replace(i * 97 % tris.len(), moved).expect("in range");
                }
                grid
            },
            BatchSize::LargeInput,
        );
    });
    group.finish();
}

/// `Bvh4`'s build, inserts and removes, beside the AABB tree's in the same group.
fn bvh4_updates(group: &mut BenchmarkGroup<'_, WallTime>, tris: &[Triangle3], hundredth: usize) {
    group.bench_function("Bvh4: build", |b| {
        b.iter(|| Bvh4::build(black_box(tris)));
    });
    group.bench_function("Bvh4: insert one by one", |b| {
        b.iter(|| {
            let mut tree = Bvh4::build(&[]);
            for &t in tris {
                tree.insert(black_box(t));
            }
            tree
        });
    });
    let wide = Bvh4::build(tris);
    group.bench_function("Bvh4: remove and reinsert a hundredth", |b| {
        b.iter_batched(
            || wide.clone(),
            |mut tree| {
                for _ in 0..hundredth {
                    let removed = tree.remove(0).expect("in range");
                    tree.insert(removed.prim);
                }
                tree
            },
            BatchSize::LargeInput,
        );
    });
}

criterion_group!(benches, updates);
criterion_main!(benches);
