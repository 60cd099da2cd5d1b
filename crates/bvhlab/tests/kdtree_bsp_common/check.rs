//! Queries that hit the hard cases, and the check of every answer against brute force.

use bvhlab::RayCast;
use bvhlab::SpatialQuery;
use bvhlab::structure::{BruteForce, Event, PrimitiveResult, RangeShape, Recorder};
use bvhlab::volume::BoundingVolume;
use bvhlab::{Aabb, Hit, Nearest, Primitive, Ray, SpatialIndex, Sphere, Vector};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::random_vector;

/// The queries of one check.
pub struct Queries<V: Vector> {
    /// Rays with their `t_max`.
    pub rays: Vec<(Ray<V>, f32)>,
    /// Query points for nearest neighbours.
    pub points: Vec<V>,
    /// Range regions.
    pub ranges: Vec<RangeShape<V>>,
}

/// The box of the finite primitives, or the unit box.
pub fn scene_box<P: Primitive>(prims: &[P]) -> Aabb<P::Point> {
    let b = prims
        .iter()
        .map(Primitive::bounds)
        .filter(|b| b.min.is_finite() && b.max.is_finite())
        .fold(Aabb::EMPTY, |a, b| a.merge(&b));
    if b.is_empty() {
        Aabb::new(-P::Point::splat(1.0), P::Point::splat(1.0))
    } else {
        b
    }
}

/// A point in the box grown by a fifth of its size.
fn in_box<V: Vector>(rng: &mut ChaCha8Rng, b: &Aabb<V>) -> V {
    let mut v = V::ZERO;
    for i in 0..V::DIM {
        let (lo, hi) = (b.min.coord(i), b.max.coord(i));
        let pad = (hi - lo) * 0.2 + hi.abs().max(lo.abs()) * 1e-3 + f32::MIN_POSITIVE;
        v.set_coord(i, rng.random_range(lo - pad..=hi + pad));
    }
    v
}

fn vertex<P: Primitive>(rng: &mut ChaCha8Rng, prims: &[P]) -> Option<P::Point> {
    if prims.is_empty() {
        return None;
    }
    let p = &prims[rng.random_range(0..prims.len())];
    let vs: Vec<P::Point> = p.vertices().collect();
    let v = vs[rng.random_range(0..vs.len())];
    v.is_finite().then_some(v)
}

fn direction<V: Vector>(rng: &mut ChaCha8Rng) -> V {
    loop {
        let d: V = random_vector(rng, 1.0);
        if d.length() > 1e-3 {
            return d;
        }
    }
}

/// Rays of every hard kind: random, axis-parallel, from a vertex, through a vertex or an edge
/// midpoint (grazing shared edges), inside a plane through a vertex coordinate (a split plane
/// of the SAH and median builders), and with short or zero `t_max`.
pub fn rays<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    n: usize,
) -> Vec<(Ray<P::Point>, f32)> {
    let b = scene_box(prims);
    let mut rays = Vec::with_capacity(n);
    while rays.len() < n {
        let mut origin = in_box(rng, &b);
        let mut dir: P::Point = direction(rng);
        let axis = rng.random_range(0..P::Point::DIM);
        match rng.random_range(0..7) {
            0 => {}
            1 => dir = P::Point::unit_axis(axis) * if rng.random_bool(0.5) { 1.0 } else { -1.0 },
            2 => origin = vertex(rng, prims).unwrap_or(origin),
            3 => {
                if let Some(v) = vertex(rng, prims) {
                    dir = v - origin;
                }
            }
            4 => {
                if let (Some(u), Some(v)) = (vertex(rng, prims), vertex(rng, prims)) {
                    dir = (u + v) * 0.5 - origin;
                }
            }
            5 => {
                if let Some(v) = vertex(rng, prims) {
                    origin.set_coord(axis, v.coord(axis));
                    dir.set_coord(axis, 0.0);
                }
            }
            _ => {
                if let Some(v) = vertex(rng, prims) {
                    dir = P::Point::unit_axis(axis);
                    origin = v - dir * (b.max.coord(axis) - b.min.coord(axis) + 1.0);
                }
            }
        }
        let t_max = match rng.random_range(0..6) {
            0 => rng.random_range(0.0f32..2.0),
            1 => 0.0,
            _ => f32::INFINITY,
        };
        if let Ok(ray) = Ray::new(origin, dir) {
            rays.push((ray, t_max));
        }
    }
    rays
}

