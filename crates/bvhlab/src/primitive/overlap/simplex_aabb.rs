//! Triangle (or segment, or point) against a box: the separating-axis test of Akenine-Möller,
//! "Fast 3D Triangle-Box Overlap Testing", Journal of Graphics Tools 6(1), 2001.
//!
//! The candidate axes are the box's three face normals, the triangle's normal, and the nine
//! cross products of a triangle edge with a box edge direction. The face normals are the
//! bounds test, done by the caller. A degenerate triangle has no normal, and its edges are
//! all parallel to one direction `d` (or zero): the remaining candidates `d × u_k` are then
//! exactly the facet normals of the box swept along the segment, so the test stays complete
//! for segments and points (where only the bounds test is left, which is exact).

use std::cell::OnceCell;

use glam::Vec3;

use super::expansion::Exact;
use super::sat::{any_separates, separates_from_box};
use super::scalar::{Filtered, Scalar, V3};
use super::simplex::{Dim, Simplex, Vec3Edges};

/// A candidate axis beyond the box's face normals.
#[derive(Clone, Copy, Debug)]
enum Axis {
    /// The triangle's normal.
    Normal,
    /// Spanning edge `i` crossed with coordinate axis `k`.
    EdgeCrossUnit(usize, usize),
}

/// The test's inputs in one number type: the corners as `2p − (min + max)` (the box centred
/// at the origin, everything doubled), the box's doubled half-size `max − min`, the edges and
/// the normal.
struct Frame<T> {
    rel: [V3<T>; 3],
    ext: V3<T>,
    edges: Vec3Edges<T>,
    normal: Option<V3<T>>,
}

impl<T: Scalar> Frame<T> {
    fn new(simplex: &Simplex, min: Vec3, max: Vec3) -> Self {
        let corners = simplex.corners_as::<T>();
        let (min, max) = (V3::<T>::from_vec3(min), V3::<T>::from_vec3(max));
        let centre = min.add(&max);
        Self {
            rel: std::array::from_fn(|i| corners[i].add(&corners[i]).sub(&centre)),
            ext: max.sub(&min),
            edges: simplex.edge_vectors(&corners),
            normal: simplex.normal(&corners),
        }
    }

    fn axis(&self, axis: Axis) -> Option<V3<T>> {
        match axis {
            Axis::Normal => self.normal.clone(),
            Axis::EdgeCrossUnit(i, k) => self.edges[i].as_ref().map(|e| e.cross_unit(k)),
        }
    }

    /// Whether `axis` separates (`None`: cannot tell in this arithmetic). A missing axis
    /// (an edge the simplex does not have) separates nothing.
    fn separates(&self, axis: Axis) -> Option<bool> {
        self.axis(axis).map_or(Some(false), |a| {
            separates_from_box(&a, &self.rel, &self.ext)
        })
    }
}

/// Whether the simplex and the box `[min, max]` share a point, given that their bounds overlap
/// (the box's face normals do not separate) and that `min <= max` are finite. With `planar`
/// the simplex and box lie in the plane `z = 0` (2D input): only the in-plane axes `e × u_z`
/// can separate there, so the others are skipped.
pub(super) fn simplex_aabb(simplex: &Simplex, min: Vec3, max: Vec3, planar: bool) -> bool {
    let normal = (simplex.dim == Dim::Triangle).then_some(Axis::Normal);
    let units = if planar { 2..3 } else { 0..3 };
    let crosses = (0..simplex.edges().len())
        .flat_map(|i| units.clone().map(move |k| Axis::EdgeCrossUnit(i, k)));
    let fast = Frame::<Filtered>::new(simplex, min, max);
    let exact = OnceCell::new();
    let separated = any_separates(
        normal.into_iter().chain(crosses),
        |axis| fast.separates(axis),
        |axis| {
            exact
                .get_or_init(|| Frame::<Exact>::new(simplex, min, max))
                .separates(axis)
                == Some(true)
        },
    );
    !separated
}
