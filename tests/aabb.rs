//! Axis-aligned boxes: the lecture's slab test and its "when does this fail?" cases, then
//! random rays, distances and overlaps against sampling, in 2D and 3D.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb, Vector};
use bvhlab_tests::{
    assert_interval_matches_sampling, random_cloud, random_ray, random_vector, rng,
};
use rand::RngExt;

fn unit_square() -> Aabb2 {
    Aabb2::new(Vec2::ZERO, Vec2::ONE)
}

fn ray2(o: (f32, f32), d: (f32, f32)) -> Ray2 {
    Ray2::new(Vec2::new(o.0, o.1), Vec2::new(d.0, d.1)).expect("valid test ray")
}

#[test]
fn zero_and_negative_zero_direction_components() {
    let b = unit_square();
    for zero in [0.0, -0.0] {
        // Parallel to the x slabs, inside them: decided by y alone.
        assert_eq!(
            b.ray_interval(&ray2((0.5, -1.0), (zero, 1.0))),
            Some((1.0, 2.0))
        );
        assert_eq!(
            b.ray_interval(&ray2((0.5, 3.0), (zero, -2.0))),
            Some((1.0, 1.5))
        );
        // Parallel and outside the x slabs: a miss, whatever y does.
        assert_eq!(b.ray_interval(&ray2((1.5, -1.0), (zero, 1.0))), None);
        assert_eq!(b.ray_interval(&ray2((-0.5, -1.0), (zero, 1.0))), None);
    }
}

/// The lecture's failure case: `x_d = 0` with the origin exactly on a slab plane gives
/// `(x_min - x_e) / x_d = 0 / 0 = NaN` in the naive test. Boxes are closed, so these hit.
#[test]
fn origin_exactly_on_a_slab_plane_with_a_parallel_direction() {
    let b = unit_square();
    for zero in [0.0, -0.0] {
        for x in [0.0, 1.0] {
            let test = b.slab_test(&ray2((x, -1.0), (zero, 1.0)));
            assert!(!test.t_near.is_nan() && !test.t_far.is_nan(), "{test:?}");
            assert_eq!(test.interval(), Some((1.0, 2.0)));
        }
    }
    let cube = Aabb3::new(Vec3::ZERO, Vec3::ONE);
    let along_edge = Ray3::new(Vec3::new(1.0, 0.0, -3.0), Vec3::new(-0.0, 0.0, 2.0)).expect("ray");
    assert_eq!(cube.ray_interval(&along_edge), Some((1.5, 2.0)));
}

#[test]
fn rays_along_a_face_touching_a_corner_starting_inside_or_behind() {
    let b = unit_square();
    // Along the top face (in its plane): hits over the face's extent.
    assert_eq!(
        b.ray_interval(&ray2((-1.0, 1.0), (1.0, 0.0))),
        Some((1.0, 2.0))
    );
    // Touching the corner (0, 1) only: t_enter == t_exit.
    assert_eq!(
        b.ray_interval(&ray2((-1.0, 0.0), (1.0, 1.0))),
        Some((1.0, 1.0))
    );
    // Just past the corner: a miss.
    assert_eq!(b.ray_interval(&ray2((-1.0, 0.01), (1.0, 1.0))), None);
    // Origin inside: t_enter = 0.
    assert_eq!(
        b.ray_interval(&ray2((0.5, 0.5), (2.0, 0.0))),
        Some((0.0, 0.25))
    );
    // Box behind the origin.
    assert_eq!(b.ray_interval(&ray2((2.0, 0.5), (1.0, 0.0))), None);
    // 3D: in the plane of a face, with two zero components.
    let cube = Aabb3::new(Vec3::ZERO, Vec3::ONE);
    let in_face = Ray3::new(Vec3::new(0.5, 1.0, -1.0), Vec3::Z).expect("ray");
    assert_eq!(cube.ray_interval(&in_face), Some((1.0, 2.0)));
    let beside_face = Ray3::new(Vec3::new(0.5, 1.0 + 1e-6, -1.0), Vec3::Z).expect("ray");
    assert_eq!(cube.ray_interval(&beside_face), None);
}

