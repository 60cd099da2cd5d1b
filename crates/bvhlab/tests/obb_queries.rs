//! Ray and distance queries of oriented boxes against independent references: dense
//! sampling along the ray with `contains`, the `Aabb` slab test, and brute force over a fine
//! sample of the box.

use crate::obb_common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb, Obb, Ray};
use obb_common::{offset, random_obb2, random_obb3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Checks `ray_interval` against dense sampling with `contains`: a sample inside the box
/// shrunk by `eps` must be in the interval, and a sample in the interval inside the box grown
/// by `eps` (the margin absorbs rounding for rays along a face). Returns whether it hit.
fn check_ray<V: Vector>(obb: &Obb<V>, ray: &Ray<V>) -> bool {
    let interval = obb.ray_interval(ray);
    assert_eq!(
        obb.contains(ray.origin()),
        matches!(interval, Some((t, _)) if t == 0.0),
        "t_enter = 0 exactly when the origin is inside: {obb:?} {ray:?} {interval:?}"
    );
    let reach = (ray.origin() - obb.center).length() + obb.half_extents.length();
    let eps = 1e-4 * (1.0 + reach);
    let (inner, outer) = (offset(obb, -eps), offset(obb, eps));
    let t_max = 2.0 * reach / ray.dir().length();
    for k in 0..=2000 {
        let t = t_max * k as f32 / 2000.0;
        let p = ray.at(t);
        let in_interval = interval.is_some_and(|(t0, t1)| t0 <= t && t <= t1);
        if inner.contains(p) {
            assert!(
                in_interval,
                "t = {t} inside but not in {interval:?}: {obb:?} {ray:?}"
            );
        }
        if in_interval {
            assert!(
                outer.contains(p),
                "t = {t} in {interval:?} but outside: {obb:?} {ray:?}"
            );
        }
    }
    if let Some((t0, t1)) = interval {
        assert!(0.0 <= t0 && t0 <= t1);
    }
    interval.is_some()
}

#[test]
fn ray_intervals_agree_with_sampling_in_2d_and_3d() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut hits = 0;
    for _ in 0..300 {
        let obb = random_obb3(&mut rng);
        let mut v = || {
            Vec3::new(
                rng.random_range(-8.0..8.0),
                rng.random_range(-8.0..8.0),
                rng.random_range(-8.0..8.0),
            )
        };
        let (origin, target, random_dir) = (v(), v(), v());
        let [x, y, z] = obb.axes;
        let on_face = obb.center + x * obb.half_extents.x + y * 0.3 + z * -0.2;
        let rays = [
            Ray3::new(origin, random_dir),
            Ray3::through(origin, obb.to_world(target * 0.1)),
            Ray3::new(origin, Vec3::X),
            Ray3::new(origin, -Vec3::Z),
            // In the plane of a face, starting on it and outside of it; along an edge.
            Ray3::new(on_face, y - z * 0.5),
            Ray3::new(on_face + y * 9.0, -y),
            Ray3::new(on_face + y * (obb.half_extents.y - 0.3), z * 0.01),
            // From a point on a face, into the box and out of it.
            Ray3::new(on_face, target - on_face),
            Ray3::new(on_face, x),
        ];
        for ray in rays.into_iter().flatten() {
            hits += usize::from(check_ray(&obb, &ray));
        }
        let obb = random_obb2(&mut rng);
        let mut v = || Vec2::new(rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0));
        let (origin, target, random_dir) = (v(), v(), v());
        let [x, y] = obb.axes;
        let on_face = obb.center + x * obb.half_extents.x + y * 0.1;
        let rays = [
            Ray2::new(origin, random_dir),
            Ray2::through(origin, obb.to_world(target * 0.1)),
            Ray2::new(origin, Vec2::Y),
            Ray2::new(on_face, y),
            Ray2::new(on_face + y * 9.0, -y * 3.0),
            Ray2::new(on_face, -x),
            Ray2::new(on_face, target - on_face),
        ];
        for ray in rays.into_iter().flatten() {
            hits += usize::from(check_ray(&obb, &ray));
        }
    }
    assert!(hits > 1500, "too few hits ({hits}) to test much");
}

