//! The 2^D tree's invariants and numbers.

use super::build::{Split, child_mask};
use super::layout::{MAX_DEPTH, Orthtree, child_box_at, child_count, split_point};
use crate::structure::check_primitives_contract;
use crate::structure::stats::sah_cost_boxes;
use crate::structure::{NodeId, Stats, ValidationError, contract_rounding};
use crate::volume::Aabb;
use crate::{BoundingVolume, Primitive, Vector};

/// Up to this many (leaf, primitive) pairs, validation also tests every primitive against
/// every leaf, independently of the build's rule.
const EXHAUSTIVE_PAIRS: usize = 50_000;

fn fail(message: String) -> Result<(), ValidationError> {
    Err(ValidationError::new(message))
}

impl<P: Primitive> Orthtree<P> {
    /// Nodes, leaves (empty ones included: the histogram's bucket 0 counts them), depth,
    /// references (leaf entries),
    /// memory, and the SAH cost with the cells' boxes as node regions.
    pub(super) fn tree_stats(&self) -> Stats {
        let cells = self.cells();
        let leaves = cells.iter().filter_map(|c| c.prims.map(<[u32]>::len));
        Stats {
            nodes: cells.len(),
            leaves: leaves.clone().count(),
            max_depth: cells.iter().map(|c| c.depth as usize).max().unwrap_or(0),
            leaf_sizes: Stats::leaf_size_histogram(leaves),
            primitives: self.prims.len(),
            references: self.refs.len(),
            memory_bytes: self.memory_bytes(),
            sah_cost: sah_cost_boxes(cells.iter().map(|c| (c.bounds, c.prims.map(<[u32]>::len)))),
        }
    }

    /// Checks the topology (every node reached once from the root, children after their
    /// parent, within the depth limit), that each child's box lies in its parent's, that the
    /// leaves' lists partition the reference array, that no primitive with a non-finite
    /// coordinate is listed, and that every leaf lists exactly the primitives
    /// that share a point with it (descending from the root with the build's rule, and on
    /// moderate inputs also against every leaf independently).
    pub(super) fn check(&self) -> Result<(), ValidationError> {
        self.check_indices()?;
        check_primitives_contract(&self.prims)?;
        if let Some(&i) = self
            .refs
            .iter()
            .find(|&&i| !self.prims[i as usize].has_finite_coordinates())
        {
            return fail(format!(
                "primitive {i} has a NaN or infinite coordinate but is listed"
            ));
        }
        let placed: Vec<u32> = (0..self.prims.len() as u32)
            .filter(|&i| self.prims[i as usize].has_finite_coordinates())
            .collect();
        if self.nodes.is_empty() {
            return if placed.is_empty() && self.refs.is_empty() {
                Ok(())
            } else {
                fail("no nodes, but primitives to place".into())
            };
        }
        if placed.is_empty() || !(self.root.min.is_finite() && self.root.max.is_finite()) {
            return fail(format!(
                "{} nodes over {} placed primitives in the root cell {:?}",
                self.nodes.len(),
                placed.len(),
                self.root
            ));
        }
        for &i in &placed {
            let b = self.prims[i as usize].bounds();
            if !(self.root.contains(b.min) && self.root.contains(b.max)) {
                return fail(format!("primitive {i} sticks out of the root cell"));
            }
        }
        let mut reached = vec![false; self.nodes.len()];
        let mut ref_used = vec![false; self.refs.len()];
        let mut stack = vec![(0u32, self.root, 0usize, placed.clone())];
        while let Some((node, bounds, depth, expected)) = stack.pop() {
            if std::mem::replace(&mut reached[node as usize], true) {
                return fail(format!("node {node} is reached twice"));
            }
            if let Some(children) = self.children(NodeId(node)) {
                if children.start <= node || children.end as usize > self.nodes.len() {
                    return fail(format!("node {node}: children {children:?} out of order"));
                }
                if depth >= self.options.max_depth {
                    return fail(format!("node {node} is split below the depth limit"));
                }
                let split = Split::new(&bounds);
                let masks: Vec<u32> = expected
                    .iter()
                    .map(|&i| child_mask(&self.prims[i as usize], &split))
                    .collect();
                let mid = split_point(&bounds);
                for (k, child) in children.enumerate() {
                    let child_bounds = child_box_at(&bounds, mid, k);
                    if !(bounds.contains(child_bounds.min) && bounds.contains(child_bounds.max)) {
                        return fail(format!("child {child} is not inside node {node}"));
                    }
                    let mine = expected
                        .iter()
                        .zip(&masks)
                        .filter(|&(_, mask)| mask >> k & 1 == 1)
                        .map(|(&i, _)| i)
                        .collect();
                    stack.push((child, child_bounds, depth + 1, mine));
                }
                continue;
            }
            let n = self.nodes[node as usize];
            let range = n.first as usize..n.first as usize + n.count as usize;
            if range.end > self.refs.len() || ref_used[range.clone()].iter().any(|&u| u) {
                return fail(format!(
                    "leaf {node}: list {range:?} out of range or shared"
                ));
            }
            ref_used[range.clone()].fill(true);
            // By its box, not its exact test: the build (child_mask) may store a primitive
            // in a cell holding one of its vertices, which the primitive itself need not
            // touch (a ball's vertices are its box's corners); the list is then checked
            // against that rule below.
            if let Some(&i) = self.refs[range.clone()]
                .iter()
                .find(|&&i| !self.prims[i as usize].bounds().overlaps(&bounds))
            {
                return fail(format!(
                    "leaf {node} lists primitive {i}, whose box misses it"
                ));
            }
            if self.refs[range.clone()] != expected[..] {
                return fail(format!(
                    "leaf {node} lists {:?}, but these touch it: {expected:?}",
                    &self.refs[range]
                ));
            }
        }
        if let Some(node) = reached.iter().position(|&r| !r) {
            return fail(format!("node {node} is not reachable from the root"));
        }
        if ref_used.iter().any(|&u| !u) {
            return fail("a reference belongs to no leaf".into());
        }
        self.check_every_leaf(&placed)
    }

