//! The BSP tree's node: a plane and the box of everything below it.

use crate::Vector;
use crate::structure::NodeId;
use crate::volume::Aabb;

/// Marks a leaf in [`BspNode`]'s last word.
const LEAF_BIT: u32 = 1 << 31;

/// One node of a [`BspTree`](super::BspTree), in a depth-first array: an inner node's below
/// child follows it, its above child is stored.
///
/// Byte layout (36 bytes in 2D, 48 in 3D):
/// - `bounds` (16 / 24): the box around the primitives under the node, the conservative
///   region that distance, range and collision queries prune with;
/// - `normal` (8 / 12) and `offset` (4): the plane `normal · x = offset` of an inner node
///   (zero in a leaf);
/// - `first_or_above` (4): a leaf's first entry in the index list, an inner node's above child;
/// - `count_or_inner` (4): a leaf's primitive count with the top bit set; 0 for an inner node.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct BspNode<V: Vector> {
    bounds: Aabb<V>,
    normal: V,
    offset: f32,
    first_or_above: u32,
    count_or_inner: u32,
}

const _: () = assert!(size_of::<BspNode<glam::Vec2>>() == 36);
const _: () = assert!(size_of::<BspNode<glam::Vec3>>() == 48);

/// A node of a [`BspTree`](super::BspTree), as the lab draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BspNodeView<'a, V: Vector> {
    /// An inner node split by the plane `normal · x = offset`.
    Inner {
        /// The plane's unit normal; "above" is the side it points to.
        normal: V,
        /// The plane's offset.
        offset: f32,
        /// The box around the primitives below the node.
        bounds: Aabb<V>,
        /// The children, `[below, above]`.
        children: [NodeId; 2],
    },
    /// A leaf.
    Leaf {
        /// The box around its primitives.
        bounds: Aabb<V>,
        /// The indices of its primitives.
        prims: &'a [u32],
    },
}

impl<V: Vector> BspNode<V> {
    /// A leaf listing `count` indices from `first`.
    pub(crate) fn leaf(bounds: Aabb<V>, first: u32, count: u32) -> Self {
        Self {
            bounds,
            normal: V::ZERO,
            offset: 0.0,
            first_or_above: first,
            count_or_inner: count | LEAF_BIT,
        }
    }

    /// An inner node; its above child is set later with [`BspNode::set_above`].
    pub(crate) fn inner(bounds: Aabb<V>, normal: V, offset: f32) -> Self {
        Self {
            bounds,
            normal,
            offset,
            first_or_above: 0,
            count_or_inner: 0,
        }
    }

    /// Records where the above child was put.
    pub(crate) fn set_above(&mut self, above: u32) {
        self.first_or_above = above;
    }

    /// Whether this is a leaf.
    pub fn is_leaf(&self) -> bool {
        self.count_or_inner & LEAF_BIT != 0
    }

    /// The box around the primitives below the node.
    pub fn bounds(&self) -> Aabb<V> {
        self.bounds
    }

    /// The plane's unit normal (zero in a leaf).
    pub fn normal(&self) -> V {
        self.normal
    }

    /// The plane's offset (zero in a leaf).
    pub fn offset(&self) -> f32 {
        self.offset
    }

    /// An inner node's above child.
    pub(crate) fn above(&self) -> u32 {
        self.first_or_above
    }

    /// A leaf's range in the index list.
    pub(crate) fn range(&self) -> std::ops::Range<usize> {
        let first = self.first_or_above as usize;
        first..first + (self.count_or_inner & !LEAF_BIT) as usize
    }
}
