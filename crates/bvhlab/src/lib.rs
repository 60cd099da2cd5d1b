//! # bvhlab: bounding volumes and exact geometric queries in 2D and 3D
//!
//! The query core of bvh-lab, an interactive lab for the bounding-volume-hierarchy lecture
//! (University of Toronto CSC418/2504, after Marschner and Shirley). It is a library first: it
//! knows nothing of drawing, and every answer it gives is exact or says why it cannot be.
//!
//! - Primitives: [`Ray2`]/[`Ray3`], [`Segment2`], [`Triangle3`], points as glam vectors.
//! - Bounding volumes, each fitted to a point set and each answering the queries of
//!   [`prelude::BoundingVolume`] (ray interval, distance, containment, overlap, merge,
//!   measures): [`Aabb2`]/[`Aabb3`], [`Sphere2`]/[`Sphere3`] (the lecture's centroid fit,
//!   Ritter's and Welzl's), [`Obb2`]/[`Obb3`] (PCA, with the separating-axis test), and
//!   [`ConvexHull2`]/[`ConvexHull3`].
//!
//! One implementation serves both dimensions: every type is generic over [`Vector`],
//! implemented for [`glam::Vec2`] and [`glam::Vec3`], and the `2`/`3` names are aliases.
//!
//! ```
//! use bvhlab::prelude::*;
//! use bvhlab::glam::Vec2;
//!
//! let points = [Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0), Vec2::new(2.0, 1.0)];
//! let sphere = Sphere2::welzl_fit(&points);
//! let ray = Ray2::new(Vec2::new(-5.0, 0.0), Vec2::X)?;
//! let (t_enter, t_exit) = sphere.ray_interval(&ray).expect("the ray passes the centre");
//! // The minimal circle is the one on the long side: centre (2, 0), radius 2.
//! assert_eq!((t_enter, t_exit), (5.0, 9.0));
//! # Ok::<(), bvhlab::GeometryError>(())
//! ```
//!
//! ## Which structure for which job
//!
//! Every structure answers the same queries with the same answers (brute force's); they
//! differ in what they cost and what else they offer. Times are criterion medians from one
//! run each of `cargo bench -p bvhlab --bench structures` (the bunny, 69k triangles: 20k
//! random rays, 5k random points in its box) and `--bench point_cloud` (200k uniform points,
//! 20k queries), on a shared 2-core machine under load: read the ratios, not the times.
//!
//! | job | structure | why |
//! | --- | --- | --- |
//! | many first hits, any hits or closest points on a static triangle mesh | [`Bvh4`] (`Bvh4::build`) | the fastest here: on the bunny, first hits in 0.40 and closest points in 0.43 of the binary tree's time, 0.09 and 0.08 of the k-d tree's; it also answers all hits, the k nearest and ranges ([`Bvh4::ray_all_hits`], [`Bvh4::k_nearest`], [`Bvh4::range`]), and refits ([`Bvh4::refit`]). No events, no collision query, no [`SpatialIndex`]. |
//! | stepping through a query, its events and [`QueryCost`]; collision between two trees; sphere or OBB node volumes; refit after motion | [`Bvh`] ([`AabbTree3`], [`SphereTree3`], [`ObbTree3`], and their 2D forms) | every query observed ([`Observer`]), which the lab plays back; [`SpatialIndex::collide`]; three node volumes; [`Bvh::refit`](structure::bvh::Bvh::refit) and `needs_rebuild`. Its plain first hit and closest point have fast walks of their own. |
//! | primitives of about one size spread evenly, rebuilt often | [`Grid`] | built in linear time (a counting sort into cells): builds 200k uniform points in 0.14 of [`Bvh4`]'s time and answers their closest points in 2.2 times its time; on the bunny (uneven density) its build takes 1.4 times [`Bvh4`]'s and its first hits 16 times. |
//! | point clouds, the textbook nearest-neighbour tree | [`KdTree`] | over points [`KdTree::build`] splits at the median with leaves of at most 4 (Friedman, Bentley and Finkel 1977), 2.5 times [`Bvh4`]'s closest-point time on 200k points; over triangles it builds the SAH tree for rays (pbrt-v3), 11 times [`Bvh4`]'s first-hit time on the bunny. |
//! | splitting by arbitrary planes (autopartition along the primitives' own planes) | [`BspTree`] | what the lecture's BSP trees teach (front-to-back order by planes); the slowest build and queries here (first hits 29 times [`Bvh4`]'s time on the bunny). |
//! | regular, adaptive subdivision of space: cells halved on every axis | [`Orthtree`] ([`Quadtree2`], [`Octree3`]) | cells of fixed shape that adapt to density; first hits 15 times [`Bvh4`]'s time on the bunny, closest points 3.7 times on 200k points. |
//!
//! ## Saving and loading a tree
//!
//! With the `serde` feature, `bvhlab::saved` saves any built structure (every [`Bvh`] node
//! volume, [`Bvh4`], [`KdTree`], [`BspTree`], [`Grid`], [`Orthtree`], [`BruteForce`], over
//! segments, triangles or points) as bytes and loads it back as the type the caller names,
//! so a tree is built once and loaded many times. The file names its format version and what
//! it holds, and a load refuses, with an error that says why, a file of another version or
//! kind, one cut short or damaged, and one whose structure fails its full check (every index
//! in range, no cycle, volumes around their primitives): a load never panics and never gives a
//! wrong tree.
//!
//! ```
//! # #[cfg(feature = "serde")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! let tree = AabbTree3::build(&[Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)]);
//! let bytes = bvhlab::saved::save(&tree)?;
//! let loaded: AabbTree3 = bvhlab::saved::load(&bytes)?;
//! assert_eq!(loaded, tree);
//! let err = bvhlab::saved::load::<Grid3>(&bytes).unwrap_err();
//! assert_eq!(err.to_string(), "the file holds a Bvh with Aabb nodes over Triangle3, not a Grid over Triangle3");
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "serde"))]
//! # fn main() {}
//! ```
//!
//! ## Where the code lives
//!
//! - [`primitive`]: segments, triangles (the watertight ray test in `primitive/triangle.rs`)
//!   and points; [`volume`]: the bounding volumes, one file each (the lecture's slab test in
//!   `volume/aabb.rs`).
//! - [`structure`]: the query interface ([`SpatialIndex`], [`Observer`] and its [`Event`]s),
//!   and one folder per structure: [`structure::bvh`] (sphere, AABB and OBB trees, in
//!   `layout/`, `volume/` (node volumes and the BVH's slab test), `build/` (`median.rs`,
//!   `sah.rs`), `walk/` and `wide/`), [`structure::kdtree`] and [`structure::bsp`], whose
//!   walks they share in [`structure::plane_tree`], [`structure::grid`], and
//!   [`structure::quadtree`] (the quadtree in 2D, the octree in 3D). Across structures a job
//!   has one file name: `layout`, `build`, `ray`, `nearest`, `range`, `collide`, `validate`.
//! - [`mesh`] (OBJ files), [`ray`], [`vector`], [`math`], [`error`]; with the `serde`
//!   feature, `saved` (saving and loading built structures).

