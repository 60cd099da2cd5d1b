//! The comparison of every query against brute force, and the rays and query points that
//! exercise cell boundaries and split planes.

use bvhlab::RayCast;
use bvhlab::SpatialQuery;
use bvhlab::structure::{BruteForce, PointOf, PrimitiveResult, RangeShape, Recorder};
use bvhlab::{Aabb, BoundingVolume, Event, Primitive, Ray, SpatialIndex, Sphere, Vector};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::random_vector;

/// The box around the primitives with finite coordinates.
fn scene_box<P: Primitive>(prims: &[P]) -> Aabb<P::Point> {
    prims
        .iter()
        .filter(|p| p.vertices().all(Vector::is_finite))
        .fold(Aabb::EMPTY, |b, p| b.merge(&p.bounds()))
}

/// The centre and the longest side of the scene's box, finite and positive.
fn centre_and_size<P: Primitive>(prims: &[P]) -> (P::Point, f32) {
    let bounds = scene_box(prims);
    if bounds.is_empty() {
        (P::Point::ZERO, 1.0)
    } else {
        let size = bounds.size().max_element();
        (
            bounds.center(),
            if size.is_finite() {
                size.clamp(1e-30, 1e37)
            } else {
                1e37
            },
        )
    }
}

/// Rays for a scene: random ones, ones aimed exactly at vertices (they graze shared edges and
/// corners), axis-parallel ones from vertex coordinates, and for each of `corners` (cell or
/// split-plane corners of the structure under test) rays that start on it and run along the
/// boundary planes through it, along axes and diagonally, and rays from outside aimed at it.
pub fn rays_for<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    corners: &[P::Point],
    count: usize,
) -> Vec<Ray<P::Point>> {
    let (centre, size) = centre_and_size(prims);
    let vertices: Vec<P::Point> = prims
        .iter()
        .flat_map(Primitive::vertices)
        .filter(|v| v.is_finite())
        .collect();
    let mut rays = Vec::new();
    for _ in 0..count {
        let origin = centre + random_vector::<P::Point>(rng, size);
        let ray = match rng.random_range(0..3) {
            1 if !vertices.is_empty() => {
                let target = vertices[rng.random_range(0..vertices.len())];
                Ray::new(origin, target - origin)
            }
            2 if !vertices.is_empty() => {
                let mut start = vertices[rng.random_range(0..vertices.len())];
                let along = rng.random_range(0..P::Point::DIM);
                start.set_coord(along, origin.coord(along));
                let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                Ray::new(start, P::Point::unit_axis(along) * (sign * size))
            }
            _ => Ray::new(origin, random_vector::<P::Point>(rng, 1.0) * size),
        };
        rays.extend(ray.ok());
    }
    for &corner in corners {
        let axis = rng.random_range(0..P::Point::DIM);
        let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        rays.extend(Ray::new(corner, P::Point::unit_axis(axis) * sign).ok());
        // Runs inside the boundary plane normal to `axis` through the corner.
        let mut in_plane = P::Point::splat(sign);
        in_plane.set_coord(axis, 0.0);
        rays.extend(Ray::new(corner, in_plane).ok());
        rays.extend(Ray::new(corner, -in_plane).ok());
        rays.extend(Ray::new(corner, P::Point::splat(-sign)).ok());
        let outside = centre + random_vector::<P::Point>(rng, 2.0 * size);
        rays.extend(Ray::through(outside, corner).ok());
        // From outside the scene, along an axis, on the corner's boundary planes.
        let mut from_far = corner;
        from_far.set_coord(axis, centre.coord(axis) - sign * 3.0 * size);
        rays.extend(Ray::new(from_far, P::Point::unit_axis(axis) * sign).ok());
    }
    rays
}

/// Query points: random around the scene, the scene's vertices, and the given corners.
pub fn points_for<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    corners: &[P::Point],
    count: usize,
) -> Vec<P::Point> {
    let (centre, size) = centre_and_size(prims);
    let mut points: Vec<P::Point> = (0..count)
        .map(|_| centre + random_vector::<P::Point>(rng, 0.8 * size))
        .collect();
    points.push(centre + P::Point::splat(5.0 * size));
    points.extend(prims.iter().take(4).flat_map(Primitive::vertices));
    points.extend(corners.iter().take(8));
    points
}

/// The number of primitive tests an observed query reported (mailboxed ones excluded).
fn reported_tests<V: Vector>(events: &[Event<V>]) -> u64 {
    events
        .iter()
        .filter(|e| {
            matches!(e, Event::PrimitiveTest { result, .. } if *result != PrimitiveResult::AlreadyTested)
                || matches!(e, Event::PairTest { .. })
        })
        .count() as u64
}

