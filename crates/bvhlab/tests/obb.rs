//! Oriented boxes through the public API: the PCA fit (containment, degenerate and symmetric
//! sets, recovering a known box) and the cheap queries (measures, `aabb`, `merge`).

use crate::obb_common;

use std::f32::consts::TAU;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Aabb, Obb};
use obb_common::{frame2, frame3, random_obb2, random_obb3};
use proptest::collection::vec;
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A fit must be a box: orthonormal axes, right-handed in 3D, and contain every point.
fn assert_valid_fit<V: Vector>(points: &[V], obb: &Obb<V>) {
    let axes = obb.axes.as_ref();
    for i in 0..V::DIM {
        assert!(obb.half_extents.coord(i) >= 0.0, "{obb:?}");
        for j in 0..V::DIM {
            let expected = if i == j { 1.0 } else { 0.0 };
            assert!((axes[i].dot(axes[j]) - expected).abs() < 1e-5, "{obb:?}");
        }
    }
    if V::DIM == 3 {
        let [x, y, z] = axes.iter().map(|a| a.to_dvec3()).collect::<Vec<_>>()[..] else {
            unreachable!("three axes in 3D")
        };
        assert!(x.cross(y).dot(z) > 0.999, "left-handed frame {obb:?}");
    }
    for &p in points {
        assert!(obb.contains(p), "{p:?} outside {obb:?}");
    }
    // Tight: each half extent is reached by some point, and the centre is in the middle.
    for i in 0..V::DIM {
        let local: Vec<f32> = points.iter().map(|&p| obb.to_local(p).coord(i)).collect();
        let h = obb.half_extents.coord(i);
        assert!(local.iter().any(|l| l.abs() == h));
        let (lo, hi) = local
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &l| {
                (lo.min(l), hi.max(l))
            });
        assert!(
            (lo + hi).abs() <= 1e-5 * (1.0 + h + obb.center.length()),
            "{lo} {hi}"
        );
    }
}

fn p2() -> impl Strategy<Value = Vec2> {
    (-100.0f32..100.0, -100.0f32..100.0).prop_map(|(x, y)| Vec2::new(x, y))
}

