//! Primitive against primitive (`Triangle3::intersects`, `Segment2::intersects`): exact
//! touching cases, degenerate primitives, random cases against clipping and against the
//! watertight ray test along edges, and the identities an exact test must keep (splitting a
//! primitive in two loses nothing; order of arguments and corners changes nothing).

use crate::overlap_common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use overlap_common::{int2, int3, permutations, point2, point3, segment_oracle, triangle};
use overlap_common::{triangle_oracle, up};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle3 {
    Triangle3::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
}

fn seg(a: [f32; 2], b: [f32; 2]) -> Segment2 {
    Segment2::new(Vec2::from(a), Vec2::from(b))
}

/// Both argument orders, checked to agree.
fn meets<P: Primitive>(a: P, b: P) -> bool {
    let answer = a.intersects(&b);
    assert_eq!(answer, b.intersects(&a), "asymmetric: {a:?} {b:?}");
    answer
}

const D: f32 = 1.0 / 1_048_576.0;

#[test]
fn segments_crossing_touching_collinear_parallel_and_points() {
    assert!(meets(
        seg([0.0, 0.0], [2.0, 2.0]),
        seg([0.0, 2.0], [2.0, 0.0])
    ));
    // T-junction, and one step of 2^-20 short of it.
    assert!(meets(
        seg([0.0, 0.0], [2.0, 0.0]),
        seg([1.0, 0.0], [1.0, 5.0])
    ));
    assert!(!meets(
        seg([0.0, 0.0], [2.0, 0.0]),
        seg([1.0, D], [1.0, 5.0])
    ));
    // An end on the other's interior, and just beside it.
    assert!(meets(
        seg([0.0, 0.0], [2.0, 2.0]),
        seg([2.0, 0.0], [1.0, 1.0])
    ));
    assert!(!meets(
        seg([0.0, 0.0], [2.0, 2.0]),
        seg([2.0, 0.0], [1.0 + D, 1.0 - D])
    ));
    // Collinear: overlapping, nested, sharing an end, disjoint with overlapping bounds.
    let diag = seg([0.0, 0.0], [3.0, 3.0]);
    assert!(meets(diag, seg([2.0, 2.0], [5.0, 5.0])));
    assert!(meets(diag, seg([1.0, 1.0], [2.0, 2.0])));
    assert!(meets(diag, seg([3.0, 3.0], [4.0, 4.0])));
    assert!(!meets(
        seg([0.0, 0.0], [1.0, 1.0]),
        seg([up(1.0), up(1.0)], [4.0, 4.0])
    ));
    // Parallel, 2^-20 · √2 apart, bounds overlapping.
    assert!(!meets(diag, seg([D, -D], [3.0 + D, 3.0 - D])));
    // Zero-length segments are points.
    assert!(meets(diag, seg([1.0, 1.0], [1.0, 1.0])));
    assert!(!meets(diag, seg([1.0, up(1.0)], [1.0, up(1.0)])));
    assert!(meets(
        seg([1.0, 1.0], [1.0, 1.0]),
        seg([1.0, 1.0], [1.0, 1.0])
    ));
    assert!(!meets(
        seg([1.0, 1.0], [1.0, 1.0]),
        seg([1.0, up(1.0)], [1.0, up(1.0)])
    ));
    // Identical and reversed.
    assert!(meets(diag, diag));
    assert!(meets(diag, seg([3.0, 3.0], [0.0, 0.0])));
}

#[test]
fn coplanar_triangles_inside_touching_and_apart() {
    let a = tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]);
    assert!(meets(
        a,
        tri([1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0])
    ));
    // Beyond the hypotenuse x + y = 4, bounds overlapping: only an in-plane axis separates.
    assert!(!meets(
        a,
        tri([3.0, 3.0, 0.0], [5.0, 1.0, 0.0], [1.0, 5.0, 0.0])
    ));
    assert!(meets(
        a,
        tri([2.0, 2.0, 0.0], [5.0, 1.0, 0.0], [1.0, 5.0, 0.0])
    ));
    assert!(!meets(
        a,
        tri([2.0 + D, 2.0 + D, 0.0], [5.0, 1.0, 0.0], [1.0, 5.0, 0.0])
    ));
    // Sharing part of an edge from opposite sides.
    assert!(meets(
        a,
        tri([1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.0, -2.0, 0.0])
    ));
    assert!(!meets(
        a,
        tri([1.0, -D, 0.0], [3.0, -D, 0.0], [2.0, -2.0, 0.0])
    ));
    // Identical, in any corner order.
    for p in permutations(&a) {
        assert!(meets(a, p));
    }
}