/// Checks every query of `structure` (built over `prims`) against brute force, panicking
/// with the scene's name and the query on the first disagreement.
pub fn check_queries<S: SpatialIndex>(
    name: &str,
    structure: &S,
    other: Option<&S>,
    rays: &[Ray<PointOf<S>>],
    points: &[PointOf<S>],
    rng: &mut ChaCha8Rng,
) {
    let prims = structure.primitives();
    let brute = BruteForce::build(prims);
    structure
        .validate()
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let stats = structure.stats();
    assert_eq!(stats.primitives, prims.len(), "{name}");
    let finite = prims
        .iter()
        .filter(|prim| prim.has_finite_coordinates())
        .count();
    assert!(stats.references >= finite, "{name}: {stats:?}");
    check_rays(name, structure, &brute, rays, rng);
    check_points(name, structure, &brute, points, rng);
    let Some(other) = other else { return };
    let mut recorder = Recorder::default();
    let traced = structure.collide_observed(other, &mut recorder);
    assert_eq!(
        traced.cost.prim_tests,
        reported_tests(&recorder.events),
        "{name}: collide cost vs events"
    );
    assert_eq!(
        traced.answer,
        brute.collide(&BruteForce::build(other.primitives())),
        "{name}: collide"
    );
}

/// First hit, any hit and all hits against brute force.
fn check_rays<S: SpatialIndex>(
    name: &str,
    structure: &S,
    brute: &BruteForce<S::Prim>,
    rays: &[Ray<PointOf<S>>],
    rng: &mut ChaCha8Rng,
) {
    let prims = structure.primitives();
    for ray in rays {
        for t_max in [f32::INFINITY, rng.random_range(0.0f32..2.0)] {
            let want = brute.ray_first_hit(ray, t_max);
            let mut recorder = Recorder::default();
            let traced = structure.ray_first_hit_observed(ray, t_max, &mut recorder);
            let got = traced.answer;
            assert_eq!(
                got,
                structure.ray_first_hit(ray, t_max),
                "{name}: observing changed the answer"
            );
            assert_eq!(
                traced.cost.prim_tests,
                reported_tests(&recorder.events),
                "{name}: cost vs events"
            );
            match (got, want) {
                (None, None) => {}
                (Some(g), Some(w)) => {
                    assert_eq!(
                        g.t, w.t,
                        "{name}: first hit {g:?}, brute force {w:?}, t_max {t_max}, {ray:?}"
                    );
                    if g.prim != w.prim {
                        assert_eq!(
                            prims[g.prim].ray_hit(ray),
                            Some(w.t),
                            "{name}: not a tie {g:?} {w:?}"
                        );
                    }
                }
                _ => panic!(
                    "{name}: first hit {got:?}, brute force {want:?}, t_max {t_max}, {ray:?}"
                ),
            }
            match structure.ray_any_hit(ray, t_max) {
                Some(h) => assert!(
                    prims[h.prim].ray_hit(ray) == Some(h.t) && h.t <= t_max && want.is_some(),
                    "{name}: any hit {h:?} is not a hit, {ray:?}"
                ),
                None => assert!(want.is_none(), "{name}: any hit missed {want:?}, {ray:?}"),
            }
            assert_eq!(
                structure.ray_all_hits(ray, t_max),
                brute.ray_all_hits(ray, t_max),
                "{name}: all hits, t_max {t_max}, {ray:?}"
            );
        }
    }
}

/// k nearest and range queries against brute force.
fn check_points<S: SpatialIndex>(
    name: &str,
    structure: &S,
    brute: &BruteForce<S::Prim>,
    points: &[PointOf<S>],
    rng: &mut ChaCha8Rng,
) {
    let (_, scale) = centre_and_size(structure.primitives());
    for &point in points {
        for k in [1, 4, 12] {
            let mut recorder = Recorder::default();
            let traced = structure.k_nearest_observed(point, k, &mut recorder);
            assert_eq!(
                traced.cost.prim_tests,
                reported_tests(&recorder.events),
                "{name}: cost vs events"
            );
            assert_eq!(
                traced.answer,
                brute.k_nearest(point, k),
                "{name}: {k} nearest to {point:?}"
            );
        }
        let radius = rng.random_range(0.0..0.3) * scale;
        let ball = RangeShape::Ball(Sphere::new(point, radius));
        assert_eq!(
            structure.range(&ball),
            brute.range(&ball),
            "{name}: {ball:?}"
        );
        let corner = point + random_vector::<PointOf<S>>(rng, 0.3 * scale);
        let boxed = RangeShape::Box(Aabb::new(point.min(corner), point.max(corner)));
        assert_eq!(
            structure.range(&boxed),
            brute.range(&boxed),
            "{name}: {boxed:?}"
        );
    }
    let nan = PointOf::<S>::splat(f32::NAN);
    assert!(
        structure.k_nearest(nan, 3).is_empty(),
        "{name}: NaN query point"
    );
    let odd = RangeShape::Box(Aabb::new(
        PointOf::<S>::splat(f32::NEG_INFINITY),
        PointOf::<S>::splat(f32::NAN),
    ));
    assert_eq!(
        structure.range(&odd),
        brute.range(&odd),
        "{name}: odd range"
    );
}
