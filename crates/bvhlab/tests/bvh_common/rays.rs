//! Rays and query points that meet the hard cases.

use bvhlab::prelude::*;
use bvhlab::structure::bvh::SplitRecord;
use bvhlab::{Aabb, Ray};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::{random_vector, scene_box};

/// Rays that meet the hard cases: random ones, rays aimed exactly at vertices, along
/// primitive edges (grazing shared edges), axis-parallel from vertex coordinates, and rays
/// that start on a split plane and run inside it.
pub fn rays_for<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    log: &[SplitRecord],
    count: usize,
) -> Vec<Ray<P::Point>> {
    let (bounds, size) = scene_box(prims);
    let vertices: Vec<P::Point> = prims
        .iter()
        .flat_map(Primitive::vertices)
        .filter(|v| v.is_finite())
        .collect();
    let pick = |rng: &mut ChaCha8Rng| vertices[rng.random_range(0..vertices.len())];
    let mut rays = Vec::with_capacity(count);
    while rays.len() < count {
        let origin = bounds.center() + random_vector::<P::Point>(rng, size);
        let dir = random_vector::<P::Point>(rng, size);
        let kind = if vertices.is_empty() {
            0
        } else {
            rng.random_range(0..6)
        };
        let ray = match kind {
            0 => Ray::new(origin, dir),
            1 => Ray::through(origin, pick(rng)),
            2 => Ray::through(pick(rng), pick(rng)),
            3 => {
                let mut start = pick(rng);
                let along = rng.random_range(0..P::Point::DIM);
                start.set_coord(along, origin.coord(along));
                let sign = if rng.random_bool(0.5) { size } else { -size };
                Ray::new(start, P::Point::unit_axis(along) * sign)
            }
            4 => {
                // Along a primitive's own edge.
                let prim = &prims[rng.random_range(0..prims.len())];
                let vs: Vec<P::Point> = prim.vertices().collect();
                let (a, b) = (vs[0], vs[vs.len() - 1]);
                Ray::through(a + (a - b), b)
            }
            _ => match log.get(rng.random_range(0..log.len().max(1))) {
                Some(split) => {
                    let (mut o, mut d) = (origin, dir);
                    o.set_coord(split.axis, split.position);
                    d.set_coord(split.axis, 0.0);
                    Ray::new(o, d)
                }
                None => Ray::through(origin, pick(rng)),
            },
        };
        if let Ok(ray) = ray {
            rays.push(ray);
        }
    }
    rays
}

/// Query points: random ones around the scene, vertices, and points on split planes.
pub fn points_for<P: Primitive>(
    rng: &mut ChaCha8Rng,
    prims: &[P],
    log: &[SplitRecord],
    count: usize,
) -> Vec<P::Point> {
    let (bounds, size) = scene_box(prims);
    let mut points: Vec<P::Point> = (0..count)
        .map(|_| bounds.center() + random_vector::<P::Point>(rng, size))
        .collect();
    points.extend(prims.iter().take(count / 4).flat_map(Primitive::vertices));
    for split in log.iter().take(count / 4) {
        let mut p = bounds.center() + random_vector::<P::Point>(rng, 0.5 * size);
        p.set_coord(split.axis, split.position);
        points.push(p);
    }
    points.retain(|p| p.is_finite());
    points
}

/// Whether the hit point lies on the primitive's box, up to 1e-5 of the coordinates'
/// magnitude. `Segment2::ray_hit` computes `t` from `a - origin` rounded to `f32` and divides
/// by the sine of the angle between ray and segment, so a ray nearly parallel to a very short
/// segment far from its origin can get a `t` whose point is far off the segment; no tree
/// (whose volumes contain the primitive) can reproduce such a hit.
pub fn plausible_hit<P: Primitive>(prim: &P, ray: &Ray<P::Point>, t: f32) -> bool {
    let b = prim.bounds();
    let scale = b
        .min
        .abs()
        .max(b.max.abs())
        .max(ray.origin().abs())
        .max_element();
    let tol = P::Point::splat(1e-5 * scale + 1e-20);
    Aabb::new(b.min - tol, b.max + tol).contains(ray.at(t))
}
