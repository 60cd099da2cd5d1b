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
