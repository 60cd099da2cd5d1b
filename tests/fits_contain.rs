//! Every fit contains every one of its points, for every kind of volume, in 2D and 3D, at
//! every finite scale and on degenerate sets (property tests).

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb, ConvexHull, Obb, Sphere, Vector};
use bvhlab_tests::{degenerate_sets, rng};
use proptest::prelude::*;

fn assert_every_fit_contains<V: Vector>(points: &[V]) -> Result<(), TestCaseError> {
    fn check<B: BoundingVolume>(
        name: &str,
        volume: &B,
        points: &[B::Point],
    ) -> Result<(), TestCaseError> {
        for p in points {
            prop_assert!(
                volume.contains(*p),
                "{} {:?} does not contain {:?}",
                name,
                volume,
                p
            );
        }
        Ok(())
    }
    check("centroid sphere", &Sphere::centroid_fit(points), points)?;
    check("Ritter sphere", &Sphere::ritter_fit(points), points)?;
    check("Welzl sphere", &Sphere::welzl_fit(points), points)?;
    check("AABB", &Aabb::from_points(points), points)?;
    check("PCA OBB", &Obb::pca_fit(points), points)?;
    check("convex hull", &ConvexHull::from_points(points), points)?;
    Ok(())
}

fn points3(raw: &[(f32, f32, f32)], scale: f32) -> Vec<Vec3> {
    raw.iter()
        .map(|&(x, y, z)| Vec3::new(x, y, z) * scale)
        .collect()
}

proptest! {
    #[test]
    fn random_sets_at_every_scale(
        raw in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 1..60),
        scale in prop::sample::select(vec![1e-30f32, 1e-12, 1e-3, 1.0, 1e3, 1e12, 1e30]),
    ) {
        let pts = points3(&raw, scale);
        assert_every_fit_contains(&pts)?;
        assert_every_fit_contains(&pts.iter().map(|p| p.truncate()).collect::<Vec<Vec2>>())?;
    }

    #[test]
    fn clusters_far_from_the_origin(
        raw in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 1..30),
        offset in prop::sample::select(vec![1e3f32, 1e6, -1e9]),
    ) {
        let pts: Vec<Vec3> = points3(&raw, 1.0).into_iter().map(|p| p + Vec3::splat(offset)).collect();
        assert_every_fit_contains(&pts)?;
        assert_every_fit_contains(&pts.iter().map(|p| p.truncate()).collect::<Vec<Vec2>>())?;
    }

    #[test]
    fn points_on_a_plane_or_a_line(
        raw in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0), 1..40),
        tilt in -1.0f32..1.0,
    ) {
        let plane: Vec<Vec3> = raw.iter().map(|&(x, y)| Vec3::new(x, y, x * tilt - y * 0.5)).collect();
        assert_every_fit_contains(&plane)?;
        let line: Vec<Vec2> = raw.iter().map(|&(x, _)| Vec2::new(x, x * tilt)).collect();
        assert_every_fit_contains(&line)?;
    }
}

#[test]
fn degenerate_sets_2d_and_3d() -> Result<(), TestCaseError> {
    let mut rng = rng(40);
    for _ in 0..20 {
        for set in degenerate_sets::<Vec2>(&mut rng) {
            assert_every_fit_contains(&set)?;
        }
        for set in degenerate_sets::<Vec3>(&mut rng) {
            assert_every_fit_contains(&set)?;
        }
    }
    Ok(())
}
