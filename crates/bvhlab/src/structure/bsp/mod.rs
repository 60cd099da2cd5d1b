//! Binary space partitioning trees (lecture §3, "Non-uniform spatial subdivision": split by
//! arbitrary planes).
//!
//! A [`BspTree`] cuts space with arbitrary planes (lines in 2D) chosen by autopartition
//! ([`splitter`]); primitives that straddle a plane are listed on both sides. The queries are
//! written once for every binary tree of half-spaces, in [`super::plane_tree`], and shared
//! with the k-d tree ([`super::kdtree`]), which is the special case with axis-aligned planes:
//! front-to-back ray traversal by plane distance ([`plane_tree::ray`]), branch-and-bound
//! nearest neighbours ([`plane_tree::nearest`]), range ([`plane_tree::range`]) and collision
//! ([`plane_tree::collide`]) queries. A node's region is a convex polytope; the queries that
//! need a bound of it use the box of the node's primitives, which is conservative.
//!
//! Files: [`layout`] (the node), [`plane`] (side and crossing tests), [`splitter`] and
//! [`build`] (construction), and [`validate`] (with the checks of
//! [`plane_tree::validate`]).

pub mod build;
pub mod layout;
pub mod plane;
pub mod splitter;
pub mod validate;

pub use super::plane_tree::REFERENCE_BUDGET;
pub use layout::{BspNode, BspNodeView};

use self::plane::Plane;
use super::plane_tree::{self, Crossing, PlaneNode, PlaneTree};
use super::{
    Hit, Nearest, NodeId, Observer, RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::structure::query::{placed_all_traced, placed_traced};
use crate::volume::Aabb;
use crate::{Primitive, Ray};

/// How a [`BspTree`] is built.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
pub struct BspOptions {
    /// A node with at most this many primitives becomes a leaf (at least 1).
    pub leaf_size: usize,
    /// The deepest a leaf may be; `None`: `2 ⌈log2 n⌉ + 8`. Never more than
    /// [`build::DEPTH_LIMIT`].
    pub max_depth: Option<usize>,
    /// How many random primitives' planes are tried at each node (Paterson and Yao's random
    /// autopartition is 1).
    pub candidates: usize,
    /// The price of one straddler against one unit of imbalance in a candidate's score.
    pub straddle_weight: f32,
    /// Whether the plane through the median of the centroids, across their principal axis,
    /// competes with the primitives' own planes at every node (not only as the fallback when
    /// none of them separates anything). Pure autopartition when `false`; much better trees
    /// for meshes when `true`, where a triangle's plane is nearly tangent to the surface and
    /// separates little.
    pub median_candidate: bool,
    /// The seed of the random choice of candidates; equal seeds give equal trees.
    pub seed: u64,
}

impl Default for BspOptions {
    fn default() -> Self {
        Self {
            leaf_size: 4,
            max_depth: None,
            candidates: 5,
            straddle_weight: 4.0,
            median_candidate: false,
            seed: 0x5eed_b5b0,
        }
    }
}

/// A BSP tree over primitives `P`: segments in 2D, triangles in 3D, or points.
///
/// Primitives with a NaN or infinite coordinate are not stored, so queries never report them.
///
/// ```
/// use bvhlab::glam::Vec2;
/// use bvhlab::prelude::*;
/// use bvhlab::structure::bsp::BspTree;
///
/// // A square room: every wall's line is a splitting line of the autopartition.
/// let corners = [Vec2::ZERO, Vec2::new(4.0, 0.0), Vec2::new(4.0, 4.0), Vec2::new(0.0, 4.0)];
/// let walls: Vec<Segment2> = (0..4)
///     .map(|i| Segment2::new(corners[i], corners[(i + 1) % 4]))
///     .collect();
/// let tree = BspTree::build(&walls);
/// tree.validate()?;
/// let nearest = tree.closest_point(Vec2::new(1.0, 2.0)).expect("four walls");
/// assert_eq!((nearest.prim, nearest.distance), (3, 1.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "P: serde::Serialize, P::Point: serde::Serialize",
        deserialize = "P: serde::Deserialize<'de>, P::Point: serde::Deserialize<'de>"
    ))
)]
pub struct BspTree<P: Primitive> {
    prims: Vec<P>,
    nodes: Vec<BspNode<P::Point>>,
    indices: Vec<u32>,
    options: BspOptions,
}