fn p3() -> impl Strategy<Value = Vec3> {
    (-100.0f32..100.0, -100.0f32..100.0, -100.0f32..100.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Random, single-point, collinear, repeated, square and far-away clusters in 2D.
fn cloud2() -> impl Strategy<Value = Vec<Vec2>> {
    prop_oneof![
        vec(p2(), 1..40),
        p2().prop_map(|p| vec![p]),
        (p2(), p2(), vec(-2.0f32..2.0, 1..20))
            .prop_map(|(p, d, ts)| ts.iter().map(|&t| p + d * t).collect()),
        (p2(), 2..6usize, vec(p2(), 0..4))
            .prop_map(|(p, n, rest)| { std::iter::repeat_n(p, n).chain(rest).collect() }),
        (p2(), 0.01f32..50.0, 0.0f32..TAU).prop_map(|(c, s, a)| {
            let [x, y] = frame2(a);
            [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
                .map(|(u, v)| c + x * (s * u) + y * (s * v))
                .to_vec()
        }),
        (vec(p2(), 1..20), -1e4f32..1e4)
            .prop_map(|(ps, far)| ps.iter().map(|&p| p * 1e-4 + Vec2::splat(far)).collect()),
    ]
}

/// As [`cloud2`], plus coplanar sets and cubes, in 3D.
fn cloud3() -> impl Strategy<Value = Vec<Vec3>> {
    prop_oneof![
        vec(p3(), 1..40),
        p3().prop_map(|p| vec![p]),
        (p3(), p3(), vec(-2.0f32..2.0, 1..20))
            .prop_map(|(p, d, ts)| ts.iter().map(|&t| p + d * t).collect()),
        (p3(), p3(), p3(), vec((-2.0f32..2.0, -2.0f32..2.0), 1..20))
            .prop_map(|(p, u, v, st)| st.iter().map(|&(s, t)| p + u * s + v * t).collect()),
        (p3(), 2..6usize, vec(p3(), 0..4))
            .prop_map(|(p, n, rest)| { std::iter::repeat_n(p, n).chain(rest).collect() }),
        (
            p3(),
            0.01f32..50.0,
            (0.0f32..TAU, 0.0f32..TAU, 0.0f32..TAU),
            any::<bool>()
        )
            .prop_map(|(c, s, (a, b, d), square)| {
                let frame = frame3(a, b, d);
                let corners = Obb::new(c, frame, Vec3::splat(s))
                    .corners()
                    .collect::<Vec<_>>();
                if square {
                    corners[..4].to_vec()
                } else {
                    corners
                }
            }),
        (vec(p3(), 1..20), -1e4f32..1e4)
            .prop_map(|(ps, far)| ps.iter().map(|&p| p * 1e-4 + Vec3::splat(far)).collect()),
    ]
}

proptest! {
    #[test]
    fn every_2d_fit_contains_its_points(points in cloud2()) {
        let (obb, pca) = Obb2::pca_fit_detailed(&points);
        assert_valid_fit(&points, &obb);
        prop_assert_eq!(pca.axes, obb.axes);
        prop_assert!(pca.variances.x >= pca.variances.y && pca.variances.y >= 0.0);
        prop_assert_eq!(Obb2::try_pca_fit(&points), Ok(obb));
    }

    #[test]
    fn every_3d_fit_contains_its_points(points in cloud3()) {
        let (obb, pca) = Obb3::pca_fit_detailed(&points);
        assert_valid_fit(&points, &obb);
        let v = pca.variances;
        prop_assert!(v.x >= v.y && v.y >= v.z && v.z >= 0.0);
        let mean = points.iter().copied().sum::<Vec3>() / points.len() as f32;
        prop_assert!((pca.mean - mean).length() <= 1e-4 * (1.0 + mean.length()));
        prop_assert_eq!(Obb3::try_pca_fit(&points), Ok(obb));
    }
}

#[test]
fn the_pca_fit_of_a_rotated_boxs_corners_recovers_the_box() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let truth = random_obb3(&mut rng);
        // Distinct extents, so the principal axes are unique up to sign.
        let truth = Obb::new(truth.center, truth.axes, Vec3::new(3.0, 1.7, 0.6));
        let corners: Vec<Vec3> = truth.corners().collect();
        let fit = Obb3::pca_fit(&corners);
        assert!(
            (fit.center - truth.center).length() < 1e-4,
            "{fit:?} vs {truth:?}"
        );
        for (i, axis) in fit.axes.iter().enumerate() {
            let j = (0..3)
                .max_by(|&j, &k| {
                    axis.dot(truth.axes[j])
                        .abs()
                        .total_cmp(&axis.dot(truth.axes[k]).abs())
                })
                .expect("three axes");
            assert!(
                axis.dot(truth.axes[j]).abs() > 1.0 - 1e-5,
                "axis {i} of {fit:?}"
            );
            assert!((fit.half_extents[i] - truth.half_extents[j]).abs() < 1e-4);
        }
    }
    for _ in 0..200 {
        let truth = random_obb2(&mut rng);
        let truth = Obb::new(truth.center, truth.axes, Vec2::new(0.8, 2.5));
        let fit = Obb2::pca_fit(&truth.corners().collect::<Vec<_>>());
        assert!((fit.center - truth.center).length() < 1e-4);
        // Largest variance first: the fit's first axis is the truth's second.
        assert!(fit.axes[0].dot(truth.axes[1]).abs() > 1.0 - 1e-5);
        assert!((fit.half_extents - Vec2::new(2.5, 0.8)).abs().max_element() < 1e-4);
    }
}

#[test]
fn non_finite_points_are_skipped_or_reported_and_no_points_give_the_empty_box() {
    let points = [
        Vec3::ONE,
        Vec3::NAN,
        Vec3::new(2.0, 0.0, 1.0),
        Vec3::INFINITY,
    ];
    let finite = [Vec3::ONE, Vec3::new(2.0, 0.0, 1.0)];
    assert_eq!(Obb3::pca_fit(&points), Obb3::pca_fit(&finite));
    assert!(matches!(
        Obb3::try_pca_fit(&points),
        Err(GeometryError::NonFinite { .. })
    ));
    assert!(matches!(
        Obb2::try_pca_fit(&[]),
        Err(GeometryError::Empty { .. })
    ));
    let empty = Obb2::pca_fit(&[Vec2::NAN]);
    assert!(empty.is_empty() && !empty.contains(Vec2::ZERO));
    assert_eq!(empty.closest_point(Vec2::ZERO), None);
    assert_eq!(empty.distance(Vec2::ZERO), f32::INFINITY);
    let ray = Ray2::new(Vec2::new(-1.0, 0.0), Vec2::X).expect("valid ray");
    assert_eq!(empty.ray_interval(&ray), None);
    assert_eq!((empty.measure(), empty.boundary_measure()), (0.0, 0.0));
    assert!(empty.aabb().is_empty() && empty.corners().next().is_none());
    let b = Obb2::pca_fit(&[Vec2::ZERO, Vec2::ONE]);
    assert_eq!((empty.merge(&b), b.merge(&empty)), (b, b));
}

#[test]
fn measures_frames_aabbs_and_merges() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..200 {
        let (a, b) = (random_obb3(&mut rng), random_obb3(&mut rng));
        let h = a.half_extents;
        assert!((a.measure() - 8.0 * h.x * h.y * h.z).abs() < 1e-4 * a.measure());
        let area = 8.0 * (h.x * h.y + h.y * h.z + h.z * h.x);
        assert!((a.boundary_measure() - area).abs() < 1e-4 * area);
        let p = Vec3::new(1.0, -2.0, 0.5);
        assert!((a.to_world(a.to_local(p)) - p).length() < 1e-5 * (1.0 + a.center.length()));
        // The AABB is tight around the corners.
        let corners_box = Aabb::from_points(&a.corners().collect::<Vec<_>>());
        let aabb = a.aabb();
        assert!((aabb.min - corners_box.min).abs().max_element() < 1e-5 * 10.0);
        assert!((aabb.max - corners_box.max).abs().max_element() < 1e-5 * 10.0);
        // The merge contains both boxes' corners, exactly (it is fitted to them).
        let m = a.merge(&b);
        assert!(
            a.corners().chain(b.corners()).all(|c| m.contains(c)),
            "{m:?}"
        );
        // An AABB as a box: the same region.
        let c = Obb3::from_aabb(&aabb);
        assert!(aabb.corners().all(|p| c.contains(p)));
        assert!((c.measure() - aabb.measure()).abs() <= 1e-5 * aabb.measure());
    }
    assert!(Obb2::from_aabb(&Aabb::EMPTY).is_empty());
}
