//! Well-formedness of a [`Bvh4`]: topology, primitive bookkeeping, and every box inside its
//! parent's (what a refit must keep; the binary tree's `validate.rs` checks the same).

use super::layout::{Bvh4, WIDTH};
use super::refit::node_box;
use crate::primitive::check_enclosed_by_vertices;
use crate::structure::ValidationError;
use crate::structure::bvh::MAX_DEPTH;
use crate::volume::BoundingVolume;
use crate::{Primitive, Vector};

fn fail<T>(message: String) -> Result<T, ValidationError> {
    Err(ValidationError::new(message))
}

impl<P: Primitive> Bvh4<P> {
    /// Checks that every primitive id is distinct and within the input, each primitive
    /// finite and keeping the [`Primitive`] contract's enclosure; every wide node is reached
    /// once from the root through child indices that point forward; the recorded depth is the
    /// tree's (the walks size their stacks by it) and at most [`MAX_DEPTH`]; the leaf lanes
    /// cover the leaf order exactly once; every leaf lane's box contains its primitives' boxes
    /// and every inner lane's box contains every lane of its child node. A tree loaded from a
    /// file that passes these answers every query without indexing out of bounds.
    ///
    /// # Errors
    /// A [`ValidationError`] saying what is wrong.
    pub fn validate(&self) -> Result<(), ValidationError> {
        if self.leaf_ids.len() != self.leaf_prims.len() {
            return fail(format!(
                "{} leaf ids for {} leaf primitives",
                self.leaf_ids.len(),
                self.leaf_prims.len()
            ));
        }
        // Sorted rather than flagged in a table of `input_len` entries: a loaded file's
        // `input_len` is only a number, and must not size an allocation.
        let mut ids = self.leaf_ids.clone();
        ids.sort_unstable();
        if let Some(&[id, _]) = ids.windows(2).find(|pair| pair[0] == pair[1]) {
            return fail(format!("primitive {id} is in more than one leaf slot"));
        }
        for (slot, (&id, prim)) in self.leaf_ids.iter().zip(&self.leaf_prims).enumerate() {
            if id as usize >= self.input_len {
                return fail(format!(
                    "leaf slot {slot} names primitive {id}, out of range"
                ));
            }
            if !prim.vertices().all(Vector::is_finite) {
                return fail(format!("primitive {id} is non-finite but indexed"));
            }
            if let Err(why) = check_enclosed_by_vertices(prim) {
                return fail(format!(
                    "primitive {id} breaks the Primitive contract: {why}"
                ));
            }
        }
        let mut reached = vec![false; self.nodes.len()];
        let mut covered = vec![false; self.leaf_prims.len()];
        let mut stack = if self.nodes.is_empty() {
            vec![]
        } else {
            vec![(0usize, 1usize)]
        };
        let mut depth = 0;
        while let Some((i, level)) = stack.pop() {
            if std::mem::replace(&mut reached[i], true) {
                return fail(format!("wide node {i} is reached twice"));
            }
            depth = level.max(depth);
            let node = &self.nodes[i];
            for lane in (0..WIDTH).filter(|&lane| node.is_used(lane)) {
                let lane_box = node.lane_box::<P::Point>(lane);
                let inside = |b: &crate::Aabb<P::Point>| {
                    lane_box.contains(b.min) && lane_box.contains(b.max)
                };
                if node.count[lane] > 0 {
                    let start = node.child[lane] as usize;
                    for slot in start..start + node.count[lane] as usize {
                        let Some(flag) = covered.get_mut(slot) else {
                            return fail(format!(
                                "wide node {i} lane {lane} holds slot {slot}, beyond the primitives"
                            ));
                        };
                        if std::mem::replace(flag, true) {
                            return fail(format!("leaf slot {slot} is in two leaf lanes"));
                        }
                        if !inside(&self.leaf_prims[slot].bounds()) {
                            return fail(format!(
                                "the box of wide node {i} lane {lane} does not contain primitive {}",
                                self.leaf_ids[slot]
                            ));
                        }
                    }
                } else {
                    let child = node.child[lane] as usize;
                    if child <= i || child >= self.nodes.len() {
                        return fail(format!("wide node {i} lane {lane} points to node {child}"));
                    }
                    if !inside(&node_box::<P>(&self.nodes[child])) {
                        return fail(format!(
                            "the boxes of wide node {child} are not inside its parent {i}'s lane {lane}"
                        ));
                    }
                    stack.push((child, level + 1));
                }
            }
        }
        if let Some(i) = reached.iter().position(|r| !r) {
            return fail(format!("wide node {i} is not reachable from the root"));
        }
        if let Some(slot) = covered.iter().position(|c| !c) {
            return fail(format!("leaf slot {slot} is in no leaf lane"));
        }
        if depth != self.depth || depth > MAX_DEPTH {
            return fail(format!(
                "the tree is {depth} wide levels deep, but records {} (at most {MAX_DEPTH})",
                self.depth
            ));
        }
        Ok(())
    }
}
