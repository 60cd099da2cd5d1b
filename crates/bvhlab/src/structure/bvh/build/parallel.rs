//! The one-go binned-SAH build of [`fast`](super::fast) on every core (the `parallel`
//! feature): the same tree, bit for bit, for [`Bvh::build_parallel`] and
//! [`Bvh4::build_parallel`](crate::structure::bvh::Bvh4::build_parallel).
//!
//! Once a node is split its two children are independent: each owns its own run of the
//! primitives, and what the serial build does inside one never reads the other. So above
//! [`SUBTREE`] primitives the two children are built with `rayon::join` (work stealing keeps
//! both cores busy however unevenly the SAH splits), each into a node vector of its own
//! whose indices count from its own root; below it a subtree is built by the serial loop.
//! The pieces are then copied into one vector in the serial build's depth-first order, their
//! child and leaf indices shifted by where they land, so every index is the serial build's.
//!
//! The nodes near the root read many primitives before there is a second subtree to hand
//! to the other core, so these steps run on every core too: computing the primitives'
//! boxes and centres (an order-keeping parallel map), the root's boxes (a reduction of
//! minima and maxima), the binning of every node of at least [`BINS_PARALLEL`] primitives
//! (per-thread bins, merged: see [`Binner`]'s `cheapest_parallel`) and the copies into leaf
//! order. What stays serial is each node's partition (its order of swaps is what fixes the
//! leaf order) and the final copy of the pieces.
//!
//! Every decision is taken from the same numbers as in the serial build: counts are sums of
//! integers, boxes are minima and maxima of finite numbers, which do not depend on the order
//! of merges (up to the sign of a zero, which no decision and no fitted box sees, as
//! `fast.rs` explains). The test `bvh_parallel_build.rs` compares the trees node for node.

use rayon::prelude::*;

use super::fast::{Boxes, Item, TreeParts, build_nodes, is_leaf_unbinned, split_node};
use super::fast_bins::Binner;
use crate::Primitive;
use crate::structure::bvh::layout::BvhNode;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::bvh::{Bvh, BvhOptions};

/// Nodes of at least this many primitives hand their second child to another thread; below
/// it a subtree is built by the serial loop (a few hundred microseconds of work, far more
/// than a `join` costs).
const SUBTREE: usize = 4096;

/// Nodes of at least this many primitives are binned on every core.
const BINS_PARALLEL: usize = 1 << 15;

/// The primitives each thread takes at a time in the parallel scans.
const CHUNK: usize = 1 << 13;

/// [`build_sah_boxes`](super::build_sah_boxes) on every core: the same tree.
pub(in crate::structure::bvh) fn build_sah_boxes_parallel<B, P>(
    prims: &[P],
    options: &BvhOptions,
) -> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    build_sah_box_parts_parallel(prims, options)
        .into_bvh(prims.par_iter().copied().collect(), options)
}

/// [`build_sah_box_parts`](super::build_sah_box_parts) on every core: the same parts.
pub(in crate::structure::bvh) fn build_sah_box_parts_parallel<B, P>(
    prims: &[P],
    options: &BvhOptions,
) -> TreeParts<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    debug_assert!(
        !B::NEEDS_VERTICES,
        "only volumes fitted to the bounds alone"
    );
    let mut items: Vec<Item> = prims
        .par_iter()
        .with_min_len(CHUNK)
        .enumerate()
        .filter_map(|(index, prim)| Item::indexed(index, prim))
        .collect();
    let mut nodes = Vec::new();
    if !items.is_empty() {
        let boxes = items
            .par_chunks(CHUNK)
            .map(Boxes::of)
            .reduce(|| Boxes::EMPTY, |a, b| a.merge(&b));
        let piece = build_piece::<B>(&mut items, boxes, 0, options);
        nodes = Vec::with_capacity(piece.len());
        piece.place(0, &mut nodes);
    }
    let leaf_prims = items
        .par_iter()
        .with_min_len(CHUNK)
        .map(|item| prims[item.index as usize])
        .collect();
    let leaf_ids = items
        .par_iter()
        .with_min_len(CHUNK)
        .map(|item| item.index)
        .collect();
    TreeParts {
        nodes,
        leaf_prims,
        leaf_ids,
    }
}

