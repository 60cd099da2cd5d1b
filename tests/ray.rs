//! Rays refuse input they cannot measure along, with messages a student can act on.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;

#[test]
fn non_finite_or_zero_input_is_rejected_with_an_actionable_message() {
    let nan = Ray3::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X).expect_err("NaN origin");
    assert!(matches!(nan, GeometryError::NonFinite { .. }));
    assert!(
        nan.to_string().contains("ray origin") && nan.to_string().contains("NaN"),
        "{nan}"
    );
    let inf = Ray2::new(Vec2::ZERO, Vec2::new(f32::INFINITY, 1.0)).expect_err("inf direction");
    assert!(inf.to_string().contains("ray direction"), "{inf}");
    for zero in [Vec3::ZERO, Vec3::new(-0.0, 0.0, -0.0)] {
        let err = Ray3::new(Vec3::ONE, zero).expect_err("zero direction");
        assert_eq!(err, GeometryError::ZeroDirection);
        assert!(err.to_string().contains("non-zero"), "{err}");
    }
    assert_eq!(
        Ray2::through(Vec2::ONE, Vec2::ONE),
        Err(GeometryError::ZeroDirection)
    );
    // It is a std error, so `?` works into Box<dyn Error>.
    let boxed: Box<dyn std::error::Error> = Box::new(GeometryError::ZeroDirection);
    assert!(!boxed.to_string().is_empty());
}

#[test]
fn t_is_measured_in_units_of_the_direction() {
    let ray = Ray3::through(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0)).expect("ray");
    assert_eq!(ray.at(1.0), Vec3::new(0.0, 2.0, 0.0));
    assert_eq!(ray.inv_dir(), Vec3::new(f32::INFINITY, 0.5, f32::INFINITY));
    let tiny = Ray2::new(Vec2::ZERO, Vec2::new(0.0, -0.0)).expect_err("zero");
    assert_eq!(tiny, GeometryError::ZeroDirection);
}