/// Query points: random near the scene, on vertices, and on vertex coordinates.
pub fn points<P: Primitive>(rng: &mut ChaCha8Rng, prims: &[P], n: usize) -> Vec<P::Point> {
    let b = scene_box(prims);
    (0..n)
        .map(|i| {
            let mut p = in_box(rng, &b);
            match (i % 3, vertex(rng, prims)) {
                (1, Some(v)) => p = v,
                (2, Some(v)) => {
                    let axis = rng.random_range(0..P::Point::DIM);
                    p.set_coord(axis, v.coord(axis));
                }
                _ => {}
            }
            p
        })
        .collect()
}

/// Boxes and balls of several sizes, some touching vertices, some empty.
pub fn ranges<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    n: usize,
) -> Vec<RangeShape<P::Point>> {
    let b = scene_box(prims);
    let size = (b.max - b.min).max_element();
    (0..n)
        .map(|i| {
            let c = vertex(rng, prims)
                .filter(|_| i % 2 == 0)
                .unwrap_or_else(|| in_box(rng, &b));
            let r = size * rng.random_range(0.0f32..0.3);
            match i % 4 {
                0 | 1 => RangeShape::Ball(Sphere::new(c, if i % 8 == 1 { 0.0 } else { r })),
                2 => RangeShape::Box(Aabb::new(
                    c - P::Point::splat(r),
                    c + P::Point::splat(r * 0.5),
                )),
                _ => RangeShape::Box(Aabb::new(c, c + random_vector::<P::Point>(rng, r).abs())),
            }
        })
        .collect()
}

/// The standard queries for a scene.
pub fn queries<P: Primitive>(rng: &mut ChaCha8Rng, prims: &[P], n: usize) -> Queries<P::Point> {
    Queries {
        rays: rays(rng, prims, n),
        points: points(rng, prims, n / 2),
        ranges: ranges(rng, prims, n / 4),
    }
}

fn close(a: f32, b: f32) -> bool {
    a == b || (a - b).abs() <= 1e-5 * a.abs().max(b.abs())
}

fn same_hit<P: Primitive>(
    what: &str,
    prims: &[P],
    ray: &Ray<P::Point>,
    got: Option<Hit>,
    want: Option<Hit>,
) {
    match (got, want) {
        (None, None) => {}
        (Some(g), Some(w)) => {
            assert!(
                close(g.t, w.t),
                "{what}: t {} != brute force {} ({ray:?})",
                g.t,
                w.t
            );
            assert_eq!(
                prims[g.prim].ray_hit(ray),
                Some(g.t),
                "{what}: not a real hit"
            );
        }
        _ => panic!("{what}: {got:?} != brute force {want:?} for {ray:?}"),
    }
}

fn same_nearest<V: Vector>(what: &str, got: &[Nearest<V>], want: &[Nearest<V>]) {
    assert_eq!(
        got.len(),
        want.len(),
        "{what}: {got:?} != brute force {want:?}"
    );
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.prim == w.prim || close(g.distance, w.distance),
            "{what}: {got:?} != brute force {want:?}"
        );
        assert!(
            close(g.distance, w.distance) || g.distance.is_nan(),
            "{what}: {got:?} != {want:?}"
        );
    }
}