/// A built subtree, before it is copied into place.
enum Piece<B> {
    /// A subtree the serial loop built: node indices count from its root, leaf indices from
    /// its first primitive.
    Serial(Vec<BvhNode<B>>),
    /// A node split with its children built apart (`len`: nodes in the whole subtree).
    Split {
        node: BvhNode<B>,
        first: Box<Piece<B>>,
        second: Box<Piece<B>>,
        /// Primitives under the first child.
        first_prims: u32,
        len: usize,
    },
}

impl<B: NodeVolume> Piece<B> {
    fn len(&self) -> usize {
        match self {
            Self::Serial(nodes) => nodes.len(),
            Self::Split { len, .. } => *len,
        }
    }

    /// Appends the subtree to `nodes` where the serial build puts it (its root at the end
    /// of `nodes`), its leaves indexing primitives from `first_prim` on.
    fn place(self, first_prim: u32, nodes: &mut Vec<BvhNode<B>>) {
        let base = nodes.len() as u32;
        match self {
            Self::Serial(local) => nodes.extend(local.into_iter().map(|mut node| {
                // An inner node (count 0) names its second child; a leaf its first primitive.
                node.start += if node.count == 0 { base } else { first_prim };
                node
            })),
            Self::Split {
                mut node,
                first,
                second,
                first_prims,
                ..
            } => {
                node.start = base + 1 + first.len() as u32;
                node.count = 0;
                nodes.push(node);
                first.place(first_prim, nodes);
                second.place(first_prim + first_prims, nodes);
            }
        }
    }
}

/// Builds the subtree over `items` (with `boxes`, its root at `depth`): the serial loop
/// below [`SUBTREE`] primitives, otherwise its root here and its children at once.
fn build_piece<B: NodeVolume>(
    items: &mut [Item],
    boxes: Boxes,
    depth: usize,
    options: &BvhOptions,
) -> Piece<B> {
    let n = items.len();
    if n < SUBTREE {
        let mut nodes = Vec::with_capacity(2 * n);
        let mut binner = Binner::new(options);
        build_nodes(items, boxes, depth, &mut binner, options, &mut nodes);
        return Piece::Serial(nodes);
    }
    // The root as `make_node` makes it: a leaf until split.
    let node = BvhNode {
        volume: B::fit(&boxes.bounds.to_aabb(), &[], options),
        start: 0,
        count: n as u32,
    };
    let leaf = || Piece::Serial(vec![node]);
    if is_leaf_unbinned(n, depth, options) {
        return leaf();
    }
    let mut binner = Binner::new(options);
    let cheapest = if n >= BINS_PARALLEL {
        let chunk = (n / (2 * rayon::current_num_threads())).max(CHUNK);
        binner.cheapest_parallel::<B::Point>(&boxes.bounds, &boxes.centroids, items, chunk)
    } else {
        binner.cheapest::<B::Point>(&boxes.bounds, &boxes.centroids, items)
    };
    drop(binner);
    let leaf_cost = (n <= options.leaf_limit()).then(|| options.leaf_cost(n));
    let Some((split, left, right)) = split_node::<B::Point>(items, &boxes, cheapest, leaf_cost)
    else {
        return leaf();
    };
    let (first_items, second_items) = items.split_at_mut(split);
    let (first, second) = rayon::join(
        || build_piece::<B>(first_items, left, depth + 1, options),
        || build_piece::<B>(second_items, right, depth + 1, options),
    );
    Piece::Split {
        node,
        len: 1 + first.len() + second.len(),
        first: Box::new(first),
        second: Box::new(second),
        first_prims: split as u32,
    }
}
