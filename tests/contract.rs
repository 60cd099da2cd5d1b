//! The public contract of issue 2, exercised exactly as code outside the repository uses it:
//! only the names the issue fixes, imported from the crate root and `bvhlab::prelude`.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{
    Aabb2, Aabb3, AabbTree2, AabbTree3, Bsp2, Bsp3, Grid2, Grid3, KdTree2, KdTree3, Obb2, Obb3,
    ObbTree2, ObbTree3, Octree3, Quadtree2, Ray2, Ray3, Segment2, Sphere2, Sphere3, SphereTree2,
    SphereTree3, Triangle3,
};

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
        segment.project_point(Vec2::new(3.0, 0.5)),
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
        tri.project_point(Vec3::new(8.0, 0.0, 0.0)),
        Vec3::new(5.0, 0.0, 0.0)
    );
    let _ = (tri.b, tri.c);

    let err = Ray3::new(Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::X).expect_err("infinite origin");
    let message: &dyn std::error::Error = &err;
    assert!(!message.to_string().is_empty() && !format!("{err:?}").is_empty());
    Ok(())
}

/// Issue 3's contract: `Mesh::from_obj`, the structure names with `build`, and the prelude
/// trait's `ray_first_hit` / `closest_point` with `Hit` and `Nearest`.
#[test]
fn structures_contract() -> Result<(), Box<dyn std::error::Error>> {
    let obj = b"# two triangles, one quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nmtllib missing.mtl\nf 1 2 3 4\n";
    let mesh = Mesh::from_obj(obj)?;
    let tris: Vec<Triangle3> = mesh.triangles().to_vec();
    assert_eq!(tris.len(), 2);
    assert!(Mesh::from_obj(b"v 0 0 nan\nf 1 1 1\n").is_err());
    assert!(Mesh::from_obj(b"v 0 0 0\nf 1 2 3\n").is_err());

    let down = Ray3::new(Vec3::new(0.25, 0.25, 2.0), Vec3::new(0.0, 0.0, -1.0))?;
    let above = Vec3::new(0.5, 0.5, 3.0);
    macro_rules! check_3d {
        ($($t:ty),*) => {$(
            let s = <$t>::build(&tris);
            let hit = s.ray_first_hit(&down, f32::INFINITY).expect("the ray hits the quad");
            assert!(hit.prim < 2 && (hit.t - 2.0).abs() < 1e-6);
            assert!(s.ray_first_hit(&down, 1.0).is_none(), "t_max bounds the hit");
            let near = s.closest_point(above).expect("non-empty");
            assert!(near.prim < 2 && (near.distance - 3.0).abs() < 1e-6 && (near.point.z).abs() < 1e-6);
            let empty = <$t>::build(&[]);
            assert!(empty.ray_first_hit(&down, f32::INFINITY).is_none() && empty.closest_point(above).is_none());
        )*};
    }
    check_3d!(
        SphereTree3,
        AabbTree3,
        ObbTree3,
        KdTree3,
        Grid3,
        Octree3,
        Bsp3
    );

    let segments = [
        Segment2::new(Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0)),
        Segment2::new(Vec2::new(3.0, -1.0), Vec2::new(3.0, 1.0)),
    ];
    let right = Ray2::new(Vec2::ZERO, Vec2::X)?;
    macro_rules! check_2d {
        ($($t:ty),*) => {$(
            let s = <$t>::build(&segments);
            let hit = s.ray_first_hit(&right, f32::INFINITY).expect("hits the first segment");
            assert_eq!((hit.prim, hit.t), (0, 1.0));
            let near = s.closest_point(Vec2::new(2.9, 5.0)).expect("non-empty");
            assert_eq!(near.prim, 1);
            assert!((near.point - Vec2::new(3.0, 1.0)).length() < 1e-6 && (near.distance - 0.1f32.hypot(4.0)).abs() < 1e-5);
            assert!(<$t>::build(&[]).closest_point(Vec2::ZERO).is_none());
        )*};
    }
    check_2d!(
        SphereTree2,
        AabbTree2,
        ObbTree2,
        KdTree2,
        Grid2,
        Quadtree2,
        Bsp2
    );
    Ok(())
}
