//! [`Bvh4::range`], [`Bvh4::range_count`] and [`Bvh4::range_for_each`] answer as brute force
//! now that a lane wholly inside the region is taken without testing its primitives (issue
//! 33): on seeded random points in 2D and 3D (with duplicates and non-finite points), on a
//! real mesh's triangles, and on integer grids whose points lie exactly on a ball's surface
//! or a box's face, for balls and boxes from radius 0 to beyond the scene, and for empty and
//! NaN regions. A counting primitive shows that the whole lanes are taken: a large ball tests
//! far fewer primitives than it finds.

use std::cell::Cell;

use crate::bvh_common;

use bvh_common::{random_vector, rng, scene_box, shared_mesh};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh4, BvhOptions};
use bvhlab::structure::{BruteForce, RangeShape};
use bvhlab::{Aabb, Ray, Sphere};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// The three forms against brute force on one region: the same indices, the same count,
/// and every index visited once by the callback. Returns how many were found.
fn check<P: Primitive>(
    name: &str,
    wide: &Bvh4<P>,
    brute: &BruteForce<P>,
    shape: &RangeShape<P::Point>,
) -> usize {
    let expected = brute.range(shape);
    assert_eq!(wide.range(shape), expected, "{name}: range {shape:?}");
    assert_eq!(
        wide.range_count(shape),
        expected.len(),
        "{name}: count {shape:?}"
    );
    let mut visited = Vec::new();
    wide.range_for_each(shape, |index| visited.push(index));
    let visits = visited.len();
    visited.sort_unstable();
    visited.dedup();
    assert_eq!(visited.len(), visits, "{name}: an index visited twice");
    assert_eq!(visited, expected, "{name}: for each {shape:?}");
    expected.len()
}

/// Balls and boxes around `point` with sizes from 0 to twice the scene, plus the scene's own
/// box and a ball around it.
fn shapes_at<V: Vector>(rng: &mut ChaCha8Rng, point: V, size: f32) -> Vec<RangeShape<V>> {
    let mut shapes = Vec::new();
    for scale in [0.0, 1e-4, 0.01, 0.05, 0.2, 0.5, 1.0, 2.0] {
        let radius = scale * size * rng.random_range(0.5f32..1.0);
        shapes.push(RangeShape::Ball(Sphere::new(point, radius)));
        let corner = point + random_vector::<V>(rng, scale * size);
        shapes.push(RangeShape::Box(Aabb::new(
            point.min(corner),
            point.max(corner),
        )));
    }
    shapes
}

/// Every form against brute force on `prims`, with regions at random points and at
/// primitives' own centroids (so that radius 0 finds them); returns how many were found.
fn check_scene<P: Primitive>(
    name: &str,
    prims: &[P],
    rng: &mut ChaCha8Rng,
    points: usize,
) -> usize {
    let brute = BruteForce::build(prims);
    let (bounds, size) = scene_box(prims);
    let mut found = 0;
    for options in [
        BvhOptions::default(),
        BvhOptions {
            leaf_size: 16,
            ..BvhOptions::default()
        },
    ] {
        let wide = Bvh4::build_with(prims, &options);
        wide.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        let scene = RangeShape::Ball(Sphere::new(bounds.center(), size));
        found += check(name, &wide, &brute, &scene);
        found += check(name, &wide, &brute, &RangeShape::Box(bounds));
        for i in 0..points {
            let point = if i % 2 == 0 {
                bounds.center() + random_vector::<P::Point>(rng, 0.6 * size)
            } else {
                prims[rng.random_range(0..prims.len())].centroid()
            };
            for shape in shapes_at(rng, point, size) {
                found += check(name, &wide, &brute, &shape);
            }
        }
    }
    found
}

/// `n` random points in `[-10, 10]^DIM`, a tenth of them repeated and a few non-finite.
fn cloud<V: Vector>(rng: &mut ChaCha8Rng, n: usize) -> Vec<V> {
    let mut points: Vec<V> = (0..n).map(|_| random_vector(rng, 10.0)).collect();
    for i in 0..n / 10 {
        let twin = points[rng.random_range(0..n)];
        points[i * 7 % n] = twin;
    }
    points.push(V::splat(f32::NAN));
    points.push(V::splat(f32::INFINITY));
    points
}

#[test]
fn points_in_3d_match_brute_force() {
    let mut rng = rng(3301);
    let points = cloud::<Vec3>(&mut rng, 4_000);
    let found = check_scene("3D points", &points, &mut rng, 12);
    assert!(found > 10_000, "the ranges found something: {found}");
}

#[test]
fn points_in_2d_match_brute_force() {
    let mut rng = rng(3302);
    let points = cloud::<Vec2>(&mut rng, 4_000);
    let found = check_scene("2D points", &points, &mut rng, 12);
    assert!(found > 10_000, "the ranges found something: {found}");
}

