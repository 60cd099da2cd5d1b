//! The separating-axis test of oriented boxes against an independent method: two convex boxes
//! intersect exactly when a vertex of one lies in the other or an edge of one meets the other.
//! The reference works in `f64`, clipping each edge against the other box's slabs.

use std::f32::consts::{FRAC_1_SQRT_2, FRAC_PI_4, SQRT_2, TAU};

use bvhlab::glam::{DVec3, EulerRot, Quat, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{AxisSource, AxisTest, Obb};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A box in `f64` (2D padded with `z = 0`), its half extents moved out by `grow`.
struct Box64 {
    center: DVec3,
    axes: Vec<DVec3>,
    half: Vec<f64>,
}

impl Box64 {
    fn new<V: Vector>(obb: &Obb<V>, grow: f64) -> Self {
        Self {
            center: obb.center.to_dvec3(),
            axes: obb.axes.as_ref().iter().map(|a| a.to_dvec3()).collect(),
            half: (0..V::DIM)
                .map(|i| f64::from(obb.half_extents.coord(i)) + grow)
                .collect(),
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        self.axes
            .iter()
            .zip(&self.half)
            .all(|(a, &h)| a.dot(p - self.center).abs() <= h)
    }

    fn corners(&self) -> Vec<DVec3> {
        (0..1usize << self.axes.len())
            .map(|bits| {
                (0..self.axes.len()).fold(self.center, |p, i| {
                    let sign = if bits >> i & 1 == 1 { 1.0 } else { -1.0 };
                    p + self.axes[i] * (sign * self.half[i])
                })
            })
            .collect()
    }

    /// The 4 (2D) or 12 (3D) edges: corner pairs that differ in one bit.
    fn edges(&self) -> Vec<(DVec3, DVec3)> {
        let corners = self.corners();
        (0..corners.len())
            .flat_map(|k| (0..self.axes.len()).map(move |i| (k, i)))
            .filter(|&(k, i)| k >> i & 1 == 0)
            .map(|(k, i)| (corners[k], corners[k | 1 << i]))
            .collect()
    }

    /// Whether the segment `pq` meets the box: its interval of `t ∈ [0, 1]` in every slab.
    fn meets_segment(&self, p: DVec3, q: DVec3) -> bool {
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for (a, &h) in self.axes.iter().zip(&self.half) {
            let (o, d) = (a.dot(p - self.center), a.dot(q - p));
            if d == 0.0 {
                if o.abs() > h {
                    return false;
                }
            } else {
                let (t0, t1) = ((-h - o) / d, (h - o) / d);
                lo = lo.max(t0.min(t1));
                hi = hi.min(t0.max(t1));
            }
        }
        lo <= hi
    }
}

fn intersect_by_features(a: &Box64, b: &Box64) -> bool {
    a.corners().into_iter().any(|p| b.contains(p))
        || b.corners().into_iter().any(|p| a.contains(p))
        || a.edges().into_iter().any(|(p, q)| b.meets_segment(p, q))
        || b.edges().into_iter().any(|(p, q)| a.meets_segment(p, q))
}

/// The reference answer, or `None` when growing and shrinking the boxes by a little changes
/// it (near-touching boxes, where `f32` rounding may decide either way).
fn reference<V: Vector>(a: &Obb<V>, b: &Obb<V>) -> Option<bool> {
    let shrunk = intersect_by_features(&Box64::new(a, -1e-3), &Box64::new(b, -1e-3));
    let grown = intersect_by_features(&Box64::new(a, 1e-3), &Box64::new(b, 1e-3));
    (shrunk == grown).then_some(shrunk)
}

/// Checks `overlaps`, `separating_axis` and `sat_tests` of one pair against the reference.
/// Returns the reference answer, `None` when skipped.
fn check_pair<V: Vector>(a: &Obb<V>, b: &Obb<V>) -> Option<bool> {
    let expected = reference(a, b)?;
    assert_eq!(a.overlaps(b), expected, "{a:?} {b:?}");
    assert_eq!(b.overlaps(a), expected, "{a:?} {b:?}");
    assert_eq!(BoundingVolume::overlaps(a, b), expected);
    let tests = a.sat_tests(b);
    assert!(if V::DIM == 2 {
        tests.len() == 4
    } else {
        (6..=15).contains(&tests.len())
    });
    let (ca, cb) = (Box64::new(a, 0.0).corners(), Box64::new(b, 0.0).corners());
    let shadow = |corners: &[DVec3], axis: DVec3| {
        let dots = corners.iter().map(|c| c.dot(axis));
        (
            dots.clone().fold(f64::INFINITY, f64::min),
            dots.fold(f64::NEG_INFINITY, f64::max),
        )
    };
    for test in &tests {
        let axis = test.axis.to_dvec3();
        assert!((axis.length() - 1.0).abs() < 1e-5, "{test:?}");
        for (interval, corners) in [(test.interval_a, &ca), (test.interval_b, &cb)] {
            let (lo, hi) = shadow(corners, axis);
            let tol = 1e-4 * (1.0 + lo.abs().max(hi.abs()));
            assert!(
                (f64::from(interval.0) - lo).abs() < tol
                    && (f64::from(interval.1) - hi).abs() < tol
            );
        }
    }
    match a.separating_axis(b) {
        None => assert!(expected && tests.iter().all(|t| !t.separates())),
        Some(sep) => {
            let first = tests
                .iter()
                .find(|t| t.separates())
                .expect("a separating test");
            assert_eq!((first.source, first.gap), (sep.source, sep.gap));
            // The axis, oriented from A to B, really separates the corners by the gap.
            let axis = sep.axis.to_dvec3();
            let (_, a_hi) = shadow(&ca, axis);
            let (b_lo, _) = shadow(&cb, axis);
            assert!((b_lo - a_hi - f64::from(sep.gap)).abs() < 1e-4, "{sep:?}");
            assert!(sep.gap > 0.0);
        }
    }
    Some(expected)
}

fn random_obb2(rng: &mut ChaCha8Rng) -> Obb2 {
    let c = Vec2::new(rng.random_range(-3.0..3.0), rng.random_range(-3.0..3.0));
    let h = Vec2::new(rng.random_range(0.2..2.0), rng.random_range(0.2..2.0));
    let x = Vec2::from_angle(rng.random_range(0.0..TAU));
    Obb::new(c, [x, x.perp()], h)
}

fn random_obb3(rng: &mut ChaCha8Rng, rotation: Quat) -> Obb3 {
    let mut v = |lo: f32, hi: f32| {
        Vec3::new(
            rng.random_range(lo..hi),
            rng.random_range(lo..hi),
            rng.random_range(lo..hi),
        )
    };
    let (c, h) = (v(-3.0, 3.0), v(0.2, 2.0));
    Obb::new(
        c,
        [rotation * Vec3::X, rotation * Vec3::Y, rotation * Vec3::Z],
        h,
    )
}

fn random_rotation(rng: &mut ChaCha8Rng) -> Quat {
    let mut a = || rng.random_range(0.0..TAU);
    Quat::from_euler(EulerRot::ZYX, a(), a(), a())
}

/// Runs `count` seeded pairs and checks that both answers occur often enough to matter.
fn run_pairs(count: usize, mut pair: impl FnMut() -> Option<bool>) {
    let results: Vec<bool> = (0..count).filter_map(|_| pair()).collect();
    let overlapping = results.iter().filter(|&&o| o).count();
    assert!(
        results.len() > count * 9 / 10,
        "too many near-touching pairs skipped"
    );
    let separated = results.len() - overlapping;
    assert!(
        overlapping > count / 10 && separated > count / 10,
        "{overlapping} overlap, {separated} not"
    );
}

#[test]
fn random_2d_pairs_agree_with_the_vertex_and_edge_method() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    run_pairs(3000, || {
        let (a, b) = (random_obb2(&mut rng), random_obb2(&mut rng));
        check_pair(&a, &b)
    });
}

#[test]
fn random_3d_pairs_agree_with_the_vertex_and_edge_method() {
    let mut rng = ChaCha8Rng::seed_from_u64(22);
    run_pairs(3000, || {
        let (qa, qb) = (random_rotation(&mut rng), random_rotation(&mut rng));
        let (a, b) = (random_obb3(&mut rng, qa), random_obb3(&mut rng, qb));
        check_pair(&a, &b)
    });
}

#[test]
fn nearly_parallel_frames_skip_degenerate_edge_axes_and_still_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    run_pairs(2000, || {
        let q = random_rotation(&mut rng);
        let tiny = Quat::from_axis_angle(Vec3::ONE.normalize(), rng.random_range(-1e-6..1e-6));
        let (a, b) = (random_obb3(&mut rng, q), random_obb3(&mut rng, tiny * q));
        check_pair(&a, &b)
    });
}

