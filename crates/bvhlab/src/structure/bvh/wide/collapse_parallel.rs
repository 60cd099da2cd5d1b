//! The collapse of `layout.rs` on every core (the `parallel` feature), for
//! [`Bvh4::build_parallel`](super::Bvh4::build_parallel): the same wide nodes at the same
//! indices.
//!
//! The serial collapse makes the root, gives a node's inner lanes consecutive indices when
//! it makes the node, and then makes the lanes' subtrees from the last lane to the first (a
//! stack). So the subtree under a node is laid out as: the node, its inner lanes' nodes in
//! lane order, then the rest of the last lane's subtree, ..., the rest of the first lane's.
//! Each lane's subtree depends only on the binary nodes below it: above [`SUBTREE`] binary
//! nodes the lanes are collapsed at once, each into a vector of its own (its root at 0, the
//! rest after it, in the serial order); [`Piece::emit`] then copies them into that layout,
//! shifting their child indices by where they land.

use rayon::prelude::*;

use super::layout::{Bvh4Node, Lanes, WIDTH, collapse, collapse_from, lanes_of};
use crate::Vector;
use crate::structure::bvh::layout::BvhNode;
use crate::volume::Aabb;

/// Wide subtrees over fewer binary nodes than this are collapsed by the serial loop.
const SUBTREE: usize = 1 << 13;

/// [`collapse`] on every core: the same wide nodes and depth.
pub(super) fn collapse_parallel<V: Vector>(binary: &[BvhNode<Aabb<V>>]) -> (Vec<Bvh4Node>, usize) {
    if binary.len() < SUBTREE || binary[0].is_leaf() {
        return collapse(binary);
    }
    let piece = piece(binary, lanes_of(binary, 0), binary.len());
    let mut nodes = Vec::with_capacity(piece.len());
    nodes.push(Bvh4Node::EMPTY);
    let depth = piece.depth();
    piece.emit(0, &mut nodes);
    (nodes, depth)
}

/// A collapsed wide subtree, before it is copied into place.
enum Piece {
    /// Collapsed by the serial loop: its root at 0, child indices counted from it.
    Serial(Vec<Bvh4Node>, usize),
    /// A root whose inner lanes (`lane`, subtree) were collapsed apart; the root's inner
    /// lanes' child indices are set when it is placed.
    Split {
        root: Bvh4Node,
        lanes: Vec<(usize, Piece)>,
        len: usize,
        depth: usize,
    },
}

impl Piece {
    fn len(&self) -> usize {
        match self {
            Self::Serial(nodes, _) => nodes.len(),
            Self::Split { len, .. } => *len,
        }
    }

    fn depth(&self) -> usize {
        match self {
            Self::Serial(_, depth) | Self::Split { depth, .. } => *depth,
        }
    }

    /// Writes the subtree's root at `at` (already reserved) and appends the rest of it to
    /// `nodes`, as the serial collapse lays it out.
    fn emit(self, at: usize, nodes: &mut Vec<Bvh4Node>) {
        match self {
            Self::Serial(local, _) => {
                // Local index 0 is the root at `at`; the others follow the end of `nodes`.
                let base = nodes.len() as u32 - 1;
                let shift = |mut node: Bvh4Node| {
                    for lane in 0..WIDTH {
                        if node.count[lane] == 0 && node.is_used(lane) {
                            node.child[lane] += base;
                        }
                    }
                    node
                };
                let mut local = local.into_iter();
                if let Some(root) = local.next() {
                    nodes[at] = shift(root);
                }
                nodes.extend(local.map(shift));
            }
            Self::Split {
                mut root, lanes, ..
            } => {
                let first = nodes.len();
                for (k, &(lane, _)) in lanes.iter().enumerate() {
                    root.child[lane] = (first + k) as u32;
                    nodes.push(Bvh4Node::EMPTY);
                }
                nodes[at] = root;
                for (k, (_, lane)) in lanes.into_iter().enumerate().rev() {
                    lane.emit(first + k, nodes);
                }
            }
        }
    }
}

/// Collapses the wide subtree whose root has the binary nodes `root_lanes` as lanes, over
/// about `size` binary nodes (the lanes' ids and the size bound where each lane's binary
/// subtree ends, give or take the few inner nodes the lanes replaced).
fn piece<V: Vector>(binary: &[BvhNode<Aabb<V>>], root_lanes: Lanes, size: usize) -> Piece {
    if size < SUBTREE {
        let (nodes, depth) = collapse_from(binary, root_lanes, size);
        return Piece::Serial(nodes, depth);
    }
    let start = root_lanes[0] as usize;
    let end = start + size;
    let mut root = Bvh4Node::EMPTY;
    let mut inner = Vec::new();
    for (lane, &id) in root_lanes.iter().enumerate() {
        let b = &binary[id as usize];
        root.set_lane(lane, &b.volume);
        if b.is_leaf() {
            (root.child[lane], root.count[lane]) = (b.start, b.count);
        } else {
            let next = root_lanes.get(lane + 1).map_or(end, |&next| next as usize);
            inner.push((lane, id, next - id as usize));
        }
    }
    let lanes: Vec<(usize, Piece)> = inner
        .into_par_iter()
        .map(|(lane, id, size)| (lane, piece(binary, lanes_of(binary, id), size)))
        .collect();
    let depth = 1 + lanes.iter().map(|(_, p)| p.depth()).max().unwrap_or(0);
    Piece::Split {
        root,
        len: 1 + lanes.iter().map(|(_, p)| p.len()).sum::<usize>(),
        lanes,
        depth,
    }
}
