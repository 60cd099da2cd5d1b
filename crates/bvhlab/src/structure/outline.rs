//! One description of every structure's nodes, for drawing them.
//!
//! The structures lay their nodes out in different ways (a BVH stores volumes, a k-d tree
//! only split positions, a grid cell coordinates). [`Outline`] turns each into the same list
//! of [`NodeOutline`]s, indexed by the [`NodeId`] that the structure's query and build
//! events report, so a viewer draws any structure, and highlights the nodes a query
//! visited, with one code path and without knowing how the structure is built.

use super::{
    BruteForce, BspTree, Bvh, Grid, KdTree, NodeId, Orthtree, PointOf, SpatialIndex,
    bsp::BspNodeView, bvh::NodeVolume, kdtree::KdNodeView,
};
use crate::volume::{Aabb, Obb, Sphere};
use crate::{Primitive, Vector};

/// The region a node stands for: its bounding volume (BVHs, the BSP tree's boxes) or its
/// cell (k-d tree, grid, quadtree/octree).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NodeShape<V: Vector> {
    /// An axis-aligned box.
    Aabb(Aabb<V>),
    /// A sphere (a circle in 2D).
    Sphere(Sphere<V>),
    /// An oriented box.
    Obb(Obb<V>),
}

impl<V: Vector> NodeShape<V> {
    /// The axis-aligned box around the shape.
    pub fn aabb(&self) -> Aabb<V> {
        use crate::BoundingVolume;
        match self {
            Self::Aabb(b) => *b,
            Self::Sphere(s) => s.aabb(),
            Self::Obb(o) => o.aabb(),
        }
    }
}

/// A splitting plane `normal · x = offset`; "above" is the side `normal` points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitPlane<V: Vector> {
    /// The plane's normal (a unit axis for k-d trees and octrees).
    pub normal: V,
    /// The plane's offset along `normal`.
    pub offset: f32,
}

/// One node as a viewer draws it.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeOutline<V: Vector> {
    /// The id the structure's events use for this node.
    pub id: NodeId,
    /// Its parent (`None` for a root, and for every grid cell).
    pub parent: Option<NodeId>,
    /// Its depth: 0 for the root (and for grid cells).
    pub depth: u32,
    /// Its bounding volume or cell.
    pub shape: NodeShape<V>,
    /// The planes that split an inner node: one for k-d and BSP trees, one per axis through
    /// the centre for quadtrees and octrees; none for leaves, BVH nodes and grid cells.
    pub splits: Vec<SplitPlane<V>>,
    /// Its children, in the order the structure stores them.
    pub children: Vec<NodeId>,
    /// The primitives a leaf (or grid cell) lists; empty for inner nodes.
    pub primitives: Vec<u32>,
}

impl<V: Vector> NodeOutline<V> {
    /// Whether the node has no children.
    pub fn is_leaf(&self) -> bool {
        self.children.is_empty()
    }
}

/// A structure that can list its nodes for drawing.
pub trait Outline: SpatialIndex {
    /// Every node, such that `outline()[id.index()]` is the node that events call `id`.
    /// Empty for an empty structure and for [`BruteForce`].
    fn outline(&self) -> Vec<NodeOutline<PointOf<Self>>>;
}

/// Fills in `parent` and `depth` from the `children` lists; parents must come before their
/// children (the structures store nodes root first).
fn link_parents<V: Vector>(nodes: &mut [NodeOutline<V>]) {
    for i in 0..nodes.len() {
        let depth = nodes[i].depth;
        for k in 0..nodes[i].children.len() {
            let c = &mut nodes[nodes[i].children[k].index()];
            c.parent = Some(NodeId(i as u32));
            c.depth = depth + 1;
        }
    }
}

fn axis_plane<V: Vector>(axis: usize, offset: f32) -> SplitPlane<V> {
    SplitPlane {
        normal: V::unit_axis(axis),
        offset,
    }
}

impl<P: Primitive> Outline for BruteForce<P> {
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        Vec::new()
    }
}

