//! Triangles, segments and points as one kind of input: the convex hull of three corners
//! (repeats allowed), classified exactly by the dimension of that hull.
//!
//! The classification decides which separating axes are needed (a degenerate triangle has no
//! normal; a segment needs the axes of a segment), but it never drops a corner: every test
//! projects all three corners, so a wrong guess could only cost a missed separation, never a
//! missed overlap. And the guess is not wrong: "zero area" is decided exactly.

use glam::Vec3;

use super::expansion::Exact;
use super::scalar::{Filtered, Scalar, V3};

/// The dimension of the hull of the corners.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dim {
    /// All corners coincide.
    Point,
    /// The corners are collinear and not all equal.
    Segment,
    /// A proper triangle.
    Triangle,
}

/// Three corners, their hull's dimension, and the edges that span it, as corner index pairs:
/// the three sides of a triangle, one side of positive length for a segment, none for a point.
#[derive(Clone, Copy, Debug)]
pub(super) struct Simplex {
    pub corners: [Vec3; 3],
    pub dim: Dim,
    edges: [(usize, usize); 3],
    edge_count: usize,
}

impl Simplex {
    /// Classifies the hull of `corners` (which must be finite).
    pub fn new(corners: [Vec3; 3]) -> Self {
        let [a, b, c] = corners;
        let (dim, edges, edge_count) = if a == b && b == c {
            (Dim::Point, [(0, 0); 3], 0)
        } else if normal_is_zero(corners) {
            // Collinear: any side of positive length spans the hull's line.
            let side = if a == b { (0, 2) } else { (0, 1) };
            (Dim::Segment, [side; 3], 1)
        } else {
            (Dim::Triangle, [(0, 1), (1, 2), (2, 0)], 3)
        };
        Self {
            corners,
            dim,
            edges,
            edge_count,
        }
    }

    /// A segment (a triangle with a repeated corner).
    pub fn segment(a: Vec3, b: Vec3) -> Self {
        Self::new([a, b, b])
    }

    /// The spanning edges, as corner index pairs `(from, to)`.
    pub fn edges(&self) -> &[(usize, usize)] {
        &self.edges[..self.edge_count]
    }

    /// The corners as [`V3`] values of the chosen number type.
    pub fn corners_as<T: Scalar>(&self) -> [V3<T>; 3] {
        self.corners.map(V3::from_vec3)
    }

    /// The edge vectors, in the order of [`edges`](Self::edges).
    pub fn edge_vectors<T: Scalar>(&self, corners: &[V3<T>; 3]) -> Vec3Edges<T> {
        let mut out: Vec3Edges<T> = [None, None, None];
        for (slot, &(from, to)) in out.iter_mut().zip(self.edges()) {
            *slot = Some(corners[to].sub(&corners[from]));
        }
        out
    }

    /// `(b − a) × (c − a)` for a triangle, `None` otherwise.
    pub fn normal<T: Scalar>(&self, corners: &[V3<T>; 3]) -> Option<V3<T>> {
        (self.dim == Dim::Triangle).then(|| {
            let [a, b, c] = corners;
            b.sub(a).cross(&c.sub(a))
        })
    }
}

/// Up to three edge vectors (`None` past the simplex's edge count).
pub(super) type Vec3Edges<T> = [Option<V3<T>>; 3];

/// Whether `(b − a) × (c − a)` is exactly zero: decided in [`Filtered`] arithmetic, and in
/// [`Exact`] arithmetic when rounding leaves it open.
fn normal_is_zero(corners: [Vec3; 3]) -> bool {
    fn normal<T: Scalar>(corners: [Vec3; 3]) -> V3<T> {
        let [a, b, c] = corners.map(V3::<T>::from_vec3);
        b.sub(&a).cross(&c.sub(&a))
    }
    normal::<Filtered>(corners)
        .is_zero()
        .unwrap_or_else(|| normal::<Exact>(corners).is_zero() == Some(true))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classifies_points_segments_and_triangles_exactly() {
        let p = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(Simplex::new([p; 3]).dim, Dim::Point);
        let seg = Simplex::new([p, p, Vec3::ZERO]);
        assert_eq!((seg.dim, seg.edges()), (Dim::Segment, &[(0, 2)][..]));
        let line = Simplex::new([Vec3::ZERO, p, p * 2.0]);
        assert_eq!(line.dim, Dim::Segment);
        let tri = Simplex::new([Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!((tri.dim, tri.edges().len()), (Dim::Triangle, 3));
        // Collinear exactly, though b − a and c − a are not exact in f64 (1e-30 next to 1).
        let a = Vec3::splat(1.0e-30);
        assert_eq!(
            Simplex::new([a, Vec3::ONE, Vec3::splat(3.0)]).dim,
            Dim::Segment
        );
        // One unit in the last place off the line: a (very thin) triangle.
        let off = Vec3::new(3.0, 3.0, f32::from_bits(3.0f32.to_bits() + 1));
        assert_eq!(Simplex::new([a, Vec3::ONE, off]).dim, Dim::Triangle);
    }
}
