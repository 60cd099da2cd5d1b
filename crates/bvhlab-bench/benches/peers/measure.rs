//! Times one library on one scene (medians of a few repeats), counts what its queries cost,
//! and checks every answer against bvhlab's (the reference: bvhlab's answers equal brute
//! force's).

use std::hint::black_box;
use std::time::Instant;

use bvhlab::Triangle3;
use bvhlab_bench::workload::{RayKind, Workload};

use crate::library::{Library, TreeFacts};

/// Relative tolerance for two libraries' `t` (or distance) to count as the same answer.
pub const TOLERANCE: f64 = 1e-5;
/// At most this many disagreements are kept as examples per library, scene and kind.
const EXAMPLES: usize = 5;

/// Results of one ray kind.
#[derive(Clone, Debug)]
pub struct KindResult {
    /// The ray kind.
    pub kind: RayKind,
    /// Rays asked.
    pub rays: usize,
    /// Of which hit something (by this library).
    pub hits: usize,
    /// Millions of rays per second (median).
    pub mrays_per_s: f64,
    /// Mean nodes visited per ray, where the library reports them.
    pub nodes_per_ray: Option<f64>,
    /// Mean triangles tested per ray, where known.
    pub prims_per_ray: Option<f64>,
    /// Rays whose answer differs from bvhlab's (hit vs miss, or `t` beyond the tolerance).
    pub disagreements: usize,
    /// Of which: bvhlab hits, this library misses.
    pub missed: usize,
    /// A few of them: (ray index, bvhlab's t, this library's t).
    pub examples: Vec<(usize, Option<f32>, Option<f32>)>,
    /// The same rays asked as occlusion (any hit), where the library has the call and the
    /// kind is [`RayKind::Shadow`].
    pub occlusion: Option<Occlusion>,
}

/// The shadow rays asked as occlusion queries.
#[derive(Clone, Copy, Debug)]
pub struct Occlusion {
    /// Millions of rays per second (median).
    pub mrays_per_s: f64,
    /// Rays blocked, by this library.
    pub blocked: usize,
    /// Rays whose verdict differs from bvhlab's first hit (a hit within `t_max` or none).
    pub disagreements: usize,
}

/// Results of one library on one scene.
#[derive(Clone, Debug)]
pub struct LibResult {
    /// The library's name.
    pub library: &'static str,
    /// Build time in ms (median).
    pub build_ms: f64,
    /// Tree shape and memory.
    pub facts: TreeFacts,
    /// One entry per ray kind.
    pub kinds: Vec<KindResult>,
    /// Closest-point queries per second (median), if supported.
    pub closest_per_s: Option<f64>,
    /// Closest-point distances that differ from bvhlab's, if supported.
    pub closest_disagreements: Option<usize>,
    /// A few of them: (point index, bvhlab's distance, this library's).
    pub closest_examples: Vec<(usize, Option<f32>, Option<f32>)>,
}

/// bvhlab's answers, the reference for the others.
#[derive(Clone, Debug, Default)]
pub struct Answers {
    /// First-hit `t` per ray, per kind (in the workload's order).
    pub hits: Vec<Vec<Option<f32>>>,
    /// Closest distance per point.
    pub closest: Vec<Option<f32>>,
}

/// How much to repeat.
#[derive(Clone, Copy, Debug)]
pub struct Repeats {
    /// Timed runs of each build and query set; the median is reported.
    pub count: usize,
}

/// The median of `count` timings of `f`, in seconds.
pub fn median_secs(count: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..count.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Whether two answers are the same (both none, or equal to [`TOLERANCE`] relative, with
/// `floor` as the smallest magnitude compared).
pub fn agree(a: Option<f32>, b: Option<f32>, floor: f64) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            let (a, b) = (f64::from(a), f64::from(b));
            (a - b).abs() <= TOLERANCE * a.abs().max(b.abs()).max(floor)
        }
        _ => false,
    }
}

/// Times `rays` as occlusion queries and checks each verdict against `expected` first hits.
fn occlusion<L: Library>(
    tree: &L::Tree<'_>,
    rays: &[L::Ray],
    expected: &[Option<f32>],
    repeats: Repeats,
) -> Occlusion {
    let secs = median_secs(repeats.count, || {
        let mut blocked = 0usize;
        for ray in rays {
            blocked += usize::from(L::occluded(tree, ray));
        }
        black_box(blocked);
    });
    let verdicts: Vec<bool> = rays.iter().map(|r| L::occluded(tree, r)).collect();
    Occlusion {
        mrays_per_s: rays.len() as f64 / secs / 1e6,
        blocked: verdicts.iter().filter(|&&b| b).count(),
        disagreements: verdicts
            .iter()
            .zip(expected)
            .filter(|(b, want)| **b != want.is_some())
            .count(),
    }
}

