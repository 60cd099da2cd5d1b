//! Triangle against triangle (either may be a segment or a point): a separating-axis test
//! whose candidate axes are the facet normals of the Minkowski difference `A − B`, which
//! contains the origin exactly when `A` and `B` share a point.
//!
//! For two proper triangles these are the two normals and the nine edge × edge products
//! (Gottschalk, Lin and Manocha, "`OBBTree`", SIGGRAPH 1996; Möller's interval test, "A Fast
//! Triangle-Triangle Intersection Test", JGT 1997, decides the same question by other means),
//! plus, for coplanar triangles, the in-plane edge normals `n × e` of both (Eberly, "Intersection
//! of Convex Objects: The Method of Separating Axes", 2001). Degenerate input needs more,
//! because `A − B` is then flat or a segment:
//! - a triangle and a segment in its plane: the segment's in-plane normal `n × d`;
//! - two segments on skew lines: the lines' common normal `d_A × d_B` (an edge × edge axis);
//! - two segments in one plane, or a segment and a point: the in-plane normal of a segment,
//!   found as the part of `w = b₀ − a₀` perpendicular to its direction `d`, `d × (w × d)`.
//!   (For crossing lines this is the normal `(d_A × d_B) × d` up to scale, and where it
//!   vanishes, `b₀` lies on that segment's line, whose normal then cannot separate anyway);
//! - and along a common line the coordinate axes (the bounds test) suffice.
//!
//! Every axis is built from exact input in the number type under test, so an axis that the
//! filter cannot decide is rebuilt exactly, along with the projections.

use std::cell::OnceCell;

use super::expansion::Exact;
use super::sat::{any_separates, separates_sets};
use super::scalar::{Filtered, Scalar, V3};
use super::simplex::{Dim, Simplex, Vec3Edges};

/// One of the two inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    A,
    B,
}

/// A candidate axis beyond the coordinate axes.
#[derive(Clone, Copy, Debug)]
enum Axis {
    /// The normal of a triangle.
    Normal(Side),
    /// Edge `i` of `A` × edge `j` of `B`.
    EdgeEdge(usize, usize),
    /// The normal of one triangle × edge `i` of either input.
    NormalEdge(Side, Side, usize),
    /// `d × (w × d)` with `d` the side's direction and `w = b₀ − a₀`.
    Perpendicular(Side),
}

/// Everything relative to `a₀` (smaller numbers, smaller rounding), in one number type.
struct Frame<T> {
    a: [V3<T>; 3],
    b: [V3<T>; 3],
    edges: [Vec3Edges<T>; 2],
    normals: [Option<V3<T>>; 2],
}

impl<T: Scalar> Frame<T> {
    fn new(sa: &Simplex, sb: &Simplex) -> Self {
        let (ca, cb) = (sa.corners_as::<T>(), sb.corners_as::<T>());
        let origin = ca[0].clone();
        Self {
            a: std::array::from_fn(|i| ca[i].sub(&origin)),
            b: std::array::from_fn(|i| cb[i].sub(&origin)),
            edges: [sa.edge_vectors(&ca), sb.edge_vectors(&cb)],
            normals: [sa.normal(&ca), sb.normal(&cb)],
        }
    }

    fn edge(&self, side: Side, i: usize) -> Option<&V3<T>> {
        self.edges[side as usize][i].as_ref()
    }

    fn axis(&self, axis: Axis) -> Option<V3<T>> {
        match axis {
            Axis::Normal(side) => self.normals[side as usize].clone(),
            Axis::EdgeEdge(i, j) => Some(self.edge(Side::A, i)?.cross(self.edge(Side::B, j)?)),
            Axis::NormalEdge(normal, side, i) => {
                let n = self.normals[normal as usize].as_ref()?;
                Some(n.cross(self.edge(side, i)?))
            }
            Axis::Perpendicular(side) => {
                let d = self.edge(side, 0)?;
                Some(d.cross(&self.b[0].cross(d)))
            }
        }
    }

    fn separates(&self, axis: Axis) -> Option<bool> {
        self.axis(axis)
            .map_or(Some(false), |n| separates_sets(&n, &self.a, &self.b))
    }
}

/// The candidate axes for this pair of shapes, cheapest rejections first.
fn candidates(sa: &Simplex, sb: &Simplex) -> impl Iterator<Item = Axis> + use<> {
    let sides = [(Side::A, sa.dim), (Side::B, sb.dim)];
    let with = move |dim: Dim| sides.into_iter().filter(move |s| s.1 == dim).map(|s| s.0);
    let (na, nb) = (sa.edges().len(), sb.edges().len());
    let normals = with(Dim::Triangle).map(Axis::Normal);
    let edge_edge = (0..na).flat_map(move |i| (0..nb).map(move |j| Axis::EdgeEdge(i, j)));
    // In-plane edge normals: a triangle's own, and the other input's edges turned by the
    // triangle's normal when the other has no normal of its own (two triangles that are
    // coplanar have parallel normals, so each turning its own edges is enough).
    let both_triangles = sa.dim == Dim::Triangle && sb.dim == Dim::Triangle;
    let in_plane = with(Dim::Triangle).flat_map(move |normal| {
        (0..na)
            .map(move |i| (Side::A, i))
            .chain((0..nb).map(move |j| (Side::B, j)))
            .filter(move |&(side, _)| side == normal || !both_triangles)
            .map(move |(side, i)| Axis::NormalEdge(normal, side, i))
    });
    let no_triangle = sa.dim != Dim::Triangle && sb.dim != Dim::Triangle;
    let perpendicular = with(Dim::Segment)
        .filter(move |_| no_triangle)
        .map(Axis::Perpendicular);
    normals
        .chain(edge_edge)
        .chain(in_plane)
        .chain(perpendicular)
}

/// Whether the two simplices share a point, given that their bounds overlap (the coordinate
/// axes do not separate them).
pub(super) fn simplex_simplex(sa: &Simplex, sb: &Simplex) -> bool {
    let fast = Frame::<Filtered>::new(sa, sb);
    let exact = OnceCell::new();
    let separated = any_separates(
        candidates(sa, sb),
        |axis| fast.separates(axis),
        |axis| {
            exact
                .get_or_init(|| Frame::<Exact>::new(sa, sb))
                .separates(axis)
                == Some(true)
        },
    );
    !separated
}