    /// What the walk below and every query take for granted, and a tree loaded from a file
    /// may break: the depth limit is [`MAX_DEPTH`] at most (the walks' stacks are sized by
    /// the depth), every reference
    /// names a primitive, and every inner node's children lie inside the node array.
    fn check_indices(&self) -> Result<(), ValidationError> {
        if self.options.max_depth > MAX_DEPTH {
            return fail(format!(
                "the depth limit {} is beyond {MAX_DEPTH}",
                self.options.max_depth
            ));
        }
        if let Some(&i) = self.refs.iter().find(|&&i| i as usize >= self.prims.len()) {
            return fail(format!(
                "a leaf lists primitive {i} of {}",
                self.prims.len()
            ));
        }
        let children = child_count::<P::Point>();
        for (node, n) in self.nodes.iter().enumerate() {
            if !n.is_leaf() && n.first as usize + children > self.nodes.len() {
                return fail(format!(
                    "node {node}: children from {} past the {} nodes",
                    n.first,
                    self.nodes.len()
                ));
            }
        }
        Ok(())
    }

    /// On moderate inputs: every primitive that shares a point with a leaf is listed there,
    /// beyond the rounding the primitive contract allows its own tests (a few units in the
    /// last place of its coordinates: a ball whose box ends just short of a cell may touch
    /// it by its exact test).
    fn check_every_leaf(&self, placed: &[u32]) -> Result<(), ValidationError> {
        let cells = self.cells();
        let leaves = cells.iter().filter(|c| c.prims.is_some()).count();
        if leaves.saturating_mul(placed.len()) > EXHAUSTIVE_PAIRS {
            return Ok(());
        }
        for cell in cells.iter().filter(|c| c.prims.is_some()) {
            let listed = cell.prims.unwrap_or_default();
            for &i in placed {
                let prim = &self.prims[i as usize];
                if within_rounding(&cell.bounds, prim).is_some_and(|b| prim.intersects_aabb(&b))
                    && listed.binary_search(&i).is_err()
                {
                    return fail(format!(
                        "primitive {i} touches leaf {} but is not listed",
                        cell.node.0
                    ));
                }
            }
        }
        Ok(())
    }
}

/// `cell` shrunk on every side by the rounding the primitive contract allows `prim`'s tests
/// ([`contract_rounding`]); `None` when nothing is left.
fn within_rounding<P: Primitive>(cell: &Aabb<P::Point>, prim: &P) -> Option<Aabb<P::Point>> {
    let rounding = contract_rounding(prim);
    let mut inner = *cell;
    for axis in 0..P::Point::DIM {
        let (lo, hi) = (
            cell.min.coord(axis) + rounding,
            cell.max.coord(axis) - rounding,
        );
        if lo > hi {
            return None;
        }
        inner.min.set_coord(axis, lo);
        inner.max.set_coord(axis, hi);
    }
    Some(inner)
}
