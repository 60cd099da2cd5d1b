//! Every query of every tree kind (AABB, sphere, OBB) and every builder agrees with brute
//! force on seeded random scenes: segments and points in 2D, triangles and points in 3D.

use crate::bvh_common;

use bvh_common::scenes::random;
use bvh_common::{Budget, TestPrim, check_collide, check_scene, rng};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{BvhOptions, NodeVolume, SphereFit, SplitMethod};
use bvhlab::{Aabb, Obb, Sphere};

fn run<B, P>(seed: u64, options: &BvhOptions)
where
    B: NodeVolume<Point = P::Point>,
    P: TestPrim,
{
    let mut rng = rng(seed);
    let prims: Vec<P> = random(&mut rng, 500);
    let budget = Budget::default();
    let checked = check_scene::<B, P>("random", &prims, options, &mut rng, budget);
    // Points are never hit by random rays; segments and triangles must be, often.
    if prims[0].vertices().count() > 1 {
        assert!(
            checked.rays_hit * 4 >= budget.rays,
            "only {} rays hit",
            checked.rays_hit
        );
    }
    // A second scene that overlaps the first in many places.
    let other: Vec<P> = random(&mut rng, 200);
    check_collide::<B, P>("random pair", &prims, &other, options);
}

/// One test per primitive kind for a node volume type constructor.
macro_rules! volume_tests {
    ($module:ident, $volume:ident) => {
        mod $module {
            use super::*;

            #[test]
            fn segments_2d() {
                run::<$volume<Vec2>, Segment2>(11, &BvhOptions::default());
            }
            #[test]
            fn triangles_3d() {
                run::<$volume<Vec3>, Triangle3>(12, &BvhOptions::default());
            }
            #[test]
            fn points_2d() {
                run::<$volume<Vec2>, Vec2>(13, &BvhOptions::default());
            }
            #[test]
            fn points_3d() {
                run::<$volume<Vec3>, Vec3>(14, &BvhOptions::default());
            }
            #[test]
            fn median_builders() {
                for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
                    let options = BvhOptions {
                        leaf_size: 2,
                        ..BvhOptions::with_method(method)
                    };
                    run::<$volume<Vec2>, Segment2>(15, &options);
                    run::<$volume<Vec3>, Triangle3>(16, &options);
                }
            }
            #[test]
            fn one_primitive_per_leaf_and_few_bins() {
                let options = BvhOptions {
                    leaf_size: 1,
                    bins: 2,
                    ..BvhOptions::default()
                };
                run::<$volume<Vec3>, Triangle3>(17, &options);
                let options = BvhOptions {
                    leaf_size: 16,
                    bins: 64,
                    ..BvhOptions::default()
                };
                run::<$volume<Vec2>, Segment2>(18, &options);
            }
        }
    };
}

volume_tests!(aabb, Aabb);
volume_tests!(sphere, Sphere);
volume_tests!(obb, Obb);

#[test]
fn welzl_spheres() {
    let options = BvhOptions {
        sphere_fit: SphereFit::Welzl,
        ..BvhOptions::default()
    };
    run::<Sphere<Vec3>, Triangle3>(19, &options);
    run::<Sphere<Vec2>, Vec2>(20, &options);
}

#[test]
fn shallow_trees_with_big_leaves() {
    for max_depth in [0, 1, 3] {
        let options = BvhOptions {
            max_depth,
            ..BvhOptions::default()
        };
        run::<Aabb<Vec3>, Triangle3>(21, &options);
        run::<Obb<Vec2>, Segment2>(22, &options);
    }
}
