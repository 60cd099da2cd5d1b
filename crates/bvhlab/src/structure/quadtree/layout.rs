//! The 2^D tree's memory layout: 8-byte nodes, children stored consecutively, boxes derived
//! from the root box rather than stored.

use crate::structure::NodeId;
use crate::volume::Aabb;
use crate::{Primitive, Vector};

/// The deepest a tree may grow whatever the options say: 2^-40 of the root's side is far
/// below `f32` resolution, so no split that deep could separate anything.
pub const MAX_DEPTH: usize = 40;

/// Options of a quadtree/octree build. [`OrthtreeOptions::default`]: leaves of at most 8
/// primitives, depth at most 10 (1024 cells along each side of the root).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OrthtreeOptions {
    /// A cell holding more primitives than this is split into 2^D children (unless it is at
    /// `max_depth`, or splitting would only copy its primitives). At least 1.
    pub leaf_size: usize,
    /// Cells at this depth become leaves whatever they hold (the root is depth 0). Clamped
    /// to [`MAX_DEPTH`].
    pub max_depth: usize,
}

impl Default for OrthtreeOptions {
    fn default() -> Self {
        Self {
            leaf_size: 8,
            max_depth: 10,
        }
    }
}

/// Marks an inner node in [`Node::count`].
pub(super) const INNER: u32 = u32::MAX;

/// One cell of the tree, 8 bytes: `#[repr(C)] { first: u32, count: u32 }`.
///
/// A leaf has `count` primitive references at `refs[first..first + count]`; an inner node has
/// `count == INNER` and its 2^D children at `nodes[first..first + 2^D]`, child `k` being the
/// closed sub-box that takes the upper half of axis `i` when bit `i` of `k` is set.
/// Boxes are not stored: each is computed from its parent's by [`child_box_at`] during traversal,
/// the same computation the build did, so build and queries agree to the bit.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Node {
    pub first: u32,
    pub count: u32,
}

const _: () = assert!(size_of::<Node>() == 8);

impl Node {
    pub(super) fn is_leaf(self) -> bool {
        self.count != INNER
    }
}

/// A region quadtree (2D) or octree (3D) over primitives, one generic implementation with
/// 2^D children per cell (CGAL calls this family "orthtree").
///
/// The lecture's construction: a square (cube) root cell around the scene, split into four
/// (eight) equal children until each cell holds few primitives. Each primitive is listed in
/// every leaf it shares a point with, so a primitive crossing a split plane is duplicated,
/// and queries test it once (mailboxing). Build with [`Orthtree::build`] or
/// [`Orthtree::build_with`]; query through [`SpatialIndex`](crate::SpatialIndex).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "P: serde::Serialize, P::Point: serde::Serialize",
        deserialize = "P: serde::Deserialize<'de>, P::Point: serde::Deserialize<'de>"
    ))
)]
pub struct Orthtree<P: Primitive> {
    pub(super) prims: Vec<P>,
    /// The root cell: a cube (square) around the placeable primitives; empty when none.
    pub(super) root: Aabb<P::Point>,
    /// Root at 0; empty when no primitive could be placed.
    pub(super) nodes: Vec<Node>,
    /// The leaves' primitive lists, each ascending.
    pub(super) refs: Vec<u32>,
    pub(super) options: OrthtreeOptions,
}

/// One cell of an [`Orthtree`], as [`Orthtree::cells`] lists them for drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrthtreeCell<'a, V: Vector> {
    /// The node.
    pub node: NodeId,
    /// Its box.
    pub bounds: Aabb<V>,
    /// Its depth (the root is 0).
    pub depth: u32,
    /// Its primitives, for a leaf; `None` for an inner node.
    pub prims: Option<&'a [u32]>,
}

/// The number of children of a cell: 4 in 2D, 8 in 3D.
pub(super) const fn child_count<V: Vector>() -> usize {
    1 << V::DIM
}

/// The midpoint of `[lo, hi]`, rounded once from `f64` (no overflow near `f32::MAX`).
pub(super) fn midpoint(lo: f32, hi: f32) -> f32 {
    ((f64::from(lo) + f64::from(hi)) * 0.5) as f32
}

/// The centre of a cell, where its children meet: the split planes, one per axis.
pub(super) fn split_point<V: Vector>(cell: &Aabb<V>) -> V {
    let mut mid = cell.min;
    for i in 0..V::DIM {
        mid.set_coord(i, midpoint(cell.min.coord(i), cell.max.coord(i)));
    }
    mid
}

/// Child `k`'s box, given the parent's [`split_point`]: along axis `i`, the upper half of
/// `parent` when bit `i` of `k` is set.
pub(super) fn child_box_at<V: Vector>(parent: &Aabb<V>, mid: V, k: usize) -> Aabb<V> {
    let mut b = *parent;
    for i in 0..V::DIM {
        if k >> i & 1 == 1 {
            b.min.set_coord(i, mid.coord(i));
        } else {
            b.max.set_coord(i, mid.coord(i));
        }
    }
    b
}

impl<P: Primitive> Orthtree<P> {
    /// The root cell (empty when no primitive could be placed).
    pub fn root_box(&self) -> Aabb<P::Point> {
        self.root
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The options the tree was built with.
    pub fn options(&self) -> &OrthtreeOptions {
        &self.options
    }

    /// A node's children (2^D consecutive ids), or `None` for a leaf.
    pub fn children(&self, node: NodeId) -> Option<std::ops::Range<u32>> {
        let n = self.nodes[node.index()];
        (!n.is_leaf()).then(|| n.first..n.first + child_count::<P::Point>() as u32)
    }

    /// A leaf's primitives, ascending (empty for an inner node).
    pub fn leaf_primitives(&self, node: NodeId) -> &[u32] {
        let n = self.nodes[node.index()];
        if n.is_leaf() {
            &self.refs[n.first as usize..(n.first + n.count) as usize]
        } else {
            &[]
        }
    }

    /// Whether a node is a leaf that lists no primitive (queries do not queue those).
    pub(super) fn is_empty_leaf(&self, node: u32) -> bool {
        self.nodes[node as usize].count == 0
    }

    /// Every cell with its box, depth first from the root, children in order.
    pub fn cells(&self) -> Vec<OrthtreeCell<'_, P::Point>> {
        let mut cells = Vec::with_capacity(self.nodes.len());
        let mut stack = Vec::new();
        if !self.nodes.is_empty() {
            stack.push((0u32, self.root, 0u32));
        }
        while let Some((node, bounds, depth)) = stack.pop() {
            let id = NodeId(node);
            cells.push(OrthtreeCell {
                node: id,
                bounds,
                depth,
                prims: self.nodes[node as usize]
                    .is_leaf()
                    .then(|| self.leaf_primitives(id)),
            });
            if let Some(children) = self.children(id) {
                let mid = split_point(&bounds);
                for (k, child) in children.enumerate().rev() {
                    stack.push((child, child_box_at(&bounds, mid, k), depth + 1));
                }
            }
        }
        cells
    }

    /// Heap bytes: the primitives, the nodes and the lists.
    pub(super) fn memory_bytes(&self) -> usize {
        self.prims.len() * size_of::<P>()
            + self.nodes.len() * size_of::<Node>()
            + self.refs.len() * 4
    }
}
