//! Batch queries (issue 20, "no batch or parallel queries"): `ray_first_hits`,
//! `ray_any_hits` and `closest_points` answer exactly as one call per query, in order, with
//! and without the `parallel` feature (`cargo test -p bvhlab --features parallel --test
//! batch_queries` runs this file on every core).

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::{Bvh4, Grid, KdTree, PointQuery, RayCast};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_vec3(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
    )
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
    let tris: Vec<Triangle3> = (0..4000)
        .map(|_| {
            let a = random_vec3(&mut rng, 10.0);
            Triangle3::new(
                a,
                a + random_vec3(&mut rng, 1.5),
                a + random_vec3(&mut rng, 1.5),
            )
        })
        .collect();
    let rays: Vec<Ray3> = (0..3000)
        .map(|_| {
            Ray3::through(random_vec3(&mut rng, 14.0), random_vec3(&mut rng, 8.0))
                .expect("a valid ray")
        })
        .collect();
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
