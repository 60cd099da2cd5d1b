//! The one abstraction over dimension.
//!
//! Every volume, primitive and query in this crate is written once, generic over a [`Vector`]
//! type, and compiled for both [`Vec2`] and [`Vec3`] (as madmann91/bvh does with a `Dim`
//! template parameter). What genuinely differs between 2D and 3D lives here and nowhere else:
//! the measure of a box or ball (area vs volume), the extra separating axes that 3D edges
//! contribute, the eigen-decomposition size, and which convex-hull algorithm builds a hull.

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::{DVec2, DVec3, Vec2, Vec3};

use crate::math::eigen::principal_components;
use crate::primitive::{Primitive, Segment2, Triangle3};
use crate::volume::ConvexHull;
use crate::volume::hull_build2::monotone_chain;
use crate::volume::hull_build3::quickhull;
use crate::volume::obb::PcaFit;

/// A point or direction in 2D ([`Vec2`]) or 3D ([`Vec3`]) space, with `f32` coordinates.
///
/// Implemented only for glam's `Vec2` and `Vec3`; generic code uses it so that one
/// implementation of each query serves both dimensions.
pub trait Vector:
    Copy
    + Debug
    + Default
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
    + Neg<Output = Self>
{
    /// Number of coordinates: 2 or 3.
    const DIM: usize;
    /// All coordinates zero.
    const ZERO: Self;
    /// All coordinates `+inf`.
    const INFINITY: Self;
    /// All coordinates `-inf`.
    const NEG_INFINITY: Self;

    /// An orthonormal frame: `[Self; DIM]` (one unit vector per axis).
    type Axes: Copy + Debug + PartialEq + AsRef<[Self]> + AsMut<[Self]> + Send + Sync;

    /// The boundary element of a polytope in this dimension: a [`Segment2`] in 2D, a
    /// [`Triangle3`] in 3D. Convex hulls are bounded by these.
    type Facet: Primitive<Point = Self>;

    /// All coordinates equal to `value`.
    fn splat(value: f32) -> Self;
    /// The unit vector along coordinate axis `i` (`i < DIM`).
    fn unit_axis(i: usize) -> Self;
    /// Coordinate `i`.
    fn coord(self, i: usize) -> f32;
    /// Sets coordinate `i`.
    fn set_coord(&mut self, i: usize, value: f32);
    /// Dot product.
    fn dot(self, other: Self) -> f32;
    /// Component-wise minimum.
    #[must_use]
    fn min(self, other: Self) -> Self;
    /// Component-wise maximum.
    #[must_use]
    fn max(self, other: Self) -> Self;
    /// Component-wise absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// Euclidean length.
    fn length(self) -> f32;
    /// Squared Euclidean length.
    fn length_squared(self) -> f32;
    /// Whether every coordinate is finite (not NaN, not infinite).
    fn is_finite(self) -> bool;
    /// The largest coordinate.
    fn max_element(self) -> f32;
    /// The smallest coordinate.
    fn min_element(self) -> f32;
    /// The same vector in double precision, padded with `z = 0` in 2D.
    ///
    /// Fits that solve small linear systems (Welzl's circumsphere, PCA, quickhull) do their
    /// arithmetic in `f64` and pad 2D with zeros so that one routine serves both dimensions.
    fn to_dvec3(self) -> DVec3;
    /// Back from double precision; drops `z` in 2D.
    fn from_dvec3(v: DVec3) -> Self;

    /// The identity frame (the coordinate axes).
    fn identity_axes() -> Self::Axes;
    /// Area (2D) or volume (3D) of a box with the given side lengths.
    fn box_measure(size: Self) -> f32;
    /// Perimeter (2D) or surface area (3D) of a box with the given side lengths.
    fn box_boundary_measure(size: Self) -> f32;
    /// Area (2D) or volume (3D) of a ball of radius `r`.
    fn ball_measure(r: f32) -> f32;
    /// Perimeter (2D) or surface area (3D) of a ball of radius `r`.
    fn ball_boundary_measure(r: f32) -> f32;

    /// The separating-axis candidate perpendicular to two edge directions, normalised.
    ///
    /// In 3D two convex polyhedra can be separated by a plane parallel to one edge of each,
    /// so the separating-axis theorem adds the cross products of edge pairs (Gottschalk, Lin
    /// and Manocha, "`OBBTree`", SIGGRAPH 1996). In 2D face normals suffice, so this is `None`.
    /// Also `None` when the edges are (nearly) parallel: then a face axis already decides.
    fn edge_pair_axis(a: Self, b: Self) -> Option<Self>;

    /// Principal component analysis of a point set (the lecture's OBB fit, before the
    /// extents): its centroid, covariance matrix, and principal axes, the eigenvectors of the
    /// covariance by decreasing variance, as a right-handed orthonormal frame, with those
    /// variances (eigenvalues). The arithmetic is `f64` Jacobi ([`crate::math::eigen`]).
    ///
    /// The points should be finite (the fits filter them first). No points, one point or
    /// repeated eigenvalues (a square, a cube) still give an orthonormal frame: then any
    /// orthonormal basis of the eigenspace is as principal as another.
    fn principal_axes(points: &[Self]) -> PcaFit<Self>;

    /// The convex hull: monotone chain in 2D, quickhull in 3D.
    fn convex_hull(points: &[Self]) -> ConvexHull<Self>;
}

