//! Independent oracles for the overlap tests: polygon clipping in `f64` with a safety margin
//! (Sutherland and Hodgman, "Reentrant Polygon Clipping", CACM 1974), and the exact
//! set identities any exact test must satisfy.
#![allow(
    dead_code,
    reason = "each test file uses a different part of this module"
)]

use bvhlab::glam::{DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// The part of the convex polygon (or segment, or point) `poly` with `n · x <= c`.
pub fn clip(poly: &[DVec3], n: DVec3, c: f64) -> Vec<DVec3> {
    let inside = |p: DVec3| n.dot(p) <= c;
    let mut out = Vec::new();
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        if inside(p) {
            out.push(p);
        }
        if inside(p) != inside(q) {
            let (dp, dq) = (n.dot(p) - c, n.dot(q) - c);
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// Clips `poly` by every half-space `(n, c)`, each moved outward by `slack · |n|`.
fn clip_all(poly: &[DVec3], half_spaces: &[(DVec3, f64)], slack: f64) -> Vec<DVec3> {
    half_spaces.iter().fold(poly.to_vec(), |p, &(n, c)| {
        if p.is_empty() {
            p
        } else {
            clip(&p, n, c + slack * n.length())
        }
    })
}

/// The six half-spaces of a box.
fn box_half_spaces(min: DVec3, max: DVec3) -> Vec<(DVec3, f64)> {
    (0..3)
        .flat_map(|k| {
            let u = DVec3::AXES[k];
            [(u, max[k]), (-u, -min[k])]
        })
        .collect()
}

/// Whether the hull of `points` meets the box: `Some(true)` when it meets the box shrunk by
/// `margin`, `Some(false)` when it misses the box grown by `margin`, `None` in between.
pub fn box_oracle(points: &[Vec3], min: Vec3, max: Vec3, margin: f64) -> Option<bool> {
    let poly: Vec<DVec3> = points.iter().map(|p| p.as_dvec3()).collect();
    let spaces = box_half_spaces(min.as_dvec3(), max.as_dvec3());
    if !clip_all(&poly, &spaces, -margin).is_empty() {
        Some(true)
    } else if clip_all(&poly, &spaces, margin).is_empty() {
        Some(false)
    } else {
        None
    }
}

/// Whether a proper triangle `a` meets the hull of `b`: clip `b` by the three side walls of
/// `a` (the half-spaces through its edges, perpendicular to its plane), then see whether what
/// is left crosses `a`'s plane. Margins as in [`box_oracle`].
pub fn triangle_oracle(a: [Vec3; 3], b: &[Vec3], margin: f64) -> Option<bool> {
    let [p, q, r] = a.map(Vec3::as_dvec3);
    let n = (q - p).cross(r - p).normalize();
    let walls: Vec<(DVec3, f64)> = [(p, q), (q, r), (r, p)]
        .iter()
        .map(|&(s, e)| {
            let out = (e - s).cross(n).normalize();
            (out, out.dot(s))
        })
        .collect();
    let poly: Vec<DVec3> = b.iter().map(|v| v.as_dvec3()).collect();
    let heights = |part: &[DVec3]| {
        let h: Vec<f64> = part.iter().map(|x| n.dot(*x - p)).collect();
        let lo = h.iter().copied().fold(f64::INFINITY, f64::min);
        (lo, h.iter().copied().fold(f64::NEG_INFINITY, f64::max))
    };
    let inner = clip_all(&poly, &walls, -margin);
    if !inner.is_empty() {
        let (lo, hi) = heights(&inner);
        // Crossing the plane by more than the margin, or lying exactly in it.
        if (lo < -margin && hi > margin) || (lo == 0.0 && hi == 0.0) {
            return Some(true);
        }
    }
    let outer = clip_all(&poly, &walls, margin);
    if outer.is_empty() {
        return Some(false);
    }
    let (lo, hi) = heights(&outer);
    (lo > margin || hi < -margin).then_some(false)
}

/// Whether the segment `a` (of positive length) meets the segment `b` in the plane: clip `b`
/// to the strip across `a`'s ends, then see whether what is left crosses `a`'s line.
pub fn segment_oracle(a: [Vec2; 2], b: [Vec2; 2], margin: f64) -> Option<bool> {
    let [p, q] = a.map(|v| v.as_dvec2().extend(0.0));
    let d = (q - p).normalize();
    let n = DVec3::new(-d.y, d.x, 0.0);
    let caps = [(d, d.dot(q)), (-d, -d.dot(p))];
    let poly: Vec<DVec3> = b.iter().map(|v| v.as_dvec2().extend(0.0)).collect();
    let heights = |part: &[DVec3]| {
        let h: Vec<f64> = part.iter().map(|x| n.dot(*x - p)).collect();
        let lo = h.iter().copied().fold(f64::INFINITY, f64::min);
        (lo, h.iter().copied().fold(f64::NEG_INFINITY, f64::max))
    };
    let inner = clip_all(&poly, &caps, -margin);
    if !inner.is_empty() {
        let (lo, hi) = heights(&inner);
        if lo < -margin && hi > margin {
            return Some(true);
        }
    }
    let outer = clip_all(&poly, &caps, margin);
    if outer.is_empty() {
        return Some(false);
    }
    let (lo, hi) = heights(&outer);
    (lo > margin || hi < -margin).then_some(false)
}

/// A random point in `[-r, r]^3`.
pub fn point3(rng: &mut ChaCha8Rng, r: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-r..r),
        rng.random_range(-r..r),
        rng.random_range(-r..r),
    )
}

/// A random point in `[-r, r]^2`.
pub fn point2(rng: &mut ChaCha8Rng, r: f32) -> Vec2 {
    Vec2::new(rng.random_range(-r..r), rng.random_range(-r..r))
}

/// A random small-integer point in `[-r, r]^3` (times `scale`): exact arithmetic galore,
/// so touching and collinear configurations are common.
pub fn int3(rng: &mut ChaCha8Rng, r: i32, scale: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-r..=r) as f32,
        rng.random_range(-r..=r) as f32,
        rng.random_range(-r..=r) as f32,
    ) * scale
}

