//! Building a convex polyhedron: quickhull.
//!
//! Barber, Dobkin and Huhdanpaa, "The Quickhull Algorithm for Convex Hulls", ACM Transactions
//! on Mathematical Software 22(4), 1996. Start from a tetrahedron of extreme points and give
//! every other point to one face it lies outside of. Then, while some face has outside points,
//! take its farthest one (the eye), delete the faces the eye sees, close the hole with a cone
//! of triangles from the eye to the horizon, and hand the deleted faces' points to the new
//! faces: a point above a deleted face is above a new face or inside the hull for good (the
//! segment from the deleted face's interior to the point leaves the new hull through the
//! cone). Expected O(n log n).
//!
//! Robustness, with arithmetic in `f64` on `f32` input: every decision is exact.
//! - "Is this point above that face?" compares the point's height over the face's plane with
//!   a margin that bounds the height's rounding error, `64 · f64::EPSILON · (max|x| + max|y| +
//!   max|z|)`: a tolerance scaled to the input, as in qhull and Lloyd's quickhull3d. Inside the
//!   margin, Shewchuk's adaptive orientation predicate decides exactly. The result is the
//!   exact hull of the `f32` points: convex, with every input point inside, however nearly
//!   coplanar or collinear they are. (A tolerance band in which points count as inside is
//!   not safe: around a thin hull's rim a point can be far outside yet barely above any face.)
//! - Face planes come from an accurately rounded cross product, so that thin faces, which
//!   nearly coplanar points make, still have normals that point the right way.
//! - The faces the eye sees are gathered by a breadth-first search from the face it was chosen
//!   for, and a face joins only if the region stays a topological disk. The horizon is then one
//!   simple loop and the mesh a closed, consistently wound sphere.
//! - Exactly coplanar points (a grid, a machined part) can leave vertices on a flat side or an
//!   edge of the hull; a second pass over the true corners removes them.
//! - Point sets that span less than 3D are detected up front, also exactly: all points equal
//!   (one vertex), collinear (a segment), coplanar (a flat polygon from the 2D monotone chain
//!   in the plane, triangulated once per side).

mod mesh;

use glam::{DVec3, Vec2, Vec3};

use super::hull::predicates::{accurate_cross, orient2d, orient3d};
use super::hull_build2::chain_order;
use super::{ConvexHull, finite_points};
use crate::Triangle3;
use mesh::Quickhull;

/// A direction with no simple relation to the axes, to break ties between equally far points.
const SKEW: DVec3 = DVec3::new(0.579_612_3, 0.317_207_9, 0.749_813_1);

/// The convex hull of points in space (see [`ConvexHull3`](crate::ConvexHull3)), by quickhull.
/// Non-finite points are skipped; lower-dimensional point sets give a point, a segment or a
/// flat polygon (see [`ConvexHull::dimension`]).
#[must_use]
pub fn quickhull(points: &[Vec3]) -> ConvexHull<Vec3> {
    let input = finite_points(points);
    let points: Vec<DVec3> = input.iter().map(|p| p.as_dvec3()).collect();
    match initial_simplex(&input, &points) {
        Simplex::Empty => ConvexHull::EMPTY,
        Simplex::Point(i) => ConvexHull::from_parts(vec![input[i]], Vec::new(), Some(0)),
        Simplex::Segment(lo, hi) => {
            ConvexHull::from_parts(vec![input[lo], input[hi]], Vec::new(), Some(1))
        }
        Simplex::Flat(normal) => flat_polygon(&input, normal),
        Simplex::Solid(corners) => {
            let mut mesh = Quickhull::new(points, corners);
            mesh.run();
            let (corners, vertex_count) = mesh.corners();
            if corners.len() == vertex_count || corners.len() < 4 {
                return mesh.into_hull(&input);
            }
            // Vertices left on flat sides: build again from the corners alone, every one of
            // which is a corner of their hull, so none can be left over (and the point count
            // shrinks, so this ends).
            let corners: Vec<Vec3> = corners.iter().map(|&i| input[i as usize]).collect();
            quickhull(&corners)
        }
    }
}

/// What the extreme points say about the dimension of a point set.
enum Simplex {
    Empty,
    /// All points equal this one.
    Point(usize),
    /// All points on the segment between these two.
    Segment(usize, usize),
    /// All points in a plane with this normal.
    Flat(DVec3),
    /// A tetrahedron, its fourth corner below the plane of the first three (so that the faces
    /// `abc`, `adb`, `bdc`, `cda` all face outward).
    Solid([usize; 4]),
}