#[test]
fn mesh_triangles_match_brute_force() {
    let Some(tris) = shared_mesh("spot.obj") else {
        return;
    };
    let mut rng = rng(3303);
    let found = check_scene("spot.obj", &tris, &mut rng, 8);
    assert!(found > 10_000, "the ranges found something: {found}");
}

/// Grid points `offset + step * (i, j, k)` for `0 <= i, j, k < n`.
fn grid3(n: i32, step: f32, offset: f32) -> Vec<Vec3> {
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let ijk = Vec3::new(i as f32, j as f32, k as f32);
                points.push(Vec3::splat(offset) + ijk * step);
            }
        }
    }
    points
}

/// Balls whose radius is exactly a distance between grid points (3, 5 = |(3, 4, 0)|,
/// 7 = |(2, 3, 6)|, and the rounded √2 and √3), so that many points lie on the surface up
/// to rounding; boxes whose faces are grid planes.
#[test]
fn grid_points_on_the_surface_match_brute_force() {
    for (step, offset) in [(1.0, 0.0), (0.5, -3.0), (0.25, 1000.0), (3.0, -1e6)] {
        let name = format!("grid of step {step} at {offset}");
        let points = grid3(17, step, offset);
        let wide = Bvh4::build(&points);
        let brute = BruteForce::build(&points);
        let mut on_surface = 0;
        for centre in [[8, 8, 8], [0, 0, 0], [3, 5, 8], [16, 1, 9]] {
            let centre = Vec3::splat(offset) + Vec3::from(centre.map(|c: i32| c as f32)) * step;
            for units in [0.0, 1.0, 2f32.sqrt(), 3f32.sqrt(), 3.0, 5.0, 7.0, 8.0, 30.0] {
                let radius = units * step;
                let ball = RangeShape::Ball(Sphere::new(centre, radius));
                check(&name, &wide, &brute, &ball);
                on_surface += points
                    .iter()
                    .filter(|p| p.distance(centre) == radius)
                    .count();
                for half in [0.0, 1.0, 3.0, 5.0] {
                    let half = Vec3::new(half, half + 1.0, half + 2.0) * step;
                    let boxed = RangeShape::Box(Aabb::new(centre - half, centre + half));
                    check(&name, &wide, &brute, &boxed);
                }
            }
        }
        assert!(
            on_surface > 100,
            "{name}: points on the surface: {on_surface}"
        );
    }
}

/// The same on a 2D grid, with the radius of the 3-4-5 and 5-12-13 triangles.
#[test]
fn grid_points_on_the_circle_match_brute_force() {
    let mut points = Vec::new();
    for i in 0..41 {
        for j in 0..41 {
            points.push(Vec2::new(i as f32, j as f32) * 0.5 + Vec2::splat(-7.0));
        }
    }
    let wide = Bvh4::build(&points);
    let brute = BruteForce::build(&points);
    for centre in [
        Vec2::new(3.0, 3.0),
        Vec2::new(-7.0, -7.0),
        Vec2::new(0.5, 6.0),
    ] {
        for radius in [0.0, 0.5, 2.5, 6.5, 2f32.sqrt() * 0.5, 100.0] {
            check(
                "2D grid",
                &wide,
                &brute,
                &RangeShape::Ball(Sphere::new(centre, radius)),
            );
            let half = Vec2::new(radius, radius * 0.5);
            let boxed = RangeShape::Box(Aabb::new(centre - half, centre + half));
            check("2D grid", &wide, &brute, &boxed);
        }
    }
}

