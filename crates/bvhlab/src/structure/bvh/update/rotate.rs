//! Tree rotations after an insert: on the way back up, a node may swap one child with a
//! grandchild on the other side when that shrinks the inner node between them.
//!
//! The greedy insertion alone builds long chains from sorted input (each new primitive
//! lands beside the root, which grows a level per insert). `Box2D`'s dynamic tree fixes this
//! with rotations (Catto, "Dynamic Bounding Volume Hierarchies", GDC 2019, after Kopta et
//! al., "Fast, Effective BVH Updates for Animated Scenes", I3D 2012): at a node `A` with
//! children `B` and `C = (F, G)`, swapping `B` with `F` turns `C` into `B ∪ G`, and only
//! that node's area changes (the leaves are the same, and so is `A`'s box). Of the four
//! swaps (`B` with `F` or `G`, and `C` with `B`'s children), the one that lowers the area
//! most is made, if any does. Each rotation lowers the SAH cost.
//!
//! In the depth-first arrays a rotation rewrites `A`'s run of nodes and leaf slots in
//! place (the same nodes and slots, in a new order): O(size of `A`'s subtree), and nothing
//! outside it moves.

use super::splice::Subtree;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::NodeVolume;
use crate::structure::bvh::layout::BvhNode;
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// A rotation at a node: which child goes down (`low`), swapped with which grandchild
/// (`high`) under the other child (`other`'s remaining child is `stay`).
struct Rotation {
    low: usize,
    high: usize,
    stay: usize,
    gain: f32,
}

impl<V, P> Bvh<Aabb<V>, P>
where
    V: Vector,
    P: Primitive<Point = V>,
{
    /// Tries a rotation at each of `path` (root first, each the parent of the next),
    /// deepest first, keeping the tree within its depth limit.
    ///
    /// A rotation moves one subtree a level down, so it can deepen the tree by one. While
    /// the tree's height (measured once, when a rotation is first in view, then counted up
    /// by one per rotation) stays below the limit, every rotation is safe; only at the limit
    /// is the subtree's own height measured.
    pub(super) fn rotate_path(&mut self, path: &[usize]) {
        let mut height = None;
        for (depth, &node) in path.iter().enumerate().rev() {
            let Some(rotation) = self.best_rotation(node, depth, &mut height) else {
                continue;
            };
            self.rotate(node, &rotation);
            height = height.map(|h| h + 1);
        }
    }

    /// The swap at `node` (at `depth`) that lowers the area most, if one does and it keeps
    /// the tree within its depth limit; `height` is a bound on the tree's height, measured
    /// when first needed.
    fn best_rotation(
        &self,
        node: usize,
        depth: usize,
        height: &mut Option<usize>,
    ) -> Option<Rotation> {
        let area = |i: usize| self.nodes[i].volume.boundary_measure();
        let union = |i: usize, j: usize| {
            self.nodes[i]
                .volume
                .merge(&self.nodes[j].volume)
                .boundary_measure()
        };
        let (b, c) = (node + 1, self.nodes[node].start as usize);
        let mut best: Option<Rotation> = None;
        for (low, other) in [(b, c), (c, b)] {
            if self.nodes[other].is_leaf() {
                continue;
            }
            let (f, g) = (other + 1, self.nodes[other].start as usize);
            for (high, stay) in [(f, g), (g, f)] {
                let gain = area(other) - union(low, stay);
                if gain > 0.0 && best.as_ref().is_none_or(|r| gain > r.gain) {
                    best = Some(Rotation {
                        low,
                        high,
                        stay,
                        gain,
                    });
                }
            }
        }
        let best = best?;
        let limit = self.options.depth_limit();
        let tree_height = *height.get_or_insert_with(|| self.heights()[0]);
        // `low` goes one level down: its deepest node ends at `depth + 2 + height(low)`,
        // which is at most one more than the tree's height.
        (tree_height < limit || depth + 2 + self.height_of(best.low) <= limit).then_some(best)
    }

    /// Makes `node` the parent of `high` and of a new inner node over `low` and `stay`,
    /// rewriting `node`'s run in place.
    fn rotate(&mut self, node: usize, r: &Rotation) {
        let joined = self.join(self.copy_subtree(r.low), self.copy_subtree(r.stay));
        let whole = self.join(self.copy_subtree(r.high), joined);
        let slots = self.slot_span(node);
        debug_assert_eq!(whole.ids.len(), slots.len(), "a rotation keeps the slots");
        for (i, mut n) in whole.nodes.into_iter().enumerate() {
            n.start += if n.is_leaf() { slots.start } else { node } as u32;
            self.nodes[node + i] = n;
        }
        self.leaf_prims[slots.clone()].copy_from_slice(&whole.prims);
        self.leaf_ids[slots].copy_from_slice(&whole.ids);
    }

    /// A copy of the subtree at `node`, its links relative to it.
    fn copy_subtree(&self, node: usize) -> Subtree<V, P> {
        let end = super::splice::subtree_end(&self.nodes, node);
        let slots = self.slot_span(node);
        let mut nodes = self.nodes[node..end].to_vec();
        for n in &mut nodes {
            n.start -= if n.is_leaf() { slots.start } else { node } as u32;
        }
        Subtree {
            nodes,
            prims: self.leaf_prims[slots.clone()].to_vec(),
            ids: self.leaf_ids[slots].to_vec(),
        }
    }

    /// A subtree with a new root over `first` and `second`, depth-first.
    fn join(&self, first: Subtree<V, P>, second: Subtree<V, P>) -> Subtree<V, P> {
        let volume = Aabb::enclose(&first.volume(), &second.volume(), &self.options);
        let (first_nodes, first_slots) = (first.nodes.len() as u32, first.ids.len() as u32);
        let mut nodes = Vec::with_capacity(1 + first.nodes.len() + second.nodes.len());
        nodes.push(BvhNode {
            volume,
            start: 1 + first_nodes,
            count: 0,
        });
        nodes.extend(first.nodes.into_iter().map(|mut n| {
            n.start += u32::from(!n.is_leaf());
            n
        }));
        nodes.extend(second.nodes.into_iter().map(|mut n| {
            n.start += if n.is_leaf() {
                first_slots
            } else {
                1 + first_nodes
            };
            n
        }));
        let mut prims = first.prims;
        prims.extend(second.prims);
        let mut ids = first.ids;
        ids.extend(second.ids);
        Subtree { nodes, prims, ids }
    }
}