/// The index of the point with the largest `key` among those that `keep` accepts; of points
/// whose keys are equal up to rounding, the one farthest along [`SKEW`]. Many points tie in
/// structured input (a grid, a flat side), and this picks a corner among them: a point that
/// is not a corner would stay a needless vertex on a flat part of the hull.
fn farthest(
    points: &[DVec3],
    keep: impl Fn(usize) -> bool,
    key: impl Fn(DVec3) -> f64,
) -> Option<usize> {
    let kept: Vec<usize> = (0..points.len()).filter(|&i| keep(i)).collect();
    let top = kept
        .iter()
        .map(|&i| key(points[i]))
        .fold(f64::NEG_INFINITY, f64::max);
    let tie = 1e-12 * top.abs();
    let skew = |i: usize| SKEW.dot(points[i]);
    kept.into_iter()
        .filter(|&i| key(points[i]) >= top - tie)
        .max_by(|&i, &j| skew(i).total_cmp(&skew(j)))
}

/// The extremes along the widest axis, then the point farthest from their line, then the
/// point farthest from the plane of those three: the starting tetrahedron, as large as is
/// cheap. The distances only choose; whether a point is off the line or the plane is decided
/// exactly.
fn initial_simplex(input: &[Vec3], points: &[DVec3]) -> Simplex {
    let extremes = |axis: usize| {
        let lo = farthest(points, |_| true, |p| -p[axis])?;
        let hi = farthest(points, |_| true, |p| p[axis])?;
        Some((points[hi][axis] - points[lo][axis], lo, hi))
    };
    let Some((_, a, b)) = (0..3)
        .filter_map(extremes)
        .max_by(|x, y| x.0.total_cmp(&y.0))
    else {
        return Simplex::Empty;
    };
    if input[a] == input[b] {
        return Simplex::Point(a);
    }
    // A point is on the line ab when its three shadows on the coordinate planes are.
    let off_line = |i: usize| {
        [(0, 1), (1, 2), (2, 0)].into_iter().any(|(u, v)| {
            let shadow = |p: Vec3| Vec2::new(p[u], p[v]);
            orient2d(shadow(input[a]), shadow(input[b]), shadow(input[i])) != 0.0
        })
    };
    let along = (points[b] - points[a]).normalize();
    let Some(c) = farthest(points, off_line, |p| {
        (p - points[a]).cross(along).length_squared()
    }) else {
        return Simplex::Segment(a, b);
    };
    let [pa, pb, pc] = [a, b, c].map(|i| points[i]);
    let normal = accurate_cross(pa, pb, pc).normalize();
    let off_plane = |i: usize| orient3d(pa, pb, pc, points[i]) != 0.0;
    let Some(d) = farthest(points, off_plane, |p| normal.dot(p - pa).abs()) else {
        return Simplex::Flat(normal);
    };
    if orient3d(pa, pb, pc, points[d]) > 0.0 {
        Simplex::Solid([a, c, b, d])
    } else {
        Simplex::Solid([a, b, c, d])
    }
}

/// Coplanar points: the 2D hull in the plane, triangulated as a fan once for each side.
///
/// The points are projected on the coordinate plane most nearly parallel to theirs (dropping
/// the normal's largest coordinate): a bijection of their plane, so it maps the hull to the
/// hull, and it keeps their `f32` coordinates, so the monotone chain's turn tests stay exact.
fn flat_polygon(input: &[Vec3], normal: DVec3) -> ConvexHull<Vec3> {
    let drop = normal.abs().max_position();
    let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
    let projected: Vec<Vec2> = input.iter().map(|p| Vec2::new(p[u], p[v])).collect();
    let vertices: Vec<Vec3> = chain_order(&projected).iter().map(|&i| input[i]).collect();
    // The sides are fanned from different corners so that they share only the outline: each
    // edge then borders exactly two triangles, as in a closed solid.
    let n = vertices.len();
    let top =
        (1..n.saturating_sub(1)).map(|j| Triangle3::new(vertices[0], vertices[j], vertices[j + 1]));
    let bottom = (2..n).map(|j| Triangle3::new(vertices[1], vertices[(j + 1) % n], vertices[j]));
    let facets = top.chain(bottom).collect();
    // The chain runs counter-clockwise around the axis it projected along.
    ConvexHull::from_flat_parts(vertices, facets, normal, DVec3::AXES[drop])
}