pub use glam;

pub mod error;
pub mod math;
pub mod mesh;
pub mod primitive;
pub mod ray;
#[cfg(feature = "serde")]
pub mod saved;
pub mod structure;
pub mod vector;
pub mod volume;

pub use error::GeometryError;
pub use mesh::{Mesh, MeshError, MeshStats};
pub use primitive::{Primitive, Segment2, Triangle3};
pub use ray::Ray;
pub use structure::bvh::Bvh4;
pub use structure::{
    BruteForce, BspTree, Bvh, Event, Grid, Hit, KdTree, Nearest, NodeId, NodeOutline, NodeShape,
    Observer, Orthtree, Outline, QueryCost, RangeShape, Recorder, SpatialIndex, SplitPlane, Stats,
    Traced,
};
pub use vector::Vector;
pub use volume::{
    Aabb, AxisSource, AxisTest, BoundingVolume, ConvexHull, FitKind, FitReport, Obb, PcaFit,
    SeparatingAxis, SlabTest, Sphere,
};

use glam::{Vec2, Vec3};

/// A 2D ray.
pub type Ray2 = Ray<Vec2>;
/// A 3D ray.
pub type Ray3 = Ray<Vec3>;
/// A 2D axis-aligned box.
pub type Aabb2 = Aabb<Vec2>;
/// A 3D axis-aligned box.
pub type Aabb3 = Aabb<Vec3>;
/// A circle (a 2D sphere).
pub type Sphere2 = Sphere<Vec2>;
/// A 3D sphere.
pub type Sphere3 = Sphere<Vec3>;
/// A 2D oriented box.
pub type Obb2 = Obb<Vec2>;
/// A 3D oriented box.
pub type Obb3 = Obb<Vec3>;
/// A convex polygon.
pub type ConvexHull2 = ConvexHull<Vec2>;
/// A convex polyhedron.
pub type ConvexHull3 = ConvexHull<Vec3>;