#[test]
fn slab_test_shows_the_per_axis_intervals_with_swapped_ends_for_negative_directions() {
    let b = Aabb2::new(Vec2::new(1.0, 1.0), Vec2::new(3.0, 2.0));
    let test = b.slab_test(&ray2((4.0, 0.0), (-1.0, 1.0)));
    // x: t_xmin = (x_max - x_e)/x_d = 1, t_xmax = (x_min - x_e)/x_d = 3 (swapped, x_d < 0).
    assert_eq!(
        (test.t_near, test.t_far),
        (Vec2::new(1.0, 1.0), Vec2::new(3.0, 2.0))
    );
    assert_eq!((test.t_enter(), test.t_exit()), (1.0, 2.0));
    // A miss: max(t_xmin, t_ymin) > min(t_xmax, t_ymax), the lecture's "CHECK".
    let miss = b.slab_test(&ray2((0.0, 0.0), (1.0, 4.0)));
    assert!(miss.t_enter() > miss.t_exit() && miss.interval().is_none());
}

fn check_random<V: Vector>(seed: u64) {
    let mut rng = rng(seed);
    for _ in 0..300 {
        let n = rng.random_range(1..20);
        let points: Vec<V> = random_cloud(&mut rng, n, 2.0);
        let b = Aabb::from_points(&points);
        // The lecture's fit: every point inside, and every face touched by a point.
        assert!(points.iter().all(|&p| b.contains(p)));
        for i in 0..V::DIM {
            assert!(points.iter().any(|p| p.coord(i) == b.min.coord(i)));
            assert!(points.iter().any(|p| p.coord(i) == b.max.coord(i)));
        }

        let ray = random_ray::<V>(&mut rng, 5.0);
        let t_max = 12.0 / ray.dir().length();
        assert_interval_matches_sampling(
            &ray,
            b.ray_interval(&ray),
            |p| b.contains(p),
            t_max,
            1e-4 * t_max,
        );

        // Distance: never beaten by a grid of points in the box, and 0 exactly inside.
        let p: V = random_vector(&mut rng, 5.0);
        let d = b.distance(p);
        assert_eq!(d == 0.0, b.contains(p));
        for _ in 0..300 {
            let mut s = b.min;
            for i in 0..V::DIM {
                let u: f32 = rng.random_range(0.0..=1.0);
                s.set_coord(i, b.min.coord(i) + u * (b.max.coord(i) - b.min.coord(i)));
            }
            assert!(d <= (s - p).length() + 1e-5);
        }
        assert!(b.contains(b.closest_point(p).expect("non-empty").point));

        // Overlap iff the boxes share a point: test with the clamp of a random point into
        // one box, then into the other (a point of both exists iff that lands in both).
        let c = Aabb::from_points(&random_cloud::<V>(&mut rng, 3, 2.0));
        let witness = c
            .closest_point(b.closest_point(c.center()).expect("non-empty").point)
            .expect("non-empty")
            .point;
        assert_eq!(
            b.overlaps(&c),
            b.contains(witness) && c.contains(witness),
            "{b:?} {c:?}"
        );
        let m = b.merge(&c);
        assert!(b.corners().chain(c.corners()).all(|q| m.contains(q)));
    }
}

#[test]
fn random_rays_distances_and_overlaps_2d() {
    check_random::<Vec2>(20);
}

#[test]
fn random_rays_distances_and_overlaps_3d() {
    check_random::<Vec3>(21);
}

#[test]
fn measures_empty_box_and_bad_input() {
    let b = Aabb3::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!((b.measure(), b.boundary_measure()), (6.0, 22.0));
    assert_eq!(unit_square().boundary_measure(), 4.0);
    let empty = Aabb3::from_points(&[]);
    assert!(empty.is_empty() && !empty.contains(Vec3::ZERO) && empty.measure() == 0.0);
    assert_eq!(
        empty.ray_interval(&Ray3::new(Vec3::ZERO, Vec3::X).expect("ray")),
        None
    );
    assert_eq!(empty.merge(&b), b);
    assert_eq!(
        Aabb3::from_points(&[Vec3::NAN, Vec3::ONE]),
        Aabb3::new(Vec3::ONE, Vec3::ONE)
    );
    let err =
        Aabb3::try_from_points(&[Vec3::ONE, Vec3::new(0.0, f32::INFINITY, 0.0)]).expect_err("inf");
    assert!(
        err.to_string().contains("point 1") && err.to_string().contains("finite"),
        "{err}"
    );
    assert!(b.checked_distance(Vec3::NAN).is_err());
}
