//! # bvhlab: bounding volumes and exact geometric queries in 2D and 3D
//!
//! The query core of bvh-lab, an interactive lab for the bounding-volume-hierarchy lecture
//! (University of Toronto CSC418/2504, after Marschner and Shirley). It is a library first: it
//! knows nothing of drawing, and every answer it gives is exact or says why it cannot be.
//!
//! - Primitives: [`Ray2`]/[`Ray3`], [`Segment2`], [`Triangle3`], points as glam vectors.
//! - One query API: one trait per question, answered alike by volumes, primitives and
//!   structures ([`queries`]): [`RayCast`] (`ray_first_hit`, `ray_any_hit`) and
//!   [`PointQuery`] (`closest_point`, `distance`), each with a batch form over a slice
//!   (`ray_first_hits`, `closest_points`, ...) that the `parallel` feature spreads over every
//!   core (it also builds the AABB tree and [`Bvh4`] on every core: `build_parallel`, the same
//!   tree). Every structure, [`Bvh4`] included, also answers [`SpatialQuery`]
//!   (`ray_all_hits`, `k_nearest`, `range`): write code for any structure against these
//!   three traits. Builds take their options the same way everywhere
//!   (`Tree::build_with(&prims, &options)`, the leaf option is `leaf_size`).
//! - Bounding volumes, each fitted to a point set and each answering [`RayCast`],
//!   [`PointQuery`] and the queries of [`prelude::BoundingVolume`] (ray interval,
//!   containment, overlap, merge, measures): [`Aabb2`]/[`Aabb3`], [`Sphere2`]/[`Sphere3`] (the lecture's centroid fit,
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
//! 20k queries), on a shared 2-core machine under load: read the ratios, not the times. The
//! bunny's numbers were measured again on 2026-12-03, after [`Bvh4`] took its triangles in
//! blocks of four; the point cloud's are from an earlier run (points are kept one per slot, as
//! before).
//!
//! | job | structure | why |
//! | --- | --- | --- |
//! | many first hits, any hits or closest points on a static triangle mesh | [`Bvh4`] (`Bvh4::build`) | the fastest here: over triangles its leaves hold blocks of four tested at once; on the bunny, first hits in 0.44 and closest points in 0.77 of the binary tree's time, 0.18 and 0.17 of the k-d tree's; it also answers all hits, the k nearest and ranges ([`Bvh4::ray_all_hits`], [`Bvh4::k_nearest`], [`Bvh4::range`]), refits ([`Bvh4::refit`]), and takes inserts and removes ([`Bvh4::insert`], [`Bvh4::remove`]). It answers [`SpatialQuery`], the trait to write code for any structure against; it has no events, no collision query, and is no [`SpatialIndex`] (the lab's stepping). |
//! | stepping through a query, its events and [`QueryCost`]; collision between two trees; sphere or OBB node volumes; refit after motion | [`Bvh`] ([`AabbTree<P>`](AabbTree), [`SphereTree<P>`](SphereTree), [`ObbTree<P>`](ObbTree) over any primitive; `AabbTree3` is `AabbTree<Triangle3>`, `AabbTree2` is `AabbTree<Segment2>`, and so on) | every query observed ([`Observer`]), which the lab plays back; [`SpatialIndex::collide`]; three node volumes; [`Bvh::refit`](structure::bvh::Bvh::refit) and `needs_rebuild`. Its plain first hit and closest point have fast walks of their own. |
//! | primitives of about one size spread evenly, rebuilt often | [`Grid`] | built in linear time (a counting sort into cells): builds 200k uniform points in 0.14 of [`Bvh4`]'s time and answers their closest points in 2.2 times its time; on the bunny (uneven density) its build takes 0.81 of [`Bvh4`]'s time and its first hits 8.2 times. |
//! | point clouds, the textbook nearest-neighbour tree | [`KdTree`] | over points [`KdTree::build`] splits at the median with leaves of at most 4 (Friedman, Bentley and Finkel 1977), 2.5 times [`Bvh4`]'s closest-point time on 200k points; over triangles it builds the SAH tree for rays (pbrt-v3), 5.7 times [`Bvh4`]'s first-hit time on the bunny. |
//! | splitting by arbitrary planes (autopartition along the primitives' own planes) | [`BspTree`] | what the lecture's BSP trees teach (front-to-back order by planes); the slowest build and queries here (first hits 40 times [`Bvh4`]'s time on the bunny). |
//! | regular, adaptive subdivision of space: cells halved on every axis | [`Orthtree`] ([`Quadtree2`], [`Octree3`]) | cells of fixed shape that adapt to density; first hits 8.0 times [`Bvh4`]'s time on the bunny, closest points 3.7 times on 200k points. |
//!
//! ## Start here: one job, one example
//!
//! Each job below has a short doc-tested snippet here and a longer, commented program in
//! `crates/bvhlab/examples/` that prints what it finds (`cargo run -p bvhlab --example
//! NAME`) and runs as a test against [`BruteForce`], which tests every primitive. The
//! pattern is always the same: build a structure once over a slice of primitives, then ask
//! it many queries; answers name primitives by their index in that slice.
//!
//! - **Ray cast a mesh** (`examples/ray_cast_mesh.rs`: an OBJ file, a camera's rays,
//!   normals interpolated at the hits). [`Mesh::from_obj`] reads the file; a hit's `u`,
//!   `v` are its barycentric coordinates, which blend anything stored per vertex.
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! // One square (two triangles) in the plane z = 0; for a file:
//! // `Mesh::from_obj(&std::fs::read("bunny.obj")?)?`.
//! let mesh = Mesh::from_obj(b"v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n")?;
//! let tree = Bvh4::build(mesh.triangles());
//! let ray = Ray3::new(Vec3::new(1.5, 0.5, 5.0), -Vec3::Z)?;
//! let hit = tree.ray_first_hit(&ray, f32::INFINITY).expect("the ray crosses the square");
//! assert_eq!(hit.t, 5.0);
//! // `u` weighs corner b, `v` corner c: the same weights give the hit point.
//! let tri = mesh.triangles()[hit.prim];
//! let point = tri.a * (1.0 - hit.u - hit.v) + tri.b * hit.u + tri.c * hit.v;
//! assert!(point.distance(ray.at(hit.t)) < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - **Closest point on a mesh** (`examples/closest_points.rs`: a torus made with
//!   [`Mesh::from_indexed`], nearest points and the triangles within a distance).
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! let tris = [Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
//! let tree = Bvh4::build(&tris);
//! let nearest = tree.closest_point(Vec3::new(0.25, 0.25, 3.0)).expect("a non-empty tree");
//! assert_eq!(nearest.prim, 0);
//! assert_eq!(nearest.point, Vec3::new(0.25, 0.25, 0.0));
//! assert_eq!(nearest.distance, 3.0);
//! ```
//!
//! - **k nearest in a point cloud** (`examples/point_cloud_knn.rs`: 100k points, the k
//!   nearest, ball and box ranges, and what each query cost). Points are primitives
//!   (`Vec2` and `Vec3` implement [`Primitive`]): build any structure over a `&[Vec3]`;
//!   [`KdTree`] is the textbook one, [`Bvh4`] the fastest here.
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//! use bvhlab::{KdTree, RangeShape};
//!
//! let points: Vec<Vec3> = (0..10).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
//! let tree = KdTree::build(&points);
//! let three = tree.k_nearest(Vec3::new(3.2, 1.0, 0.0), 3);
//! assert_eq!(three.iter().map(|n| n.prim).collect::<Vec<_>>(), [3, 4, 2]); // nearest first
//! let ball = RangeShape::Ball(Sphere3::new(Vec3::ZERO, 2.0));
//! assert_eq!(tree.range(&ball), [0, 1, 2]);
//! ```
//!
//! - **A primitive of your own** (`examples/custom_primitive.rs`: balls, their texture
//!   coordinates at hits, a sphere tree and [`Bvh4`] over them). Implement [`Primitive`],
//!   keeping the contract written on it;
//!   [`check_enclosed_by_vertices`](primitive::check_enclosed_by_vertices) and
//!   [`check_bounds_hold`](primitive::check_bounds_hold) check the clauses most easily
//!   broken (the vertices must enclose the whole primitive, its bounds must hold it), and
//!   every structure's `validate()` runs both; a debug build also stops at the first hit or
//!   projected point outside a primitive's bounds. Condensed:
//!
//! ```
//! use bvhlab::glam::{BVec3, Vec3};
//! use bvhlab::prelude::*;
//! use bvhlab::primitive::{check_bounds_hold, check_enclosed_by_vertices};
//! use bvhlab::structure::bvh::SphereTree;
//!
//! #[derive(Clone, Copy, Debug, PartialEq)]
//! struct Ball {
//!     center: Vec3,
//!     radius: f32,
//! }
//!
//! impl Primitive for Ball {
//!     type Point = Vec3;
//!     fn bounds(&self) -> Aabb3 {
//!         Aabb3::new(self.center - self.radius, self.center + self.radius)
//!     }
//!     fn centroid(&self) -> Vec3 {
//!         self.center
//!     }
//!     // The least t >= 0 with |origin + t dir - center| <= radius (0 from inside).
//!     fn ray_hit(&self, ray: &Ray3) -> Option<f32> {
//!         let (e, d) = (ray.origin() - self.center, ray.dir());
//!         let (a, half_b) = (d.dot(d), e.dot(d));
//!         let disc = half_b * half_b - a * (e.dot(e) - self.radius * self.radius);
//!         let (enter, exit) = ((-half_b - disc.sqrt()) / a, (-half_b + disc.sqrt()) / a);
//!         (disc >= 0.0 && exit >= 0.0).then(|| enter.max(0.0))
//!     }
//!     fn project_point(&self, p: Vec3) -> Vec3 {
//!         self.center + (p - self.center).clamp_length_max(self.radius)
//!     }
//!     fn measure(&self) -> f32 {
//!         4.0 / 3.0 * std::f32::consts::PI * self.radius.powi(3)
//!     }
//!     fn normal(&self) -> Vec3 {
//!         Vec3::ZERO // no plane holds a ball
//!     }
//!     // Points whose hull holds the whole ball: its box's corners, not its centre alone.
//!     fn vertices(&self) -> impl Iterator<Item = Vec3> {
//!         let (low, high) = (self.center - self.radius, self.center + self.radius);
//!         (0..8u32).map(move |i| {
//!             Vec3::select(BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), high, low)
//!         })
//!     }
//!     fn intersects_aabb(&self, aabb: &Aabb3) -> bool {
//!         aabb.distance(self.center) <= self.radius
//!     }
//!     fn intersects(&self, other: &Self) -> bool {
//!         self.center.distance(other.center) <= self.radius + other.radius
//!     }
//! }
//!
//! let balls = [
//!     Ball { center: Vec3::ZERO, radius: 1.0 },
//!     Ball { center: Vec3::new(5.0, 0.0, 0.0), radius: 2.0 },
//! ];
//! for ball in &balls {
//!     check_enclosed_by_vertices(ball)?;
//!     check_bounds_hold(ball)?;
//! }
//! let tree = SphereTree::<Ball>::build(&balls);
//! tree.validate()?;
//! let ray = Ray3::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X)?;
//! let hit = tree.ray_first_hit(&ray, f32::INFINITY).expect("the ray meets ball 0");
//! assert_eq!((hit.prim, hit.t), (0, 4.0));
//! let nearest = tree.closest_point(Vec3::new(5.0, 3.0, 0.0)).expect("two balls");
//! assert!(nearest.prim == 1 && (nearest.distance - 1.0).abs() < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - **Refit a moving mesh** (`examples/refit_moving_mesh.rs`: a sheet that slides, then
//!   bursts apart, refitted each frame and rebuilt when it pays). A refit keeps the tree's
//!   shape and fits its boxes to the moved primitives, in linear time; the
//!   [`RefitReport`](structure::bvh::RefitReport) says how much the SAH cost grew.
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//!
//! let row = |slot: usize| {
//!     let p = Vec3::X * slot as f32;
//!     Triangle3::new(p, p + Vec3::X, p + Vec3::Y)
//! };
//! let mut tris: Vec<Triangle3> = (0..64).map(row).collect();
//! let mut tree = Bvh4::build(&tris);
//! // The triangles trade places: the same triangles, in the same order, moved.
//! for (i, tri) in tris.iter_mut().enumerate() {
//!     *tri = row(i * 37 % 64);
//! }
//! let report = tree.refit(&tris)?;
//! // Neighbours in a leaf now lie far apart: the boxes grew, and a rebuild pays.
//! assert!(report.cost_ratio().expect("a cost") > 1.5);
//! if report.needs_rebuild(1.5) {
//!     tree = Bvh4::build(&tris);
//! }
//! assert!(!tree.needs_rebuild(1.5));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - **Save and load a tree** (`examples/save_load.rs`, with the `serde` feature): the next
//!   section.
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
//!
//! ## Features
//!
//! Both are off by default, so a WebAssembly build or a small program pulls in neither.
//!
//! | feature | what it adds |
//! | --- | --- |
//! | `serde` | `bvhlab::saved`: saving a built structure as bytes and loading it back; serde derives on the layouts (postcard is the byte format) |
//! | `parallel` | the batch queries (`ray_first_hits`, `ray_any_hits`, `closest_points`) on every core, and `build_parallel` for the AABB tree and [`Bvh4`] (the same tree as `build`); rayon, re-exported as `bvhlab::rayon`; `queries::with_threads` sets the thread count |
//!
//! These docs as docs.rs builds them show every feature's items, each marked with the feature
//! it needs; `cargo doc` alone leaves them out. To read them here:
//! `RUSTC_BOOTSTRAP=1 RUSTDOCFLAGS="--cfg docsrs" cargo doc -p bvhlab --all-features --open`
//! (the `docsrs` cfg turns on rustdoc's `doc_cfg`, which stable rustdoc keeps behind
//! `RUSTC_BOOTSTRAP`, as docs.rs's nightly does not need to).

// docs.rs (and the command above) mark each item with the features it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

pub use glam;
/// rayon, whose pool the `parallel` feature's batch queries and builds run on: build a
/// [`rayon::ThreadPool`] of the size you want and run them inside its `install`
/// ([`queries::with_threads`] does it for one call).
#[cfg(feature = "parallel")]
pub use rayon;

pub mod error;
pub mod math;
pub mod mesh;
pub mod primitive;
pub mod queries;
pub mod ray;
#[cfg(feature = "serde")]
pub mod saved;
pub mod structure;
pub mod vector;
pub mod volume;

pub use error::GeometryError;
pub use mesh::{Mesh, MeshError, MeshStats};
pub use primitive::{Primitive, Segment2, Triangle3};
pub use queries::{PointQuery, RayCast};
pub use ray::Ray;
pub use structure::bvh::{AabbTree, Bvh4, ObbTree, SphereTree};
pub use structure::{
    BruteForce, BspTree, Bvh, Event, Grid, Hit, KdTree, Nearest, NodeId, NodeOutline, NodeShape,
    Observer, Orthtree, Outline, QueryCost, RangeShape, Recorder, SpatialIndex, SpatialQuery,
    SplitPlane, Stats, Traced,
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

/// The AABB tree ([`AabbTree`]) over 2D segments: `AabbTree<Segment2>`.
pub type AabbTree2 = AabbTree<Segment2>;
/// The AABB tree ([`AabbTree`]) over triangles: `AabbTree<Triangle3>`.
pub type AabbTree3 = AabbTree<Triangle3>;
/// The sphere tree ([`SphereTree`]) over 2D segments (circles as node volumes):
/// `SphereTree<Segment2>`.
pub type SphereTree2 = SphereTree<Segment2>;
/// The sphere tree ([`SphereTree`]) over triangles: `SphereTree<Triangle3>`.
pub type SphereTree3 = SphereTree<Triangle3>;
/// The OBB tree ([`ObbTree`]) over 2D segments: `ObbTree<Segment2>`.
pub type ObbTree2 = ObbTree<Segment2>;
/// The OBB tree ([`ObbTree`]) over triangles: `ObbTree<Triangle3>`.
pub type ObbTree3 = ObbTree<Triangle3>;
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
    pub use crate::queries::{PointQuery, RayCast};
    pub use crate::structure::bvh::{AabbTree, Bvh4, ObbTree, SphereTree};
    pub use crate::structure::{Outline, SpatialIndex, SpatialQuery};
    pub use crate::vector::Vector;
    pub use crate::volume::BoundingVolume;
    pub use crate::{
        Aabb2, Aabb3, AabbTree2, AabbTree3, Bsp2, Bsp3, ConvexHull2, ConvexHull3, GeometryError,
        Grid2, Grid3, KdTree2, KdTree3, Mesh, Obb2, Obb3, ObbTree2, ObbTree3, Octree3, Quadtree2,
        Ray2, Ray3, Segment2, Sphere2, Sphere3, SphereTree2, SphereTree3, Triangle3,
    };
}
