//! The check every spatial structure must pass: the same answers as brute force, for every
//! query, on the same scenes and the same rays and points.

use bvhlab::prelude::*;
use bvhlab::structure::{BruteForce, PointOf, RangeShape, Recorder};
use bvhlab::{Aabb, Ray, Sphere, Vector};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use crate::scenes::Scene;
use crate::{random_direction, random_vector};

/// How many of each query a scene gets.
pub struct Budget {
    /// Rays per scene.
    pub rays: usize,
    /// Query points per scene.
    pub points: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            rays: 120,
            points: 40,
        }
    }
}

fn close(a: f32, b: f32, scale: f32) -> bool {
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-6 * scale
}

/// Rays for a scene: random ones through its box, rays aimed exactly at primitive vertices
/// (they graze shared edges and vertices), and axis-parallel rays from vertex coordinates
/// (they start on and run along split planes and cell boundaries). The box is that of the
/// finite primitives; the finite vertices of the others are aimed at too.
pub fn rays_for<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    count: usize,
) -> Vec<Ray<P::Point>> {
    let bounds = finite_bounds(prims);
    let (centre, size) = if bounds.is_empty() {
        (P::Point::ZERO, 1.0)
    } else {
        (
            bounds.center(),
            bounds.size().max_element().max(f32::MIN_POSITIVE * 1e6),
        )
    };
    let vertices: Vec<P::Point> = prims
        .iter()
        .flat_map(Primitive::vertices)
        .filter(|v| v.is_finite())
        .collect();
    let mut rays = Vec::with_capacity(count);
    while rays.len() < count {
        let origin = centre + random_vector::<P::Point>(rng, size);
        let kind = rng.random_range(0..3);
        let ray = if kind == 0 || vertices.is_empty() {
            Ray::new(origin, random_direction::<P::Point>(rng) * size)
        } else if kind == 1 {
            let target = vertices[rng.random_range(0..vertices.len())];
            Ray::new(origin, target - origin)
        } else {
            let mut start = vertices[rng.random_range(0..vertices.len())];
            let along = rng.random_range(0..P::Point::DIM);
            start.set_coord(along, origin.coord(along));
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            Ray::new(start, P::Point::unit_axis(along) * (sign * size))
        };
        if let Ok(ray) = ray {
            rays.push(ray);
        }
    }
    rays
}

/// The box of the primitives that queries may answer with: the finite ones.
fn finite_bounds<P: Primitive>(prims: &[P]) -> Aabb<P::Point> {
    prims
        .iter()
        .filter(|p| p.has_finite_coordinates())
        .fold(Aabb::EMPTY, |b, p| b.merge(&p.bounds()))
}

/// Panics when an answer names a primitive with a NaN or infinite coordinate, which no query
/// may report ([`Primitive::has_finite_coordinates`]).
fn assert_finite<P: Primitive>(name: &str, what: &str, prims: &[P], answer: &[usize]) {
    if let Some(&i) = answer.iter().find(|&&i| !prims[i].has_finite_coordinates()) {
        panic!(
            "{name}: {what} names primitive {i}, which is not finite: {:?}",
            prims[i]
        );
    }
}

/// Checks structure `S` against brute force on `scene`, with a second scene for collisions.
///
/// # Panics
/// On the first disagreement, naming the scene, the query and both answers.
pub fn check_against_brute_force<S>(
    rng: &mut ChaCha8Rng,
    scene: &Scene<S::Prim>,
    other: &Scene<S::Prim>,
    budget: &Budget,
) where
    S: SpatialIndex,
{
    let name = &scene.name;
    let structure = S::build(&scene.prims);
    let brute = BruteForce::build(&scene.prims);
    structure
        .validate()
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let stats = structure.stats();
    assert_eq!(
        stats.primitives,
        scene.prims.len(),
        "{name}: stats.primitives"
    );
    let finite = scene
        .prims
        .iter()
        .filter(|p| p.has_finite_coordinates())
        .count();
    assert!(stats.references >= finite, "{name}: references {stats:?}");

    check_rays(rng, scene, &structure, &brute, budget);
    check_points(rng, scene, &structure, &brute, budget);

    let other_structure = S::build(&other.prims);
    let other_brute = BruteForce::build(&other.prims);
    let mut pairs = structure.collide(&other_structure);
    pairs.sort_unstable();
    let (mine, theirs): (Vec<usize>, Vec<usize>) = pairs.iter().copied().unzip();
    assert_finite(name, "a collision pair", &scene.prims, &mine);
    assert_finite(name, "a collision pair", &other.prims, &theirs);
    assert_eq!(
        pairs,
        brute.collide(&other_brute),
        "{name} against {}: collision pairs",
        other.name
    );
}

