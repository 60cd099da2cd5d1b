//! Convex hulls, checked against closed forms and independent brute-force answers, in 2D and
//! 3D. The building checks are in `hull/build.rs`, the queries in `hull/queries.rs`; shared
//! point sets and checks are here.

mod build;
mod queries;

use std::collections::HashMap;

use bvhlab::glam::{DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{ConvexHull, Vector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A deterministic random generator.
fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A point uniformly in `[-extent, extent]^DIM`.
fn random_vector<V: Vector>(rng: &mut ChaCha8Rng, extent: f64) -> V {
    let mut c = || rng.random_range(-extent..=extent);
    V::from_dvec3(DVec3::new(c(), c(), c()))
}

/// `n` points uniformly in the ball of radius `r` about `centre`.
fn ball_points<V: Vector>(rng: &mut ChaCha8Rng, n: usize, centre: V, r: f64) -> Vec<V> {
    let mut points = Vec::with_capacity(n);
    while points.len() < n {
        let p: V = random_vector(rng, r);
        if f64::from(p.length()) <= r {
            points.push(centre + p);
        }
    }
    points
}

/// `n` points spread evenly over the unit sphere (a Fibonacci lattice) or, in 2D, the unit
/// circle (a regular polygon).
fn sphere_points<V: Vector>(n: usize) -> Vec<V> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let p = if V::DIM == 2 {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), 0.0)
            } else {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let (r, a) = ((1.0 - z * z).sqrt(), golden * i as f64);
                DVec3::new(r * a.cos(), r * a.sin(), z)
            };
            V::from_dvec3(p)
        })
        .collect()
}

/// An `f64` copy, padded with zeros.
fn d<V: Vector>(v: V) -> DVec3 {
    v.to_dvec3()
}

/// The bit pattern of a point, to use it as a map key.
fn key<V: Vector>(v: V) -> [u32; 3] {
    let mut k = [0; 3];
    for (i, slot) in k.iter_mut().enumerate().take(V::DIM) {
        *slot = (v.coord(i) + 0.0).to_bits();
    }
    k
}

/// The magnitude of a point set's coordinates: the scale of rounding errors.
fn magnitude<V: Vector>(points: &[V]) -> f64 {
    let reach = points.iter().fold(V::ZERO, |m, p| m.max(p.abs()));
    (0..V::DIM).map(|i| f64::from(reach.coord(i))).sum::<f64>() + 1e-30
}

/// A facet's outward normal in `f64`, not normalised, from its corners alone.
fn outward<V: Vector>(facet: &V::Facet) -> DVec3 {
    let c: Vec<DVec3> = facet.vertices().map(d).collect();
    if c.len() == 2 {
        let e = c[1] - c[0];
        DVec3::new(e.y, -e.x, 0.0)
    } else {
        (c[1] - c[0]).cross(c[2] - c[0])
    }
}

/// The checks every hull must pass, whatever its dimension: it contains every input point,
/// its vertices are input points, and (for a full-dimensional hull) every input point is on
/// the inner side of every facet's plane, up to `f32` rounding of the input's magnitude.
fn check_hull<V: Vector>(points: &[V], hull: &ConvexHull<V>) {
    let finite: Vec<V> = points.iter().copied().filter(|p| p.is_finite()).collect();
    let slack = 2e-6 * magnitude(&finite);
    assert_eq!(hull.is_empty(), finite.is_empty());
    for &p in &finite {
        assert!(hull.contains(p), "input point {p:?} is outside the hull");
    }
    for v in hull.vertices() {
        assert!(
            finite.contains(v),
            "hull vertex {v:?} is not an input point"
        );
    }
    if hull.dimension() == Some(V::DIM) {
        for facet in hull.facets() {
            let corner = d(facet.vertices().next().expect("a facet has corners"));
            let n = outward::<V>(facet).normalize();
            for &p in &finite {
                let height = n.dot(d(p) - corner);
                assert!(height <= slack, "{p:?} is {height} above facet {facet:?}");
            }
        }
    }
}

/// A 2D hull's boundary: vertices counter-clockwise and strictly convex, facets `v_i → v_i+1`.
fn check_polygon(hull: &ConvexHull2) {
    let v = hull.vertices();
    let n = v.len();
    if hull.dimension() == Some(2) {
        for i in 0..n {
            let (a, b, c) = (d(v[i]), d(v[(i + 1) % n]), d(v[(i + 2) % n]));
            assert!(
                (b - a).cross(c - b).z > 0.0,
                "no strict left turn at {:?}",
                v[(i + 1) % n]
            );
        }
    }
    let expected: Vec<Segment2> = match n {
        0 | 1 => Vec::new(),
        _ => (0..n)
            .map(|i| Segment2::new(v[i], v[(i + 1) % n]))
            .collect(),
    };
    assert_eq!(hull.facets(), expected.as_slice());
}

/// A 3D hull's boundary is a closed, consistently wound triangle mesh of genus 0: each
/// directed edge occurs once and its reverse once, and `V − E + F = 2`. Returns `E`.
fn check_closed_mesh(hull: &ConvexHull3) -> usize {
    let mut directed: HashMap<([u32; 3], [u32; 3]), usize> = HashMap::new();
    for t in hull.facets() {
        let (a, b, c) = (d(t.a), d(t.b), d(t.c));
        assert!(
            (b - a).cross(c - a).length() > 0.0,
            "degenerate facet {t:?}"
        );
        for (a, b) in [(t.a, t.b), (t.b, t.c), (t.c, t.a)] {
            *directed.entry((key(a), key(b))).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(count, 1, "edge {a:?} → {b:?} is used {count} times");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "edge {a:?} → {b:?} has no twin"
        );
    }
    let edges = directed.len() / 2;
    let (v, f) = (hull.vertices().len(), hull.facets().len());
    assert_eq!(v + f, edges + 2, "Euler: V − E + F = {v} − {edges} + {f}");
    edges
}

/// Both checks, in the dimension at hand.
fn check_2d(points: &[Vec2]) -> ConvexHull2 {
    let hull = ConvexHull2::from_points(points);
    check_hull(points, &hull);
    check_polygon(&hull);
    hull
}

fn check_3d(points: &[Vec3]) -> ConvexHull3 {
    let hull = ConvexHull3::from_points(points);
    check_hull(points, &hull);
    if hull.dimension() >= Some(2) {
        check_closed_mesh(&hull);
    } else {
        assert!(hull.facets().is_empty());
    }
    hull
}