/// A random small-integer point in `[-r, r]^2` (times `scale`).
pub fn int2(rng: &mut ChaCha8Rng, r: i32, scale: f32) -> Vec2 {
    Vec2::new(
        rng.random_range(-r..=r) as f32,
        rng.random_range(-r..=r) as f32,
    ) * scale
}

/// A random box with corners in `[-r, r]^3`.
pub fn box3(rng: &mut ChaCha8Rng, r: f32) -> Aabb3 {
    let (p, q) = (point3(rng, r), point3(rng, r));
    Aabb3::new(p.min(q), p.max(q))
}

/// A random small-integer box (possibly flat) with corners in `[-r, r]^3`.
pub fn int_box3(rng: &mut ChaCha8Rng, r: i32) -> Aabb3 {
    let (p, q) = (int3(rng, r, 1.0), int3(rng, r, 1.0));
    Aabb3::new(p.min(q), p.max(q))
}

/// A random small-integer box (possibly flat) with corners in `[-r, r]^2`.
pub fn int_box2(rng: &mut ChaCha8Rng, r: i32) -> Aabb2 {
    let (p, q) = (int2(rng, r, 1.0), int2(rng, r, 1.0));
    Aabb2::new(p.min(q), p.max(q))
}

/// A random triangle with corners from `corner`: mostly proper, sometimes a segment (a
/// repeated corner, or a third corner on the line of the first two) or a point.
pub fn triangle(rng: &mut ChaCha8Rng, corner: impl Fn(&mut ChaCha8Rng) -> Vec3) -> Triangle3 {
    let (a, b) = (corner(rng), corner(rng));
    let c = match rng.random_range(0..8) {
        0 => a,
        1 => b,
        2 => a + (b - a) * 2.0,
        _ => corner(rng),
    };
    let t = Triangle3::new(a, b, c);
    if rng.random_range(0..10) == 0 {
        Triangle3::new(a, a, a)
    } else {
        t
    }
}

/// The six orders of a triangle's corners.
pub fn permutations(t: &Triangle3) -> [Triangle3; 6] {
    let (a, b, c) = (t.a, t.b, t.c);
    [
        Triangle3::new(a, b, c),
        Triangle3::new(a, c, b),
        Triangle3::new(b, a, c),
        Triangle3::new(b, c, a),
        Triangle3::new(c, a, b),
        Triangle3::new(c, b, a),
    ]
}

/// The next `f32` above `x`.
pub fn up(x: f32) -> f32 {
    x.next_up()
}
