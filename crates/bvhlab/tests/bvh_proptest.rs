//! Property tests: builds and queries over primitives with extreme finite coordinates
//! (0, ±1e-30, ±1e30, `±f32::MAX`, subnormals, any finite value) never panic, always give a
//! well-formed tree, and report only real hits.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::RangeShape;
use bvhlab::structure::bvh::{Bvh, BvhOptions, NodeVolume, SplitMethod};
use bvhlab::{Aabb, Obb, Ray, Sphere};
use proptest::prelude::*;

fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -10.0f32..10.0,
        1 => prop::sample::select(vec![
            0.0, -0.0, 1e-30, -1e-30, 1e30, -1e30, f32::MAX, f32::MIN, f32::MIN_POSITIVE, 1e-45, 3.0e38
        ]),
        1 => prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
    ]
}

fn vec2() -> impl Strategy<Value = Vec2> {
    (coordinate(), coordinate()).prop_map(|(x, y)| Vec2::new(x, y))
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Builds every tree kind with every builder and runs every query once.
fn exercise<B, P>(prims: &[P], origin: P::Point, dir: P::Point, radius: f32)
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    for method in [
        SplitMethod::BinnedSah,
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
    ] {
        let options = BvhOptions {
            leaf_size: 2,
            ..BvhOptions::with_method(method)
        };
        let bvh = Bvh::<B, P>::build_with(prims, &options);
        if let Err(e) = bvh.validate() {
            panic!("{} tree, {method:?}: {e}", B::NAME);
        }
        let _ = bvh.stats();
        if let Ok(ray) = Ray::new(origin, dir) {
            for t_max in [f32::INFINITY, 1.0] {
                if let Some(hit) = bvh.ray_first_hit(&ray, t_max) {
                    assert_eq!(prims[hit.prim].ray_hit(&ray), Some(hit.t));
                }
                if let Some(hit) = bvh.ray_any_hit(&ray, t_max) {
                    assert_eq!(prims[hit.prim].ray_hit(&ray), Some(hit.t));
                }
                for hit in bvh.ray_all_hits(&ray, t_max) {
                    assert_eq!(prims[hit.prim].ray_hit(&ray), Some(hit.t));
                }
            }
        }
        let _ = bvh.k_nearest(origin, 3);
        let _ = bvh.range(&RangeShape::Ball(Sphere::new(origin, radius)));
        let _ = bvh.range(&RangeShape::Box(Aabb::new(
            origin.min(dir),
            origin.max(dir),
        )));
        let _ = bvh.collide(&bvh);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn segments_never_panic(
        ends in prop::collection::vec((vec2(), vec2()), 0..24),
        origin in vec2(), dir in vec2(), radius in coordinate(),
    ) {
        let prims: Vec<Segment2> = ends.into_iter().map(|(a, b)| Segment2::new(a, b)).collect();
        exercise::<Aabb<Vec2>, Segment2>(&prims, origin, dir, radius);
        exercise::<Sphere<Vec2>, Segment2>(&prims, origin, dir, radius);
        exercise::<Obb<Vec2>, Segment2>(&prims, origin, dir, radius);
    }

    #[test]
    fn triangles_never_panic(
        corners in prop::collection::vec((vec3(), vec3(), vec3()), 0..24),
        origin in vec3(), dir in vec3(), radius in coordinate(),
    ) {
        let prims: Vec<Triangle3> = corners.into_iter().map(|(a, b, c)| Triangle3::new(a, b, c)).collect();
        exercise::<Aabb<Vec3>, Triangle3>(&prims, origin, dir, radius);
        exercise::<Sphere<Vec3>, Triangle3>(&prims, origin, dir, radius);
        exercise::<Obb<Vec3>, Triangle3>(&prims, origin, dir, radius);
    }

    #[test]
    fn points_never_panic(
        points in prop::collection::vec(vec3(), 0..32),
        origin in vec3(), dir in vec3(), radius in coordinate(),
    ) {
        exercise::<Aabb<Vec3>, Vec3>(&points, origin, dir, radius);
        exercise::<Sphere<Vec3>, Vec3>(&points, origin, dir, radius);
        exercise::<Obb<Vec3>, Vec3>(&points, origin, dir, radius);
    }
}