/// The README's examples, compiled and run as doc tests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// A bounding volume hierarchy with boxes as node volumes, over 2D segments.
pub type AabbTree2 = Bvh<Aabb2, Segment2>;
/// A bounding volume hierarchy with boxes as node volumes, over triangles.
pub type AabbTree3 = Bvh<Aabb3, Triangle3>;
/// A bounding volume hierarchy with circles as node volumes, over 2D segments.
pub type SphereTree2 = Bvh<Sphere2, Segment2>;
/// A bounding volume hierarchy with spheres as node volumes, over triangles.
pub type SphereTree3 = Bvh<Sphere3, Triangle3>;
/// A bounding volume hierarchy with oriented boxes as node volumes, over 2D segments.
pub type ObbTree2 = Bvh<Obb2, Segment2>;
/// A bounding volume hierarchy with oriented boxes as node volumes, over triangles.
pub type ObbTree3 = Bvh<Obb3, Triangle3>;
/// A k-d tree over 2D segments.
pub type KdTree2 = KdTree<Segment2>;
/// A k-d tree over triangles.
pub type KdTree3 = KdTree<Triangle3>;
/// A BSP tree over 2D segments (split by lines).
pub type Bsp2 = BspTree<Segment2>;
/// A BSP tree over triangles (split by planes).
pub type Bsp3 = BspTree<Triangle3>;
/// A uniform grid over 2D segments.
pub type Grid2 = Grid<Segment2>;
/// A uniform grid over triangles.
pub type Grid3 = Grid<Triangle3>;
/// A quadtree over 2D segments (the 2D orthtree).
pub type Quadtree2 = Orthtree<Segment2>;
/// An octree over triangles (the 3D orthtree).
pub type Octree3 = Orthtree<Triangle3>;

/// The names most programs need: the query traits, the 2D/3D types, and [`Bvh4`], the
/// fastest tree for many first-hit and closest-point queries.
pub mod prelude {
    pub use crate::primitive::Primitive;
    pub use crate::structure::bvh::Bvh4;
    pub use crate::structure::{Outline, SpatialIndex};
    pub use crate::vector::Vector;
    pub use crate::volume::BoundingVolume;
    pub use crate::{
        Aabb2, Aabb3, AabbTree2, AabbTree3, Bsp2, Bsp3, ConvexHull2, ConvexHull3, GeometryError,
        Grid2, Grid3, KdTree2, KdTree3, Mesh, Obb2, Obb3, ObbTree2, ObbTree3, Octree3, Quadtree2,
        Ray2, Ray3, Segment2, Sphere2, Sphere3, SphereTree2, SphereTree3, Triangle3,
    };
}