impl<P: Primitive> BspTree<P> {
    /// Builds the tree with [`BspOptions::default`].
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &BspOptions::default())
    }

    /// Builds the tree with the given options.
    pub fn build_with(prims: &[P], options: &BspOptions) -> Self {
        build::build(prims, options, &mut ())
    }

    /// Builds the tree, reporting each node ([`Event::BuildNode`](crate::Event::BuildNode),
    /// `BuildSplit`, `BuildLeaf`) in depth-first order.
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &BspOptions,
        observer: &mut O,
    ) -> Self {
        build::build(prims, options, observer)
    }

    /// The options it was built with.
    pub fn options(&self) -> &BspOptions {
        &self.options
    }

    /// The nodes, root first, in depth-first order (empty for an empty tree).
    pub fn nodes(&self) -> &[BspNode<P::Point>] {
        &self.nodes
    }

    /// One node, for drawing.
    ///
    /// # Panics
    /// When `node` is not a node of this tree.
    pub fn node(&self, node: NodeId) -> BspNodeView<'_, P::Point> {
        let n = &self.nodes[node.index()];
        if n.is_leaf() {
            BspNodeView::Leaf {
                bounds: n.bounds(),
                prims: &self.indices[n.range()],
            }
        } else {
            BspNodeView::Inner {
                normal: n.normal(),
                offset: n.offset(),
                bounds: n.bounds(),
                children: [NodeId(node.0 + 1), NodeId(n.above())],
            }
        }
    }

    fn plane(&self, node: u32) -> Plane<P::Point> {
        let n = &self.nodes[node as usize];
        Plane {
            normal: n.normal(),
            offset: n.offset(),
        }
    }
}

impl<P: Primitive> PlaneTree for BspTree<P> {
    type Prim = P;

    fn prims(&self) -> &[P] {
        &self.prims
    }

    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    fn root_bound(&self) -> Option<Aabb<P::Point>> {
        self.nodes.first().map(BspNode::bounds)
    }

    fn node(&self, node: u32) -> PlaneNode<'_> {
        let n = &self.nodes[node as usize];
        if n.is_leaf() {
            PlaneNode::Leaf(&self.indices[n.range()])
        } else {
            PlaneNode::Inner([node + 1, n.above()])
        }
    }

    fn crossing(&self, node: u32, ray: &Ray<P::Point>) -> Crossing {
        self.plane(node).crossing(ray)
    }

    fn child_bounds(&self, node: u32, _bound: &Aabb<P::Point>) -> [Aabb<P::Point>; 2] {
        let above = self.nodes[node as usize].above();
        [
            self.nodes[node as usize + 1].bounds(),
            self.nodes[above as usize].bounds(),
        ]
    }

    fn side_of(&self, node: u32, point: P::Point) -> usize {
        self.plane(node).side_of(point)
    }
}

impl<P: Primitive> SpatialIndex for BspTree<P> {
    type Prim = P;

    fn build(prims: &[P]) -> Self {
        Self::build(prims)
    }

    fn primitives(&self) -> &[P] {
        &self.prims
    }

    fn ray_first_hit_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        placed_traced(
            plane_tree::ray::first_hit(self, ray, t_max, observer),
            &self.prims,
            ray,
        )
    }

    fn ray_any_hit_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        placed_traced(
            plane_tree::ray::any_hit(self, ray, t_max, observer),
            &self.prims,
            ray,
        )
    }

    fn ray_all_hits_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        placed_all_traced(
            plane_tree::ray::all_hits(self, ray, t_max, observer),
            &self.prims,
            ray,
        )
    }

    fn k_nearest_observed<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        plane_tree::nearest::k_nearest(self, point, k, observer)
    }

    fn range_observed<O: Observer<P::Point>>(
        &self,
        shape: &RangeShape<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        plane_tree::range::range(self, shape, observer)
    }

    fn collide_observed<O: Observer<P::Point>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        plane_tree::collide::collide(self, other, observer)
    }

    /// The SAH cost is that of the nodes' boxes (the boxes of their primitives).
    fn stats(&self) -> Stats {
        let memory = self.nodes.len() * size_of::<BspNode<P::Point>>()
            + self.indices.len() * size_of::<u32>()
            + self.prims.len() * size_of::<P>();
        plane_tree::validate::plane_tree_stats(self, memory)
    }

    fn validate(&self) -> Result<(), ValidationError> {
        validate::validate(self)
    }
}