#[test]
fn with_identity_axes_the_ray_interval_is_the_aabbs() {
    // Dyadic coordinates: every subtraction is exact, so both slab tests compute the same.
    let obb = Obb3::new(
        Vec3::new(0.5, -1.25, 2.0),
        Vec3::identity_axes(),
        Vec3::new(1.5, 0.75, 0.25),
    );
    let aabb = Aabb::new(obb.center - obb.half_extents, obb.center + obb.half_extents);
    assert_eq!(obb.aabb(), aabb);
    let (lo, hi) = (aabb.min, aabb.max);
    let rays = [
        (Vec3::new(-3.0, -1.0, 2.0), Vec3::X), // axis-parallel, through
        (Vec3::new(-3.0, lo.y, 2.0), Vec3::X), // in a face plane
        (Vec3::new(-3.0, lo.y, hi.z), Vec3::X * 2.0), // along an edge
        (Vec3::new(-3.0, lo.y - 0.5, 2.0), Vec3::X), // parallel, beside
        (Vec3::new(hi.x, -1.0, 2.0), Vec3::X), // origin on a face, leaving
        (Vec3::new(hi.x, -1.0, 2.0), -Vec3::X * 0.5), // origin on a face, entering
        (Vec3::new(hi.x, hi.y, hi.z), Vec3::ONE), // from a corner, outwards
        (Vec3::new(-3.0, -3.0, 2.0), Vec3::new(1.0, 1.0, 0.0)),
        (Vec3::new(0.0, -1.0, 2.0), Vec3::new(0.25, -0.5, 1.0)), // from inside
    ];
    for (origin, dir) in rays {
        let ray = Ray3::new(origin, dir).expect("valid ray");
        assert_eq!(obb.ray_interval(&ray), aabb.ray_interval(&ray), "{ray:?}");
        check_ray(&obb, &ray);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..500 {
        let b = random_obb2(&mut rng);
        let obb = Obb2::new(b.center, Vec2::identity_axes(), b.half_extents);
        let aabb = Aabb::new(obb.center - obb.half_extents, obb.center + obb.half_extents);
        let mut v = || Vec2::new(rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0));
        let ray = Ray2::new(v(), v()).expect("valid ray");
        match (obb.ray_interval(&ray), aabb.ray_interval(&ray)) {
            (Some((a0, a1)), Some((b0, b1))) => {
                assert!((a0 - b0).abs() < 1e-4 && (a1 - b1).abs() < 1e-4);
            }
            (a, b) => assert_eq!(a.is_some(), b.is_some(), "{ray:?}"),
        }
    }
}

/// The distance to the nearest of a fine grid of points of the box, and the grid's spacing.
fn brute_force_distance<V: Vector>(obb: &Obb<V>, p: V, n: usize) -> (f32, f32) {
    let mut best = f32::INFINITY;
    for k in 0..(n + 1).pow(V::DIM as u32) {
        let mut local = V::ZERO;
        let mut rest = k;
        for i in 0..V::DIM {
            let s = (rest % (n + 1)) as f32 / n as f32 * 2.0 - 1.0;
            rest /= n + 1;
            local.set_coord(i, s * obb.half_extents.coord(i));
        }
        best = best.min((obb.to_world(local) - p).length());
    }
    (best, (obb.half_extents * 2.0 / n as f32).length())
}

fn check_closest<V: Vector>(obb: &Obb<V>, p: V, n: usize) {
    let q = obb.closest_point(p).expect("a box is not empty").point;
    assert!(offset(obb, 1e-4).contains(q), "{q:?} outside {obb:?}");
    if obb.contains(p) {
        assert_eq!(q, p);
    }
    let (brute, spacing) = brute_force_distance(obb, p, n);
    let d = (q - p).length();
    assert_eq!(d, obb.distance(p));
    assert!(d <= brute + 1e-4, "{d} > {brute}: {obb:?} {p:?}");
    assert!(
        brute <= d + spacing / 2.0 + 1e-4,
        "{brute} far from {d}: {obb:?} {p:?}"
    );
}

#[test]
fn closest_points_agree_with_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..40 {
        let obb = random_obb3(&mut rng);
        for _ in 0..5 {
            let local = Vec3::new(
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
            );
            check_closest(&obb, obb.to_world(local * obb.half_extents), 24);
        }
        let obb = random_obb2(&mut rng);
        for _ in 0..5 {
            let local = Vec2::new(rng.random_range(-3.0..3.0), rng.random_range(-3.0..3.0));
            check_closest(&obb, obb.to_world(local * obb.half_extents), 200);
        }
    }
}
