//! The k-d tree's node: 8 bytes, as in pbrt-v3's `KdAccelNode` (§4.4.1).

use crate::structure::NodeId;

/// The axis field of a leaf.
const LEAF: u32 = 3;

/// One node of a [`KdTree`](super::KdTree), in a depth-first array: an inner node's below
/// child follows it, its above child is stored. Cells are not stored: a node's cell is its
/// parent's, cut at the parent's plane, and queries carry it down.
///
/// Byte layout (8 bytes, so that eight nodes share a cache line):
/// - `split_or_first` (4): an inner node's split position (the bits of an `f32`), or a leaf's
///   first entry in the index list;
/// - `axis_and_index` (4): bits 0-1 hold the split axis (0, 1, 2) or 3 for a leaf; bits 2-31
///   hold an inner node's above child or a leaf's primitive count (so at most 2^30 of either).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct KdNode {
    split_or_first: u32,
    axis_and_index: u32,
}

const _: () = assert!(size_of::<KdNode>() == 8);

/// A node of a [`KdTree`](super::KdTree), as the lab draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KdNodeView<'a> {
    /// An inner node split by the plane `x_axis = split`.
    Inner {
        /// The split axis (0: x, 1: y, 2: z).
        axis: usize,
        /// The split position.
        split: f32,
        /// The children, `[below, above]`.
        children: [NodeId; 2],
    },
    /// A leaf and the indices of its primitives.
    Leaf {
        /// The indices of its primitives.
        prims: &'a [u32],
    },
}

impl KdNode {
    /// An inner node; its above child is set later with [`KdNode::set_above`].
    pub(crate) fn inner(axis: usize, split: f32) -> Self {
        Self {
            split_or_first: split.to_bits(),
            axis_and_index: axis as u32,
        }
    }

    /// A leaf listing `count` indices from `first`.
    pub(crate) fn leaf(first: u32, count: u32) -> Self {
        Self {
            split_or_first: first,
            axis_and_index: (count << 2) | LEAF,
        }
    }

    /// Records where the above child was put.
    pub(crate) fn set_above(&mut self, above: u32) {
        self.axis_and_index = (above << 2) | (self.axis_and_index & 3);
    }

    /// Whether this is a leaf.
    #[inline]
    pub fn is_leaf(self) -> bool {
        self.axis_and_index & 3 == LEAF
    }

    /// An inner node's split axis.
    #[inline]
    pub fn axis(self) -> usize {
        (self.axis_and_index & 3) as usize
    }

    /// An inner node's split position.
    #[inline]
    pub fn split(self) -> f32 {
        f32::from_bits(self.split_or_first)
    }

    /// An inner node's above child.
    #[inline]
    pub(crate) fn above(self) -> u32 {
        self.axis_and_index >> 2
    }

    /// A leaf's range in the index list.
    #[inline]
    pub(crate) fn range(self) -> std::ops::Range<usize> {
        let first = self.split_or_first as usize;
        first..first + (self.axis_and_index >> 2) as usize
    }
}