/// Completes `first` to an orthonormal frame. Used when an eigen-decomposition or a fit leaves
/// the frame slightly non-orthogonal in `f32`.
fn orthonormal_frame2(first: Vec2) -> [Vec2; 2] {
    let x = first.try_normalize().unwrap_or(Vec2::X);
    [x, x.perp()]
}

fn orthonormal_frame3(first: Vec3, second: Vec3) -> [Vec3; 3] {
    let x = first.try_normalize().unwrap_or(Vec3::X);
    let y = (second - x * x.dot(second))
        .try_normalize()
        .unwrap_or_else(|| x.any_orthonormal_vector());
    [x, y, x.cross(y)]
}

macro_rules! forward_glam_methods {
    () => {
        #[inline]
        fn splat(value: f32) -> Self {
            Self::splat(value)
        }
        #[inline]
        fn coord(self, i: usize) -> f32 {
            self[i]
        }
        #[inline]
        fn set_coord(&mut self, i: usize, value: f32) {
            self[i] = value;
        }
        #[inline]
        fn dot(self, other: Self) -> f32 {
            Self::dot(self, other)
        }
        #[inline]
        fn min(self, other: Self) -> Self {
            Self::min(self, other)
        }
        #[inline]
        fn max(self, other: Self) -> Self {
            Self::max(self, other)
        }
        #[inline]
        fn abs(self) -> Self {
            Self::abs(self)
        }
        #[inline]
        fn length(self) -> f32 {
            Self::length(self)
        }
        #[inline]
        fn length_squared(self) -> f32 {
            Self::length_squared(self)
        }
        #[inline]
        fn is_finite(self) -> bool {
            Self::is_finite(self)
        }
        #[inline]
        fn max_element(self) -> f32 {
            Self::max_element(self)
        }
        #[inline]
        fn min_element(self) -> f32 {
            Self::min_element(self)
        }
    };
}

impl Vector for Vec2 {
    const DIM: usize = 2;
    const ZERO: Self = Vec2::ZERO;
    const INFINITY: Self = Vec2::INFINITY;
    const NEG_INFINITY: Self = Vec2::NEG_INFINITY;
    type Axes = [Vec2; 2];
    type Facet = Segment2;

    forward_glam_methods!();

