//! The half-spaces of a convex hull, derived once from its vertices and facets.
//!
//! A full-dimensional hull is bounded by one half-space per facet. A lower-dimensional one is
//! pinned in its flat directions by pairs of opposite half-spaces (a slab) and bounded within
//! its flat by half-spaces standing on it: the ends of a segment, the edges of a flat polygon.
//! Every hull also gets its bounding box's slabs.

use std::cmp::Ordering;

use glam::DVec3;

use super::predicates::accurate_cross;
use super::{ConvexHull, TOLERANCE_ULPS};
use crate::Vector;
use crate::primitive::Primitive;

/// A closed half-space `{x : normal · x <= offset}` with a unit `normal`, in `f64`; 2D is
/// padded with `z = 0` (see [`Vector::to_dvec3`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct HalfSpace {
    pub(super) normal: DVec3,
    pub(super) offset: f64,
}

impl HalfSpace {
    /// The half-space with outward unit `normal` whose plane touches the outermost of `points`,
    /// so that all of them are inside even after rounding.
    pub(super) fn supporting(normal: DVec3, points: impl Iterator<Item = DVec3>) -> Self {
        let offset = points
            .map(|p| normal.dot(p))
            .fold(f64::NEG_INFINITY, f64::max);
        Self { normal, offset }
    }
}

impl<V: Vector> ConvexHull<V> {
    /// Assembles a hull from a builder's output and derives its half-spaces.
    ///
    /// `vertices` must be counter-clockwise in 2D, and in 3D too when `dimension` is 2 (the
    /// polygon then runs counter-clockwise around its Newell normal); a 3D builder that knows
    /// its flat polygon's plane better uses [`Self::from_flat_parts`].
    pub(crate) fn from_parts(
        vertices: Vec<V>,
        facets: Vec<V::Facet>,
        dimension: Option<usize>,
    ) -> Self {
        Self::assemble(vertices, facets, dimension, None)
    }

    /// A flat polygon in 3D, in a plane with unit `normal`, its `vertices` counter-clockwise
    /// around `upright`: the coordinate axis along which the builder projected the points to
    /// find their outline. The sides stand on the outline along `upright`, so that they test
    /// exactly what the 2D hull tested in that projection.
    pub(crate) fn from_flat_parts(
        vertices: Vec<V>,
        facets: Vec<V::Facet>,
        normal: DVec3,
        upright: DVec3,
    ) -> Self {
        Self::assemble(vertices, facets, Some(2), Some([normal, upright]))
    }

    fn assemble(
        vertices: Vec<V>,
        facets: Vec<V::Facet>,
        dimension: Option<usize>,
        plane: Option<[DVec3; 2]>,
    ) -> Self {
        let reach = vertices.iter().fold(V::ZERO, |m, v| m.max(v.abs()));
        let magnitude: f64 = (0..V::DIM).map(|i| f64::from(reach.coord(i))).sum();
        let mut hull = Self {
            vertices,
            facets,
            tolerance: TOLERANCE_ULPS * f64::from(f32::EPSILON) * magnitude,
            dimension,
            ..Self::EMPTY
        };
        if hull.vertices.is_empty() {
            return Self::EMPTY;
        }
        // The bounding box's slabs come first: they are valid for every hull, reject most far
        // points after a few comparisons, and are all a single point needs.
        let axes: Vec<DVec3> = (0..V::DIM).map(|i| V::unit_axis(i).to_dvec3()).collect();
        hull.add_slabs(&axes);
        match dimension {
            Some(d) if d == V::DIM => hull.bound_by_facets(),
            Some(1) => hull.bound_segment(),
            Some(2) => hull.bound_flat_polygon(plane),
            _ => {} // A point: its bounding box is all of it.
        }
        hull
    }

    /// The two half-spaces `±axis` that pin the hull between parallel planes, per axis.
    fn add_slabs(&mut self, axes: &[DVec3]) {
        for &axis in axes {
            for normal in [axis, -axis] {
                let plane = HalfSpace::supporting(normal, self.points());
                self.planes.push(plane);
            }
        }
    }

