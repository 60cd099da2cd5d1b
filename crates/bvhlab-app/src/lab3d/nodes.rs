//! Reading a 3D structure's nodes for drawing, at any size.
//!
//! Small structures are read through the core's [`NodeOutline`](bvhlab::NodeOutline) list;
//! a BVH is read from its own nodes, so a two-million-node tree over a million triangles is
//! not copied into an outline to draw the few levels on screen.

use bvhlab::glam::Vec3;
use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Bvh, NodeId, NodeShape, SplitPlane, Triangle3};

use crate::model::build_job::Structure;
use crate::model::structures::Built;

/// A node's drawing: its region, the planes that split it, and its children.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeView {
    /// The node.
    pub id: NodeId,
    /// Its volume or cell.
    pub shape: NodeShape<Vec3>,
    /// Its splitting planes (k-d, BSP, octree inner nodes).
    pub splits: Vec<SplitPlane<Vec3>>,
    /// Whether it is a leaf (or a grid cell).
    pub leaf: bool,
}

/// A BVH's node as a view.
fn bvh_view<B, S>(bvh: &Bvh<B, Triangle3>, id: NodeId, shape: S) -> Option<NodeView>
where
    B: NodeVolume<Point = Vec3>,
    S: Fn(B) -> NodeShape<Vec3>,
{
    let node = bvh.nodes().get(id.index())?;
    Some(NodeView {
        id,
        shape: shape(node.volume),
        splits: Vec::new(),
        leaf: node.is_leaf(),
    })
}

impl Structure<Triangle3> {
    /// Node `id`, or `None` past the last node.
    pub fn node(&self, id: NodeId) -> Option<NodeView> {
        match &self.built {
            Built::SphereTree(b) => bvh_view(b, id, NodeShape::Sphere),
            Built::AabbTree(b) => bvh_view(b, id, NodeShape::Aabb),
            Built::ObbTree(b) => bvh_view(b, id, NodeShape::Obb),
            _ => {
                let n = self.outline.as_ref()?.get(id.index())?;
                Some(NodeView {
                    id,
                    shape: n.shape,
                    splits: n.splits.clone(),
                    leaf: n.is_leaf(),
                })
            }
        }
    }

    /// The roots: one for a tree, every cell for a grid.
    fn roots(&self) -> Vec<NodeId> {
        match &self.built {
            Built::SphereTree(b) => b.root().into_iter().collect(),
            Built::AabbTree(b) => b.root().into_iter().collect(),
            Built::ObbTree(b) => b.root().into_iter().collect(),
            _ => self.outline.as_ref().map_or_else(Vec::new, |o| {
                o.iter()
                    .filter(|n| n.parent.is_none())
                    .map(|n| n.id)
                    .collect()
            }),
        }
    }

    /// A node's children, in stored order.
    pub fn children(&self, id: NodeId) -> Vec<NodeId> {
        let pair = |p: Option<(NodeId, NodeId)>| p.map_or_else(Vec::new, |(a, b)| vec![a, b]);
        let valid = |len: usize| id.index() < len;
        match &self.built {
            Built::SphereTree(b) if valid(b.nodes().len()) => pair(b.children(id)),
            Built::AabbTree(b) if valid(b.nodes().len()) => pair(b.children(id)),
            Built::ObbTree(b) if valid(b.nodes().len()) => pair(b.children(id)),
            Built::SphereTree(_) | Built::AabbTree(_) | Built::ObbTree(_) => Vec::new(),
            _ => self
                .outline
                .as_ref()
                .and_then(|o| o.get(id.index()))
                .map_or_else(Vec::new, |n| n.children.clone()),
        }
    }

    /// The primitives a leaf (or cell) lists; empty for inner nodes.
    pub fn leaf_primitives(&self, id: NodeId) -> Vec<u32> {
        let valid = |len: usize| id.index() < len;
        match &self.built {
            Built::SphereTree(b) if valid(b.nodes().len()) => b.leaf_primitives(id).to_vec(),
            Built::AabbTree(b) if valid(b.nodes().len()) => b.leaf_primitives(id).to_vec(),
            Built::ObbTree(b) if valid(b.nodes().len()) => b.leaf_primitives(id).to_vec(),
            Built::SphereTree(_) | Built::AabbTree(_) | Built::ObbTree(_) => Vec::new(),
            _ => self
                .outline
                .as_ref()
                .and_then(|o| o.get(id.index()))
                .map_or_else(Vec::new, |n| n.primitives.clone()),
        }
    }

    /// The nodes at `depth` (0 is the root; every grid cell is at depth 0), at most `cap` of
    /// them, breadth first; and whether more were left out. Leaves above `depth` are
    /// included, so the level shows the whole mesh covered.
    pub fn level(&self, depth: u32, cap: usize) -> (Vec<NodeView>, bool) {
        let mut frontier = self.roots();
        for _ in 0..depth {
            let mut next = Vec::with_capacity(frontier.len() * 2);
            for &id in &frontier {
                let children = self.children(id);
                if children.is_empty() {
                    next.push(id);
                } else {
                    next.extend(children);
                }
            }
            if next == frontier {
                break;
            }
            frontier = next;
            if frontier.len() > cap {
                break;
            }
        }
        let more = frontier.len() > cap;
        let views = frontier
            .into_iter()
            .take(cap)
            .filter_map(|id| self.node(id))
            // A grid's empty cells say nothing about the mesh: leave them out.
            .filter(|n| {
                !(matches!(self.built, Built::Grid(_))
                    && n.leaf
                    && self.leaf_primitives(n.id).is_empty())
            })
            .collect();
        (views, more)
    }
}
