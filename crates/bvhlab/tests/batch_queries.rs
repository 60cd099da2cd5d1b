//! Batch queries (issue 20, "no batch or parallel queries"): `ray_first_hits`,
//! `ray_any_hits` and `closest_points` answer exactly as one call per query, in order, with
//! and without the `parallel` feature (`cargo test -p bvhlab --features parallel --test
//! batch_queries` runs this file on every core).

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::{Bvh4, Grid, KdTree, PointQuery, RayCast};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub(crate) fn random_vec3(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
    )
}

/// `n` triangles of up to 1.5 a side scattered over a 20-wide cube, and `m` rays from a
/// 28-wide cube through points of a 16-wide one: a scene where about half the rays hit.
pub(crate) fn triangles_and_rays(
    rng: &mut ChaCha8Rng,
    n: usize,
    m: usize,
) -> (Vec<Triangle3>, Vec<Ray3>) {
    let tris = (0..n)
        .map(|_| {
            let a = random_vec3(rng, 10.0);
            Triangle3::new(a, a + random_vec3(rng, 1.5), a + random_vec3(rng, 1.5))
        })
        .collect();
    let rays = (0..m)
        .map(|_| Ray3::through(random_vec3(rng, 14.0), random_vec3(rng, 8.0)).expect("a valid ray"))
        .collect();
    (tris, rays)
}

fn check<Q: RayCast<Vec3> + PointQuery<Vec3> + Sync>(
    what: &str,
    q: &Q,
    rays: &[Ray3],
    points: &[Vec3],
) {
    let one_by_one: Vec<_> = rays.iter().map(|r| q.ray_first_hit(r, 40.0)).collect();
    assert_eq!(
        q.ray_first_hits(rays, 40.0),
        one_by_one,
        "{what}: first hits"
    );
    let any: Vec<_> = rays.iter().map(|r| q.ray_any_hit(r, 40.0)).collect();
    assert_eq!(q.ray_any_hits(rays, 40.0), any, "{what}: any hits");
    let nearest: Vec<_> = points.iter().map(|&p| q.closest_point(p)).collect();
    assert_eq!(q.closest_points(points), nearest, "{what}: closest points");
    assert!(
        one_by_one.iter().filter(|h| h.is_some()).count() > rays.len() / 10,
        "{what}: too few hits"
    );
}

#[test]
fn batch_queries_answer_as_one_query_at_a_time() {
    let mut rng = ChaCha8Rng::seed_from_u64(26);
    let (tris, rays) = triangles_and_rays(&mut rng, 4000, 3000);
    // More points than the batch answers in the given order (4096), so the Morton-ordered
    // path runs; some repeated, to check ties in the sort keep every answer in its place.
    let mut points: Vec<Vec3> = (0..9000).map(|_| random_vec3(&mut rng, 12.0)).collect();
    points.extend_from_within(..500);
    check("Bvh4", &Bvh4::build(&tris), &rays, &points);
    check("AabbTree3", &AabbTree3::build(&tris), &rays, &points);
    check("KdTree", &KdTree::build(&tris), &rays, &points);
    check("Grid", &Grid::build(&tris), &rays, &points);
    // Empty batches give empty answers.
    assert!(Bvh4::build(&tris).ray_first_hits(&[], 1.0).is_empty());
    assert!(AabbTree3::build(&tris).closest_points(&[]).is_empty());
}

/// A thing to query that notes which pool thread answered each query (rayon's index within
/// its pool), so the test sees where the batch ran.
#[cfg(feature = "parallel")]
struct Recording<'a> {
    tree: &'a Bvh4<Triangle3>,
    threads: std::sync::Mutex<std::collections::BTreeSet<Option<usize>>>,
}

#[cfg(feature = "parallel")]
impl RayCast<Vec3> for Recording<'_> {
    fn ray_first_hit(&self, ray: &Ray3, t_max: f32) -> Option<bvhlab::Hit> {
        let index = rayon::current_thread_index();
        self.threads.lock().expect("not poisoned").insert(index);
        self.tree.ray_first_hit(ray, t_max)
    }
}

/// A newcomer's report (issue 33): batch calls offered no thread count, only rayon's global
/// pool. `with_threads(n, ..)` runs them on n threads, with the same answers.
#[cfg(feature = "parallel")]
#[test]
fn with_threads_runs_batches_and_builds_on_that_many_threads_with_the_same_answers() {
    let mut rng = ChaCha8Rng::seed_from_u64(33);
    let (tris, rays) = triangles_and_rays(&mut rng, 2000, 5000);
    let tree = Bvh4::build(&tris);
    let want = tree.ray_first_hits(&rays, f32::INFINITY);
    for threads in [1, 3] {
        let recording = Recording {
            tree: &tree,
            threads: std::sync::Mutex::default(),
        };
        let (hits, built, pool_size) = bvhlab::queries::with_threads(threads, || {
            (
                recording.ray_first_hits(&rays, f32::INFINITY),
                Bvh4::build_parallel(&tris),
                rayon::current_num_threads(),
            )
        })
        .expect("threads start");
        assert_eq!(hits, want, "{threads} threads: the answers");
        assert_eq!(built, tree, "{threads} threads: the same tree");
        assert_eq!(pool_size, threads);
        let used = recording.threads.into_inner().expect("not poisoned");
        // Every query was answered on a thread of that pool (index < threads), none on the
        // caller's thread (which is in no pool: index None).
        assert!(
            !used.is_empty() && used.iter().all(|i| i.is_some_and(|i| i < threads)),
            "{threads} threads: answered on {used:?}"
        );
    }
}
