//! Building a convex polygon: Andrew's monotone chain.
//!
//! A. M. Andrew, "Another efficient algorithm for convex hulls in two dimensions", Information
//! Processing Letters 9(5), 1979. Sort the points by x (then y); sweep left to right keeping
//! the lower hull and right to left keeping the upper hull, each time dropping the last kept
//! point while it does not make a strict left turn. O(n log n) for the sort, O(n) after it.
//!
//! The only numerical question is the turn direction, the sign of `(b − a) × (c − a)`. It is
//! decided exactly (Shewchuk's adaptive predicate), so repeated and collinear points, which
//! are dropped from the boundary, can never make the chain fold over.

use std::cmp::Ordering;

use glam::Vec2;

use super::hull::predicates::orient2d;
use super::{ConvexHull, finite_points};
use crate::Segment2;

/// The convex hull of points in the plane (see [`ConvexHull2`](crate::ConvexHull2)), by
/// Andrew's monotone chain. Non-finite points are skipped.
///
/// The result has one vertex (all points equal), two (collinear points: a segment with the
/// facets `a → b` and `b → a`) or a counter-clockwise polygon without collinear vertices.
#[must_use]
pub fn monotone_chain(points: &[Vec2]) -> ConvexHull<Vec2> {
    let points = finite_points(points);
    let vertices: Vec<Vec2> = chain_order(&points).iter().map(|&i| points[i]).collect();
    let n = vertices.len();
    let facets = if n < 2 {
        Vec::new()
    } else {
        (0..n)
            .map(|i| Segment2::new(vertices[i], vertices[(i + 1) % n]))
            .collect()
    };
    let dimension = n.checked_sub(1).map(|d| d.min(2));
    ConvexHull::from_parts(vertices, facets, dimension)
}

/// The indices of the hull's vertices, counter-clockwise from the lowest-leftmost point,
/// without repeated or collinear boundary points. Fewer than three indices when the points are
/// all equal (one) or collinear (two: the ends). The points must be finite.
///
/// Also used by quickhull for a flat point set, projected on a coordinate plane.
pub(crate) fn chain_order(points: &[Vec2]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_unstable_by(|&i, &j| lexicographic(points[i], points[j]));
    order.dedup_by(|i, j| points[*i] == points[*j]);
    if order.len() < 3 {
        return order;
    }
    let turns_left = |hull: &[usize], c: usize| {
        let [a, b] = [hull[hull.len() - 2], hull[hull.len() - 1]];
        orient2d(points[a], points[b], points[c]) > 0.0
    };
    let mut hull: Vec<usize> = Vec::with_capacity(order.len() + 1);
    // Lower hull, left to right.
    for &i in &order {
        while hull.len() >= 2 && !turns_left(&hull, i) {
            hull.pop();
        }
        hull.push(i);
    }
    // Upper hull, right to left, never popping into the lower hull.
    let lower_len = hull.len();
    for &i in order.iter().rev().skip(1) {
        while hull.len() > lower_len && !turns_left(&hull, i) {
            hull.pop();
        }
        hull.push(i);
    }
    hull.pop(); // The sweep ends where it began.
    hull
}

/// By x, then y; `+ 0.0` turns `-0.0` into `+0.0` so that the two zeros sort (and dedupe) as
/// one point.
fn lexicographic(a: Vec2, b: Vec2) -> Ordering {
    let key = |v: Vec2| (v.x + 0.0, v.y + 0.0);
    let ((ax, ay), (bx, by)) = (key(a), key(b));
    ax.total_cmp(&bx).then(ay.total_cmp(&by))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_edge_midpoints_and_repeats() {
        let p = |x, y| Vec2::new(x, y);
        let pts = [
            p(0., 0.),
            p(1., 0.),
            p(2., 0.),
            p(2., 2.),
            p(0., 2.),
            p(0., 2.),
            p(1., 1.),
        ];
        let order = chain_order(&pts);
        let corners: Vec<Vec2> = order.iter().map(|&i| pts[i]).collect();
        assert_eq!(corners, vec![p(0., 0.), p(2., 0.), p(2., 2.), p(0., 2.)]);
    }

    #[test]
    fn collinear_and_equal_points() {
        let line: Vec<Vec2> = (0..7).map(|i| Vec2::splat(((i * 3) % 7) as f32)).collect();
        let order = chain_order(&line);
        assert_eq!(order.len(), 2);
        assert_eq!(
            [line[order[0]], line[order[1]]],
            [Vec2::ZERO, Vec2::splat(6.0)]
        );
        assert_eq!(chain_order(&[Vec2::ONE, -Vec2::ZERO + Vec2::ONE]).len(), 1);
        assert_eq!(
            chain_order(&[Vec2::new(0.0, 1.0), Vec2::new(-0.0, 1.0)]).len(),
            1
        );
        assert!(chain_order(&[]).is_empty());
    }
}