/// Measures library `L` on `tris` with the workload `work`; compares with `reference` when
/// given, and returns its own answers (to serve as the reference when `L` is bvhlab).
pub fn measure<L: Library>(
    tris: &[Triangle3],
    work: &Workload,
    repeats: Repeats,
    reference: Option<&Answers>,
    scale: f32,
) -> (LibResult, Answers) {
    let input = L::input(tris);
    let mut tree = None;
    let build_s = median_secs(repeats.count, || {
        drop(tree.take());
        tree = Some(L::build(&input));
    });
    let Some(tree) = tree else {
        unreachable!("median_secs runs at least once")
    };
    let floor = 1e-6 * f64::from(scale);
    let mut answers = Answers::default();
    let mut kinds = Vec::new();
    for (k, (kind, bench_rays)) in work.rays.iter().enumerate() {
        let rays: Vec<L::Ray> = bench_rays.iter().map(L::ray).collect();
        let secs = median_secs(repeats.count, || {
            let mut sum = 0.0f32;
            for ray in &rays {
                sum += L::first_hit(&tree, ray).unwrap_or(0.0);
            }
            black_box(sum);
        });
        let got: Vec<Option<f32>> = rays.iter().map(|r| L::first_hit(&tree, r)).collect();
        let (mut nodes, mut prims) = (Some(0u64), Some(0u64));
        for ray in &rays {
            let cost = L::first_hit_cost(&tree, ray);
            nodes = nodes.zip(cost.nodes).map(|(a, b)| a + b);
            prims = prims.zip(cost.prims).map(|(a, b)| a + b);
        }
        let per_ray = |n: Option<u64>| {
            n.filter(|_| !rays.is_empty())
                .map(|n| n as f64 / rays.len() as f64)
        };
        let mut result = KindResult {
            kind: *kind,
            rays: rays.len(),
            hits: got.iter().flatten().count(),
            mrays_per_s: rays.len() as f64 / secs / 1e6,
            nodes_per_ray: per_ray(nodes),
            prims_per_ray: per_ray(prims),
            disagreements: 0,
            missed: 0,
            examples: Vec::new(),
            occlusion: None,
        };
        if let Some(expected) = reference.and_then(|r| r.hits.get(k)) {
            for (i, (&want, &have)) in expected.iter().zip(&got).enumerate() {
                if !agree(want, have, floor) {
                    result.disagreements += 1;
                    result.missed += usize::from(want.is_some() && have.is_none());
                    if result.examples.len() < EXAMPLES {
                        result.examples.push((i, want, have));
                    }
                }
            }
        }
        if L::HAS_OCCLUSION && *kind == RayKind::Shadow {
            let expected = reference.and_then(|r| r.hits.get(k)).unwrap_or(&got);
            result.occlusion = Some(occlusion::<L>(&tree, &rays, expected, repeats));
        }
        answers.hits.push(got);
        kinds.push(result);
    }
    let mut result = LibResult {
        library: L::NAME,
        build_ms: build_s * 1e3,
        facts: L::facts(&tree),
        kinds,
        closest_per_s: None,
        closest_disagreements: None,
        closest_examples: Vec::new(),
    };
    if L::HAS_CLOSEST {
        let secs = median_secs(repeats.count, || {
            let mut sum = 0.0f32;
            for &p in &work.points {
                sum += L::closest_distance(&tree, p).unwrap_or(0.0);
            }
            black_box(sum);
        });
        result.closest_per_s = Some(work.points.len() as f64 / secs);
        let got: Vec<Option<f32>> = work
            .points
            .iter()
            .map(|&p| L::closest_distance(&tree, p))
            .collect();
        if let Some(expected) = reference.map(|r| &r.closest) {
            let mut count = 0;
            for (i, (&want, &have)) in expected.iter().zip(&got).enumerate() {
                if !agree(want, have, floor) {
                    count += 1;
                    if result.closest_examples.len() < EXAMPLES {
                        result.closest_examples.push((i, want, have));
                    }
                }
            }
            result.closest_disagreements = Some(count);
        }
        answers.closest = got;
    }
    (result, answers)
}
