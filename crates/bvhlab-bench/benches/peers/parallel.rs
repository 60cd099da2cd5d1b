//! bvhlab on every core (its `parallel` feature): the batch queries (`ray_first_hits`,
//! `ray_any_hits`, `closest_points`) and the build, each timed in a one-thread rayon pool and
//! in a pool of every core, on the same scene and workload as the single-threaded tables.
//!
//! Run unpinned (`compare.sh` does, after the pinned runs): a pinned process has one core to
//! give. The answers of the two pools are compared (they must be equal: queries are
//! independent and the parallel build makes the serial build's tree).

use std::hint::black_box;

use bvhlab::structure::bvh::Bvh4;
use bvhlab::{Hit, PointQuery, Ray3, RayCast, Triangle3};
use bvhlab_bench::workload::{BenchRay, RayKind, Workload};
use serde_json::{Value, json};

use crate::measure::{Repeats, median_secs};

/// One timed operation in both pools.
pub struct Row {
    /// What was timed, e.g. "first hits, primary rays".
    pub what: String,
    /// Queries (or triangles, for the build) per second with one thread.
    pub one_thread: f64,
    /// With every core.
    pub all_cores: f64,
    /// Whether both pools gave the same answers (the same tree, for the build).
    pub same_answers: bool,
}

/// A rayon pool of `threads` threads.
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("a rayon pool of {threads} threads: {e}"))
}

/// The rays of one kind as one batch: a shadow ray's own limit is put into its direction
/// (the ray reaches the light at `t = 1`), so that every ray of the batch takes the limit 1;
/// the other kinds have no limit.
fn batch_rays(rays: &[BenchRay]) -> (Vec<Ray3>, f32) {
    let finite = rays.iter().all(|r| r.t_max.is_finite());
    let limit = if finite { 1.0 } else { f32::INFINITY };
    let rays = rays
        .iter()
        .map(|r| {
            let dir = if finite { r.dir * r.t_max } else { r.dir };
            Ray3::new(r.origin, dir).unwrap_or_else(|e| panic!("bad ray {r:?}: {e}"))
        })
        .collect();
    (rays, limit)
}

/// Times `run` in both pools; `count` queries per run.
fn both<A: PartialEq + Send>(
    what: String,
    count: usize,
    repeats: Repeats,
    one: &rayon::ThreadPool,
    all: &rayon::ThreadPool,
    run: impl Fn() -> A + Sync,
) -> Row {
    let mut answers = [None, None];
    let mut rates = [0.0; 2];
    for (i, pool) in [one, all].into_iter().enumerate() {
        let secs = median_secs(repeats.count, || {
            answers[i] = Some(pool.install(|| black_box(run())));
        });
        rates[i] = count as f64 / secs;
    }
    let [a, b] = answers;
    Row {
        what,
        one_thread: rates[0],
        all_cores: rates[1],
        same_answers: a.is_some() && a == b,
    }
}

/// `Bvh4::build` in one thread against `Bvh4::build_parallel` on every core (triangles per
/// second), and whether they made the same tree.
fn build_row(
    tris: &[Triangle3],
    repeats: Repeats,
    one: &rayon::ThreadPool,
    all: &rayon::ThreadPool,
) -> Row {
    let (mut serial, mut parallel) = (None, None);
    let serial_secs = median_secs(repeats.count, || {
        serial = Some(one.install(|| Bvh4::build(tris)));
    });
    let parallel_secs = median_secs(repeats.count, || {
        parallel = Some(all.install(|| Bvh4::build_parallel(tris)));
    });
    Row {
        what: "build (Bvh4::build, Bvh4::build_parallel)".into(),
        one_thread: tris.len() as f64 / serial_secs,
        all_cores: tris.len() as f64 / parallel_secs,
        same_answers: serial.is_some() && serial == parallel,
    }
}

/// Every row for one scene.
pub fn measure(tris: &[Triangle3], work: &Workload, repeats: Repeats) -> Vec<Row> {
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let (one, all) = (pool(1), pool(cores));
    let mut rows = vec![build_row(tris, repeats, &one, &all)];
    let tree = Bvh4::build(tris);
    for (kind, bench_rays) in &work.rays {
        let (rays, limit) = batch_rays(bench_rays);
        let first = |hits: Vec<Option<Hit>>| hits.into_iter().map(|h| h.map(|h| (h.prim, h.t)));
        rows.push(both(
            format!("first hits, {} rays", kind.name()),
            rays.len(),
            repeats,
            &one,
            &all,
            || first(tree.ray_first_hits(&rays, limit)).collect::<Vec<_>>(),
        ));
        if *kind == RayKind::Shadow {
            rows.push(both(
                "any hits (occlusion), shadow rays".into(),
                rays.len(),
                repeats,
                &one,
                &all,
                || {
                    tree.ray_any_hits(&rays, limit)
                        .iter()
                        .map(Option::is_some)
                        .collect::<Vec<_>>()
                },
            ));
        }
    }
    rows.push(both(
        "closest points".into(),
        work.points.len(),
        repeats,
        &one,
        &all,
        || {
            tree.closest_points(&work.points)
                .into_iter()
                .map(|n| n.map(|n| (n.prim, n.distance)))
                .collect::<Vec<_>>()
        },
    ));
    rows
}

/// The rows as JSON, for `parallel.json`.
pub fn to_json(scene: &str, rows: &[Row]) -> Value {
    json!({
        "scene": scene,
        "rows": rows.iter().map(|r| json!({
            "what": r.what, "one_thread_per_s": r.one_thread, "all_cores_per_s": r.all_cores,
            "speedup": r.all_cores / r.one_thread, "same_answers": r.same_answers,
        })).collect::<Vec<_>>(),
    })
}
