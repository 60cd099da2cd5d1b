//! Well-formedness: topology, primitive bookkeeping, and every volume around its primitives
//! (parry's `bvh_validation.rs` checks the same for its trees).

use super::volume::NodeVolume;
use super::{Bvh, MAX_DEPTH};
use crate::Primitive;
use crate::structure::ValidationError;
use crate::structure::check_primitive_contract;

fn fail<T>(message: String) -> Result<T, ValidationError> {
    Err(ValidationError::new(message))
}

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Checks, in this order: the leaf-order primitives are copies of distinct input
    /// primitives, and exactly the indexable ones (all vertices finite), each keeping the
    /// [`Primitive`] contract's enclosure ([`check_enclosed_by_vertices`]); every node is
    /// reached once from the root by child links that point forward, inner nodes have two
    /// children, the tree is at most [`MAX_DEPTH`] deep; the leaves' ranges cover leaf order
    /// exactly once and each subtree's primitives are contiguous (counts add up); every node's
    /// volume contains every primitive below it (its box, for an AABB tree; its vertices for
    /// spheres and OBBs) and, for an AABB tree, every child's box lies in its parent's.
    pub(super) fn validate_impl(&self) -> Result<(), ValidationError> {
        self.validate_primitives()?;
        let ranges = self.validate_topology()?;
        self.validate_volumes(&ranges)
    }

    fn validate_primitives(&self) -> Result<(), ValidationError> {
        if self.leaf_ids.len() != self.leaf_prims.len() {
            return fail(format!(
                "{} leaf ids for {} leaf primitives",
                self.leaf_ids.len(),
                self.leaf_prims.len()
            ));
        }
        let mut seen = vec![false; self.prims.len()];
        for (slot, (&id, prim)) in self.leaf_ids.iter().zip(&self.leaf_prims).enumerate() {
            let Some(flag) = seen.get_mut(id as usize) else {
                return fail(format!(
                    "leaf slot {slot} names primitive {id}, out of range"
                ));
            };
            if std::mem::replace(flag, true) {
                return fail(format!("primitive {id} is in more than one leaf slot"));
            }
            if self.prims[id as usize] != *prim {
                return fail(format!("leaf slot {slot} is not a copy of primitive {id}"));
            }
        }
        for (i, prim) in self.prims.iter().enumerate() {
            check_primitive_contract(i, prim)?;
            if seen[i] != prim.has_finite_coordinates() {
                let what = if seen[i] {
                    "non-finite but indexed"
                } else {
                    "finite but not in any leaf"
                };
                return fail(format!("primitive {i} is {what}"));
            }
        }
        if self.nodes.is_empty() != self.leaf_ids.is_empty() {
            return fail(format!(
                "{} nodes for {} primitives",
                self.nodes.len(),
                self.leaf_ids.len()
            ));
        }
        Ok(())
    }

    /// Walks the tree from the root; returns each node's range of primitives in leaf order.
    fn validate_topology(&self) -> Result<Vec<(usize, usize)>, ValidationError> {
        let n = self.nodes.len();
        let mut visited = vec![false; n];
        let mut covered = vec![false; self.leaf_prims.len()];
        let mut stack = if n > 0 {
            vec![(0usize, 0usize)]
        } else {
            Vec::new()
        };
        while let Some((i, depth)) = stack.pop() {
            if std::mem::replace(&mut visited[i], true) {
                return fail(format!("node {i} is reached twice"));
            }
            if depth > MAX_DEPTH {
                return fail(format!("node {i} is at depth {depth}, beyond {MAX_DEPTH}"));
            }
            let node = &self.nodes[i];
            if node.is_leaf() {
                // Checked before `leaf_range`, whose `u32` sum a loaded file could overflow.
                if node.start.checked_add(node.count).is_none() {
                    return fail(format!(
                        "leaf {i} holds {} primitives from {}, past the end of any tree",
                        node.count, node.start
                    ));
                }
                let range = node.leaf_range();
                if range.end > covered.len() {
                    return fail(format!(
                        "leaf {i} holds {range:?}, beyond {} primitives",
                        covered.len()
                    ));
                }
                for slot in range {
                    if std::mem::replace(&mut covered[slot], true) {
                        return fail(format!(
                            "leaf slot {slot} is in two leaves (the second is node {i})"
                        ));
                    }
                }
                continue;
            }
            let right = node.start as usize;
            if i + 1 >= n || right <= i + 1 || right >= n {
                return fail(format!(
                    "inner node {i} has children {} and {right} of {n} nodes",
                    i + 1
                ));
            }
            stack.extend([(right, depth + 1), (i + 1, depth + 1)]);
        }
        if let Some(i) = visited.iter().position(|v| !v) {
            return fail(format!("node {i} is not reachable from the root"));
        }
        if let Some(slot) = covered.iter().position(|c| !c) {
            return fail(format!("leaf slot {slot} is in no leaf"));
        }
        // Children come after their parent: a backward pass sees both before it.
        let mut ranges = vec![(0, 0); n];
        for i in (0..n).rev() {
            let node = &self.nodes[i];
            ranges[i] = if node.is_leaf() {
                let r = node.leaf_range();
                (r.start, r.end)
            } else {
                let (left, right) = (ranges[i + 1], ranges[node.start as usize]);
                if left.1 != right.0 {
                    return fail(format!(
                        "node {i}: its children's primitives {left:?} and {right:?} are not contiguous"
                    ));
                }
                (left.0, right.1)
            };
        }
        Ok(ranges)
    }

    fn validate_volumes(&self, ranges: &[(usize, usize)]) -> Result<(), ValidationError> {
        for (i, node) in self.nodes.iter().enumerate() {
            if !node.volume.is_well_formed() {
                return fail(format!("the {} of node {i} is malformed", B::NAME));
            }
            let (start, end) = ranges[i];
            for slot in start..end {
                if !node.volume.contains_primitive(&self.leaf_prims[slot]) {
                    return fail(format!(
                        "the {} of node {i} does not contain primitive {}",
                        B::NAME,
                        self.leaf_ids[slot]
                    ));
                }
            }
            if !node.is_leaf() {
                for child in [i + 1, node.start as usize] {
                    if !self.nodes[child].volume.nests_in(&node.volume) {
                        return fail(format!(
                            "the {} of node {child} is not inside its parent {i}'s",
                            B::NAME
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}
