//! Building a BSP tree: recursive autopartition, top down.
//!
//! Each node takes the box of its primitives, asks the [`splitter`](super::splitter) for a
//! plane, sends every primitive to each side it reaches (a straddler goes to both, by
//! reference: primitives are never clipped) and recurses. A node becomes a leaf when it holds
//! at most `leaf_size` primitives, reaches `max_depth`, when no plane separates its primitives
//! (identical or inseparable primitives), or when every plane tried would exceed the node's
//! share of the reference budget ([`REFERENCE_BUDGET`] references per primitive, shared out
//! among children in proportion to their sizes), so that a scene whose every plane cuts many
//! primitives cannot blow up.

use super::layout::BspNode;
use super::splitter::{SplitMix64, choose_split};
use super::{BspOptions, BspTree};
use crate::Primitive;
use crate::structure::plane_tree::{REFERENCE_BUDGET, share_budget};
use crate::structure::{Event, NodeId, Observer};
use crate::volume::{Aabb, BoundingVolume};

/// The deepest a tree may grow, whatever the options say (the recursion depth).
pub const DEPTH_LIMIT: usize = 64;

struct Builder<'a, P: Primitive, O> {
    prims: &'a [P],
    options: &'a BspOptions,
    max_depth: usize,
    rng: SplitMix64,
    nodes: Vec<BspNode<P::Point>>,
    indices: Vec<u32>,
    observer: &'a mut O,
}

/// The default depth limit: twice the depth of a balanced tree, plus slack for the
/// imbalance that random splitters bring.
pub(crate) fn default_max_depth(n: usize) -> usize {
    let log2 = usize::BITS - n.max(1).leading_zeros();
    (2 * log2 as usize + 8).min(DEPTH_LIMIT)
}

/// Builds the tree; primitives with a non-finite coordinate are left out.
pub(crate) fn build<P: Primitive, O: Observer<P::Point>>(
    prims: &[P],
    options: &BspOptions,
    observer: &mut O,
) -> BspTree<P> {
    let refs: Vec<u32> = (0..prims.len() as u32)
        .filter(|&i| prims[i as usize].has_finite_coordinates())
        .collect();
    let mut builder = Builder {
        prims,
        options,
        max_depth: options
            .max_depth
            .unwrap_or_else(|| default_max_depth(refs.len()))
            .min(DEPTH_LIMIT),
        rng: SplitMix64::new(options.seed),
        nodes: Vec::new(),
        indices: Vec::new(),
        observer,
    };
    if !refs.is_empty() {
        let budget = REFERENCE_BUDGET * refs.len();
        builder.node(refs, 0, None, budget);
    }
    BspTree {
        prims: prims.to_vec(),
        nodes: builder.nodes,
        indices: builder.indices,
        options: options.clone(),
    }
}

impl<P: Primitive, O: Observer<P::Point>> Builder<'_, P, O> {
    /// Builds the subtree over `refs` and returns its root.
    fn node(&mut self, refs: Vec<u32>, depth: usize, parent: Option<NodeId>, budget: usize) -> u32 {
        let id = self.nodes.len() as u32;
        self.observer.on(Event::BuildNode {
            node: NodeId(id),
            parent,
            depth: depth as u32,
            prims: refs.len() as u32,
        });
        let bounds = bounds_of(self.prims, &refs);
        let split = if refs.len() <= self.options.leaf_size.max(1) || depth >= self.max_depth {
            None
        } else {
            choose_split(
                self.prims,
                &refs,
                self.options.candidates,
                self.options.straddle_weight,
                self.options.median_candidate,
                budget,
                &mut self.rng,
            )
        };
        let Some(split) = split else {
            return self.leaf(id, bounds, refs);
        };
        self.nodes.push(BspNode::inner(
            bounds,
            split.plane.normal,
            split.plane.offset,
        ));
        self.observer.on(Event::BuildSplit {
            node: NodeId(id),
            normal: split.plane.normal,
            offset: split.plane.offset,
            left: split.below.len() as u32,
            right: split.above.len() as u32,
            cost: None,
        });
        let budgets = share_budget(budget, [split.below.len(), split.above.len()])
            .expect("choose_split keeps to the budget");
        drop(refs);
        self.node(split.below, depth + 1, Some(NodeId(id)), budgets[0]);
        let above = self.nodes.len() as u32;
        self.nodes[id as usize].set_above(above);
        self.node(split.above, depth + 1, Some(NodeId(id)), budgets[1]);
        id
    }

    fn leaf(&mut self, id: u32, bounds: Aabb<P::Point>, mut refs: Vec<u32>) -> u32 {
        refs.sort_unstable();
        self.observer.on(Event::BuildLeaf {
            node: NodeId(id),
            prims: refs.len() as u32,
        });
        self.nodes.push(BspNode::leaf(
            bounds,
            self.indices.len() as u32,
            refs.len() as u32,
        ));
        self.indices.extend(refs);
        id
    }
}

/// The box around the primitives in `refs`.
pub(crate) fn bounds_of<P: Primitive>(prims: &[P], refs: &[u32]) -> Aabb<P::Point> {
    refs.iter().fold(Aabb::EMPTY, |b: Aabb<P::Point>, &r| {
        b.merge(&prims[r as usize].bounds())
    })
}
