//! The layout: a flat, depth-first array of binary nodes, and the primitives in leaf order.
//!
//! Beside it: [`gpu`], the same AABB tree flattened for the app's GPU heat map (the layout
//! its WGSL mirrors), and `stats.rs`, the numbers that compare one tree with another.

pub mod gpu;
mod stats;

use super::BvhOptions;
use crate::Primitive;
use crate::structure::NodeId;
use crate::volume::Aabb;

/// One node of a [`Bvh`]: its bounding volume and where its children or primitives are.
///
/// Nodes are stored depth-first (pbrt-v4's `LinearBVHNode`): an inner node's first child is
/// the next node in the array, so only the second child's index is stored. With an
/// axis-aligned box in 3D the node is 32 bytes, two to a 64-byte cache line:
///
/// ```text
/// offset  0  volume.min   3 × f32   (12 bytes)
/// offset 12  volume.max   3 × f32   (12 bytes)
/// offset 24  start        u32       leaf: first primitive (leaf order); inner: second child
/// offset 28  count        u32       leaf: primitive count (>= 1); inner: 0
/// ```
///
/// A sphere node is 24 bytes (centre, radius, start, count), an OBB node 68 (centre, three
/// axes, half extents, start, count); in 2D every volume is smaller.
///
/// The app's GPU heat map reads AABB nodes as [`gpu::GpuNode`], which [`gpu`] makes from
/// these: a change here must be carried there (and into the WGSL it names).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct BvhNode<B> {
    /// The node's bounding volume: it contains every primitive below the node.
    pub volume: B,
    /// Leaf: index of its first primitive in leaf order. Inner node: index of its second
    /// child.
    pub start: u32,
    /// Leaf: how many primitives it holds (at least 1). Inner node: 0.
    pub count: u32,
}

const _: () = assert!(size_of::<BvhNode<Aabb<glam::Vec3>>>() == 32);
const _: () = assert!(size_of::<BvhNode<Aabb<glam::Vec2>>>() == 24);

impl<B> BvhNode<B> {
    /// Whether the node is a leaf.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The range of its primitives in leaf order (empty for an inner node).
    pub fn leaf_range(&self) -> std::ops::Range<usize> {
        if self.is_leaf() {
            self.start as usize..(self.start + self.count) as usize
        } else {
            0..0
        }
    }
}

/// A bounding volume hierarchy over primitives `P` with node volumes `B`: an
/// [`AabbTree`](super::AabbTree) when `B` is an [`Aabb`], a [`SphereTree`](super::SphereTree)
/// for a [`Sphere`](crate::Sphere), an [`ObbTree`](super::ObbTree) for an
/// [`Obb`](crate::Obb). One implementation serves all three, in 2D and 3D.
///
/// Primitives with a NaN or infinite coordinate are left out of the tree: no query reports
/// them (brute force would only report what the primitive's own tests make of NaN).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh<B, P: Primitive> {
    /// The input, in input order.
    pub(super) prims: Vec<P>,
    /// Depth-first nodes; the root is node 0. Empty when no primitive is indexed.
    pub(super) nodes: Vec<BvhNode<B>>,
    /// Copies of the indexed primitives in leaf order, so that a leaf's primitives are
    /// contiguous in memory.
    pub(super) leaf_prims: Vec<P>,
    /// `leaf_ids[i]` is the input index of `leaf_prims[i]`.
    pub(super) leaf_ids: Vec<u32>,
    /// What the tree was built with.
    pub(super) options: BvhOptions,
    /// The SAH cost when the tree was built, for [`Bvh::needs_rebuild`] after refits.
    pub(super) build_sah_cost: Option<f32>,
}

impl<B, P: Primitive> Bvh<B, P> {
    /// The nodes, depth-first; the root is node 0.
    pub fn nodes(&self) -> &[BvhNode<B>] {
        &self.nodes
    }

    /// The root, or `None` for a tree with no primitives.
    pub fn root(&self) -> Option<NodeId> {
        (!self.nodes.is_empty()).then_some(NodeId(0))
    }

    /// A node.
    ///
    /// # Panics
    /// When `id` is not a node of this tree.
    pub fn node(&self, id: NodeId) -> &BvhNode<B> {
        &self.nodes[id.index()]
    }

    /// The two children of an inner node (`None` for a leaf).
    pub fn children(&self, id: NodeId) -> Option<(NodeId, NodeId)> {
        let node = self.nodes.get(id.index())?;
        (!node.is_leaf()).then(|| (NodeId(id.0 + 1), NodeId(node.start)))
    }

    /// The input indices of a leaf's primitives (empty for an inner node).
    pub fn leaf_primitives(&self, id: NodeId) -> &[u32] {
        self.nodes
            .get(id.index())
            .map_or(&[][..], |node| &self.leaf_ids[node.leaf_range()])
    }

    /// The options the tree was built with.
    pub fn options(&self) -> &BvhOptions {
        &self.options
    }

    /// The SAH cost the tree had when it was built (before any [`refit`](Bvh::refit),
    /// [`insert`](Bvh::insert), [`remove`](Bvh::remove), [`replace`](Bvh::replace) or
    /// [`optimize_by_reinsertion`](Bvh::optimize_by_reinsertion), which leave it as it was,
    /// so that [`needs_rebuild`](Bvh::needs_rebuild) measures against the last build); see
    /// [`Stats::sah_cost`](crate::structure::Stats::sah_cost).
    pub fn build_sah_cost(&self) -> Option<f32> {
        self.build_sah_cost
    }

    /// How many input primitives were left out because a coordinate is NaN or infinite.
    pub fn skipped(&self) -> usize {
        self.prims.len() - self.leaf_ids.len()
    }
}