    /// A full-dimensional hull: one half-space per facet, and each edge once.
    fn bound_by_facets(&mut self) {
        for facet in &self.facets {
            let corners: Vec<V> = facet.vertices().collect();
            if let Some(normal) = facet_normal::<V>(facet).0.try_normalize() {
                let plane = HalfSpace::supporting(normal, corners.iter().map(|c| c.to_dvec3()));
                self.planes.push(plane);
            }
            // Each edge bounds two facets, which run it in opposite directions: keep one.
            for (i, &a) in corners.iter().enumerate() {
                let b = corners[(i + 1) % corners.len()];
                if lexicographic(a, b) == Ordering::Less {
                    self.edges.push(b - a);
                }
            }
        }
    }

    /// A segment: slabs across it (pinning the flat directions) and along it (its ends).
    fn bound_segment(&mut self) {
        let [a, b] = [self.vertices[0], self.vertices[self.vertices.len() - 1]];
        let along = (b.to_dvec3() - a.to_dvec3()).normalize_or_zero();
        let across = orthogonal_complement::<V>(along);
        self.add_slabs(&[along]);
        self.add_slabs(&across);
        self.edges = vec![b - a];
    }

    /// A flat polygon in 3D: the slab of its plane, and one half-space per edge, standing on the
    /// outline along `upright` (the plane's normal unless the builder says otherwise).
    fn bound_flat_polygon(&mut self, plane: Option<[DVec3; 2]>) {
        let points: Vec<DVec3> = self.points().collect();
        let newell = || newell_normal(&points).try_normalize().map(|n| [n, n]);
        let Some([normal, upright]) = plane.or_else(newell) else {
            return; // Not a polygon after all: the bounding box already bounds it.
        };
        self.add_slabs(&[normal]);
        for (i, &a) in points.iter().enumerate() {
            let b = points[(i + 1) % points.len()];
            // Counter-clockwise around `upright`, the inside is on the left of a → b, which is
            // `upright × (b − a)`; the outward normal is the opposite.
            if let Some(out) = (b - a).cross(upright).try_normalize() {
                self.planes
                    .push(HalfSpace::supporting(out, [a, b].into_iter()));
            }
            self.edges.push(V::from_dvec3(b - a));
        }
    }
}

/// A facet's outward normal in `f64`, not normalised, and its first corner.
///
/// `(b − a) × (c − a)` for a triangle; for a segment `a b` the same formula with `c = a + ẑ`,
/// which is `(b − a) × ẑ`, the right-hand normal. Like [`Primitive::normal`], whose direction
/// and length it has, it is `DIM − 1` times as long as the facet's measure (a segment's
/// length, twice a triangle's area); it is accurately rounded, so that thin triangles, which
/// nearly coplanar points give, still have planes that point the right way.
pub(super) fn facet_normal<V: Vector>(facet: &V::Facet) -> (DVec3, DVec3) {
    let mut corners = facet.vertices().map(V::to_dvec3);
    let a = corners.next().unwrap_or_default();
    let b = corners.next().unwrap_or(a);
    let c = corners.next().unwrap_or(a + DVec3::Z);
    (accurate_cross(a, b, c), a)
}

/// Newell's normal of a polygon: twice its vector area, `Σ (p_i − p_0) × (p_{i+1} − p_0)`,
/// well defined for any simple polygon, planar or nearly so (Sutherland, Sproull and
/// Schumacker, "A Characterization of Ten Hidden-Surface Algorithms", 1974).
fn newell_normal(points: &[DVec3]) -> DVec3 {
    let o = points[0];
    (1..points.len().saturating_sub(1))
        .map(|i| (points[i] - o).cross(points[i + 1] - o))
        .sum()
}

/// An orthonormal basis of the directions perpendicular to the unit vector `along` (within
/// the space of `V`): Gram–Schmidt over the coordinate axes, best-conditioned axis first.
fn orthogonal_complement<V: Vector>(along: DVec3) -> Vec<DVec3> {
    let mut frame = vec![along];
    while frame.len() < V::DIM {
        let residual = |i: usize| {
            let axis = V::unit_axis(i).to_dvec3();
            axis - frame.iter().map(|&f| f * f.dot(axis)).sum::<DVec3>()
        };
        let best = (0..V::DIM)
            .map(residual)
            .max_by(|r, s| r.length_squared().total_cmp(&s.length_squared()))
            .unwrap_or(DVec3::X);
        frame.push(best.normalize_or_zero());
    }
    frame.split_off(1)
}

/// Orders points by x, then y (then z): used to keep one of the two directions of an edge.
fn lexicographic<V: Vector>(a: V, b: V) -> Ordering {
    (0..V::DIM)
        .map(|i| a.coord(i).total_cmp(&b.coord(i)))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}
