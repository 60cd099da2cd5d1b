//! The part of the [`Primitive`] contract a structure can check cheaply: the primitive lies
//! inside the convex hull of its vertices, so its bounds lie inside their box.

use super::Primitive;
use crate::Vector;
use crate::volume::{Aabb, BoundingVolume};

/// Checks that `prim`'s [`bounds`](Primitive::bounds) lie inside the box of its
/// [`vertices`](Primitive::vertices) (contract 1 of [`Primitive`]: the primitive lies in the
/// convex hull of its vertices, so its box does not reach beyond theirs). A primitive with a
/// non-finite vertex passes (the structures leave it out).
///
/// This catches the mistake a custom primitive most easily makes: a ball that returns its
/// centre as its only vertex. The sphere and OBB trees fit their nodes to the vertices, so
/// such a ball pokes out of its leaf and rays and nearest-point queries miss it. Every BVH's
/// `validate()` runs this check on each primitive it indexes.
///
/// # Errors
/// A message naming the bounds and the box of the vertices.
pub fn check_enclosed_by_vertices<P: Primitive>(prim: &P) -> Result<(), String> {
    let mut hull_box = Aabb::<P::Point>::EMPTY;
    for v in prim.vertices() {
        if !v.is_finite() {
            return Ok(());
        }
        hull_box = hull_box.grown(v);
    }
    let bounds = prim.bounds();
    let inside = (0..P::Point::DIM).all(|i| {
        hull_box.min.coord(i) <= bounds.min.coord(i) && bounds.max.coord(i) <= hull_box.max.coord(i)
    });
    if inside && !hull_box.is_empty() {
        return Ok(());
    }
    Err(format!(
        "its bounds {bounds:?} reach beyond the box of its vertices {hull_box:?}: \
         the Primitive contract asks vertices() to return points whose convex hull holds the \
         whole primitive (for a ball, e.g. the corners of its box, not its centre), since the \
         sphere and OBB trees fit their nodes to them"
    ))
}

/// How far, relative to the size of the coordinates involved, a hit point or projected point
/// may lie outside [`bounds`](Primitive::bounds) before [`check_bounds_hold`] and the debug
/// build's query checks call it a broken contract. Rounding of a correct primitive is a few
/// units in the last place (about 1e-7 of the coordinates); a box too small for its primitive
/// misses by a fraction of the primitive's size. This margin lies far from both.
const BOUNDS_MARGIN: f32 = 1e-4;

/// Checks, by probing, that `prim`'s [`bounds`](Primitive::bounds) hold the points its own
/// queries give (contract 2 of [`Primitive`]): from points around its box (along each axis
/// and each diagonal, twice its size away) it projects each onto the primitive
/// ([`project_point`](Primitive::project_point)) and casts a ray from each to the box's
/// centre ([`ray_hit`](Primitive::ray_hit)), and every projected point and hit point must lie
/// in the box (within rounding). A primitive with a non-finite coordinate passes (the
/// structures leave it out).
///
/// This catches what [`check_enclosed_by_vertices`] cannot: a `bounds()` too small for the
/// primitive's own geometry (a ball whose box uses half its radius), with which every
/// structure that culls by boxes (grids, k-d trees, octrees, AABB trees) misses hits and
/// nearest points that [`BruteForce`](crate::BruteForce) finds. It is a probe, not a proof: a
/// box too small in a direction no probe looks along can pass. Every structure's
/// `validate()` runs it on each primitive it indexes, and debug builds check every hit and
/// projected point a query meets.
///
/// # Errors
/// A message naming the probe, the point found and the bounds.
pub fn check_bounds_hold<P: Primitive>(prim: &P) -> Result<(), String> {
    let bounds = prim.bounds();
    if bounds.is_empty() || !prim.has_finite_coordinates() {
        return Ok(());
    }
    let center = bounds.center();
    let size = (bounds.max - bounds.min).max_element();
    let reach = if size > 0.0 { 2.0 * size } else { 1.0 };
    for direction in probe_directions::<P::Point>() {
        let probe = center + direction * reach;
        if !probe.is_finite() {
            continue;
        }
        let projected = prim.project_point(probe);
        if let Err(why) = point_in_bounds(&bounds, projected, probe) {
            return Err(format!(
                "project_point({probe:?}) gave {projected:?}, {why}"
            ));
        }
        let Ok(ray) = crate::Ray::new(probe, center - probe) else {
            continue;
        };
        if let Some(t) = prim.ray_hit(&ray) {
            let hit = ray.at(t);
            if let Err(why) = point_in_bounds(&bounds, hit, probe) {
                return Err(format!(
                    "ray_hit of the ray from {probe:?} to the centre of its bounds gave \
                     t = {t}, the point {hit:?}, {why}"
                ));
            }
        }
    }
    Ok(())
}

