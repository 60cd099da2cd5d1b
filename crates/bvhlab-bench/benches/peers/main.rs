//! The side-by-side comparison of issue 7: bvhlab's AABB tree against the peer libraries on
//! the same triangles, rays and points ([`bvhlab_bench::workload`]), single-threaded, medians
//! of 5. Prints one table per scene and writes `bench/results.json` and `bench/RESULTS.md`
//! (with the WebAssembly results of `bench/wasm.json` when `compare.sh` has just made them).
//!
//! Run everything with `bash crates/bvhlab-bench/compare.sh` (pinned to one core, native and
//! WebAssembly), or the native half alone with
//! `cargo bench -p bvhlab-bench --bench peers [-- --quick]`.
//!
//! `-- --parallel` measures instead bvhlab's batch queries and build in a one-thread pool and
//! on every core (unpinned), into `parallel.json`, and renders `RESULTS.md` again with them.
//!
//! Environment: `BVHLAB_BENCH_QUICK=1` (or `--quick`): a smoke run (small camera, few rays
//! and points, 2 repeats, the bunny only); `BVHLAB_BENCH_SCENES=bunny,ogre` picks scenes;
//! `BVHLAB_BENCH_OUT=DIR` writes elsewhere than `bench/`.

#![expect(
    clippy::print_stdout,
    reason = "a benchmark program: its table is its output"
)]

mod lib_bvh;
mod lib_bvhlab;
mod lib_bvhlab4;
#[cfg(feature = "embree")]
mod lib_embree;
mod lib_obvhs;
mod lib_parry;
mod lib_tinybvh;
mod library;
mod measure;
mod parallel;
mod report;
mod report_md;

use std::path::PathBuf;

use bvhlab_bench::workload::{SceneId, Workload, WorkloadSize, bounds};

use crate::library::Library;
use crate::measure::{Answers, LibResult, Repeats, measure};
use crate::report::{Run, SceneResult};

/// Runs library `L` on one scene, prints its row and appends it.
fn run<L: Library>(
    scene: &SceneData,
    repeats: Repeats,
    reference: Option<&Answers>,
    rows: &mut Vec<LibResult>,
) -> Answers {
    let (result, answers) =
        measure::<L>(&scene.tris, &scene.work, repeats, reference, scene.radius);
    println!("{}", report::row_text(&result, scene.tris.len()));
    rows.push(result);
    answers
}

/// The `--parallel` run: bvhlab's batch queries and build in one thread and on every core.
fn run_parallel(scenes: &[SceneId], size: &WorkloadSize, repeats: Repeats, out: &std::path::Path) {
    let mut all = Vec::new();
    for &id in scenes {
        let Ok(tris) = id.triangles() else {
            println!("skipping {}", id.name());
            continue;
        };
        let work = Workload::generate(&tris, size);
        println!(
            "\n{} ({} triangles): per second, one thread / every core",
            id.name(),
            tris.len()
        );
        let rows = parallel::measure(&tris, &work, repeats);
        for r in &rows {
            println!(
                "{:<40} {:>12.0} {:>12.0} {:>6.2}x{}",
                r.what,
                r.one_thread,
                r.all_cores,
                r.all_cores / r.one_thread,
                if r.same_answers {
                    ""
                } else {
                    "  [ANSWERS DIFFER]"
                }
            );
        }
        all.push(parallel::to_json(id.name(), &rows));
        match report::write_parallel(&all, out) {
            Ok(files) => println!("wrote {files}"),
            Err(e) => println!("could not write the results into {}: {e}", out.display()),
        }
    }
}

/// A scene's triangles and workload.
struct SceneData {
    tris: Vec<bvhlab::Triangle3>,
    work: Workload,
    radius: f32,
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick")
        || std::env::var("BVHLAB_BENCH_QUICK").is_ok_and(|v| v == "1");
    let size = if quick {
        WorkloadSize::QUICK
    } else {
        WorkloadSize::FULL
    };
    let repeats = Repeats {
        count: if quick { 2 } else { 5 },
    };
    let scenes: Vec<SceneId> = match std::env::var("BVHLAB_BENCH_SCENES") {
        Ok(list) => SceneId::ALL
            .into_iter()
            .filter(|s| list.split(',').any(|name| name.trim() == s.name()))
            .collect(),
        Err(_) if quick => vec![SceneId::Bunny],
        Err(_) => SceneId::ALL.to_vec(),
    };
    let out = std::env::var_os("BVHLAB_BENCH_OUT").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../bench"),
        PathBuf::from,
    );
    if std::env::args().any(|a| a == "--parallel") {
        run_parallel(&scenes, &size, repeats, &out);
        return;
    }
    let mut run_result = Run::new(quick, &size, repeats);
    println!("{}", report::header_text());
    for id in scenes {
        let tris = match id.triangles() {
            Ok(tris) => tris,
            Err(e) => {
                println!("skipping {}: {e}", id.name());
                continue;
            }
        };
        let (lo, hi) = bounds(&tris);
        let work = Workload::generate(&tris, &size);
        let scene = SceneData {
            radius: (hi - lo).length() * 0.5,
            tris,
            work,
        };
        println!("\n{} ({} triangles)", id.name(), scene.tris.len());
        let mut rows = Vec::new();
        // The first row is "ours" in the ratio tables: the 4-wide tree, bvhlab's fastest
        // path. The binary tree it is collapsed from (the one the lab steps through) must
        // give the same answers: any disagreement between the two rows is a bug.
        let reference = run::<lib_bvhlab4::BvhlabWide>(&scene, repeats, None, &mut rows);
        let r = Some(&reference);
        run::<lib_bvhlab::Bvhlab>(&scene, repeats, r, &mut rows);
        run::<lib_obvhs::Obvhs>(&scene, repeats, r, &mut rows);
        run::<lib_parry::Parry>(&scene, repeats, r, &mut rows);
        run::<lib_bvh::SvenstaroBvh>(&scene, repeats, r, &mut rows);
        run::<lib_tinybvh::TinyBvh>(&scene, repeats, r, &mut rows);
        #[cfg(target_feature = "avx2")]
        run::<lib_tinybvh::TinyBvh8>(&scene, repeats, r, &mut rows);
        #[cfg(feature = "embree")]
        run::<lib_embree::Embree>(&scene, repeats, r, &mut rows);
        run_result.scenes.push(SceneResult {
            name: id.name(),
            triangles: scene.tris.len(),
            rays: scene.work.rays.iter().map(|(k, r)| (*k, r.len())).collect(),
            points: scene.work.points.len(),
            rows,
        });
        // After every scene, so that an interrupted run keeps what it measured.
        match report::write(&run_result, &out) {
            Ok(files) => println!("wrote {files}"),
            Err(e) => println!("could not write the results into {}: {e}", out.display()),
        }
    }
}