/// Checks every query of `index` against brute force over the same primitives.
pub fn check_queries<S: SpatialIndex>(
    label: &str,
    index: &S,
    queries: &Queries<bvhlab::structure::PointOf<S>>,
) {
    let prims = index.primitives();
    let brute = BruteForce::build(prims);
    for (i, (ray, t_max)) in queries.rays.iter().enumerate() {
        let what = format!("{label}, ray {i}");
        same_hit(
            &what,
            prims,
            ray,
            index.ray_first_hit(ray, *t_max),
            brute.ray_first_hit(ray, *t_max),
        );
        let any = index.ray_any_hit(ray, *t_max);
        assert_eq!(
            any.is_some(),
            brute.ray_any_hit(ray, *t_max).is_some(),
            "{what}: any hit"
        );
        if let Some(hit) = any {
            assert_eq!(prims[hit.prim].ray_hit(ray), Some(hit.t), "{what}: any hit");
            assert!(hit.t <= *t_max, "{what}: any hit beyond t_max");
        }
        let all = index.ray_all_hits(ray, *t_max);
        assert_eq!(all, brute.ray_all_hits(ray, *t_max), "{what}: all hits");
    }
    for (i, &p) in queries.points.iter().enumerate() {
        for k in [1, 3, 10] {
            let what = format!("{label}, point {i} {p:?}, k = {k}");
            same_nearest(&what, &index.k_nearest(p, k), &brute.k_nearest(p, k));
        }
    }
    for (i, shape) in queries.ranges.iter().enumerate() {
        assert_eq!(
            index.range(shape),
            brute.range(shape),
            "{label}, range {i} {shape:?}"
        );
    }
}

/// Checks the collision query of two structures against brute force.
pub fn check_collide<S: SpatialIndex>(label: &str, a: &S, b: &S) {
    let (ba, bb) = (
        BruteForce::build(a.primitives()),
        BruteForce::build(b.primitives()),
    );
    assert_eq!(a.collide(b), ba.collide(&bb), "{label}: collide");
}

const ALREADY: PrimitiveResult = PrimitiveResult::AlreadyTested;

/// Checks that the observed events agree with the answer and the cost: one `EnterNode` per
/// node visited, one real `PrimitiveTest` per counted test, and the same answer as unobserved.
pub fn check_events<S: SpatialIndex>(
    label: &str,
    index: &S,
    queries: &Queries<bvhlab::structure::PointOf<S>>,
) {
    let count = |events: &[Event<_>]| {
        let enters = events
            .iter()
            .filter(|e| matches!(e, Event::EnterNode { .. }))
            .count() as u64;
        let tests = events
            .iter()
            .filter(|e| matches!(e, Event::PrimitiveTest { result, .. } if *result != ALREADY))
            .count() as u64;
        (enters, tests)
    };
    for (ray, t_max) in &queries.rays {
        let mut recorder = Recorder::default();
        let traced = index.ray_first_hit_observed(ray, *t_max, &mut recorder);
        assert_eq!(traced.answer, index.ray_first_hit(ray, *t_max), "{label}");
        let (enters, tests) = count(&recorder.events);
        assert_eq!(
            (enters, tests),
            (traced.cost.nodes_visited, traced.cost.prim_tests),
            "{label}"
        );
        if let Some(hit) = traced.answer {
            let best = recorder.events.iter().rev().find_map(|e| match e {
                Event::NewBest { prim, value } => Some((*prim as usize, *value)),
                _ => None,
            });
            assert_eq!(
                best,
                Some((hit.prim, hit.t)),
                "{label}: last NewBest is the answer"
            );
        }
    }
    for &p in &queries.points {
        let mut recorder = Recorder::default();
        let traced = index.k_nearest_observed(p, 3, &mut recorder);
        assert_eq!(traced.answer, index.k_nearest(p, 3), "{label}");
        assert_eq!(
            count(&recorder.events),
            (traced.cost.nodes_visited, traced.cost.prim_tests),
            "{label}"
        );
    }
}
