//! What a newcomer ran into in issue 33: a custom primitive whose `bounds()` is too small
//! (contract 2 of `Primitive`) passed `validate()` and `check_enclosed_by_vertices`, and every
//! structure that culls by boxes then gave wrong answers (330 of 3,000 rays on an AABB tree)
//! without a word. Now `check_bounds_hold` probes it, every structure's `validate()` runs that
//! probe, and a debug build stops at the first hit or projected point outside the bounds.

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::primitive::{check_bounds_hold, check_enclosed_by_vertices};
use bvhlab::structure::bvh::AabbTree;
use bvhlab::structure::{BruteForce, ValidationError};
use bvhlab::{BspTree, Grid, KdTree, Orthtree};
use rand::RngExt;

use crate::newcomer::{random_vec3, rng};

/// A ball whose `bounds()` is its box scaled by `bounds_scale` about its centre: 1 is right,
/// 0.5 the newcomer's mistake (the box of half the radius). Its vertices are its bounds'
/// corners, so contract 1 holds either way.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ScaledBall {
    center: Vec3,
    radius: f32,
    bounds_scale: f32,
}

impl Primitive for ScaledBall {
    type Point = Vec3;

    fn bounds(&self) -> Aabb3 {
        let half = self.radius * self.bounds_scale;
        Aabb3::new(self.center - half, self.center + half)
    }
    fn centroid(&self) -> Vec3 {
        self.center
    }
    fn ray_hit(&self, ray: &Ray3) -> Option<f32> {
        let (e, d) = (ray.origin() - self.center, ray.dir());
        let (a, half_b) = (d.dot(d), e.dot(d));
        let disc = half_b * half_b - a * (e.dot(e) - self.radius * self.radius);
        let (enter, exit) = ((-half_b - disc.sqrt()) / a, (-half_b + disc.sqrt()) / a);
        (disc >= 0.0 && exit >= 0.0).then(|| enter.max(0.0))
    }
    fn project_point(&self, p: Vec3) -> Vec3 {
        self.center + (p - self.center).clamp_length_max(self.radius)
    }
    fn measure(&self) -> f32 {
        4.0 / 3.0 * std::f32::consts::PI * self.radius.powi(3)
    }
    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
    fn vertices(&self) -> impl Iterator<Item = Vec3> {
        self.bounds().corners().collect::<Vec<_>>().into_iter()
    }
    fn intersects_aabb(&self, aabb: &Aabb3) -> bool {
        aabb.distance(self.center) <= self.radius
    }
    fn intersects(&self, other: &Self) -> bool {
        self.center.distance(other.center) <= self.radius + other.radius
    }
}

fn balls(seed: u64, n: usize, bounds_scale: f32) -> Vec<ScaledBall> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| ScaledBall {
            center: random_vec3(&mut rng, 50.0) + Vec3::splat(20.0),
            radius: rng.random_range(0.2..2.5),
            bounds_scale,
        })
        .collect()
}

/// Every structure's `validate()` over `balls`, by name.
fn validations(balls: &[ScaledBall]) -> Vec<(&'static str, Result<(), ValidationError>)> {
    vec![
        ("AABB tree", AabbTree::<ScaledBall>::build(balls).validate()),
        ("Bvh4", Bvh4::build(balls).validate()),
        ("k-d tree", KdTree::build(balls).validate()),
        ("octree", Orthtree::<ScaledBall>::build(balls).validate()),
        ("grid", Grid::<ScaledBall>::build(balls).validate()),
        ("BSP tree", BspTree::<ScaledBall>::build(balls).validate()),
    ]
}

#[test]
fn check_bounds_hold_refuses_a_ball_whose_bounds_are_too_small_and_passes_a_right_one() {
    let right = ScaledBall {
        center: Vec3::new(3.0, -4.0, 10.0),
        radius: 1.5,
        bounds_scale: 1.0,
    };
    let small = ScaledBall {
        bounds_scale: 0.5,
        ..right
    };
    assert_eq!(check_bounds_hold(&right), Ok(()));
    // Contract 1 holds for both: only the new probe sees the difference.
    assert_eq!(check_enclosed_by_vertices(&small), Ok(()));
    let why = check_bounds_hold(&small).expect_err("half the radius is too small");
    assert!(
        why.contains("outside its bounds") && why.contains("project_point"),
        "{why}"
    );
    // Our own primitives, degenerate ones too, pass.
    let degenerate = [
        Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y),
        Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0),
        Triangle3::new(Vec3::ONE, Vec3::ONE, Vec3::ONE),
        Triangle3::new(
            Vec3::splat(1e6),
            Vec3::splat(1e6) + Vec3::X,
            Vec3::splat(1e6) + Vec3::Z,
        ),
    ];
    for tri in &degenerate {
        assert_eq!(check_bounds_hold(tri), Ok(()), "{tri:?}");
    }
    assert_eq!(check_bounds_hold(&Vec3::new(1.0, 2.0, 3.0)), Ok(()));
}

#[test]
fn every_structure_refuses_balls_whose_bounds_are_too_small_and_takes_right_ones() {
    let small = balls(41, 500, 0.5);
    for (name, result) in validations(&small) {
        let err = result.expect_err(name);
        assert!(
            err.to_string().contains("breaks the Primitive contract")
                && err.to_string().contains("outside its bounds"),
            "{name}: {err}"
        );
    }
    for (name, result) in validations(&balls(41, 500, 1.0)) {
        if let Err(e) = result {
            panic!("{name} refused right balls: {e}");
        }
    }
}

/// A debug build says what is wrong at the first hit or projected point outside the bounds,
/// from brute force and from every structure's queries, instead of answering wrongly.
#[cfg(debug_assertions)]
#[test]
fn a_debug_build_stops_at_a_hit_or_projected_point_outside_the_bounds() {
    let balls = balls(44, 200, 0.5);
    let target = balls[0];
    let ray = Ray3::new(target.center - Vec3::X * 100.0, Vec3::X).expect("a direction");
    let message = |result: std::thread::Result<()>| -> String {
        let panic = result.expect_err("the query must stop");
        panic
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_else(|| "a panic without a message".into())
    };
    let brute = BruteForce::build(&balls);
    let ray_stop = message(std::panic::catch_unwind(|| {
        brute.ray_first_hit(&ray, f32::INFINITY);
    }));
    assert!(
        ray_stop.contains("ray_hit gave") && ray_stop.contains("outside its bounds"),
        "{ray_stop}"
    );
    let far = target.center + Vec3::Y * 3.0 * target.radius;
    let tree = Bvh4::build(&balls);
    let point_stop = message(std::panic::catch_unwind(|| {
        tree.closest_point(far);
    }));
    assert!(
        point_stop.contains("project_point") && point_stop.contains("outside its bounds"),
        "{point_stop}"
    );
}
