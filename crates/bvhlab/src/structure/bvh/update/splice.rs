//! Surgery on the depth-first arrays: cut a subtree out, splice one in beside a node, grow
//! or shrink a leaf, and fit the volumes above the change again.
//!
//! The layout ([`Bvh`]'s): a node's first child is the next node, its second child's index
//! is stored (`start`), so a subtree is a contiguous run of nodes, and its primitives a
//! contiguous run of leaf slots. Every edit keeps that: it moves the runs after the edit
//! and renumbers the links that point past it. An index `v` of a node or slot that stays
//! becomes `v` minus the nodes (slots) removed before it, plus those inserted before it.

use std::ops::Range;

use crate::Primitive;
use crate::structure::bvh::layout::BvhNode;
use crate::structure::bvh::refit::bounds_of;
use crate::structure::bvh::{Bvh, NodeVolume};
use crate::vector::Vector;
use crate::volume::Aabb;

/// A subtree cut out of a tree: its nodes depth-first with links relative to its root
/// (node 0) and its first leaf slot (slot 0), and its leaf slots.
#[derive(Clone, Debug)]
pub(super) struct Subtree<V: Vector, P> {
    pub(super) nodes: Vec<BvhNode<Aabb<V>>>,
    pub(super) prims: Vec<P>,
    pub(super) ids: Vec<u32>,
}

impl<V: Vector, P> Subtree<V, P> {
    /// A leaf holding one primitive.
    pub(super) fn leaf(volume: Aabb<V>, prim: P, id: u32) -> Self {
        Self {
            nodes: vec![BvhNode {
                volume,
                start: 0,
                count: 1,
            }],
            prims: vec![prim],
            ids: vec![id],
        }
    }

    /// The root's volume.
    pub(super) fn volume(&self) -> Aabb<V> {
        self.nodes[0].volume
    }

    /// How many levels lie below the root (0 for a leaf).
    pub(super) fn height(&self) -> usize {
        run_height(&self.nodes, 0)
    }

    /// The root's two children as subtrees of their own (`None` for a leaf).
    pub(super) fn split(mut self) -> Option<(Self, Self)> {
        let root = self.nodes[0];
        if root.is_leaf() {
            return None;
        }
        let second = root.start as usize;
        let slot = leftmost_slot(&self.nodes, second);
        let mut right = Self {
            nodes: self.nodes.split_off(second),
            prims: self.prims.split_off(slot),
            ids: self.ids.split_off(slot),
        };
        self.nodes.remove(0);
        rebase(&mut self.nodes, 1, 0);
        rebase(&mut right.nodes, second, slot);
        Some((self, right))
    }
}

/// Subtracts `node_base` from the inner nodes' links and `slot_base` from the leaves'.
fn rebase<B>(nodes: &mut [BvhNode<B>], node_base: usize, slot_base: usize) {
    for node in nodes {
        let base = if node.is_leaf() { slot_base } else { node_base };
        node.start -= base as u32;
    }
}

/// The first leaf slot below `node`: follow first children down to a leaf.
fn leftmost_slot<B>(nodes: &[BvhNode<B>], mut node: usize) -> usize {
    while !nodes[node].is_leaf() {
        node += 1;
    }
    nodes[node].start as usize
}

/// The height of the subtree at `root` (0 for a leaf), from its run of nodes: one pass that
/// gives each node its depth below `root`.
fn run_height<B>(nodes: &[BvhNode<B>], root: usize) -> usize {
    let end = subtree_end(nodes, root);
    let mut depth = vec![0usize; end - root];
    let mut height = 0;
    for i in root..end {
        let d = depth[i - root];
        height = height.max(d);
        if !nodes[i].is_leaf() {
            depth[i + 1 - root] = d + 1;
            depth[nodes[i].start as usize - root] = d + 1;
        }
    }
    height
}

