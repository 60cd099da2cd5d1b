//! Property tests for the grid and the quadtree/octree: any finite input, however extreme
//! (coordinates from 1e-30 to `f32::MAX`, signed zeros, everything coincident, all in one
//! plane), builds a valid structure, and every query answers without panicking.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::grid::{Grid, GridOptions};
use bvhlab::structure::quadtree::{Orthtree, OrthtreeOptions};
use bvhlab::structure::{PointOf, RangeShape};
use bvhlab::{Aabb, Primitive, Ray, Segment2, SpatialIndex, Sphere, Triangle3, Vector};
use proptest::prelude::*;

/// A finite coordinate, drawn mostly from values that break naive arithmetic.
fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => prop::sample::select(vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            1e-30,
            -1e-30,
            1e-20,
            f32::MIN_POSITIVE,
            1e15,
            -1e15,
            1e30,
            -1e30,
            3e38,
            -3e38,
            f32::MAX,
            f32::MIN,
        ]),
        2 => (-4i32..=4).prop_map(|i| i as f32),
        2 => -1e3f32..1e3,
        1 => -1e30f32..1e30,
    ]
}

fn vec2() -> impl Strategy<Value = Vec2> {
    (coord(), coord()).prop_map(|(x, y)| Vec2::new(x, y))
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Builds both structures (with default and with extreme options) and runs every query.
fn exercise<P: Primitive>(prims: &[P], rays: &[(P::Point, P::Point)], points: &[P::Point]) {
    let grids = [
        Grid::build(prims),
        Grid::build_with(
            prims,
            &GridOptions {
                resolution: Some([3, 1, 2]),
                ..GridOptions::default()
            },
        ),
        Grid::build_with(
            prims,
            &GridOptions {
                density: 1e6,
                max_cells: 600,
                ..GridOptions::default()
            },
        ),
    ];
    let trees = [
        Orthtree::build(prims),
        Orthtree::build_with(
            prims,
            &OrthtreeOptions {
                leaf_size: 1,
                max_depth: 12,
            },
        ),
    ];
    for grid in &grids {
        run_queries(grid, &grids[0], rays, points);
    }
    for tree in &trees {
        run_queries(tree, &trees[0], rays, points);
    }
}

fn run_queries<S: SpatialIndex>(
    structure: &S,
    other: &S,
    rays: &[(PointOf<S>, PointOf<S>)],
    points: &[PointOf<S>],
) {
    if let Err(e) = structure.validate() {
        panic!("{e}");
    }
    let stats = structure.stats();
    assert_eq!(stats.primitives, structure.primitives().len());
    for &(origin, dir) in rays {
        let Ok(ray) = Ray::new(origin, dir) else {
            continue;
        };
        for t_max in [f32::INFINITY, 1.0, 0.0] {
            let first = structure.ray_first_hit(&ray, t_max);
            let any = structure.ray_any_hit(&ray, t_max);
            let all = structure.ray_all_hits(&ray, t_max);
            assert_eq!(first.is_some(), any.is_some());
            assert_eq!(first.is_some(), !all.is_empty());
        }
    }
    for &point in points {
        for k in [0, 1, 3] {
            let nearest = structure.k_nearest(point, k);
            assert!(nearest.len() <= k);
        }
        for radius in [0.0, 1.0, 1e30] {
            structure.range(&RangeShape::Ball(Sphere::new(point, radius)));
        }
        let corner = point * 0.5 + PointOf::<S>::splat(1.0);
        structure.range(&RangeShape::Box(Aabb::new(
            point.min(corner),
            point.max(corner),
        )));
    }
    structure.collide(other);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn segments_never_panic(
        ends in prop::collection::vec((vec2(), vec2()), 0..14),
        rays in prop::collection::vec((vec2(), vec2()), 1..5),
        points in prop::collection::vec(vec2(), 1..4),
    ) {
        let prims: Vec<Segment2> = ends.iter().map(|&(a, b)| Segment2::new(a, b)).collect();
        exercise(&prims, &rays, &points);
    }

    #[test]
    fn triangles_never_panic(
        corners in prop::collection::vec((vec3(), vec3(), vec3()), 0..12),
        rays in prop::collection::vec((vec3(), vec3()), 1..5),
        points in prop::collection::vec(vec3(), 1..4),
    ) {
        let prims: Vec<Triangle3> = corners.iter().map(|&(a, b, c)| Triangle3::new(a, b, c)).collect();
        exercise(&prims, &rays, &points);
    }

    #[test]
    fn point_clouds_never_panic(
        cloud2 in prop::collection::vec(vec2(), 0..16),
        cloud3 in prop::collection::vec(vec3(), 0..16),
        rays in prop::collection::vec((vec3(), vec3()), 1..4),
        points in prop::collection::vec(vec3(), 1..4),
    ) {
        let rays2: Vec<(Vec2, Vec2)> = rays.iter().map(|(o, d)| (o.truncate(), d.truncate())).collect();
        let points2: Vec<Vec2> = points.iter().map(|p| p.truncate()).collect();
        exercise(&cloud2, &rays2, &points2);
        exercise(&cloud3, &rays, &points);
    }

    #[test]
    fn coincident_and_flat_input_never_panics(
        corner in vec3(),
        copies in 1usize..40,
        flat in prop::collection::vec((-8i32..8, -8i32..8, -8i32..8, -8i32..8), 1..30),
        rays in prop::collection::vec((vec3(), vec3()), 1..4),
    ) {
        let same = vec![Triangle3::new(corner, corner, corner); copies];
        exercise(&same, &rays, &[corner]);
        let plane: Vec<Triangle3> = flat
            .iter()
            .map(|&(a, b, c, d)| {
                let p = |x: i32, y: i32| Vec3::new(x as f32, y as f32, corner.z);
                Triangle3::new(p(a, b), p(c, d), p(a, d))
            })
            .collect();
        exercise(&plane, &rays, &[corner]);
        let dim = <Vec3 as Vector>::DIM;
        prop_assert_eq!(dim, 3);
    }
}