#[test]
fn in_2d_a_face_of_b_can_be_the_only_separating_axis() {
    // A diamond beyond the corner of a square: along x or y the shadows overlap, along the
    // diamond's face normal (1, 1)/√2 they are apart by 2√2 - (√2 + 1) ≈ 0.41.
    let a = Obb2::new(Vec2::ZERO, Vec2::identity_axes(), Vec2::ONE);
    let diamond = [
        Vec2::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2),
        Vec2::new(-FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    ];
    let b = Obb2::new(Vec2::splat(2.0), diamond, Vec2::ONE);
    let sep = a.separating_axis(&b).expect("they are apart");
    assert_eq!(sep.source, AxisSource::FaceB(0));
    assert!((sep.axis - diamond[0]).length() < 1e-6);
    assert!((sep.gap - (2.0 * SQRT_2 - SQRT_2 - 1.0)).abs() < 1e-5);
    let separating: Vec<_> = a
        .sat_tests(&b)
        .into_iter()
        .filter(AxisTest::separates)
        .collect();
    assert_eq!(separating.len(), 1);
    assert_eq!(check_pair(&a, &b), Some(false));
    let closer = Obb2::new(Vec2::splat(1.6), diamond, Vec2::ONE);
    assert_eq!(check_pair(&a, &closer), Some(true));
}

