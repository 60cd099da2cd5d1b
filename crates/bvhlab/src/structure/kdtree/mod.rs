//! k-d trees (lecture §3, "Non-uniform spatial subdivision": axis-aligned splitting planes).
//!
//! A [`KdTree`] cuts its root cell (the box of all primitives) with axis-aligned planes, each
//! cell in two, down to small leaves. Primitives that straddle a plane are listed in both
//! children. Two builders choose the planes ([`KdBuilder`]): the median of the primitives'
//! centres (Bentley 1975), or the surface area heuristic with pbrt-v3's cost model over sorted
//! edge events (Wald and Havran 2006). [`KdTree::build`] takes the SAH for segments and
//! triangles and the median with small leaves for point clouds
//! ([`KdTreeOptions::for_primitives`] says why).
//!
//! A k-d tree is a BSP tree whose planes are axis-aligned, so its queries are the BSP tree's,
//! in [`super::plane_tree`] (the k-d traversal is [`plane_tree::ray`]): this type only says
//! how a ray crosses an axis-aligned plane, with one coordinate of the ray and its
//! precomputed `1/d` (the fast path of Havran's and pbrt's traversal), and that a child's
//! region is its parent's cell cut at the plane.
//!
//! Files: [`layout`] (the 8-byte node), [`options`], [`build`] (what both builders share)
//! with the median builder ([`build::median`]) and the SAH builder ([`build::sah`], over
//! the sorted edge events of [`build::sah_events`]), and [`validate`]. The queries are in
//! [`super::plane_tree`].

pub mod build;
pub mod layout;
pub mod options;
pub mod validate;

pub use layout::{KdNode, KdNodeView};
pub use options::{AxisRule, KdBuilder, KdTreeOptions, SahCosts};

use self::build::{Builder, split_cell};
use super::plane_tree::{self, Crossing, PlaneNode, PlaneTree, SLACK, axis_crossing, magnitude};
use super::{
    Hit, Nearest, NodeId, Observer, RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::structure::query::{placed_all_traced, placed_traced};
use crate::volume::Aabb;
use crate::{Primitive, Ray, Vector};

/// A k-d tree over primitives `P`: segments in 2D, triangles in 3D, or points.
///
/// Primitives with a NaN or infinite coordinate are not stored, so queries never report them.
///
/// ```
/// use bvhlab::glam::Vec2;
/// use bvhlab::prelude::*;
/// use bvhlab::structure::kdtree::{AxisRule, KdTree, KdTreeOptions};
///
/// let walls: Vec<Segment2> = (0..10)
///     .map(|i| Segment2::new(Vec2::new(i as f32, -1.0), Vec2::new(i as f32, 1.0)))
///     .collect();
/// let tree = KdTree::build_with(&walls, &KdTreeOptions::median(AxisRule::LongestAxis));
/// tree.validate()?;
/// let ray = Ray2::new(Vec2::new(2.5, 0.0), Vec2::X)?;
/// let hit = tree.ray_first_hit(&ray, f32::INFINITY).expect("the wall at x = 3");
/// assert_eq!((hit.prim, hit.t), (3, 0.5));
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
pub struct KdTree<P: Primitive> {
    prims: Vec<P>,
    nodes: Vec<KdNode>,
    indices: Vec<u32>,
    root_cell: Aabb<P::Point>,
    options: KdTreeOptions,
}

impl<P: Primitive> KdTree<P> {
    /// Builds the tree with [`KdTreeOptions::for_primitives`]: the SAH builder over segments
    /// and triangles, the median builder with small leaves over points.
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &KdTreeOptions::for_primitives(prims))
    }

    /// Builds the tree with the given options.
    pub fn build_with(prims: &[P], options: &KdTreeOptions) -> Self {
        Self::build_observed(prims, options, &mut ())
    }

    /// Builds the tree, reporting each node ([`Event::BuildNode`](crate::Event::BuildNode),
    /// `BuildSplit`, `BuildLeaf`) in depth-first order.
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &KdTreeOptions,
        observer: &mut O,
    ) -> Self {
        let (mut builder, refs, root_cell) = Builder::new(prims, options, observer);
        if !refs.is_empty() {
            let at = build::Subtree::root(root_cell, refs.len());
            match options.builder {
                KdBuilder::Median(rule) => {
                    build::median::build_median(&mut builder, rule, refs, at);
                }
                KdBuilder::Sah(costs) => {
                    let (mut arena, events) =
                        build::sah_events::EventArena::new(&refs, &builder.bounds);
                    drop(refs);
                    build::sah::build_sah(&mut builder, &mut arena, &costs, events, at, 0);
                }
            }
        }
        Self {
            prims: prims.to_vec(),
            nodes: builder.nodes,
            indices: builder.indices,
            root_cell,
            options: *options,
        }
    }

    /// The options it was built with.
    pub fn options(&self) -> &KdTreeOptions {
        &self.options
    }

    /// The nodes, root first, in depth-first order (empty for an empty tree).
    pub fn nodes(&self) -> &[KdNode] {
        &self.nodes
    }

    /// The root cell: the box around every stored primitive ([`Aabb::EMPTY`] when empty).
    pub fn root_cell(&self) -> Aabb<P::Point> {
        self.root_cell
    }

    /// One node, for drawing.
    ///
    /// # Panics
    /// When `node` is not a node of this tree.
    pub fn node(&self, node: NodeId) -> KdNodeView<'_> {
        let n = &self.nodes[node.index()];
        if n.is_leaf() {
            KdNodeView::Leaf {
                prims: &self.indices[n.range()],
            }
        } else {
            KdNodeView::Inner {
                axis: n.axis(),
                split: n.split(),
                children: [NodeId(node.0 + 1), NodeId(n.above())],
            }
        }
    }

    /// Every node's cell, indexed like [`KdTree::nodes`].
    pub fn cells(&self) -> Vec<Aabb<P::Point>> {
        let mut cells = vec![Aabb::EMPTY; self.nodes.len()];
        if let Some(first) = cells.first_mut() {
            *first = self.root_cell;
        }
        for (i, n) in self.nodes.iter().enumerate() {
            if !n.is_leaf() {
                let [below, above] = split_cell(&cells[i], n.axis(), n.split());
                cells[i + 1] = below;
                cells[n.above() as usize] = above;
            }
        }
        cells
    }
}

