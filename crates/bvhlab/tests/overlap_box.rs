//! Primitive against box (`Triangle3::intersects_aabb`, `Segment2::intersects_aabb`): exact
//! touching cases, degenerate primitives, random cases against clipping and dense sampling,
//! and the identities an exact test must keep (a box split in two loses nothing; the corner
//! order, the axis order and mirroring change nothing).

use crate::overlap_common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use overlap_common::{box_oracle, box3, int_box2, int_box3, int2, int3, permutations, point2};
use overlap_common::{point3, triangle, up};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle3 {
    Triangle3::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
}

fn seg(a: [f32; 2], b: [f32; 2]) -> Segment2 {
    Segment2::new(Vec2::from(a), Vec2::from(b))
}

fn unit_box() -> Aabb3 {
    Aabb3::new(Vec3::ZERO, Vec3::ONE)
}

#[test]
fn a_triangle_touching_only_a_corner_an_edge_or_a_face_overlaps_and_one_ulp_away_does_not() {
    let u = up(1.0) - 1.0;
    let b = unit_box();
    // An edge through the corner (1, 1, 1) on the line x + y = 2, the rest going away.
    let corner = |s: f32| tri([3.0 + s, -1.0, 1.0], [-1.0, 3.0 + s, 1.0], [3.0, 3.0, 3.0]);
    assert!(corner(0.0).intersects_aabb(&b));
    assert!(!corner(2.0 * u).intersects_aabb(&b));
    // The plane x + y = 2 contains the box edge x = y = 1.
    let edge = |s: f32| {
        tri(
            [2.0 + s, 0.0, -5.0],
            [0.0, 2.0 + s, -5.0],
            [1.0 + s, 1.0, 10.0],
        )
    };
    assert!(edge(0.0).intersects_aabb(&b));
    assert!(!edge(2.0 * u).intersects_aabb(&b));
    // A large triangle in the plane of the top face, no corner inside the box.
    let face = |z: f32| tri([-5.0, -5.0, z], [10.0, -5.0, z], [-5.0, 10.0, z]);
    assert!(face(1.0).intersects_aabb(&b));
    assert!(!face(up(1.0)).intersects_aabb(&b));
    // Touching a face with one corner only, and a face with an edge only.
    assert!(tri([0.5, 0.5, 1.0], [3.0, 3.0, 5.0], [0.0, 3.0, 5.0]).intersects_aabb(&b));
    assert!(tri([-1.0, 0.5, 1.0], [2.0, 0.5, 1.0], [0.5, 0.5, 4.0]).intersects_aabb(&b));
    assert!(!tri([-1.0, 0.5, up(1.0)], [2.0, 0.5, up(1.0)], [0.5, 0.5, 4.0]).intersects_aabb(&b));
    // A triangle around the box, with the box poking through its middle.
    assert!(tri([-4.0, -4.0, 0.5], [8.0, -4.0, 0.5], [-4.0, 8.0, 0.5]).intersects_aabb(&b));
}

#[test]
fn a_segment_touching_only_a_corner_or_a_side_overlaps_and_one_ulp_away_does_not() {
    let b = Aabb2::new(Vec2::ZERO, Vec2::ONE);
    let e = up(2.0);
    assert!(seg([2.0, 0.0], [0.0, 2.0]).intersects_aabb(&b));
    assert!(!seg([e, 0.0], [0.0, e]).intersects_aabb(&b));
    assert!(seg([-1.0, 1.0], [3.0, 1.0]).intersects_aabb(&b));
    assert!(!seg([-1.0, up(1.0)], [3.0, up(1.0)]).intersects_aabb(&b));
    assert!(seg([-1.0, -1.0], [2.0, 2.0]).intersects_aabb(&b));
    assert!(seg([0.5, 0.5], [0.5, 0.5]).intersects_aabb(&b));
    assert!(seg([1.0, 1.0], [1.0, 1.0]).intersects_aabb(&b));
    assert!(!seg([up(1.0), 1.0], [up(1.0), 1.0]).intersects_aabb(&b));
    // Flat and point boxes are closed sets too.
    let flat = Aabb2::new(Vec2::new(0.0, 1.0), Vec2::new(4.0, 1.0));
    assert!(seg([2.0, 0.0], [2.0, 5.0]).intersects_aabb(&flat));
    let point = Aabb2::new(Vec2::splat(1.0), Vec2::splat(1.0));
    assert!(seg([0.0, 0.0], [3.0, 3.0]).intersects_aabb(&point));
    assert!(!seg([0.0, 0.0], [3.0, up(3.0)]).intersects_aabb(&point));
}

