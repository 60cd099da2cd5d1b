//! Regression: a k-d tree built with its defaults over a point cloud kept big leaves. The
//! SAH builder, then the default for every primitive, cut empty slivers off its cells until
//! the depth limit: over 200k random points, 852 leaves of 32 points or more and 2908 empty
//! ones (a mean of 53 references per leaf), and closest points 20 times slower than the
//! 4-wide BVH's. `KdTree::build` now takes the median builder with leaves of up to 4 for
//! points ([`KdTreeOptions::for_primitives`]).

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::kdtree::{AxisRule, KdBuilder, KdTree, KdTreeOptions};
use bvhlab::structure::{BruteForce, Stats};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The largest leaf (the histogram's last bucket, below its 32+ bucket) and the mean
/// references per leaf.
fn leaf_sizes(stats: &Stats) -> (usize, f64) {
    let largest = stats.leaf_sizes.len().saturating_sub(1);
    (
        largest,
        stats.references as f64 / stats.leaves.max(1) as f64,
    )
}

#[test]
fn kdtree_defaults_keep_point_cloud_leaves_small() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let points: Vec<Vec3> = (0..200_000)
        .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
        .collect();
    let tree = KdTree::build(&points);
    tree.validate().expect("a well-formed tree");
    let stats = tree.stats();
    let (largest, mean) = leaf_sizes(&stats);
    assert!(largest <= 4, "a leaf of {largest} points: {stats:?}");
    assert!(
        (2.0..=4.0).contains(&mean),
        "{mean} points per leaf: {stats:?}"
    );
    assert_eq!(
        stats.leaf_sizes.first(),
        Some(&0),
        "empty leaves: {stats:?}"
    );
    assert_eq!(stats.references, points.len(), "a point is in one leaf");
    assert!(stats.max_depth <= 18, "depth {}", stats.max_depth);
    let brute = BruteForce::build(&points);
    for _ in 0..40 {
        let query = Vec3::new(rng.random(), rng.random(), rng.random()) * 1.2 - 0.1;
        assert_eq!(tree.closest_point(query), brute.closest_point(query));
        assert_eq!(tree.k_nearest(query, 8), brute.k_nearest(query, 8));
    }
}

/// Points pick the median builder, in 2D too; segments and triangles keep the SAH.
#[test]
fn kdtree_default_builder_follows_the_primitives() {
    let median = KdBuilder::Median(AxisRule::LongestAxis);
    let points = [Vec2::ZERO, Vec2::X, Vec2::new(f32::NAN, 0.0)];
    assert_eq!(KdTreeOptions::for_primitives(&points).builder, median);
    assert_eq!(KdTree::build(&points).options().builder, median);
    let segments = [Segment2::new(Vec2::ZERO, Vec2::X)];
    assert_eq!(
        KdTreeOptions::for_primitives(&segments),
        KdTreeOptions::sah()
    );
    let triangles = [Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
    assert_eq!(KdTree::build(&triangles).options(), &KdTreeOptions::sah());
    assert_eq!(
        KdTreeOptions::for_primitives::<Vec3>(&[]),
        KdTreeOptions::sah()
    );
}
