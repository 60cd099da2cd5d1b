//! The public contract of issue 2, exercised exactly as code outside the repository uses it:
//! only the names the issue fixes, imported from the crate root and `bvhlab::prelude`.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb2, Aabb3, Obb2, Obb3, Ray2, Ray3, Segment2, Sphere2, Sphere3, Triangle3};

fn assert_volume<B: BoundingVolume>(
    volume: &B,
    ray: &Ray<B::Point>,
    inside: B::Point,
    outside: B::Point,
) where
    B::Point: Vector,
{
    let (t_enter, t_exit) = volume
        .ray_interval(ray)
        .expect("the ray passes through the volume");
    assert!(0.0 <= t_enter && t_enter <= t_exit);
    assert!(volume.contains(inside) && volume.distance(inside) == 0.0);
    assert!(!volume.contains(outside) && volume.distance(outside) > 0.0);
}

use bvhlab::{Ray, Vector};

#[test]
fn two_dimensional_contract() -> Result<(), Box<dyn std::error::Error>> {
    let points = [
        Vec2::new(0.0, 0.0),
        Vec2::new(4.0, 1.0),
        Vec2::new(1.0, 3.0),
        Vec2::new(3.0, 3.5),
    ];
    let ray = Ray2::new(Vec2::new(-10.0, 1.5), Vec2::new(1.0, 0.0))?;
    let (inside, outside) = (Vec2::new(2.0, 1.5), Vec2::new(20.0, 20.0));

    let aabb = Aabb2::from_points(&points);
    assert_eq!((aabb.min, aabb.max), (Vec2::ZERO, Vec2::new(4.0, 3.5)));
    assert_volume(&aabb, &ray, inside, outside);
    for sphere in [
        Sphere2::centroid_fit(&points),
        Sphere2::ritter_fit(&points),
        Sphere2::welzl_fit(&points),
    ] {
        assert!(sphere.radius > 0.0 && sphere.center.is_finite());
        assert_volume(&sphere, &ray, inside, outside);
    }
    let obb = Obb2::pca_fit(&points);
    assert_volume(&obb, &ray, inside, outside);
    assert!(obb.overlaps(&obb));
    let far = Obb2::pca_fit(&points.map(|p| p + Vec2::new(100.0, 0.0)));
    assert!(!obb.overlaps(&far));

    let segment = Segment2::new(Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0));
    assert_eq!(
        (segment.a, segment.b),
        (Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0))
    );
    let hit = Ray2::new(Vec2::ZERO, Vec2::new(0.5, 0.0))?;
    assert_eq!(segment.ray_hit(&hit), Some(2.0));
    assert_eq!(
        segment.closest_point(Vec2::new(3.0, 0.5)),
        Vec2::new(1.0, 0.5)
    );

    assert!(Ray2::new(Vec2::new(f32::NAN, 0.0), Vec2::X).is_err());
    assert!(Ray2::new(Vec2::ZERO, Vec2::ZERO).is_err());
    Ok(())
}

#[test]
fn three_dimensional_contract() -> Result<(), Box<dyn std::error::Error>> {
    let points = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(4.0, 0.5, 0.0),
        Vec3::new(1.0, 3.0, 0.5),
        Vec3::new(0.5, 0.5, 2.0),
        Vec3::new(3.0, 3.0, 2.5),
    ];
    let ray = Ray3::new(Vec3::new(-10.0, 1.5, 1.0), Vec3::new(2.0, 0.0, 0.0))?;
    let (inside, outside) = (Vec3::new(1.8, 1.5, 1.0), Vec3::splat(20.0));

    let aabb = Aabb3::from_points(&points);
    assert_eq!((aabb.min, aabb.max), (Vec3::ZERO, Vec3::new(4.0, 3.0, 2.5)));
    assert_volume(&aabb, &ray, inside, outside);
    for sphere in [
        Sphere3::centroid_fit(&points),
        Sphere3::ritter_fit(&points),
        Sphere3::welzl_fit(&points),
    ] {
        assert!(sphere.radius > 0.0 && sphere.center.is_finite());
        assert_volume(&sphere, &ray, inside, outside);
    }
    let obb = Obb3::pca_fit(&points);
    assert_volume(&obb, &ray, inside, outside);
    assert!(obb.overlaps(&obb));
    let far = Obb3::pca_fit(&points.map(|p| p + Vec3::new(0.0, 0.0, 100.0)));
    assert!(!obb.overlaps(&far));

    let tri = Triangle3::new(
        Vec3::new(5.0, -1.0, -1.0),
        Vec3::new(5.0, 3.0, -1.0),
        Vec3::new(5.0, 0.0, 3.0),
    );
    assert_eq!(tri.a, Vec3::new(5.0, -1.0, -1.0));
    assert_eq!(tri.ray_hit(&ray), Some(7.5));
    assert_eq!(
        tri.closest_point(Vec3::new(8.0, 0.0, 0.0)),
        Vec3::new(5.0, 0.0, 0.0)
    );
    let _ = (tri.b, tri.c);

    let err = Ray3::new(Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::X).expect_err("infinite origin");
    let message: &dyn std::error::Error = &err;
    assert!(!message.to_string().is_empty() && !format!("{err:?}").is_empty());
    Ok(())
}