/// First, any and all hits, plain and observed, for finite and infinite `t_max`.
fn check_rays<S: SpatialIndex>(
    rng: &mut ChaCha8Rng,
    scene: &Scene<S::Prim>,
    structure: &S,
    brute: &BruteForce<S::Prim>,
    budget: &Budget,
) {
    let name = &scene.name;
    for ray in rays_for(rng, &scene.prims, budget.rays) {
        for t_max in [f32::INFINITY, rng.random_range(0.0f32..1.5)] {
            let want = brute.ray_first_hit(&ray, t_max);
            let got = structure.ray_first_hit(&ray, t_max);
            match (got, want) {
                (None, None) => {}
                (Some(g), Some(w)) => {
                    assert!(
                        close(g.t, w.t, 0.0),
                        "{name}: first hit t {g:?} vs brute {w:?} for {ray:?}"
                    );
                    if g.prim != w.prim {
                        let t_other = scene.prims[g.prim].ray_hit(&ray);
                        assert_eq!(
                            t_other,
                            Some(w.t),
                            "{name}: first hit {g:?} is not a tie with {w:?} for {ray:?}"
                        );
                    }
                }
                _ => panic!(
                    "{name}: first hit {got:?} vs brute {want:?} for {ray:?} (t_max {t_max})"
                ),
            }
            let mut recorder = Recorder::default();
            let observed = structure.ray_first_hit_observed(&ray, t_max, &mut recorder);
            assert_eq!(observed.answer, got, "{name}: observing changed the answer");
            assert!(
                observed.cost.prim_tests as usize <= recorder.events.len()
                    || scene.prims.is_empty()
                    || observed.cost.prim_tests == 0
            );

            let any = structure.ray_any_hit(&ray, t_max);
            match (any, want) {
                (None, None) => {}
                (Some(h), Some(_)) => {
                    let t = scene.prims[h.prim].ray_hit(&ray);
                    assert!(
                        t == Some(h.t) && h.t <= t_max,
                        "{name}: any hit {h:?} is not a hit ({t:?})"
                    );
                }
                _ => panic!("{name}: any hit {any:?} vs brute first hit {want:?} for {ray:?}"),
            }

            let all = structure.ray_all_hits(&ray, t_max);
            let all_want = brute.ray_all_hits(&ray, t_max);
            let mut got_prims: Vec<usize> = all.iter().map(|h| h.prim).collect();
            let named: Vec<usize> = (got.iter().chain(&any).chain(&all_want))
                .map(|h| h.prim)
                .collect();
            assert_finite(name, "a hit", &scene.prims, &named);
            let mut want_prims: Vec<usize> = all_want.iter().map(|h| h.prim).collect();
            got_prims.sort_unstable();
            want_prims.sort_unstable();
            assert_eq!(got_prims, want_prims, "{name}: all hits for {ray:?}");
            assert!(
                all.windows(2).all(|w| w[0].t <= w[1].t),
                "{name}: all hits not sorted"
            );
        }
    }
}

/// k nearest (k = 1 and 5), ball and box ranges, and a NaN query point.
fn check_points<S: SpatialIndex>(
    rng: &mut ChaCha8Rng,
    scene: &Scene<S::Prim>,
    structure: &S,
    brute: &BruteForce<S::Prim>,
    budget: &Budget,
) {
    let name = &scene.name;
    let bounds = finite_bounds(&scene.prims);
    let scale = if bounds.is_empty() {
        1.0
    } else {
        bounds
            .size()
            .max_element()
            .max(bounds.center().abs().max_element())
    };
    let mut points: Vec<PointOf<S>> = (0..budget.points)
        .map(|_| bounds_point(rng, &bounds))
        .collect();
    points.extend(scene.prims.iter().take(5).flat_map(Primitive::vertices));
    for point in points {
        for k in [1, 5] {
            let got = structure.k_nearest(point, k);
            let want = brute.k_nearest(point, k);
            assert_eq!(got.len(), want.len(), "{name}: {k} nearest to {point:?}");
            let named: Vec<usize> = want.iter().map(|n| n.prim).collect();
            assert_finite(name, "a nearest primitive", &scene.prims, &named);
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    close(g.distance, w.distance, 0.0),
                    "{name}: {k} nearest to {point:?}: {got:?} vs {want:?}"
                );
                let d = scene.prims[g.prim].distance(point);
                assert!(
                    close(d, g.distance, 0.0),
                    "{name}: reported distance {g:?} but the primitive is {d} away"
                );
            }
        }
        let radius = rng.random_range(0.0..0.3) * scale;
        let ball = RangeShape::Ball(Sphere::new(point, radius));
        assert_finite(name, "a range", &scene.prims, &brute.range(&ball));
        assert_eq!(
            structure.range(&ball),
            brute.range(&ball),
            "{name}: range {ball:?}"
        );
        let corner = point + random_vector::<PointOf<S>>(rng, 0.3 * scale);
        let boxed = RangeShape::Box(Aabb::new(point.min(corner), point.max(corner)));
        assert_eq!(
            structure.range(&boxed),
            brute.range(&boxed),
            "{name}: range {boxed:?}"
        );
    }
    let nan = <PointOf<S> as Vector>::splat(f32::NAN);
    assert!(
        structure.closest_point(nan).is_none(),
        "{name}: a NaN query point must get no answer"
    );
}

fn bounds_point<V: Vector>(rng: &mut ChaCha8Rng, bounds: &Aabb<V>) -> V {
    if bounds.is_empty() {
        return random_vector(rng, 1.0);
    }
    let size = bounds.size().max_element();
    bounds.center() + random_vector::<V>(rng, 0.75 * size.max(f32::MIN_POSITIVE))
}