#[test]
fn degenerate_triangles_are_the_segments_and_points_they_span() {
    // Collinear corners along x = y: bounds overlap the box, the segment passes outside it.
    // A test that only had the zero normal and zero edge products left would say "overlap".
    let b = Aabb3::new(Vec3::new(1.5, 0.0, -1.0), Vec3::new(3.0, 0.4, 1.0));
    let line = tri([0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [1.0, 1.0, 0.0]);
    assert!(!line.intersects_aabb(&b));
    assert!(line.intersects_aabb(&Aabb3::new(Vec3::new(1.5, 0.0, -1.0), Vec3::splat(3.0))));
    let repeated = tri([0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [2.0, 2.0, 0.0]);
    assert!(!repeated.intersects_aabb(&b));
    // Collinear in space, through the box's corner (1, 1, 1) only.
    let diagonal = tri([0.0, 2.0, 0.0], [2.0, 0.0, 2.0], [1.0, 1.0, 1.0]);
    assert!(diagonal.intersects_aabb(&unit_box()));
    let d = 1.0 / 1_048_576.0;
    let shifted = tri(
        [d, 2.0 + d, 0.0],
        [2.0 + d, d, 2.0],
        [1.0 + d, 1.0 + d, 1.0],
    );
    assert!(!shifted.intersects_aabb(&unit_box()));
    // Points: inside, on the boundary, outside.
    let p = |x: f32| tri([x, 0.5, 0.5], [x, 0.5, 0.5], [x, 0.5, 0.5]);
    assert!(p(0.5).intersects_aabb(&unit_box()));
    assert!(p(1.0).intersects_aabb(&unit_box()));
    assert!(!p(up(1.0)).intersects_aabb(&unit_box()));
}

#[test]
fn non_finite_input_touches_nothing_and_infinite_boxes_are_boxes() {
    let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let everything = Aabb3::new(Vec3::NEG_INFINITY, Vec3::INFINITY);
    assert!(t.intersects_aabb(&everything));
    let half = Aabb3::new(Vec3::new(0.6, 0.6, f32::NEG_INFINITY), Vec3::INFINITY);
    assert!(!t.intersects_aabb(&half));
    assert!(t.intersects_aabb(&Aabb3::new(Vec3::new(0.5, 0.5, -1.0), Vec3::INFINITY)));
    let nan = tri([f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    assert!(!nan.intersects_aabb(&everything));
    let inf = tri([f32::INFINITY, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    assert!(!inf.intersects_aabb(&everything));
    assert!(!t.intersects_aabb(&Aabb3::new(Vec3::splat(f32::NAN), Vec3::ONE)));
    assert!(!t.intersects_aabb(&Aabb3::EMPTY));
    assert!(!seg([f32::NAN, 0.0], [1.0, 1.0]).intersects_aabb(&Aabb2::new(Vec2::ZERO, Vec2::ONE)));
}

#[test]
fn huge_and_tiny_coordinates_are_exact_too() {
    // Powers of two, so that scaling keeps the corner exactly on the edge.
    for scale in [
        2.0f32.powi(-100),
        2.0f32.powi(100),
        2.0f32.powi(-147),
        2.0f32.powi(126),
    ] {
        let b = Aabb3::new(Vec3::ZERO, Vec3::splat(scale));
        let corner = tri([3.0, -1.0, 1.0], [-1.0, 3.0, 1.0], [3.0, 3.0, 3.0]);
        let t = Triangle3::new(corner.a * scale, corner.b * scale, corner.c * scale);
        assert!(t.intersects_aabb(&b), "scale {scale}");
        let lifted = Triangle3::new(t.a.with_z(up(t.a.z)), t.b.with_z(up(t.b.z)), t.c);
        assert!(!lifted.intersects_aabb(&b), "scale {scale}");
    }
    // Corners 1e30 away from a box of size 1e-30, touching its top face.
    let s = 1.0e-30;
    let tiny = Aabb3::new(Vec3::ZERO, Vec3::splat(s));
    let big = |z: f32| {
        tri(
            [-1.0e30, -1.0e30, z],
            [1.0e30, -1.0e30, z],
            [-1.0e30, 1.0e30, z],
        )
    };
    assert!(big(s).intersects_aabb(&tiny));
    assert!(!big(up(s)).intersects_aabb(&tiny));
    // The plane z = x, which cuts the tiny box along its diagonal, spanned by huge corners.
    let tilted = tri(
        [-1.0e30, -1.0e30, -1.0e30],
        [1.0e30, -1.0e30, 1.0e30],
        [-1.0e30, 1.0e30, -1.0e30],
    );
    assert!(tilted.intersects_aabb(&tiny));
    let raised = Triangle3::new(
        tilted.a + Vec3::Z * 1.0e29,
        tilted.b + Vec3::Z * 1.0e29,
        tilted.c + Vec3::Z * 1.0e29,
    );
    assert!(!raised.intersects_aabb(&tiny));
}

#[test]
fn a_gap_far_below_the_rounding_of_the_coordinates_is_still_a_gap() {
    // An edge from (h, -h, 0) to (-h, h, 0) through the origin, the triangle rising away
    // from the box: it touches the box with corner (0, 0, 0) there and nowhere else. Moving
    // the box's corner to (-e, -e, 0) opens a gap of about e / h = 2^-120 relative to the
    // coordinates: no f64 evaluation sees it, and the bounds still overlap.
    let (h, e) = (2.0f32.powi(100), 2.0f32.powi(-20));
    let t = tri([h, -h, 0.0], [-h, h, 0.0], [h, h, h]);
    let touching = Aabb3::new(Vec3::splat(-1.0), Vec3::ZERO);
    assert!(t.intersects_aabb(&touching));
    let apart = Aabb3::new(Vec3::splat(-1.0), Vec3::new(-e, -e, 0.0));
    assert!(!t.intersects_aabb(&apart));
    let s = seg([h, -h], [-h, h]);
    assert!(s.intersects_aabb(&Aabb2::new(Vec2::splat(-1.0), Vec2::ZERO)));
    assert!(!s.intersects_aabb(&Aabb2::new(Vec2::splat(-1.0), Vec2::splat(-e))));
    assert!(s.intersects_aabb(&Aabb2::new(Vec2::splat(-1.0), Vec2::new(-e, e))));
}

#[test]
fn random_triangles_agree_with_polygon_clipping_and_dense_sampling() {
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let (mut yes, mut no) = (0, 0);
    for _ in 0..20_000 {
        let t = triangle(&mut rng, |r| point3(r, 4.0));
        let b = box3(&mut rng, 3.0);
        let answer = t.intersects_aabb(&b);
        match box_oracle(&[t.a, t.b, t.c], b.min, b.max, 1.0e-6) {
            Some(expected) => assert_eq!(answer, expected, "{t:?} {b:?}"),
            None => continue,
        }
        if answer { yes += 1 } else { no += 1 }
    }
    assert!(yes > 3000 && no > 3000, "{yes} overlaps, {no} misses");
    // Dense sampling: a sample inside the (slightly shrunk) box proves an overlap; all samples
    // farther from the box than the sampling spacing proves a miss.
    let (mut inside, mut apart) = (0, 0);
    for _ in 0..400 {
        let t = triangle(&mut rng, |r| point3(r, 4.0));
        let b = box3(&mut rng, 3.0);
        let shrunk = Aabb3::new(b.min + 1.0e-4, b.max - 1.0e-4);
        let n = 40;
        let spacing = ((t.b - t.a).length() + (t.c - t.a).length()) / n as f32;
        let mut nearest = f32::INFINITY;
        for i in 0..=n {
            for j in 0..=n - i {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                let p = t.a + (t.b - t.a) * u + (t.c - t.a) * v;
                nearest = nearest.min(b.distance(p));
                if shrunk.contains(p) {
                    inside += 1;
                    assert!(t.intersects_aabb(&b), "sample {p} of {t:?} is in {b:?}");
                }
            }
        }
        if nearest > spacing + 1.0e-4 {
            apart += 1;
            assert!(!t.intersects_aabb(&b), "{t:?} is {nearest} from {b:?}");
        }
    }
    assert!(
        inside > 1000 && apart > 50,
        "{inside} samples inside, {apart} apart"
    );
}

#[test]
fn random_segments_agree_with_clipping() {
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    let (mut yes, mut no) = (0, 0);
    for _ in 0..20_000 {
        let (a, b) = (point2(&mut rng, 4.0), point2(&mut rng, 4.0));
        let s = if rng.random_range(0..10) == 0 {
            Segment2::new(a, a)
        } else {
            Segment2::new(a, b)
        };
        let (p, q) = (point2(&mut rng, 3.0), point2(&mut rng, 3.0));
        let bx = Aabb2::new(p.min(q), p.max(q));
        let answer = s.intersects_aabb(&bx);
        let lift = |v: Vec2| v.extend(0.0);
        let (lo, hi) = (lift(bx.min).with_z(-1.0), lift(bx.max).with_z(1.0));
        match box_oracle(&[lift(s.a), lift(s.b)], lo, hi, 1.0e-6) {
            Some(expected) => assert_eq!(answer, expected, "{s:?} {bx:?}"),
            None => continue,
        }
        if answer {
            yes += 1;
        } else {
            no += 1;
        }
        // The 2D test is the 3D test of the lifted segment against the lifted (flat) box.
        let lifted = Triangle3::new(lift(s.a), lift(s.b), lift(s.b));
        assert_eq!(
            answer,
            lifted.intersects_aabb(&Aabb3::new(lift(bx.min), lift(bx.max)))
        );
    }
    assert!(yes > 3000 && no > 3000, "{yes} overlaps, {no} misses");
}

#[test]
fn splitting_a_box_in_two_never_loses_a_primitive() {
    // A box split by a plane is the union of its closed halves, so an exact test answers
    // "overlap" for the box exactly when it does for one of the halves: the property that
    // keeps a grid from losing a primitive at a cell boundary. Small integers make touching
    // configurations (corners on the plane, edges along it) the rule, not the exception.
    // Powers of two keep the small-integer configurations exact at every scale, down to
    // subnormal coordinates.
    let mut rng = ChaCha8Rng::seed_from_u64(33);
    let mut boundary_cases = 0;
    for i in 0..24_000 {
        let scale = [1.0, 2.0f32.powi(100), 2.0f32.powi(-130)][i % 3];
        let t = triangle(&mut rng, |r| int3(r, 3, scale));
        let b = int_box3(&mut rng, 3);
        let b = Aabb3::new(b.min * scale, b.max * scale);
        let k = rng.random_range(0..3);
        let steps = ((b.max[k] - b.min[k]) / scale) as i32;
        let cut = b.min[k] + rng.random_range(0..=steps) as f32 * scale;
        let (mut low, mut high) = (b, b);
        low.max[k] = cut;
        high.min[k] = cut;
        let (whole, l, h) = (
            t.intersects_aabb(&b),
            t.intersects_aabb(&low),
            t.intersects_aabb(&high),
        );
        assert_eq!(whole, l || h, "{t:?} {b:?} split on axis {k} at {cut}");
        boundary_cases += usize::from(l && h);
    }
    assert!(
        boundary_cases > 1000,
        "only {boundary_cases} primitives on a cut"
    );
    for _ in 0..20_000 {
        let s = Segment2::new(int2(&mut rng, 3, 1.0), int2(&mut rng, 3, 1.0));
        let b = int_box2(&mut rng, 3);
        let k = rng.random_range(0..2);
        let cut = rng.random_range(b.min[k] as i32..=b.max[k] as i32) as f32;
        let (mut low, mut high) = (b, b);
        low.max[k] = cut;
        high.min[k] = cut;
        let whole = s.intersects_aabb(&b);
        assert_eq!(
            whole,
            s.intersects_aabb(&low) || s.intersects_aabb(&high),
            "{s:?} {b:?}"
        );
    }
}

#[test]
fn corner_order_axis_order_and_mirroring_change_nothing() {
    let mut rng = ChaCha8Rng::seed_from_u64(34);
    for _ in 0..3_000 {
        let t = triangle(&mut rng, |r| int3(r, 2, 0.5));
        let b = int_box3(&mut rng, 2);
        let answer = t.intersects_aabb(&b);
        for p in permutations(&t) {
            assert_eq!(p.intersects_aabb(&b), answer, "{p:?} {b:?}");
        }
        let swap = |v: Vec3| Vec3::new(v.z, v.x, v.y);
        let swapped = Triangle3::new(swap(t.a), swap(t.b), swap(t.c));
        assert_eq!(
            swapped.intersects_aabb(&Aabb3::new(swap(b.min), swap(b.max))),
            answer
        );
        let flip = |v: Vec3| Vec3::new(-v.x, v.y, v.z);
        let mirrored = Triangle3::new(flip(t.a), flip(t.b), flip(t.c));
        let mirror_box = Aabb3::new(b.min.with_x(-b.max.x), b.max.with_x(-b.min.x));
        assert_eq!(mirrored.intersects_aabb(&mirror_box), answer);
    }
}