impl<B, P> Outline for Bvh<B, P>
where
    B: NodeVolume<Point = P::Point> + Into<NodeShape<P::Point>>,
    P: Primitive,
{
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        let mut nodes: Vec<_> = (0..self.nodes().len())
            .map(|i| {
                let id = NodeId(i as u32);
                let children = self.children(id).map_or(Vec::new(), |(a, b)| vec![a, b]);
                NodeOutline {
                    id,
                    parent: None,
                    depth: 0,
                    shape: self.node(id).volume.into(),
                    splits: Vec::new(),
                    children,
                    primitives: self.leaf_primitives(id).to_vec(),
                }
            })
            .collect();
        // Depth-first order: parents come before their children.
        link_parents(&mut nodes);
        nodes
    }
}

impl<V: Vector> From<Aabb<V>> for NodeShape<V> {
    fn from(b: Aabb<V>) -> Self {
        Self::Aabb(b)
    }
}

impl<V: Vector> From<Sphere<V>> for NodeShape<V> {
    fn from(s: Sphere<V>) -> Self {
        Self::Sphere(s)
    }
}

impl<V: Vector> From<Obb<V>> for NodeShape<V> {
    fn from(o: Obb<V>) -> Self {
        Self::Obb(o)
    }
}

impl<P: Primitive> Outline for KdTree<P> {
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        let cells = self.cells();
        let mut nodes: Vec<_> = cells
            .iter()
            .enumerate()
            .map(|(i, cell)| {
                let id = NodeId(i as u32);
                let (splits, children, primitives) = match self.node(id) {
                    KdNodeView::Inner {
                        axis,
                        split,
                        children,
                    } => (vec![axis_plane(axis, split)], children.to_vec(), Vec::new()),
                    KdNodeView::Leaf { prims } => (Vec::new(), Vec::new(), prims.to_vec()),
                };
                NodeOutline {
                    id,
                    parent: None,
                    depth: 0,
                    shape: NodeShape::Aabb(*cell),
                    splits,
                    children,
                    primitives,
                }
            })
            .collect();
        link_parents(&mut nodes);
        nodes
    }
}

impl<P: Primitive> Outline for BspTree<P> {
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        let mut nodes: Vec<_> = (0..self.nodes().len())
            .map(|i| {
                let id = NodeId(i as u32);
                let (bounds, splits, children, primitives) = match self.node(id) {
                    BspNodeView::Inner {
                        normal,
                        offset,
                        bounds,
                        children,
                    } => (
                        bounds,
                        vec![SplitPlane { normal, offset }],
                        children.to_vec(),
                        Vec::new(),
                    ),
                    BspNodeView::Leaf { bounds, prims } => {
                        (bounds, Vec::new(), Vec::new(), prims.to_vec())
                    }
                };
                NodeOutline {
                    id,
                    parent: None,
                    depth: 0,
                    shape: NodeShape::Aabb(bounds),
                    splits,
                    children,
                    primitives,
                }
            })
            .collect();
        link_parents(&mut nodes);
        nodes
    }
}

impl<P: Primitive> Outline for Grid<P> {
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        (0..self.cell_count())
            .map(|i| NodeOutline {
                id: NodeId(i as u32),
                parent: None,
                depth: 0,
                shape: NodeShape::Aabb(self.cell_box(self.cell_coords(i))),
                splits: Vec::new(),
                children: Vec::new(),
                primitives: self.cell_primitives(i).to_vec(),
            })
            .collect()
    }
}

impl<P: Primitive> Outline for Orthtree<P> {
    fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        let mut nodes: Vec<Option<NodeOutline<P::Point>>> = vec![None; self.node_count()];
        for cell in self.cells() {
            let children: Vec<NodeId> = self
                .children(cell.node)
                .map_or(Vec::new(), |range| range.map(NodeId).collect());
            let splits = if children.is_empty() {
                Vec::new()
            } else {
                let mid = cell.bounds.center();
                (0..P::Point::DIM)
                    .map(|axis| axis_plane(axis, mid.coord(axis)))
                    .collect()
            };
            nodes[cell.node.index()] = Some(NodeOutline {
                id: cell.node,
                parent: None,
                depth: cell.depth,
                shape: NodeShape::Aabb(cell.bounds),
                splits,
                children,
                primitives: cell.prims.map_or(Vec::new(), <[u32]>::to_vec),
            });
        }
        let mut nodes: Vec<_> = nodes.into_iter().flatten().collect();
        link_parents(&mut nodes);
        nodes
    }
}
