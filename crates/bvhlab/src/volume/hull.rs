//! Convex hulls as bounding volumes (lecture §2, "Convex hull").
//!
//! The tightest convex volume around a point set, stored twice over: as its boundary (vertices
//! and facets, for drawing and for closest points) and as an intersection of half-spaces (for
//! containment, ray clipping and the separating-axis test). Only construction differs between
//! 2D and 3D ([`hull_build2`](super::hull_build2), [`hull_build3`](super::hull_build3)); the
//! half-spaces and every query below are written once for both.

mod half_spaces;
pub(super) mod predicates;

use crate::queries::{PointQuery, RayCast, volume_hit, volume_nearest};
use crate::{Hit, Nearest};
use glam::DVec3;

use self::half_spaces::{HalfSpace, facet_normal};
use super::{Aabb, BoundingVolume, checked_points, finite_points};
use crate::error::GeometryError;
use crate::primitive::Primitive;
use crate::{Ray, Vector};

/// How many `f32` rounding steps of slack the queries allow, in units of the hull's coordinate
/// magnitude; see [`ConvexHull::tolerance`].
const TOLERANCE_ULPS: f64 = 8.0;

/// A convex polygon ([`ConvexHull2`](crate::ConvexHull2)) or polyhedron
/// ([`ConvexHull3`](crate::ConvexHull3)), closed, fitted to a point set.
///
/// - [`vertices`](Self::vertices) are input points (never new ones); in 2D they run
///   counter-clockwise, and points on the boundary between two vertices are left out.
/// - [`facets`](Self::facets) bound it: segments in 2D, run counter-clockwise so that
///   [`Primitive::normal`] points out; triangles in 3D, wound so that it points out. The
///   triangles form a closed mesh: each edge is shared by two facets that run it in opposite
///   directions.
///
/// A point set that does not span the space gives a lower-dimensional hull
/// ([`dimension`](Self::dimension)): a point, a segment or (in 3D) a flat polygon. A flat hull
/// is still closed, as if it were infinitely thin: a 2D segment hull has the two facets
/// `a → b` and `b → a`, and a flat polygon in 3D is triangulated once for each side, the two
/// copies wound oppositely. A segment or a point in 3D has no triangles at all. The queries
/// treat all of these as the limit of a thin solid (see
/// [`boundary_measure`](BoundingVolume::boundary_measure)).
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexHull<V: Vector> {
    vertices: Vec<V>,
    facets: Vec<V::Facet>,
    /// The hull is the intersection of these.
    planes: Vec<HalfSpace>,
    /// Edge directions, each edge once: the separating-axis test crosses them in 3D.
    edges: Vec<V>,
    dimension: Option<usize>,
    tolerance: f64,
}

impl<V: Vector> ConvexHull<V> {
    /// The empty hull: contains nothing; merging with it gives the other hull.
    pub const EMPTY: Self = Self {
        vertices: Vec::new(),
        facets: Vec::new(),
        planes: Vec::new(),
        edges: Vec::new(),
        dimension: None,
        tolerance: 0.0,
    };

    /// The convex hull of `points`: Andrew's monotone chain in 2D, quickhull in 3D (see
    /// [`Vector::convex_hull`]). Points with NaN or infinite coordinates are skipped; no points
    /// give [`ConvexHull::EMPTY`]. Use [`ConvexHull::try_from_points`] to be told instead.
    #[must_use]
    pub fn from_points(points: &[V]) -> Self {
        V::convex_hull(&finite_points(points))
    }

