//! Inserting and removing primitives in a [`Bvh4`] without a rebuild.
//!
//! An insert walks down from the root, each time into the lane whose box grows least (by
//! surface area, as Goldsmith and Salmon 1987 place a new object), and puts the primitive in
//! the first free lane it meets; where every lane is taken it turns the chosen leaf lane into
//! a new node holding the old leaf and the new one. The primitive is appended to the leaf
//! order, so no leaf moves: O(depth).
//!
//! A remove takes the primitive out of its leaf lane, drops lanes and nodes left empty, and
//! lays the leaf order and the nodes out again (children after parents, every slot in one
//! lane) with every box fitted again bottom-up: O(n), as a refit is. [`Bvh4::needs_rebuild`]
//! tells when the updates have worn the tree enough that a rebuild pays.

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::leaves::PADDING;
use super::refit::node_box;
use crate::Primitive;
use crate::structure::bvh::MAX_DEPTH;
use crate::structure::update::{Removed, UpdateError, check_index};
use crate::volume::{Aabb, BoundingVolume};

impl<P: Primitive> Bvh4<P> {
    /// Adds a primitive and returns its index: the number of primitives the tree was built
    /// over and given since (indexed or left out); no other index changes. Every query then
    /// answers as brute force on the primitives held, and [`validate`](Self::validate)
    /// holds.
    ///
    /// A primitive with a NaN or infinite coordinate is kept aside, not indexed, as the
    /// builds leave it out.
    ///
    /// ```
    /// use bvhlab::glam::Vec3;
    /// use bvhlab::prelude::*;
    ///
    /// let floor = Triangle3::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
    /// let mut tree = Bvh4::build(&[floor]);
    /// let roof = Triangle3::new(Vec3::Z, Vec3::Z + Vec3::X * 4.0, Vec3::Z + Vec3::Y * 4.0);
    /// assert_eq!(tree.insert(roof), 1);
    /// tree.validate()?;
    /// let down = Ray3::new(Vec3::new(1.0, 1.0, 3.0), -Vec3::Z)?;
    /// assert_eq!(tree.ray_first_hit(&down, f32::INFINITY).map(|h| h.prim), Some(1));
    /// assert_eq!(tree.remove(1)?.prim, roof);
    /// assert_eq!(tree.ray_first_hit(&down, f32::INFINITY).map(|h| h.prim), Some(0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn insert(&mut self, prim: P) -> usize {
        let id = self.input_len;
        self.input_len += 1;
        if !prim.has_finite_coordinates() {
            self.left_out.push((id as u32, prim));
            return id;
        }
        let slot = self
            .leaf_prims
            .push_leaf(&prim, id as u32, &mut self.leaf_ids);
        let bounds = self.leaf_box(slot as usize, 1);
        if self.nodes.is_empty() {
            let mut root = Bvh4Node::EMPTY;
            set_leaf(&mut root, 0, slot, 1, &bounds);
            self.nodes.push(root);
            self.depth = 1;
            return id;
        }
        let (mut at, mut level) = (0, 1);
        loop {
            let node = self.nodes[at];
            if let Some(free) = (0..WIDTH).find(|&lane| !node.is_used(lane)) {
                set_leaf(&mut self.nodes[at], free, slot, 1, &bounds);
                return id;
            }
            let lane = least_growth::<P>(&node, &bounds);
            let grown = node.lane_box::<P::Point>(lane).merge(&bounds);
            self.nodes[at].set_lane(lane, &grown);
            if node.count[lane] == 0 {
                at = node.child[lane] as usize;
                level += 1;
                continue;
            }
            if level >= MAX_DEPTH {
                // No level left for a new node (sorted input can dig this deep): lay the
                // tree out afresh, the primitive a leaf lane of its own.
                self.rebuild();
                return id;
            }
            // A leaf lane in a full node: it becomes a node of the old leaf and the new one.
            let mut split = Bvh4Node::EMPTY;
            let old_box = node.lane_box::<P::Point>(lane);
            set_leaf(&mut split, 0, node.child[lane], node.count[lane], &old_box);
            set_leaf(&mut split, 1, slot, 1, &bounds);
            let index = self.nodes.len() as u32;
            self.nodes.push(split);
            self.nodes[at].child[lane] = index;
            self.nodes[at].count[lane] = 0;
            self.depth = self.depth.max(level + 1);
            return id;
        }
    }

    /// Removes primitive `index` and returns it. The last primitive takes its index (a
    /// swap-remove, as [`AabbTree::remove`](crate::structure::bvh::AabbTree) does):
    /// [`Removed::moved_from`] says which one moved, and no other index changes. A
    /// primitive left out for a non-finite coordinate is given back too.
    ///
    /// # Errors
    /// [`UpdateError::NoSuchPrimitive`] when `index` is out of range; the tree is unchanged.
    pub fn remove(&mut self, index: usize) -> Result<Removed<P>, UpdateError> {
        check_index(index, self.input_len)?;
        let id = index as u32;
        let prim = if let Some(at) = self.left_out.iter().position(|&(i, _)| i == id) {
            self.left_out.swap_remove(at).1
        } else {
            // Every index in range is indexed or left out in a valid tree; one that is
            // neither (a hand-made tree) is said to be missing, not a panic.
            let slot = self.leaf_ids.iter().position(|&i| i == id).ok_or(
                UpdateError::NoSuchPrimitive {
                    index,
                    len: self.input_len,
                },
            )?;
            let prim = self.leaf_prims.get(slot);
            self.take_out(slot as u32);
            prim
        };
        let last = (self.input_len - 1) as u32;
        self.input_len -= 1;
        if id == last {
            return Ok(Removed {
                prim,
                moved_from: None,
            });
        }
        let renamed = self
            .leaf_ids
            .iter_mut()
            .chain(self.left_out.iter_mut().map(|(i, _)| i))
            .find(|i| **i == last);
        if let Some(moved) = renamed {
            *moved = id;
        }
        Ok(Removed {
            prim,
            moved_from: Some(last as usize),
        })
    }

    /// Takes leaf slot `slot` out of the lane that holds it, then lays the tree out again.
    ///
    /// The leaves are taken out one primitive per slot ([`Bvh4::take_leaves`]); the slot
    /// moves to its lane's end, which leaves the leaf order (the slots after it move down
    /// one, and the leaf lanes past it with them), and the leaves go back (triangles in
    /// blocks again); the lane's box and those of its ancestors are fitted again. A lane
    /// left empty is dropped; a node left with no lane at all is pruned by laying the whole
    /// tree out again ([`Bvh4::lay_out`]).
    fn take_out(&mut self, slot: u32) {
        let Some((at, lane)) = self.leaf_lane_of(slot) else {
            return;
        };
        let offset = slot - self.nodes[at].child[lane];
        let (mut prims, mut ids) = self.take_leaves();
        let node = &mut self.nodes[at];
        let (slot, end) = (
            node.child[lane] + offset,
            node.child[lane] + node.count[lane] - 1,
        );
        prims.swap(slot as usize, end as usize);
        ids.swap(slot as usize, end as usize);
        node.count[lane] -= 1;
        let emptied = node.count[lane] == 0;
        if emptied {
            clear_lane(node, lane);
            if !(0..WIDTH).any(|l| node.is_used(l)) {
                self.lay_out(&prims, &ids);
                return;
            }
        }
        prims.remove(end as usize);
        ids.remove(end as usize);
        for node in &mut self.nodes {
            for lane in 0..WIDTH {
                if node.count[lane] > 0 && node.child[lane] > end {
                    node.child[lane] -= 1;
                }
            }
        }
        self.put_leaves(prims, ids);
        if emptied {
            self.fit_ancestors(at);
        } else {
            self.fit_path(at, lane);
        }
    }

    /// The node and lane whose leaf range holds `slot`.
    fn leaf_lane_of(&self, slot: u32) -> Option<(usize, usize)> {
        self.nodes.iter().enumerate().find_map(|(at, node)| {
            (0..WIDTH)
                .find(|&lane| {
                    let (start, count) = (node.child[lane], node.count[lane]);
                    count > 0 && (start..start + count).contains(&slot)
                })
                .map(|lane| (at, lane))
        })
    }

    /// Fits leaf lane `lane` of node `at` to its primitives again, then each ancestor's lane
    /// to its child node, up to the root.
    fn fit_path(&mut self, at: usize, lane: usize) {
        let (start, count) = (self.nodes[at].child[lane], self.nodes[at].count[lane]);
        let fitted = self.leaf_box(start as usize, count as usize);
        self.nodes[at].set_lane(lane, &fitted);
        self.fit_ancestors(at);
    }

    /// Fits each ancestor's lane of node `at` to its child node again, up to the root.
    fn fit_ancestors(&mut self, at: usize) {
        let mut child = at;
        while child != 0 {
            // Parents come before their children: the one lane that points to `child`.
            let parent = self.nodes[..child].iter().enumerate().find_map(|(i, n)| {
                (0..WIDTH)
                    .find(|&l| n.count[l] == 0 && n.is_used(l) && n.child[l] as usize == child)
                    .map(|l| (i, l))
            });
            let Some((i, l)) = parent else { return };
            let fitted = node_box::<P>(&self.nodes[child]);
            self.nodes[i].set_lane(l, &fitted);
            child = i;
        }
    }

    /// Lays the tree out again from the root, over the leaves `old_prims` and `old_ids`
    /// taken out by [`Bvh4::take_leaves`]: empty nodes and the lanes that lead to them
    /// dropped, nodes numbered in the order a walk from the root meets them (children after
    /// parents), the leaf order rewritten lane by lane (dropped slots gone), every box fitted
    /// again bottom-up, and the depth counted.
    fn lay_out(&mut self, old_prims: &[P], old_ids: &[u32]) {
        let (mut prims, mut ids) = (Vec::new(), Vec::new());
        let mut nodes = Vec::with_capacity(self.nodes.len());
        let mut depth = 0;
        // (old index, new index, level); the root first, if it holds anything.
        let mut queue = std::collections::VecDeque::new();
        if self.prune(0) {
            queue.push_back((0usize, 0usize, 1usize));
            nodes.push(Bvh4Node::EMPTY);
        }
        while let Some((old, new, level)) = queue.pop_front() {
            depth = depth.max(level);
            let mut node = self.nodes[old];
            for lane in 0..WIDTH {
                if !node.is_used(lane) {
                    continue;
                }
                if node.count[lane] > 0 {
                    let (start, count) = (node.child[lane] as usize, node.count[lane] as usize);
                    node.child[lane] = prims.len() as u32;
                    prims.extend_from_slice(&old_prims[start..start + count]);
                    ids.extend_from_slice(&old_ids[start..start + count]);
                } else {
                    let child = nodes.len();
                    nodes.push(Bvh4Node::EMPTY);
                    queue.push_back((node.child[lane] as usize, child, level + 1));
                    node.child[lane] = child as u32;
                }
            }
            nodes[new] = node;
        }
        self.nodes = nodes;
        self.depth = depth;
        self.put_leaves(prims, ids);
        self.fit_boxes();
    }

    /// Drops the lanes below node `at` that lead to nodes with nothing in them; whether
    /// anything is left in it.
    fn prune(&mut self, at: usize) -> bool {
        if at >= self.nodes.len() {
            return false;
        }
        for lane in 0..WIDTH {
            let node = self.nodes[at];
            if node.count[lane] == 0 && node.is_used(lane) && !self.prune(node.child[lane] as usize)
            {
                clear_lane(&mut self.nodes[at], lane);
            }
        }
        (0..WIDTH).any(|lane| self.nodes[at].is_used(lane))
    }

    /// Fits every lane's box again, children before parents.
    fn fit_boxes(&mut self) {
        for i in (0..self.nodes.len()).rev() {
            let mut node = self.nodes[i];
            let used: Vec<usize> = (0..WIDTH).filter(|&lane| node.is_used(lane)).collect();
            for lane in used {
                if node.count[lane] > 0 {
                    let (start, count) = (node.child[lane], node.count[lane]);
                    node.set_lane(lane, &self.leaf_box(start as usize, count as usize));
                } else {
                    let child = &self.nodes[node.child[lane] as usize];
                    node.set_lane(lane, &node_box::<P>(child));
                }
            }
            self.nodes[i] = node;
        }
    }

    /// Builds the tree again over the primitives it holds, keeping their indices.
    fn rebuild(&mut self) {
        let mut held: Vec<(u32, P)> = self
            .indexed_slots()
            .map(|(slot, id)| (id, self.leaf_prims.get(slot)))
            .collect();
        held.sort_unstable_by_key(|&(id, _)| id);
        let prims: Vec<P> = held.iter().map(|&(_, p)| p).collect();
        let mut fresh = Self::build(&prims);
        for id in &mut fresh.leaf_ids {
            if *id != PADDING {
                *id = held[*id as usize].0;
            }
        }
        fresh.input_len = self.input_len;
        fresh.left_out = std::mem::take(&mut self.left_out);
        *self = fresh;
    }
}

