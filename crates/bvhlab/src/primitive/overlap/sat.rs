//! The separating-axis decision itself: does one axis separate two projected point sets, and
//! does any axis of a candidate list separate them?
//!
//! Two convex sets are disjoint exactly when some axis separates their projections (the
//! separating-axis theorem; for boxes Gottschalk, Lin and Manocha, "`OBBTree`: A Hierarchical
//! Structure for Rapid Interference Detection", SIGGRAPH 1996; in general Eberly,
//! "Intersection of Convex Objects: The Method of Separating Axes", 2001).
//! Closed sets that touch share a point, so an axis separates only when the projections are
//! apart by a positive amount: a gap of exactly zero is touching.
//!
//! Each axis is first decided in [`Filtered`](super::scalar::Filtered) arithmetic; when
//! rounding leaves the sign of some gap open (the sets touch or nearly touch along that axis),
//! the same axis is rebuilt and decided in [`Exact`](super::expansion::Exact) arithmetic. The
//! answer is therefore exact for `f32` input: no false negatives and no false positives.

use std::cmp::Ordering;

use super::scalar::{Scalar, V3};

/// Whether some axis of `axes` separates: each is tried with `fast` (`None`: cannot tell) and,
/// when that cannot tell, with `exact`. Returns at the first separating axis.
pub(super) fn any_separates<A: Copy>(
    axes: impl IntoIterator<Item = A>,
    mut fast: impl FnMut(A) -> Option<bool>,
    mut exact: impl FnMut(A) -> bool,
) -> bool {
    axes.into_iter()
        .any(|axis| fast(axis).unwrap_or_else(|| exact(axis)))
}

/// Whether `axis` separates the points `rel` (given as `2p − (min + max)`) from the box
/// `[min, max]` (given as `ext = max − min`): all of `axis · rel` lie beyond the box's
/// projection radius `Σ |axis_k| ext_k` on the same side. (Both are doubled, so that no
/// halving of the box centre is ever needed.)
pub(super) fn separates_from_box<T: Scalar>(
    axis: &V3<T>,
    rel: &[V3<T>],
    ext: &V3<T>,
) -> Option<bool> {
    let mut radius = T::from_f32(0.0);
    for (a, e) in axis.0.iter().zip(&ext.0) {
        radius = radius.add(&a.abs()?.mul(e));
    }
    let centres: Vec3Values<T> = project(axis, rel);
    let values = centres.iter().take(rel.len());
    let above = all_positive(values.clone().map(|s| s.sub(&radius)));
    let below = all_positive(values.map(|s| s.add(&radius).neg()));
    either(above, below)
}

/// Whether `axis` separates the point sets `a` and `b`: every projection of one is below
/// every projection of the other.
pub(super) fn separates_sets<T: Scalar>(axis: &V3<T>, a: &[V3<T>], b: &[V3<T>]) -> Option<bool> {
    let (pa, pb) = (project(axis, a), project(axis, b));
    let (pa, pb) = (&pa[..a.len()], &pb[..b.len()]);
    let gaps = |lower: &[T], upper: &[T]| {
        let pairs: Vec9<T> = std::array::from_fn(|k| {
            let (i, j) = (k / 3, k % 3);
            (i < lower.len() && j < upper.len()).then(|| upper[j].sub(&lower[i]))
        });
        all_positive(pairs.into_iter().flatten())
    };
    either(gaps(pa, pb), gaps(pb, pa))
}

/// Up to three projections.
type Vec3Values<T> = [T; 3];
/// Up to nine gaps.
type Vec9<T> = [Option<T>; 9];

/// `axis · p` for up to three points (unused slots zero).
fn project<T: Scalar>(axis: &V3<T>, points: &[V3<T>]) -> Vec3Values<T> {
    std::array::from_fn(|i| points.get(i).map_or(T::from_f32(0.0), |p| axis.dot(p)))
}

/// `Some(true)`: every value is certainly positive; `Some(false)`: one is certainly not;
/// `None`: neither is certain.
fn all_positive<T: Scalar>(values: impl Iterator<Item = T>) -> Option<bool> {
    let mut unknown = false;
    for v in values {
        match v.sign() {
            Some(Ordering::Greater) => {}
            Some(_) => return Some(false),
            None => unknown = true,
        }
    }
    (!unknown).then_some(true)
}

/// Separated if either side certainly separates; not separated if neither can.
fn either(above: Option<bool>, below: Option<bool>) -> Option<bool> {
    match (above, below) {
        (Some(true), _) | (_, Some(true)) => Some(true),
        (Some(false), Some(false)) => Some(false),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::super::expansion::Exact;
    use super::super::scalar::Filtered;
    use super::*;

    fn v<T: Scalar>(x: f32, y: f32, z: f32) -> V3<T> {
        V3::from_vec3(Vec3::new(x, y, z))
    }

    #[test]
    fn touching_projections_do_not_separate_and_a_gap_does() {
        let axis = v::<Exact>(1.0, 0.0, 0.0);
        let a = [v(0.0, 0.0, 0.0), v(1.0, 5.0, 0.0)];
        let touching = [v(1.0, -3.0, 0.0)];
        let apart = [v(1.5, -3.0, 0.0)];
        assert_eq!(separates_sets(&axis, &a, &touching), Some(false));
        assert_eq!(separates_sets(&axis, &a, &apart), Some(true));
        assert_eq!(separates_sets(&axis, &apart, &a), Some(true));
    }

    #[test]
    fn box_projection_uses_the_doubled_radius() {
        // Box [0, 2]³: doubled centre (2, 2, 2), ext (2, 2, 2). The point (3, 1, 1) is 1 beyond
        // the face x = 2, so rel = 2p − 2c = (4, 0, 0) against a doubled radius of 2.
        let ext = v::<Filtered>(2.0, 2.0, 2.0);
        let rel = [v(4.0, 0.0, 0.0)];
        assert_eq!(
            separates_from_box(&v(1.0, 0.0, 0.0), &rel, &ext),
            Some(true)
        );
        // On the face: a gap of exactly zero, which the filter leaves open and exact
        // arithmetic calls touching.
        let on_face = [v(2.0, 0.0, 0.0)];
        assert_eq!(separates_from_box(&v(1.0, 0.0, 0.0), &on_face, &ext), None);
        let exact_face = [v::<Exact>(2.0, 0.0, 0.0)];
        let exact_ext = v::<Exact>(2.0, 2.0, 2.0);
        let decided = separates_from_box(&v(1.0, 0.0, 0.0), &exact_face, &exact_ext);
        assert_eq!(decided, Some(false));
        // Along (1, 1, 0): radius 2 + 2 = 4 and the point projects to 4, touching the edge.
        let diagonal = v::<Exact>(1.0, 1.0, 0.0);
        let exact_rel = [v::<Exact>(4.0, 0.0, 0.0)];
        assert_eq!(
            separates_from_box(&diagonal, &exact_rel, &exact_ext),
            Some(false)
        );
    }
}