/// The probes' directions: each axis both ways, and each diagonal (the corners of the cube
/// of side 2 around the origin).
fn probe_directions<V: Vector>() -> impl Iterator<Item = V> {
    let axes = (0..V::DIM).flat_map(|axis| [V::unit_axis(axis), V::unit_axis(axis) * -1.0]);
    let corners = (0..1usize << V::DIM).map(|corner| {
        (0..V::DIM).fold(V::ZERO, |sum, axis| {
            let sign = if corner >> axis & 1 == 1 { 1.0 } else { -1.0 };
            sum + V::unit_axis(axis) * sign
        })
    });
    axes.chain(corners)
}

/// Whether `point`, which a query from `query` gave, lies in `bounds` within
/// [`BOUNDS_MARGIN`] of the coordinates' size; if not, the rest of the message saying so.
fn point_in_bounds<V: Vector>(bounds: &Aabb<V>, point: V, query: V) -> Result<(), String> {
    if !point.is_finite() {
        return Ok(());
    }
    let scale = bounds
        .min
        .abs()
        .max(bounds.max.abs())
        .max(query.abs())
        .max_element();
    let margin = BOUNDS_MARGIN * scale + f32::MIN_POSITIVE;
    let outside = (0..V::DIM)
        .map(|axis| {
            (bounds.min.coord(axis) - point.coord(axis))
                .max(point.coord(axis) - bounds.max.coord(axis))
        })
        .fold(0.0, f32::max);
    if outside <= margin {
        return Ok(());
    }
    Err(format!(
        "which lies {outside} outside its bounds {bounds:?}: the Primitive contract asks \
         bounds() to hold every point of the primitive (every hit and projected point), since \
         grids, k-d trees, octrees and AABB trees skip what lies outside the boxes they build \
         from bounds()"
    ))
}

/// `prim.ray_hit(ray)`, with debug builds checking that the hit point lies in the
/// primitive's bounds (contract 2 of [`Primitive`]): a custom primitive whose `bounds()` is
/// too small gives wrong answers in every structure that culls by boxes, silently; this says
/// so at the first hit that shows it. Release builds call `ray_hit` and nothing else.
#[inline]
pub(crate) fn ray_hit<P: Primitive>(prim: &P, ray: &crate::Ray<P::Point>) -> Option<f32> {
    let t = prim.ray_hit(ray);
    #[cfg(debug_assertions)]
    if let Some(t) = t {
        let hit = ray.at(t);
        if let Err(why) = point_in_bounds(&prim.bounds(), hit, ray.origin()) {
            panic!("a query found {prim:?} broken: ray_hit gave t = {t}, the point {hit:?}, {why}");
        }
    }
    t
}

/// `prim.project_point(point)`, with debug builds checking that the projected point lies in
/// the primitive's bounds, as [`ray_hit`] does for hits.
#[inline]
pub(crate) fn project_point<P: Primitive>(prim: &P, point: P::Point) -> P::Point {
    let projected = prim.project_point(point);
    #[cfg(debug_assertions)]
    if let Err(why) = point_in_bounds(&prim.bounds(), projected, point) {
        panic!("a query found {prim:?} broken: project_point({point:?}) gave {projected:?}, {why}");
    }
    projected
}
