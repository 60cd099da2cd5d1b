//! Well-formedness of a [`Bvh4`]: topology, primitive bookkeeping, and every box inside its
//! parent's (what a refit must keep; the binary tree's `validate.rs` checks the same).

use super::layout::{Bvh4, WIDTH};
use super::leaves::{LeafPrims, PADDING};
use super::refit::node_box;
use super::triangle_block::BLOCK;
use crate::structure::ValidationError;
use crate::structure::bvh::MAX_DEPTH;
use crate::structure::check_primitive_contract;
use crate::volume::BoundingVolume;
use crate::{Primitive, Vector};

/// Every lane of `node` is either used, with no NaN among its planes, or exactly the empty
/// lane. The walks' slab test skips a NaN plane (a ray lying in it), so a lane that
/// [`Bvh4Node::is_used`] calls unused but whose planes are NaN would still be entered, and its
/// child followed, by a walk this check never made: a loaded file could send the walks round
/// a loop for ever.
fn check_lanes_are_used_or_empty<V: Vector>(
    node: &super::layout::Bvh4Node,
    i: usize,
) -> Result<(), ValidationError> {
    let empty = super::layout::Bvh4Node::EMPTY;
    for lane in 0..WIDTH {
        if node.is_used(lane) {
            let nan =
                (0..V::DIM).any(|axis| (0..2).any(|side| node.planes[side][axis][lane].is_nan()));
            if nan {
                return fail(format!("wide node {i} lane {lane} has a NaN plane"));
            }
        } else {
            let same = |a: f32, b: f32| a.to_bits() == b.to_bits();
            let planes_empty = (0..3).all(|axis| {
                (0..2).all(|side| {
                    same(
                        node.planes[side][axis][lane],
                        empty.planes[side][axis][lane],
                    )
                })
            });
            if !planes_empty || node.child[lane] != 0 || node.count[lane] != 0 {
                return fail(format!("wide node {i} lane {lane} is unused but not empty"));
            }
        }
    }
    Ok(())
}

fn fail<T>(message: String) -> Result<T, ValidationError> {
    Err(ValidationError::new(message))
}

impl<P: Primitive> Bvh4<P> {
    /// Checks that every primitive of the input is indexed or left out, once, by a distinct
    /// id within the input: an indexed one finite and keeping the [`Primitive`] contract's
    /// enclosure, a left-out one not finite; every wide node is reached
    /// once from the root through child indices that point forward; the recorded depth is the
    /// tree's (the walks size their stacks by it) and at most [`MAX_DEPTH`]; the leaf lanes
    /// cover the leaf order exactly once; every leaf lane's box contains its primitives' boxes
    /// and every inner lane's box contains every lane of its child node. A tree loaded from a
    /// file that passes these answers every query without indexing out of bounds.
    ///
    /// # Errors
    /// A [`ValidationError`] saying what is wrong.
    pub fn validate(&self) -> Result<(), ValidationError> {
        self.check_primitives()?;
        let mut reached = vec![false; self.nodes.len()];
        let mut covered = vec![false; self.leaf_ids.len()];
        let in_blocks = matches!(self.leaf_prims, LeafPrims::Blocks(_));
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
            check_lanes_are_used_or_empty::<P::Point>(node, i)?;
            for lane in (0..WIDTH).filter(|&lane| node.is_used(lane)) {
                let lane_box = node.lane_box::<P::Point>(lane);
                let inside = |b: &crate::Aabb<P::Point>| {
                    lane_box.contains(b.min) && lane_box.contains(b.max)
                };
                if node.count[lane] > 0 {
                    let start = node.child[lane] as usize;
                    if in_blocks && !start.is_multiple_of(BLOCK) {
                        return fail(format!(
                            "wide node {i} lane {lane} starts at slot {start}, inside a block"
                        ));
                    }
                    for slot in start..start + node.count[lane] as usize {
                        let Some(flag) = covered.get_mut(slot) else {
                            return fail(format!(
                                "wide node {i} lane {lane} holds slot {slot}, beyond the primitives"
                            ));
                        };
                        if std::mem::replace(flag, true) {
                            return fail(format!("leaf slot {slot} is in two leaf lanes"));
                        }
                        if self.leaf_ids[slot] == PADDING {
                            return fail(format!(
                                "wide node {i} lane {lane} holds slot {slot}, a padding slot"
                            ));
                        }
                        if !inside(&self.leaf_prims.get(slot).bounds()) {
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
        let mut uncovered = covered.iter().zip(&self.leaf_ids);
        if let Some(slot) = uncovered.position(|(&c, &id)| !c && id != PADDING) {
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

impl<P: Primitive> Bvh4<P> {
    /// The primitives' part of [`Bvh4::validate`]: ids, finiteness and the contract.
    fn check_primitives(&self) -> Result<(), ValidationError> {
        if self.leaf_ids.len() != self.leaf_prims.slots() {
            return fail(format!(
                "{} leaf ids for {} leaf slots",
                self.leaf_ids.len(),
                self.leaf_prims.slots()
            ));
        }
        if matches!(self.leaf_prims, LeafPrims::Blocks(_)) && !LeafPrims::<P>::in_blocks() {
            return fail(
                "the leaves hold triangle blocks, but the tree is over another primitive".into(),
            );
        }
        let indexed = self.indexed_slots().count();
        if indexed + self.left_out.len() != self.input_len {
            return fail(format!(
                "{} primitives indexed and {} left out, but {} given",
                indexed,
                self.left_out.len(),
                self.input_len
            ));
        }
        for &(id, prim) in &self.left_out {
            if id as usize >= self.input_len || prim.has_finite_coordinates() {
                return fail(format!(
                    "primitive {id} is left out, but is finite or out of range"
                ));
            }
        }
        // Sorted rather than flagged in a table of `input_len` entries: a loaded file's
        // `input_len` is only a number, and must not size an allocation.
        let mut ids: Vec<u32> = self.indexed_slots().map(|(_, id)| id).collect();
        ids.extend(self.left_out.iter().map(|&(id, _)| id));
        ids.sort_unstable();
        if let Some(&[id, _]) = ids.windows(2).find(|pair| pair[0] == pair[1]) {
            return fail(format!("primitive {id} is in more than one leaf slot"));
        }
        for (slot, id) in self.indexed_slots() {
            let prim = self.leaf_prims.get(slot);
            if id as usize >= self.input_len {
                return fail(format!(
                    "leaf slot {slot} names primitive {id}, out of range"
                ));
            }
            if !prim.has_finite_coordinates() {
                return fail(format!("primitive {id} is non-finite but indexed"));
            }
            check_primitive_contract(id as usize, &prim)?;
        }
        Ok(())
    }
}