/// Makes `lane` of `node` a leaf of `count` slots from `start`, in `bounds`.
fn set_leaf<V: crate::Vector>(
    node: &mut Bvh4Node,
    lane: usize,
    start: u32,
    count: u32,
    bounds: &Aabb<V>,
) {
    node.child[lane] = start;
    node.count[lane] = count;
    node.set_lane(lane, bounds);
}

/// Makes `lane` of `node` unused.
fn clear_lane(node: &mut Bvh4Node, lane: usize) {
    for side in 0..2 {
        for axis in 0..3 {
            node.planes[side][axis][lane] = Bvh4Node::EMPTY.planes[side][axis][lane];
        }
    }
    node.child[lane] = 0;
    node.count[lane] = 0;
}

/// The used lane of a full `node` whose box grows least (in surface area, then in
/// volume) to take in `bounds`.
fn least_growth<P: Primitive>(node: &Bvh4Node, bounds: &Aabb<P::Point>) -> usize {
    let growth = |lane: usize| {
        let b = node.lane_box::<P::Point>(lane);
        let grown = b.merge(bounds);
        (
            grown.boundary_measure() - b.boundary_measure(),
            grown.measure() - b.measure(),
        )
    };
    (0..WIDTH)
        .min_by(|&a, &b| {
            let (ga, gb) = (growth(a), growth(b));
            ga.0.total_cmp(&gb.0).then(ga.1.total_cmp(&gb.1))
        })
        .unwrap_or(0)
}
