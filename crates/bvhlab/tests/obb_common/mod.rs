//! Helpers shared by the oriented-box tests: random boxes and offset boxes.
#![allow(
    dead_code,
    reason = "each test file uses a different part of this module"
)]

use std::f32::consts::TAU;

use bvhlab::Obb;
use bvhlab::glam::{EulerRot, Quat, Vec2, Vec3};
use bvhlab::prelude::*;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

pub fn frame2(angle: f32) -> [Vec2; 2] {
    let x = Vec2::from_angle(angle);
    [x, x.perp()]
}

pub fn frame3(a: f32, b: f32, c: f32) -> [Vec3; 3] {
    let q = Quat::from_euler(EulerRot::ZYX, a, b, c);
    [q * Vec3::X, q * Vec3::Y, q * Vec3::Z]
}

pub fn random_obb2(rng: &mut ChaCha8Rng) -> Obb2 {
    let c = Vec2::new(rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
    let h = Vec2::new(rng.random_range(0.1..3.0), rng.random_range(0.1..3.0));
    Obb::new(c, frame2(rng.random_range(0.0..TAU)), h)
}

pub fn random_obb3(rng: &mut ChaCha8Rng) -> Obb3 {
    let mut v = || rng.random_range(-5.0..5.0);
    let c = Vec3::new(v(), v(), v());
    let h = Vec3::new(
        rng.random_range(0.1..3.0),
        rng.random_range(0.1..3.0),
        rng.random_range(0.1..3.0),
    );
    let mut a = || rng.random_range(0.0..TAU);
    Obb::new(c, frame3(a(), a(), a()), h)
}

/// The box grown (or, for negative `by`, shrunk) by `by` on every side.
pub fn offset<V: Vector>(obb: &Obb<V>, by: f32) -> Obb<V> {
    let mut h = obb.half_extents;
    for i in 0..V::DIM {
        h.set_coord(i, h.coord(i) + by);
    }
    Obb::new(obb.center, obb.axes, h)
}