    /// [`ConvexHull::from_points`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    pub fn try_from_points(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::from_points)
    }

    /// The hull's corners, each one of the input points; counter-clockwise in 2D.
    #[must_use]
    pub fn vertices(&self) -> &[V] {
        &self.vertices
    }

    /// The boundary: segments in 2D, triangles in 3D, with outward normals.
    #[must_use]
    pub fn facets(&self) -> &[V::Facet] {
        &self.facets
    }

    /// The affine dimension: `None` when empty, then 0 (a point), 1 (a segment), 2 (a polygon)
    /// or 3 (a solid).
    #[must_use]
    pub fn dimension(&self) -> Option<usize> {
        self.dimension
    }

    /// The slack of [`contains`](BoundingVolume::contains),
    /// [`ray_interval`](BoundingVolume::ray_interval) and
    /// [`overlaps`](BoundingVolume::overlaps): a point up to this far outside a facet's plane
    /// still counts as inside.
    ///
    /// It is 8 `f32` epsilons of the hull's coordinate magnitude (`Σ_i max |x_i|` over the
    /// vertices), so that points computed in `f32` on the boundary (a point between two
    /// vertices, a ray's hit point) are inside, while the hull grows by a negligible amount.
    #[must_use]
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The vertices in `f64`.
    fn points(&self) -> impl Iterator<Item = DVec3> + Clone + '_ {
        self.vertices.iter().map(|v| v.to_dvec3())
    }

    /// The smallest and largest projection of the vertices on `axis`.
    fn extent(&self, axis: DVec3) -> (f64, f64) {
        self.points()
            .map(|p| axis.dot(p))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    }

    /// The vertex average, the reference point for the divergence theorem.
    fn centroid(&self) -> DVec3 {
        self.points().sum::<DVec3>() / self.vertices.len().max(1) as f64
    }
}

impl<V: Vector> Default for ConvexHull<V> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<V: Vector> BoundingVolume for ConvexHull<V> {
    type Point = V;

    /// Cyrus–Beck clipping (Cyrus and Beck, "Generalized two- and three-dimensional
    /// clipping", Computers & Graphics 3(1), 1978): each half-space `n · x <= h` cuts the
    /// ray's interval at `t = (h - n · e) / (n · d)`, from below when the ray runs into the
    /// plane (`n · d < 0`) and from above when it runs out. A ray parallel to a plane is kept
    /// or dropped whole by which side its origin is on. Uses the [tolerance](Self::tolerance),
    /// so the interval agrees with [`contains`](BoundingVolume::contains) along the ray, and a
    /// ray that touches the hull gets a (near) zero-length interval rather than a miss.
    fn ray_interval(&self, ray: &Ray<V>) -> Option<(f32, f32)> {
        if self.is_empty() {
            return None;
        }
        let (origin, dir) = (ray.origin().to_dvec3(), ray.dir().to_dvec3());
        let (mut t_enter, mut t_exit) = (0.0f64, f64::INFINITY);
        for plane in &self.planes {
            let slack = plane.offset + self.tolerance - plane.normal.dot(origin);
            let rate = plane.normal.dot(dir);
            if rate > 0.0 {
                t_exit = t_exit.min(slack / rate);
            } else if rate < 0.0 {
                t_enter = t_enter.max(slack / rate);
            } else if slack < 0.0 {
                return None;
            }
            if t_enter > t_exit {
                return None;
            }
        }
        Some((t_enter as f32, t_exit as f32))
    }

    /// Every half-space test passes within the [tolerance](Self::tolerance). O(facets).
    fn contains(&self, point: V) -> bool {
        let p = point.to_dvec3();
        !self.is_empty()
            && self
                .planes
                .iter()
                .all(|h| h.normal.dot(p) - h.offset <= self.tolerance)
    }

