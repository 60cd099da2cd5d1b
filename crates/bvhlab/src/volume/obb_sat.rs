//! The separating-axis test for oriented boxes (lecture §2, "Collision query with OOBBs").
//!
//! Two convex sets are disjoint exactly when some axis separates their projections. For two
//! boxes only finitely many axes need trying (Gottschalk, Lin and Manocha, "`OBBTree`: a
//! hierarchical structure for rapid interference detection", SIGGRAPH 1996; Ericson,
//! "Real-Time Collision Detection", §4.4.1): the face normals of either box, which in 2D is
//! all (4 axes), and in 3D also the cross products of an edge direction of each box (3 + 3 + 9
//! = 15 axes). The lab steps through them with [`Obb::sat_tests`].
//!
//! Robustness: every axis is a unit vector, so projected intervals and gaps are distances. An
//! edge pair that is (nearly) parallel has a (nearly) zero cross product, whose direction is
//! rounding noise; [`Vector::edge_pair_axis`] skips it. Nothing is lost: when an edge of A is
//! parallel to an edge of B, both boxes are prisms along that direction, the question reduces
//! to two rectangles in the plane across it, and their face normals are face axes already
//! tested. This is why no epsilon is added to the projections, as Ericson's version does.

use super::{BoundingVolume, Obb};
use crate::Vector;

/// Where a candidate separating axis comes from, with indices into the boxes' `axes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AxisSource {
    /// The face normal `a.axes[i]` of the first box.
    FaceA(usize),
    /// The face normal `b.axes[j]` of the second box.
    FaceB(usize),
    /// `a.axes[i] × b.axes[j]` (normalised), perpendicular to an edge of each box (3D only).
    Edges(usize, usize),
}

/// One step of the separating-axis test: both boxes projected on one candidate axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisTest<V: Vector> {
    /// Which axis this is.
    pub source: AxisSource,
    /// The axis, a unit vector.
    pub axis: V,
    /// The first box's shadow on the axis: `[min, max]` of `axis · p` over its points.
    pub interval_a: (f32, f32),
    /// The second box's shadow on the axis.
    pub interval_b: (f32, f32),
    /// The distance between the two shadows: positive when the axis separates the boxes,
    /// zero when they touch, otherwise minus the length of the shadows' overlap.
    pub gap: f32,
}

impl<V: Vector> AxisTest<V> {
    /// Whether the axis separates the boxes: their shadows are disjoint. Shadows that touch do
    /// not separate (boxes are closed).
    pub fn separates(&self) -> bool {
        self.gap > 0.0
    }
}

/// An axis that separates two boxes: the answer of [`Obb::separating_axis`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeparatingAxis<V: Vector> {
    /// Which axis this is.
    pub source: AxisSource,
    /// The axis, a unit vector oriented from the first box towards the second: the normal of a
    /// separating plane.
    pub axis: V,
    /// The distance between the boxes' shadows on the axis, positive; a lower bound on the
    /// distance between the boxes.
    pub gap: f32,
}

impl<V: Vector> Obb<V> {
    /// How far the box reaches from its centre along the unit `axis`: the radius of its shadow,
    /// `Σ_i |axes[i] · axis| half_extents[i]`.
    pub fn projection_radius(&self, axis: V) -> f32 {
        (0..V::DIM)
            .map(|i| self.axes.as_ref()[i].dot(axis).abs() * self.half_extents.coord(i))
            .sum()
    }

    /// Every candidate axis of the separating-axis test, in the lecture's order (the face
    /// normals of `self`, then those of `other`, then in 3D the edge pairs `(i, j)` in
    /// row-major order), each with both shadows. Near-parallel edge pairs are left out (see
    /// the [module documentation](super::obb_sat)), so 3D gives at most 15 tests and 2D
    /// always 4. No tests when either box is empty.
    pub fn sat_tests(&self, other: &Self) -> Vec<AxisTest<V>> {
        if self.is_empty() || other.is_empty() {
            return Vec::new();
        }
        self.candidate_axes(other)
            .map(|(source, axis)| self.test_axis(other, source, axis).0)
            .collect()
    }

    /// The first axis, in the order of [`Obb::sat_tests`], that separates the boxes; `None`
    /// when they overlap (touching counts as overlapping) or when either is empty.
    ///
    /// ```
    /// use bvhlab::glam::Vec2;
    /// use bvhlab::prelude::*;
    /// use bvhlab::AxisSource;
    ///
    /// let a = Obb2::new(Vec2::ZERO, Vec2::identity_axes(), Vec2::ONE);
    /// let b = Obb2::new(Vec2::new(3.0, 0.5), Vec2::identity_axes(), Vec2::ONE);
    /// let axis = a.separating_axis(&b).expect("a gap of 1 along x");
    /// assert_eq!((axis.source, axis.axis, axis.gap), (AxisSource::FaceA(0), Vec2::X, 1.0));
    /// assert!(!a.overlaps(&b));
    /// ```
    pub fn separating_axis(&self, other: &Self) -> Option<SeparatingAxis<V>> {
        if self.is_empty() || other.is_empty() {
            return None;
        }
        self.candidate_axes(other).find_map(|(source, axis)| {
            let (test, offset) = self.test_axis(other, source, axis);
            test.separates().then(|| SeparatingAxis {
                source,
                axis: if offset < 0.0 { -axis } else { axis },
                gap: test.gap,
            })
        })
    }

