//! What a newcomer ran into in issue 33: `validate()` of the k-d tree and of the octree
//! refused correct trees over the crate docs' own `Ball` (1,000 and more of them), while
//! their queries were right. The k-d tree's check asked for a ball in a cell that the ball
//! touches only within the rounding the primitive contract allows (its box ends on the split
//! plane); the octree's asked that every ball a leaf lists touch the leaf by the ball's exact
//! test, where the build stores a primitive in each cell holding one of its vertices (a
//! ball's are its box's corners).

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::{KdTree, Orthtree};
use rand::RngExt;

use crate::newcomer::{Ball, random_vec3, rng};

/// Balls as in the newcomer's try: centres over a 100-wide cube away from the origin (so
/// coordinates carry rounding), radii 0.2 to 2.2.
fn scattered_balls(seed: u64, n: usize) -> Vec<Ball> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| Ball {
            center: random_vec3(&mut rng, 50.0) + Vec3::splat(50.0),
            radius: rng.random_range(0.2..2.2),
            honest: true,
        })
        .collect()
}

#[test]
fn the_kd_tree_and_the_octree_validate_thousands_of_custom_balls_and_answer_as_brute_force() {
    for (seed, n) in [(31, 1000), (32, 2000), (33, 5000)] {
        let balls = scattered_balls(seed, n);
        let brute = BruteForce::build(&balls);
        let kd = KdTree::build(&balls);
        let octree = Orthtree::<Ball>::build(&balls);
        if let Err(e) = kd.validate() {
            panic!("{n} balls: the k-d tree's validate(): {e}");
        }
        if let Err(e) = octree.validate() {
            panic!("{n} balls: the octree's validate(): {e}");
        }
        let mut rng = rng(seed + 100);
        let mut hits = 0;
        for _ in 0..200 {
            let from = random_vec3(&mut rng, 80.0) + Vec3::splat(50.0);
            let to = random_vec3(&mut rng, 40.0) + Vec3::splat(50.0);
            let ray = Ray3::through(from, to).expect("distinct points");
            let want = brute.ray_first_hit(&ray, f32::INFINITY);
            hits += usize::from(want.is_some());
            assert_eq!(
                kd.ray_first_hit(&ray, f32::INFINITY),
                want,
                "k-d tree, {ray:?}"
            );
            assert_eq!(
                octree.ray_first_hit(&ray, f32::INFINITY),
                want,
                "octree, {ray:?}"
            );
        }
        assert!(hits > 20, "the rays must hit balls ({hits} of 200)");
        for _ in 0..50 {
            let p = random_vec3(&mut rng, 60.0) + Vec3::splat(50.0);
            let want = brute.k_nearest(p, 3);
            assert_eq!(kd.k_nearest(p, 3), want, "k-d tree at {p}");
            assert_eq!(octree.k_nearest(p, 3), want, "octree at {p}");
        }
    }
}