/// One past the last node of the subtree at `node`: follow second children down to a leaf.
pub(super) fn subtree_end<B>(nodes: &[BvhNode<B>], mut node: usize) -> usize {
    while !nodes[node].is_leaf() {
        node = nodes[node].start as usize;
    }
    node + 1
}

impl<V, P> Bvh<Aabb<V>, P>
where
    V: Vector,
    P: Primitive<Point = V>,
{
    /// The leaf slots of the subtree at `node`.
    pub(super) fn slot_span(&self, node: usize) -> Range<usize> {
        let last = subtree_end(&self.nodes, node) - 1;
        let end = self.nodes[last].leaf_range().end;
        leftmost_slot(&self.nodes, node)..end
    }

    /// The ancestors of `node`, root first: descend from the root towards it, going to the
    /// second child when `node` lies at or past it.
    pub(super) fn path_to(&self, node: usize) -> Vec<usize> {
        let mut path = Vec::new();
        let mut at = 0;
        while at != node {
            path.push(at);
            let second = self.nodes[at].start as usize;
            at = if node < second { at + 1 } else { second };
        }
        path
    }

    /// The leaf whose range holds `slot`, and its ancestors, root first.
    pub(super) fn leaf_of_slot(&self, slot: usize) -> (usize, Vec<usize>) {
        let mut path = Vec::new();
        let mut at = 0;
        while !self.nodes[at].is_leaf() {
            path.push(at);
            let second = self.nodes[at].start as usize;
            at = if slot < leftmost_slot(&self.nodes, second) {
                at + 1
            } else {
                second
            };
        }
        (at, path)
    }

    /// The height of the subtree at `node` (0 for a leaf).
    pub(super) fn height_of(&self, node: usize) -> usize {
        run_height(&self.nodes, node)
    }

    /// The leaf volume around `prims`, as the builds fit it.
    pub(super) fn leaf_volume(&self, prims: &[P]) -> Aabb<V> {
        <Aabb<V> as NodeVolume>::fit(&bounds_of(prims), &[], &self.options)
    }

    /// Fits the volumes on `path` (ancestors, root first) again, deepest first: each inner
    /// node to its two children ([`NodeVolume::enclose`], as [`Bvh::refit`] does).
    pub(super) fn refit_path(&mut self, path: &[usize]) {
        for &i in path.iter().rev() {
            let (first, second) = (i + 1, self.nodes[i].start as usize);
            self.nodes[i].volume = <Aabb<V> as NodeVolume>::enclose(
                &self.nodes[first].volume,
                &self.nodes[second].volume,
                &self.options,
            );
        }
    }

    /// Cuts out the subtree at `node` (not the root) together with its parent, whose other
    /// child takes the parent's place; fits the volumes above again.
    pub(super) fn detach(&mut self, node: usize) -> Subtree<V, P> {
        let mut path = self.path_to(node);
        let parent = path.pop().expect("the root is never detached");
        let end = subtree_end(&self.nodes, node);
        let slots = self.slot_span(node);
        // One move of the nodes after the cut: as the first child, the parent and the cut
        // run are next to each other; as the second, the sibling's run between them is
        // copied down over the parent.
        let nodes = if node == parent + 1 {
            self.nodes.drain(parent..end).skip(1).collect()
        } else {
            let cut = self.nodes[node..end].to_vec();
            let sibling = self.nodes[parent + 1..node].to_vec();
            self.nodes.splice(parent..end, sibling);
            cut
        };
        let mut cut = Subtree {
            nodes,
            prims: self.leaf_prims.drain(slots.clone()).collect(),
            ids: self.leaf_ids.drain(slots.clone()).collect(),
        };
        rebase(&mut cut.nodes, node, slots.start);
        // Links into the parent now reach the sibling, which took its index; past it one
        // node fewer, past the cut run the whole run fewer.
        let run = (end - node) as u32;
        let (parent, end) = (parent as u32, end as u32);
        let removed_slots = slots.len() as u32;
        for n in &mut self.nodes {
            if n.is_leaf() {
                if n.start >= slots.end as u32 {
                    n.start -= removed_slots;
                }
            } else {
                let v = n.start;
                n.start -= u32::from(v > parent) + if v >= end { run } else { 0 };
            }
        }
        self.refit_path(&path);
        cut
    }

    /// Splices `sub` in as the sibling of `node`: a new parent takes `node`'s index, with
    /// `node`'s subtree as its first child and `sub` as its second; fits the volumes above
    /// again. On an empty tree `sub` becomes the tree.
    pub(super) fn attach(&mut self, mut sub: Subtree<V, P>, node: usize) {
        if self.nodes.is_empty() {
            self.nodes = sub.nodes;
            self.leaf_prims = sub.prims;
            self.leaf_ids = sub.ids;
            return;
        }
        let path = self.path_to(node);
        let end = subtree_end(&self.nodes, node);
        let slot = self.slot_span(node).end;
        let run = sub.nodes.len() as u32;
        let added_slots = sub.ids.len() as u32;
        let (node32, end32) = (node as u32, end as u32);
        // Inside `node`'s subtree everything moves down one (the new parent comes first);
        // past it, also by the spliced run. Links to `node` itself now reach the new parent.
        for n in &mut self.nodes {
            if n.is_leaf() {
                if n.start >= slot as u32 {
                    n.start += added_slots;
                }
            } else if n.start >= end32 {
                n.start += 1 + run;
            } else if n.start > node32 {
                n.start += 1;
            }
        }
        for n in &mut sub.nodes {
            n.start += if n.is_leaf() { slot as u32 } else { end32 + 1 };
        }
        let parent = BvhNode {
            volume: <Aabb<V> as NodeVolume>::enclose(
                &self.nodes[node].volume,
                &sub.volume(),
                &self.options,
            ),
            start: end32 + 1,
            count: 0,
        };
        // One move of the nodes after `node`'s subtree: its run is copied one place down,
        // behind the new parent, and the spliced run follows it.
        let rewritten: Vec<_> = std::iter::once(parent)
            .chain(self.nodes[node..end].iter().copied())
            .chain(sub.nodes)
            .collect();
        self.nodes.splice(node..end, rewritten);
        self.leaf_prims.splice(slot..slot, sub.prims);
        self.leaf_ids.splice(slot..slot, sub.ids);
        self.refit_path(&path);
    }

    /// Adds a primitive to a leaf, at the end of its range; fits the leaf and the volumes
    /// above it again.
    pub(super) fn grow_leaf(&mut self, leaf: usize, prim: P, id: u32) {
        let path = self.path_to(leaf);
        let slot = self.nodes[leaf].leaf_range().end;
        for (i, n) in self.nodes.iter_mut().enumerate() {
            if n.is_leaf() && i != leaf && n.start as usize >= slot {
                n.start += 1;
            }
        }
        self.leaf_prims.insert(slot, prim);
        self.leaf_ids.insert(slot, id);
        self.nodes[leaf].count += 1;
        self.refit_leaf(leaf, &path);
    }

    /// Takes one slot out of a leaf that holds more than it; fits the leaf and the volumes
    /// above it (`path`) again.
    pub(super) fn shrink_leaf(&mut self, leaf: usize, path: &[usize], slot: usize) {
        debug_assert!(self.nodes[leaf].count > 1, "a leaf keeps a primitive");
        for n in &mut self.nodes {
            if n.is_leaf() && n.start as usize > slot {
                n.start -= 1;
            }
        }
        self.leaf_prims.remove(slot);
        self.leaf_ids.remove(slot);
        self.nodes[leaf].count -= 1;
        self.refit_leaf(leaf, path);
    }

    fn refit_leaf(&mut self, leaf: usize, path: &[usize]) {
        let volume = self.leaf_volume(&self.leaf_prims[self.nodes[leaf].leaf_range()]);
        self.nodes[leaf].volume = volume;
        self.refit_path(path);
    }
}