/// Radius 0 finds exactly the points at the centre; an empty box, a negative or NaN radius
/// and a NaN centre or corner find nothing; an infinite radius or box finds every finite
/// primitive (and no non-finite one); an empty tree finds nothing.
#[test]
fn degenerate_regions_match_brute_force() {
    let mut rng = rng(3304);
    let points = cloud::<Vec3>(&mut rng, 2_000);
    let wide = Bvh4::build(&points);
    let brute = BruteForce::build(&points);
    let p = points[5];
    let nan = Vec3::splat(f32::NAN);
    let inf = f32::INFINITY;
    let at_p = check("3D", &wide, &brute, &RangeShape::Ball(Sphere::new(p, 0.0)));
    assert!(at_p >= 1, "radius 0 at a point finds it");
    let nothing = [
        RangeShape::Ball(Sphere::new(p, -1.0)),
        RangeShape::Ball(Sphere::new(p, f32::NAN)),
        RangeShape::Ball(Sphere::new(nan, 1e9)),
        RangeShape::Box(Aabb::new(p + Vec3::ONE, p)),
        RangeShape::Box(Aabb::new(nan, p)),
        RangeShape::Box(Aabb::new(Vec3::splat(-inf), nan)),
    ];
    for shape in &nothing {
        assert_eq!(check("3D", &wide, &brute, shape), 0, "{shape:?}");
    }
    let everything = [
        RangeShape::Ball(Sphere::new(p, inf)),
        RangeShape::Ball(Sphere::new(Vec3::ZERO, f32::MAX)),
        RangeShape::Ball(Sphere::new(Vec3::splat(1e15), 3e15)),
        RangeShape::Box(Aabb::new(Vec3::splat(-inf), Vec3::splat(inf))),
        RangeShape::Box(Aabb::new(Vec3::splat(-f32::MAX), Vec3::splat(f32::MAX))),
    ];
    for shape in &everything {
        assert_eq!(check("3D", &wide, &brute, shape), wide.len(), "{shape:?}");
    }
    // Far away the squares overflow: every distance is computed as +inf, so brute force finds
    // nothing, and neither may a lane taken whole.
    let overflowing = RangeShape::Ball(Sphere::new(Vec3::splat(1e30), 3e30));
    assert_eq!(check("3D", &wide, &brute, &overflowing), 0);
    assert_eq!(
        wide.len(),
        points.len() - 2,
        "the non-finite points are left out"
    );
    let empty = Bvh4::<Vec3>::build(&[]);
    let ball = RangeShape::Ball(Sphere::new(Vec3::ZERO, inf));
    assert_eq!(empty.range_count(&ball), 0);
    assert!(empty.range(&ball).is_empty());
}

thread_local! {
    /// How many primitive tests [`Counted`] answered on this thread.
    static TESTS: Cell<usize> = const { Cell::new(0) };
}

/// A point that counts the tests a range query makes of it (the distance of a ball goes
/// through `project_point`, a box through `intersects_aabb`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Counted(Vec3);

impl Primitive for Counted {
    type Point = Vec3;

    fn bounds(&self) -> Aabb<Vec3> {
        self.0.bounds()
    }
    fn centroid(&self) -> Vec3 {
        self.0
    }
    fn ray_hit(&self, ray: &Ray<Vec3>) -> Option<f32> {
        self.0.ray_hit(ray)
    }
    fn project_point(&self, _point: Vec3) -> Vec3 {
        TESTS.with(|t| t.set(t.get() + 1));
        self.0
    }
    fn measure(&self) -> f32 {
        0.0
    }
    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
    fn vertices(&self) -> impl Iterator<Item = Vec3> {
        std::iter::once(self.0)
    }
    fn intersects_aabb(&self, aabb: &Aabb<Vec3>) -> bool {
        TESTS.with(|t| t.set(t.get() + 1));
        self.0.intersects_aabb(aabb)
    }
    fn intersects(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

/// The primitive tests `query` makes, and what it returns.
fn tests_of<T>(query: impl FnOnce() -> T) -> (usize, T) {
    TESTS.with(|t| t.set(0));
    let answer = query();
    (TESTS.with(Cell::get), answer)
}

/// A large ball and a large box over 60k uniform points: every form finds what brute force
/// finds, while testing fewer than a third as many primitives as it finds (a walk that
/// tests every primitive it reports, as before issue 33, tests at least as many).
#[test]
fn whole_lanes_are_taken_without_tests() {
    let mut rng = rng(3305);
    let points: Vec<Counted> = (0..60_000)
        .map(|_| Counted(Vec3::new(rng.random(), rng.random(), rng.random())))
        .collect();
    let wide = Bvh4::build(&points);
    let brute = BruteForce::build(&points);
    let regions = [
        RangeShape::Ball(Sphere::new(Vec3::splat(0.5), 0.45)),
        RangeShape::Box(Aabb::new(Vec3::splat(0.1), Vec3::new(0.9, 0.8, 0.95))),
    ];
    for shape in &regions {
        let (_, expected) = tests_of(|| brute.range(shape));
        let (tests, found) = tests_of(|| wide.range(shape));
        assert_eq!(found, expected, "{shape:?}");
        assert!(
            found.len() > 20_000,
            "{shape:?} holds many: {}",
            found.len()
        );
        assert!(
            tests * 3 < found.len(),
            "{shape:?}: {tests} tests for {} found",
            found.len()
        );
        let (count_tests, count) = tests_of(|| wide.range_count(shape));
        assert_eq!((count_tests, count), (tests, found.len()), "{shape:?}");
        let (each_tests, each) = tests_of(|| {
            let mut n = 0;
            wide.range_for_each(shape, |_| n += 1);
            n
        });
        assert_eq!((each_tests, each), (tests, found.len()), "{shape:?}");
    }
}
