//! Three independent implementations of one shape must agree: an AABB, the same box as an OBB
//! (identity axes: ray transformed into the box frame, separating-axis overlap) and the convex
//! hull of its corners (Cyrus-Beck clipping, facet distances). Then the tightness report.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb, ConvexHull, FitKind, FitReport, Obb, Ray, Vector};
use bvhlab_tests::{random_cloud, random_vector, rng};

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-4 * a.abs().max(b.abs()).max(1.0)
}

fn check<V: Vector>(seed: u64) {
    let mut rng = rng(seed);
    let mut hits = 0;
    for _ in 0..300 {
        let aabb = Aabb::from_points(&random_cloud::<V>(&mut rng, 4, 2.0));
        let obb = Obb::from_aabb(&aabb);
        let hull = ConvexHull::from_points(&aabb.corners().collect::<Vec<_>>());
        assert!(close(aabb.measure(), obb.measure()) && close(aabb.measure(), hull.measure()));
        assert!(close(aabb.boundary_measure(), obb.boundary_measure()));
        assert!(close(aabb.boundary_measure(), hull.boundary_measure()));

        // Aim near the box so that about half of the rays hit it.
        let origin: V = random_vector(&mut rng, 5.0);
        let target = aabb.center() + random_vector::<V>(&mut rng, 2.0);
        let Ok(ray) = Ray::new(origin, target - origin) else {
            continue;
        };
        let answers = [
            aabb.ray_interval(&ray),
            obb.ray_interval(&ray),
            hull.ray_interval(&ray),
        ];
        match answers {
            [Some(a), Some(b), Some(c)] => {
                hits += 1;
                assert!(
                    close(a.0, b.0) && close(a.0, c.0) && close(a.1, b.1) && close(a.1, c.1),
                    "{answers:?}"
                );
            }
            [None, None, None] => {}
            _ => panic!("{ray:?} against {aabb:?}: {answers:?}"),
        }

        let p: V = random_vector(&mut rng, 5.0);
        let d = [aabb.distance(p), obb.distance(p), hull.distance(p)];
        assert!(close(d[0], d[1]) && close(d[0], d[2]), "{p:?}: {d:?}");

        let other = Aabb::from_points(&random_cloud::<V>(&mut rng, 3, 2.0));
        let gap = (0..V::DIM)
            .map(|i| {
                (other.min.coord(i) - aabb.max.coord(i)).max(aabb.min.coord(i) - other.max.coord(i))
            })
            .fold(f32::NEG_INFINITY, f32::max);
        if gap.abs() > 1e-4 {
            let other_hull = ConvexHull::from_points(&other.corners().collect::<Vec<_>>());
            let verdicts = [
                aabb.overlaps(&other),
                obb.overlaps(&Obb::from_aabb(&other)),
                hull.overlaps(&other_hull),
            ];
            assert!(
                verdicts.iter().all(|&v| v == (gap < 0.0)),
                "gap {gap}: {verdicts:?}"
            );
        }
    }
    assert!(hits > 80, "only {hits} rays hit");
}

#[test]
fn aabb_obb_and_hull_of_one_box_agree_2d() {
    check::<Vec2>(30);
}

#[test]
fn aabb_obb_and_hull_of_one_box_agree_3d() {
    check::<Vec3>(31);
}

fn check_report<V: Vector>(points: &[V]) {
    let report = FitReport::for_points(points);
    assert_eq!(report.fits.len(), FitKind::ALL.len());
    let tight = |k| {
        report
            .get(k)
            .and_then(|f| f.tightness)
            .expect("a full-dimensional set")
    };
    // The hull is the tightest convex volume; every other fit is looser or equal.
    assert!(close(tight(FitKind::ConvexHull), 1.0));
    for kind in FitKind::ALL {
        assert!(
            tight(kind) <= 1.0 + 1e-4,
            "{}: {}",
            kind.label(),
            tight(kind)
        );
    }
    // The minimal sphere is at least as tight as the other two spheres.
    assert!(tight(FitKind::SphereWelzl) >= tight(FitKind::SphereRitter) - 1e-5);
    assert!(tight(FitKind::SphereWelzl) >= tight(FitKind::SphereCentroid) - 1e-5);
}

#[test]
fn tightness_report_ranks_the_hull_first_and_welzl_among_spheres() {
    let mut rng = rng(32);
    for _ in 0..20 {
        check_report(&random_cloud::<Vec2>(&mut rng, 50, 3.0));
        check_report(&random_cloud::<Vec3>(&mut rng, 50, 3.0));
    }
    // A thin diagonal stick: the PCA box is far tighter than the axis-aligned one.
    let stick: Vec<Vec3> = (0..40)
        .map(|i| {
            Vec3::new(1.0, 1.0, 1.0) * i as f32 * 0.1 + Vec3::new(0.01, -0.01, 0.0) * (i % 3) as f32
        })
        .collect();
    let report = FitReport::for_points(&stick);
    let m = |k| report.get(k).expect("present").measure;
    assert!(
        m(FitKind::Obb) < 0.01 * m(FitKind::Aabb),
        "obb {} aabb {}",
        m(FitKind::Obb),
        m(FitKind::Aabb)
    );
}
