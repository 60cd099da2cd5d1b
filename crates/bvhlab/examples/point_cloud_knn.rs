//! Nearest neighbours in a point cloud: the points themselves are the primitives (`Vec3`
//! implements [`Primitive`]), so a [`KdTree`] or a [`Bvh4`] built over a `&[Vec3]` answers
//! the k nearest points and the points in a ball or a box. The k-d tree is the textbook one
//! of Friedman, Bentley and Finkel ("An Algorithm for Finding Best Matches in Logarithmic
//! Expected Time", ACM TOMS 1977); [`BruteForce`], which tests every point, checks both.
//!
//! Run: `cargo run -p bvhlab --example point_cloud_knn -- [points]` (default 100000).
#![expect(clippy::print_stdout, reason = "an example that prints what it found")]

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::{BruteForce, Bvh4, KdTree, RangeShape};

fn main() {
    let count = std::env::args()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(100_000);
    let points = random_points(count, 1);
    let query = Vec3::splat(0.5);
    let k = 5;

    // Build once, query many times. `KdTree::build` over points splits at the median with
    // leaves of at most 4 points; `Bvh4::build` groups them into boxes (binned SAH).
    let kd_tree = KdTree::build(&points);
    let bvh = Bvh4::build(&points);

    let nearest = kd_tree.k_nearest(query, k);
    println!("the {k} points nearest to {query} among {count}:");
    for n in &nearest {
        // `prim` is the point's index in `points`; `point` is the point, `distance` its
        // distance from the query.
        println!("  #{:<6} {} at {:.4}", n.prim, n.point, n.distance);
    }
    assert_eq!(bvh.k_nearest(query, k), nearest, "every structure agrees");

    // Every point within 0.05 of the query (a ball), and every point in a box.
    let ball = RangeShape::Ball(Sphere3::new(query, 0.05));
    let cube = RangeShape::Box(Aabb3::new(Vec3::splat(0.45), Vec3::splat(0.55)));
    println!(
        "{} points within 0.05, {} in the cube of side 0.1 around it",
        kd_tree.range(&ball).len(),
        kd_tree.range(&cube).len()
    );

    // Why build a tree: the `_observed` form also returns what the query cost.
    let tree_cost = kd_tree.k_nearest_observed(query, k, &mut ()).cost;
    let brute_cost = BruteForce::build(&points)
        .k_nearest_observed(query, k, &mut ())
        .cost;
    println!(
        "the k-d tree tested {} points, brute force {}",
        tree_cost.prim_tests, brute_cost.prim_tests
    );
}

/// `count` points spread over the unit cube by a tiny seeded generator (`SplitMix64`,
/// Steele, Lea and Flood, OOPSLA 2014), so the example needs no other crate.
fn random_points(count: usize, seed: u64) -> Vec<Vec3> {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        // The top 24 bits, as a float in [0, 1).
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|_| Vec3::new(next(), next(), next()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::Nearest;

    /// The answers of the two trees and of brute force for one query point: the k nearest, the
    /// points in a ball and the points in a box around it.
    struct Answers {
        k_nearest: [Vec<Nearest<Vec3>>; 3],
        in_ball: [Vec<usize>; 3],
        in_box: [Vec<usize>; 3],
    }

    /// Asks the k-d tree, the 4-wide BVH and brute force the same three questions.
    fn ask_all(points: &[Vec3], query: Vec3, k: usize, radius: f32) -> Answers {
        let (kd_tree, bvh, brute) = (
            KdTree::build(points),
            Bvh4::build(points),
            BruteForce::build(points),
        );
        let ball = RangeShape::Ball(Sphere3::new(query, radius));
        let cube = RangeShape::Box(Aabb3::new(query - radius, query + radius));
        Answers {
            k_nearest: [
                kd_tree.k_nearest(query, k),
                bvh.k_nearest(query, k),
                brute.k_nearest(query, k),
            ],
            in_ball: [kd_tree.range(&ball), bvh.range(&ball), brute.range(&ball)],
            in_box: [kd_tree.range(&cube), bvh.range(&cube), brute.range(&cube)],
        }
    }

    #[test]
    fn example_runs_and_agrees_with_brute_force() {
        let points = random_points(2000, 2);
        for (i, query) in random_points(20, 3).into_iter().enumerate() {
            let Answers {
                k_nearest: [kd, wide, brute],
                in_ball,
                in_box,
            } = ask_all(&points, query, 1 + i % 8, 0.1);
            assert_eq!((&kd, &wide), (&brute, &brute), "k nearest to {query}");
            assert_eq!(brute.len(), 1 + i % 8);
            // Nearest first, and each distance is the distance to that point.
            assert!(brute.windows(2).all(|w| w[0].distance <= w[1].distance));
            assert!(
                brute
                    .iter()
                    .all(|n| n.point == points[n.prim] && n.distance == n.point.distance(query))
            );
            for found in [in_ball, in_box] {
                assert_eq!((&found[0], &found[1]), (&found[2], &found[2]), "{query}");
            }
        }
        // A ball of radius 0.1 holds about 4.2 thousandths of the cube: 8 of 2000 points.
        let Answers { in_ball, .. } = ask_all(&points, Vec3::splat(0.5), 1, 0.1);
        assert!((2..30).contains(&in_ball[2].len()), "{:?}", in_ball[2]);
    }
}