    #[inline]
    fn unit_axis(i: usize) -> Self {
        Vec2::AXES[i]
    }
    #[inline]
    fn to_dvec3(self) -> DVec3 {
        self.as_dvec2().extend(0.0)
    }
    #[inline]
    fn from_dvec3(v: DVec3) -> Self {
        v.truncate().as_vec2()
    }
    #[inline]
    fn identity_axes() -> Self::Axes {
        Vec2::AXES
    }
    #[inline]
    fn box_measure(size: Self) -> f32 {
        size.x * size.y
    }
    #[inline]
    fn box_boundary_measure(size: Self) -> f32 {
        2.0 * (size.x + size.y)
    }
    #[inline]
    fn ball_measure(r: f32) -> f32 {
        std::f32::consts::PI * r * r
    }
    #[inline]
    fn ball_boundary_measure(r: f32) -> f32 {
        std::f32::consts::TAU * r
    }
    #[inline]
    fn edge_pair_axis(_: Self, _: Self) -> Option<Self> {
        None
    }
    #[inline]
    fn principal_axes(points: &[Self]) -> PcaFit<Self> {
        let pca = principal_components(points.iter().map(|p| p.as_dvec2().to_array()));
        let vec2 = |a: [f64; 2]| DVec2::from_array(a).as_vec2();
        PcaFit {
            mean: vec2(pca.mean),
            covariance: pca.covariance.map(vec2),
            axes: orthonormal_frame2(vec2(pca.axes[0])),
            variances: vec2(pca.variances),
        }
    }
    #[inline]
    fn convex_hull(points: &[Self]) -> ConvexHull<Self> {
        monotone_chain(points)
    }
}

impl Vector for Vec3 {
    const DIM: usize = 3;
    const ZERO: Self = Vec3::ZERO;
    const INFINITY: Self = Vec3::INFINITY;
    const NEG_INFINITY: Self = Vec3::NEG_INFINITY;
    type Axes = [Vec3; 3];
    type Facet = Triangle3;

    forward_glam_methods!();

    #[inline]
    fn unit_axis(i: usize) -> Self {
        Vec3::AXES[i]
    }
    #[inline]
    fn to_dvec3(self) -> DVec3 {
        self.as_dvec3()
    }
    #[inline]
    fn from_dvec3(v: DVec3) -> Self {
        v.as_vec3()
    }
    #[inline]
    fn identity_axes() -> Self::Axes {
        Vec3::AXES
    }
    #[inline]
    fn box_measure(size: Self) -> f32 {
        size.x * size.y * size.z
    }
    #[inline]
    fn box_boundary_measure(size: Self) -> f32 {
        2.0 * (size.x * size.y + size.y * size.z + size.z * size.x)
    }
    #[inline]
    fn ball_measure(r: f32) -> f32 {
        4.0 / 3.0 * std::f32::consts::PI * r * r * r
    }
    #[inline]
    fn ball_boundary_measure(r: f32) -> f32 {
        4.0 * std::f32::consts::PI * r * r
    }
    #[inline]
    fn edge_pair_axis(a: Self, b: Self) -> Option<Self> {
        // Normalising the edges first makes the parallel test independent of edge length.
        let axis = a.try_normalize()?.cross(b.try_normalize()?);
        (axis.length_squared() > 1e-10).then(|| axis.normalize())
    }
    #[inline]
    fn principal_axes(points: &[Self]) -> PcaFit<Self> {
        let pca = principal_components(points.iter().map(|p| p.as_dvec3().to_array()));
        let vec3 = |a: [f64; 3]| DVec3::from_array(a).as_vec3();
        PcaFit {
            mean: vec3(pca.mean),
            covariance: pca.covariance.map(vec3),
            axes: orthonormal_frame3(vec3(pca.axes[0]), vec3(pca.axes[1])),
            variances: vec3(pca.variances),
        }
    }
    #[inline]
    fn convex_hull(points: &[Self]) -> ConvexHull<Self> {
        quickhull(points)
    }
}