#[test]
fn triangles_in_space_piercing_touching_and_apart() {
    let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
    assert!(meets(
        a,
        tri([0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.0])
    ));
    // Edge against edge at the single point (1, 1, 0), then moved off it along (1, 1, 0).
    assert!(meets(
        a,
        tri([0.0, 2.0, 1.0], [2.0, 0.0, -1.0], [5.0, 5.0, 0.0])
    ));
    assert!(!meets(
        a,
        tri([D, 2.0 + D, 1.0], [2.0 + D, D, -1.0], [5.0, 5.0, 0.0])
    ));
    // A corner on the face, then lifted by 2^-20.
    assert!(meets(
        a,
        tri([0.5, 0.5, 0.0], [1.0, 1.0, 3.0], [2.0, 0.0, 3.0])
    ));
    assert!(!meets(
        a,
        tri([0.5, 0.5, D], [1.0, 1.0, 3.0], [2.0, 0.0, 3.0])
    ));
    // Parallel planes.
    assert!(!meets(a, tri([0.0, 0.0, D], [2.0, 0.0, D], [0.0, 2.0, D])));
}

#[test]
fn degenerate_triangles_are_the_segments_and_points_they_span() {
    let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
    // Collinear corners piercing the face; lying in the plane beyond the hypotenuse (bounds
    // overlapping: only the in-plane normal of the hypotenuse separates); on the hypotenuse.
    assert!(meets(
        a,
        tri([0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [0.5, 0.5, 3.0])
    ));
    assert!(!meets(
        a,
        tri([2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [1.5, 1.5, 0.0])
    ));
    assert!(meets(
        a,
        tri([1.5, 0.5, 0.0], [0.5, 1.5, 0.0], [1.0, 1.0, 0.0])
    ));
    // Two segments on crossing lines in space, meeting at (1, 1, 1); then skew by 2^-20.
    let line = tri([0.0, 0.0, 0.0], [2.0, 2.0, 2.0], [1.0, 1.0, 1.0]);
    assert!(meets(
        line,
        tri([0.0, 2.0, 1.0], [2.0, 0.0, 1.0], [2.0, 0.0, 1.0])
    ));
    assert!(!meets(
        line,
        tri(
            [0.0, 2.0, 1.0 + D],
            [2.0, 0.0, 1.0 + D],
            [2.0, 0.0, 1.0 + D]
        )
    ));
    // Parallel segments 2^-20 apart; collinear overlapping segments.
    assert!(!meets(
        line,
        tri(
            [D, -D, 0.0],
            [2.0 + D, 2.0 - D, 2.0],
            [2.0 + D, 2.0 - D, 2.0]
        )
    ));
    assert!(meets(
        line,
        tri([1.0, 1.0, 1.0], [3.0, 3.0, 3.0], [3.0, 3.0, 3.0])
    ));
    // Points: on the segment, beside it; on the face, in the plane beside the face.
    let point = |p: [f32; 3]| tri(p, p, p);
    assert!(meets(line, point([0.5, 0.5, 0.5])));
    assert!(!meets(line, point([0.5, 0.5, up(0.5)])));
    assert!(meets(a, point([0.5, 0.5, 0.0])));
    assert!(meets(a, point([1.0, 1.0, 0.0])));
    assert!(!meets(a, point([1.0, up(1.0), 0.0])));
    assert!(meets(point([1.0, 1.0, 0.0]), point([1.0, 1.0, 0.0])));
    assert!(!meets(point([1.0, 1.0, 0.0]), point([1.0, 1.0, D])));
}

#[test]
fn gaps_far_below_the_rounding_of_the_coordinates_are_still_gaps() {
    // Huge triangles through the origin; small ones touching them there, or 2^-120 (relative)
    // away: the f64 filter cannot tell, the exact fallback must.
    let (h, e) = (2.0f32.powi(100), 2.0f32.powi(-20));
    let big = tri([h, -h, 0.0], [-h, h, 0.0], [h, h, h]);
    assert!(meets(
        big,
        tri([-1.0, -1.0, 0.0], [0.0, 0.0, 0.0], [-1.0, -1.0, -1.0])
    ));
    assert!(!meets(
        big,
        tri([-1.0, -1.0, 0.0], [-e, -e, 0.0], [-1.0, -1.0, -1.0])
    ));
    let long = seg([h, -h], [-h, h]);
    assert!(meets(long, seg([-1.0, -1.0], [0.0, 0.0])));
    assert!(!meets(long, seg([-1.0, -1.0], [-e, -e])));
    assert!(meets(long, seg([-1.0, -1.0], [-e, e])));
}

trait Translated {
    fn translated(self, by: f32) -> Self;
}

impl Translated for Triangle3 {
    fn translated(self, by: f32) -> Self {
        let v = Vec3::splat(by);
        Triangle3::new(self.a + v, self.b + v, self.c + v)
    }
}

#[test]
fn non_finite_triangles_and_segments_touch_nothing() {
    let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
    assert!(!meets(
        a,
        tri([f32::NAN, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0])
    ));
    assert!(!meets(
        a,
        tri([f32::INFINITY, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 2.0, 0.0])
    ));
    assert!(!meets(
        seg([0.0, 0.0], [1.0, 1.0]),
        seg([f32::NAN, 0.0], [1.0, 1.0])
    ));
}

#[test]
fn random_triangles_agree_with_clipping_and_with_rays_along_edges() {
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    let (mut yes, mut no, mut ray_witnesses) = (0, 0, 0);
    for i in 0..20_000 {
        let coplanar = i % 4 == 0;
        let corner = move |r: &mut ChaCha8Rng| {
            let p = point3(r, 2.0);
            if coplanar { p.with_z(0.0) } else { p }
        };
        let a = Triangle3::new(corner(&mut rng), corner(&mut rng), corner(&mut rng));
        let b = triangle(&mut rng, corner);
        let answer = meets(a, b);
        // The watertight ray test along b's edges: a hit well inside the edge is a witness.
        for (s, t) in [(b.a, b.b), (b.b, b.c), (b.c, b.a)] {
            let ray = Ray3::new(s, t - s);
            if ray.is_ok_and(|ray| {
                a.ray_hit(&ray)
                    .is_some_and(|t| (1.0e-3..=0.999).contains(&t))
            }) {
                ray_witnesses += 1;
                assert!(answer, "edge {s}→{t} of {b:?} crosses {a:?}");
            }
        }
        if a.area() < 1.0e-3 {
            continue;
        }
        match triangle_oracle([a.a, a.b, a.c], &[b.a, b.b, b.c], 1.0e-6) {
            Some(expected) => assert_eq!(answer, expected, "{a:?} {b:?}"),
            None => continue,
        }
        if answer { yes += 1 } else { no += 1 }
    }
    assert!(
        yes > 3000 && no > 3000 && ray_witnesses > 1000,
        "{yes} {no} {ray_witnesses}"
    );
}

#[test]
fn random_segments_agree_with_clipping_and_with_rays() {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let (mut yes, mut no) = (0, 0);
    for _ in 0..20_000 {
        let a = Segment2::new(point2(&mut rng, 2.0), point2(&mut rng, 2.0));
        let b0 = point2(&mut rng, 2.0);
        let b = if rng.random_range(0..10) == 0 {
            Segment2::new(b0, b0)
        } else {
            Segment2::new(b0, point2(&mut rng, 2.0))
        };
        let answer = meets(a, b);
        let ray = Ray2::new(b.a, b.b - b.a);
        if ray.is_ok_and(|ray| {
            a.ray_hit(&ray)
                .is_some_and(|t| (1.0e-3..=0.999).contains(&t))
        }) {
            assert!(answer, "{b:?} crosses {a:?}");
        }
        if a.length() < 1.0e-3 {
            continue;
        }
        match segment_oracle([a.a, a.b], [b.a, b.b], 1.0e-6) {
            Some(expected) => assert_eq!(answer, expected, "{a:?} {b:?}"),
            None => continue,
        }
        if answer { yes += 1 } else { no += 1 }
    }
    assert!(yes > 2000 && no > 5000, "{yes} {no}");
}

#[test]
fn splitting_a_primitive_in_two_never_loses_a_contact() {
    // B = (b0, m, b2) ∪ (m, b1, b2) with m the midpoint of b0b1 (exact for even integers), so
    // an exact test meets B exactly when it meets one of the halves; likewise for segments.
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let mut both = 0;
    for _ in 0..20_000 {
        let a = triangle(&mut rng, |r| int3(r, 2, 2.0));
        let b = triangle(&mut rng, |r| int3(r, 2, 2.0));
        let m = (b.a + b.b) * 0.5;
        let (h1, h2) = (Triangle3::new(b.a, m, b.c), Triangle3::new(m, b.b, b.c));
        let (whole, one, two) = (meets(a, b), meets(a, h1), meets(a, h2));
        assert_eq!(whole, one || two, "{a:?} {b:?}");
        both += usize::from(one && two);
    }
    assert!(both > 1000, "only {both} contacts on the cut");
    for _ in 0..20_000 {
        let a = Segment2::new(int2(&mut rng, 2, 2.0), int2(&mut rng, 2, 2.0));
        let b = Segment2::new(int2(&mut rng, 2, 2.0), int2(&mut rng, 2, 2.0));
        let m = (b.a + b.b) * 0.5;
        let halves = meets(a, Segment2::new(b.a, m)) || meets(a, Segment2::new(m, b.b));
        assert_eq!(meets(a, b), halves, "{a:?} {b:?}");
    }
}

#[test]
fn corner_order_axis_order_and_translation_change_nothing() {
    let mut rng = ChaCha8Rng::seed_from_u64(44);
    for _ in 0..2_000 {
        let a = triangle(&mut rng, |r| int3(r, 2, 1.0));
        let b = triangle(&mut rng, |r| int3(r, 2, 1.0));
        let answer = meets(a, b);
        for p in permutations(&a) {
            for q in permutations(&b) {
                assert_eq!(p.intersects(&q), answer, "{p:?} {q:?}");
            }
        }
        let swap = |t: Triangle3| {
            let s = |v: Vec3| Vec3::new(v.y, v.z, v.x);
            Triangle3::new(s(t.a), s(t.b), s(t.c))
        };
        assert_eq!(meets(swap(a), swap(b)), answer);
        assert_eq!(meets(a.translated(1000.0), b.translated(1000.0)), answer);
    }
}