impl<P: Primitive> PlaneTree for KdTree<P> {
    type Prim = P;

    fn prims(&self) -> &[P] {
        &self.prims
    }

    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    fn root_bound(&self) -> Option<Aabb<P::Point>> {
        (!self.nodes.is_empty()).then_some(self.root_cell)
    }

    #[inline]
    fn node(&self, node: u32) -> PlaneNode<'_> {
        let n = &self.nodes[node as usize];
        if n.is_leaf() {
            PlaneNode::Leaf(&self.indices[n.range()])
        } else {
            PlaneNode::Inner([node + 1, n.above()])
        }
    }

    /// The axis-aligned fast path: `t = (split - o_axis) / d_axis` with the ray's `1/d`.
    ///
    /// Besides the crossing's own rounding, the margin allows for the primitives': a
    /// primitive's hit is only as exact as its coordinates, so a primitive with large
    /// coordinates may report a hit a few units in the last place of the scene's
    /// magnitude across a plane whose neighbourhood has tiny ones (a segment from 1e-7 to
    /// 6e14, a ray near the origin).
    #[inline]
    fn crossing(&self, node: u32, ray: &Ray<P::Point>) -> Crossing {
        let n = &self.nodes[node as usize];
        let (axis, split) = (n.axis(), n.split());
        let (o, d) = (ray.origin().coord(axis), ray.dir().coord(axis));
        let scene = SLACK * magnitude(self.root_cell.min).max(magnitude(self.root_cell.max));
        if d == 0.0 {
            return Crossing::Parallel {
                below: o <= split + scene,
                above: o >= split - scene,
            };
        }
        let (t, err) = axis_crossing(split, o, d, ray.inv_dir().coord(axis));
        Crossing::At {
            t,
            err: err + scene / d.abs(),
            below_first: d > 0.0,
        }
    }

    #[inline]
    fn child_bounds(&self, node: u32, bound: &Aabb<P::Point>) -> [Aabb<P::Point>; 2] {
        let n = &self.nodes[node as usize];
        split_cell(bound, n.axis(), n.split())
    }

    #[inline]
    fn side_of(&self, node: u32, point: P::Point) -> usize {
        let n = &self.nodes[node as usize];
        usize::from(point.coord(n.axis()) >= n.split())
    }
}

impl<P: Primitive> SpatialIndex for KdTree<P> {
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

    /// The SAH cost is that of the cells.
    fn stats(&self) -> Stats {
        let memory = self.nodes.len() * size_of::<KdNode>()
            + self.indices.len() * size_of::<u32>()
            + self.prims.len() * size_of::<P>();
        plane_tree::validate::plane_tree_stats(self, memory)
    }

    fn validate(&self) -> Result<(), ValidationError> {
        validate::validate(self)
    }
}