    /// The separating-axis test: the hulls are disjoint exactly when their projections on some
    /// axis are, and it suffices to try the half-space normals of both and, in 3D, the cross
    /// product of every pair of edges (Gottschalk, Lin and Manocha, "`OBBTree`", SIGGRAPH 1996,
    /// after Ericson, "Real-Time Collision Detection", §5.2.1): these are the facet normals of
    /// the Minkowski difference, which holds the origin exactly when the hulls meet. Touching
    /// (within the larger [tolerance](Self::tolerance)) counts as overlapping.
    ///
    /// Lower-dimensional hulls need no special case. Their half-spaces include the slabs that
    /// pin their flat directions and the sides standing on their outline, which are the facet
    /// normals the Minkowski difference gets from them when it is flat itself (two coplanar
    /// polygons, parallel segments, a point and a segment).
    ///
    /// Cost: O((P₁ + P₂)(V₁ + V₂)) for the face axes plus, in 3D, O(E₁ E₂ (V₁ + V₂)) for the
    /// edge pairs, with P half-spaces, E edges and V vertices: cubic in the hull size, so meant
    /// for small hulls (or after a cheaper volume has said "maybe").
    fn overlaps(&self, other: &Self) -> bool {
        if self.is_empty() || other.is_empty() {
            return false;
        }
        let tolerance = self.tolerance.max(other.tolerance);
        let separated = |axis: DVec3| {
            let ((a_lo, a_hi), (b_lo, b_hi)) = (self.extent(axis), other.extent(axis));
            b_lo > a_hi + tolerance || a_lo > b_hi + tolerance
        };
        if self
            .planes
            .iter()
            .chain(&other.planes)
            .any(|h| separated(h.normal))
        {
            return false;
        }
        // In 2D the face normals suffice (`Vector::edge_pair_axis` is always `None` there).
        if V::DIM > 2 {
            for &a in &self.edges {
                for &b in &other.edges {
                    if V::edge_pair_axis(a, b).is_some_and(|axis| separated(axis.to_dvec3())) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// The hull of both vertex sets.
    fn merge(&self, other: &Self) -> Self {
        let mut points = self.vertices.clone();
        points.extend_from_slice(&other.vertices);
        V::convex_hull(&points)
    }

    /// By the divergence theorem, `(1/DIM) Σ_f |f| n̂_f · (x_f − c)` over the facets `f` with
    /// measure `|f|`, outward unit normal `n̂_f` and any point `x_f` on `f`: the cones from a
    /// reference point `c` to the facets (the shoelace formula in 2D). `c` is the vertex
    /// average, which keeps the terms small for hulls far from the origin. Zero for a
    /// lower-dimensional hull.
    fn measure(&self) -> f32 {
        if self.dimension != Some(V::DIM) {
            return 0.0;
        }
        let c = self.centroid();
        // |f| n̂_f = N_f / (DIM − 1) for the facet normal N_f (see `facet_normal`).
        let sum: f64 = self
            .facets
            .iter()
            .map(|f| {
                let (normal, corner) = facet_normal::<V>(f);
                normal.dot(corner - c)
            })
            .sum();
        (sum / (V::DIM * (V::DIM - 1)) as f64) as f32
    }

    /// The total measure of the facets: the perimeter in 2D, the surface area in 3D.
    ///
    /// A lower-dimensional hull counts as the limit of a thin solid around it, so both of its
    /// sides count: a segment in 2D has perimeter `2 × length`, a flat polygon in 3D has
    /// surface area `2 × area`, and a point (or a segment in 3D) has none.
    fn boundary_measure(&self) -> f32 {
        let sum: f64 = self
            .facets
            .iter()
            .map(|f| facet_normal::<V>(f).0.length())
            .sum();
        (sum / (V::DIM - 1) as f64) as f32
    }

    fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    fn aabb(&self) -> Aabb<V> {
        Aabb::from_points(&self.vertices)
    }
}

impl<V: Vector> ConvexHull<V> {
    /// The point itself when [contained](BoundingVolume::contains); otherwise the nearest of
    /// the facets' closest points (for a convex set the nearest point to an outside point lies
    /// on the boundary). A segment or a point in 3D, which have no facets, clamp to the
    /// segment or return the point. O(number of facets).
    pub(crate) fn nearest_point(&self, point: V) -> Option<V> {
        if self.is_empty() {
            return None;
        }
        if self.contains(point) {
            return Some(point);
        }
        let nearer = |a: V, b: V| {
            if (a - point).length_squared() <= (b - point).length_squared() {
                a
            } else {
                b
            }
        };
        let on_facets = self.facets.iter().map(|f| f.project_point(point));
        let best = match (self.facets.is_empty(), self.vertices.as_slice()) {
            (false, _) => on_facets.reduce(nearer),
            (true, &[a, b]) => {
                let e = b - a;
                let s = ((point - a).dot(e) / e.length_squared()).clamp(0.0, 1.0);
                Some(nearer(a + e * s, a))
            }
            (true, vertices) => vertices.iter().copied().reduce(nearer),
        };
        best.or(self.vertices.first().copied())
    }
}

impl<V: Vector> RayCast<V> for ConvexHull<V> {
    /// Where the ray enters ([`BoundingVolume::ray_interval`]): `t = 0` from inside.
    #[inline]
    fn ray_first_hit(&self, ray: &Ray<V>, t_max: f32) -> Option<Hit> {
        volume_hit(self.ray_interval(ray), t_max)
    }
}

impl<V: Vector> PointQuery<V> for ConvexHull<V> {
    #[inline]
    fn closest_point(&self, point: V) -> Option<Nearest<V>> {
        volume_nearest(point, self.nearest_point(point))
    }
}