#[test]
fn in_3d_an_edge_pair_can_be_the_only_separating_axis() {
    // Two square prisms turned 45° about z and about x: the top edge of A runs along z at
    // y = √2, the bottom edge of B along x at y = y_b - √2. They cross like the bars of an X
    // with a gap `gap` along y = z × x, which no face normal sees for a small gap.
    let turn_z = Quat::from_rotation_z(FRAC_PI_4);
    let turn_x = Quat::from_rotation_x(FRAC_PI_4);
    let a = Obb3::new(
        Vec3::ZERO,
        [turn_z * Vec3::X, turn_z * Vec3::Y, Vec3::Z],
        Vec3::ONE,
    );
    let b_at = |gap: f32| {
        let center = Vec3::new(0.0, 2.0 * SQRT_2 + gap, 0.0);
        Obb3::new(
            center,
            [Vec3::X, turn_x * Vec3::Y, turn_x * Vec3::Z],
            Vec3::ONE,
        )
    };
    let b = b_at(0.1);
    let sep = a.separating_axis(&b).expect("they are apart");
    assert_eq!(sep.source, AxisSource::Edges(2, 0));
    assert!((sep.axis - Vec3::Y).length() < 1e-6, "{sep:?}");
    assert!((sep.gap - 0.1).abs() < 1e-5);
    let tests = a.sat_tests(&b);
    assert!(
        tests
            .iter()
            .filter(|t| !matches!(t.source, AxisSource::Edges(..)))
            .all(|t| !t.separates())
    );
    assert_eq!(check_pair(&a, &b), Some(false));
    assert_eq!(check_pair(&a, &b_at(-0.1)), Some(true));
    assert_eq!(a.separating_axis(&b_at(-0.1)), None);
}

#[test]
fn touching_boxes_overlap() {
    // Dyadic coordinates, so the shared face, edge and corner are exact.
    let a = Obb3::new(Vec3::ZERO, Vec3::identity_axes(), Vec3::new(1.0, 0.5, 0.25));
    for center in [
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(2.0, 1.0, 0.5),
    ] {
        let b = Obb3::new(center, Vec3::identity_axes(), a.half_extents);
        assert!(a.overlaps(&b) && b.overlaps(&a), "{center}");
        let apart = Obb3::new(center + Vec3::X / 1024.0, b.axes, b.half_extents);
        assert!(!a.overlaps(&apart));
        assert_eq!(
            a.separating_axis(&apart).map(|s| s.source),
            Some(AxisSource::FaceA(0))
        );
    }
    let square = Obb2::new(Vec2::ZERO, Vec2::identity_axes(), Vec2::ONE);
    let beside = Obb2::new(Vec2::new(0.0, -2.0), Vec2::identity_axes(), Vec2::ONE);
    assert!(square.overlaps(&beside));
}