    /// Whether the boxes share a point (touching counts): neither is empty and no axis
    /// separates them. [`BoundingVolume::overlaps`] calls this.
    pub fn overlaps(&self, other: &Self) -> bool {
        !self.is_empty() && !other.is_empty() && self.separating_axis(other).is_none()
    }

    /// The candidate axes with where they come from, lazily, so that
    /// [`Obb::separating_axis`] stops at the first that separates.
    fn candidate_axes<'a>(&'a self, other: &'a Self) -> impl Iterator<Item = (AxisSource, V)> + 'a {
        let (a, b) = (self.axes.as_ref(), other.axes.as_ref());
        let faces_a = a
            .iter()
            .enumerate()
            .map(|(i, &n)| (AxisSource::FaceA(i), n));
        let faces_b = b
            .iter()
            .enumerate()
            .map(|(j, &n)| (AxisSource::FaceB(j), n));
        let edges = (0..V::DIM).flat_map(move |i| {
            (0..V::DIM).filter_map(move |j| {
                V::edge_pair_axis(a[i], b[j]).map(|axis| (AxisSource::Edges(i, j), axis))
            })
        });
        faces_a.chain(faces_b).chain(edges)
    }

    /// Projects both boxes on `axis`. The decision uses the centre offset
    /// `d = axis · (c_b - c_a)`, taken as a difference first so that boxes far from the origin
    /// do not lose it to cancellation: the axis separates when `|d| > r_a + r_b`. Returns the
    /// test and `d`.
    fn test_axis(&self, other: &Self, source: AxisSource, axis: V) -> (AxisTest<V>, f32) {
        let (ra, rb) = (self.projection_radius(axis), other.projection_radius(axis));
        let ca = self.center.dot(axis);
        let offset = (other.center - self.center).dot(axis);
        let cb = ca + offset;
        let test = AxisTest {
            source,
            axis,
            interval_a: (ca - ra, ca + ra),
            interval_b: (cb - rb, cb + rb),
            gap: offset.abs() - (ra + rb),
        };
        (test, offset)
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};

    use super::*;

    #[test]
    fn the_trait_method_and_the_inherent_one_agree_and_do_not_recurse() {
        let a = Obb::<Vec2>::new(Vec2::ZERO, Vec2::identity_axes(), Vec2::ONE);
        let b = Obb::<Vec2>::new(Vec2::new(2.0, 0.0), Vec2::identity_axes(), Vec2::ONE);
        let c = Obb::<Vec2>::new(Vec2::new(2.5, 0.0), Vec2::identity_axes(), Vec2::ONE);
        assert!(Obb::overlaps(&a, &b), "touching boxes overlap");
        assert!(BoundingVolume::overlaps(&a, &b));
        assert!(!Obb::overlaps(&a, &c));
        assert!(!BoundingVolume::overlaps(&a, &c));
    }

    #[test]
    fn two_dimensions_test_four_axes_and_three_dimensions_fifteen() {
        let turn2 = Vec2::from_angle(0.3);
        let a2 = Obb::<Vec2>::new(Vec2::ZERO, Vec2::identity_axes(), Vec2::ONE);
        let b2 = Obb::<Vec2>::new(Vec2::X, [turn2, turn2.perp()], Vec2::ONE);
        assert_eq!(a2.sat_tests(&b2).len(), 4);
        let q = glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.5, 0.7);
        let a3 = Obb::<Vec3>::new(Vec3::ZERO, Vec3::identity_axes(), Vec3::ONE);
        let b3 = Obb::<Vec3>::new(Vec3::X, [q * Vec3::X, q * Vec3::Y, q * Vec3::Z], Vec3::ONE);
        let tests = a3.sat_tests(&b3);
        assert_eq!(tests.len(), 15);
        assert_eq!(tests[14].source, AxisSource::Edges(2, 2));
        // Identical frames: all nine edge pairs are parallel or give a face axis again; the
        // parallel ones (i == j) are skipped.
        assert_eq!(a3.sat_tests(&a3).len(), 12);
    }

    #[test]
    fn empty_boxes_overlap_nothing_and_have_no_tests() {
        let a = Obb::<Vec3>::new(Vec3::ZERO, Vec3::identity_axes(), Vec3::ONE);
        let e = Obb::<Vec3>::empty();
        assert!(!a.overlaps(&e) && !e.overlaps(&a) && !e.overlaps(&e));
        assert!(a.sat_tests(&e).is_empty());
        assert_eq!(a.separating_axis(&e), None);
    }
}
