//! The primitives of a [`Bvh4`](super::Bvh4)'s leaves, in leaf order: triangles in blocks
//! of four, any other primitive one per slot.
//!
//! A leaf lane names its primitives by slot: `count` slots from `child`. With blocks, slot
//! `s` is lane `s % 4` of block `s / 4`, every leaf starts a block of its own (its first slot
//! is a multiple of 4), and the slots past a leaf's last triangle up to the next block are
//! padding: their id is [`PADDING`] and no lane names them. The blocks replace the copy of
//! the triangles; they are not kept beside it.
//!
//! The tree is generic over its primitive, and only `Triangle3` has blocks: which form a tree
//! takes is decided by the primitive's type ([`TypeId`]), a comparison of two constants that
//! the compiler settles for each primitive type, and reading a block's triangle as `P` is a
//! downcast that cannot fail there. Code that takes another primitive never meets a block.

use std::any::{Any, TypeId};
use std::ops::Range;

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::triangle_block::{BLOCK, TriangleBlock};
use crate::primitive::contract;
use crate::structure::HitTracker;
use crate::structure::bvh::{BvhOptions, NodeVolume};
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Ray, Ray3, Triangle3};

/// The id of a padding slot in a tree with blocks.
pub(super) const PADDING: u32 = u32::MAX;

/// The leaves' primitives in leaf order.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
pub(super) enum LeafPrims<P> {
    /// One primitive per slot.
    Plain(Vec<P>),
    /// Triangles, four to a block (the module's first section).
    Blocks(Vec<TriangleBlock>),
}

/// `value` as a `U`, when `T` is `U`.
#[inline]
fn same<T: 'static, U: 'static>(value: &T) -> Option<&U> {
    (value as &dyn Any).downcast_ref::<U>()
}

/// A block's triangle as the tree's primitive type (a tree has blocks only when that is
/// `Triangle3`).
#[inline]
fn as_prim<P: Primitive>(triangle: &Triangle3) -> P {
    *same::<Triangle3, P>(triangle).expect("a Bvh4 has triangle blocks only over Triangle3")
}

/// The triangle a primitive of a tree with blocks is.
#[inline]
fn as_triangle<P: Primitive>(prim: &P) -> &Triangle3 {
    same::<P, Triangle3>(prim).expect("a Bvh4 has triangle blocks only over Triangle3")
}

impl<P: Primitive> LeafPrims<P> {
    /// Whether a tree over `P` keeps its triangles in blocks.
    #[inline]
    pub(super) fn in_blocks() -> bool {
        TypeId::of::<P>() == TypeId::of::<Triangle3>()
    }

    /// The leaves of `nodes` over `prims` and `ids` (one per slot, in leaf order): kept as
    /// they are, or, for triangles, put in blocks, with each leaf lane's `child` moved to its
    /// first slot and the ids given their padding. Returns the primitives and the ids.
    pub(super) fn lay_out(
        prims: Vec<P>,
        ids: Vec<u32>,
        nodes: &mut [Bvh4Node],
    ) -> (Self, Vec<u32>) {
        if !Self::in_blocks() {
            return (Self::Plain(prims), ids);
        }
        let mut blocks = Vec::with_capacity(prims.len().div_ceil(BLOCK) + nodes.len());
        let mut slot_ids = Vec::with_capacity(blocks.capacity() * BLOCK);
        for (start, count, lane_start) in leaf_lanes(nodes) {
            *lane_start = u32::try_from(blocks.len() * BLOCK).unwrap_or(u32::MAX);
            let leaf = start..start + count;
            for (chunk, chunk_ids) in prims[leaf.clone()]
                .chunks(BLOCK)
                .zip(ids[leaf].chunks(BLOCK))
            {
                let mut block = TriangleBlock::UNUSED;
                for (lane, prim) in chunk.iter().enumerate() {
                    block.set(lane, as_triangle(prim));
                }
                blocks.push(block);
                slot_ids.extend_from_slice(chunk_ids);
                slot_ids.resize(blocks.len() * BLOCK, PADDING);
            }
        }
        (Self::Blocks(blocks), slot_ids)
    }

    /// One primitive per slot again: the leaves in `nodes`' order with each leaf lane's
    /// `child` moved to its first slot, and their ids (no padding). Undoes
    /// [`lay_out`](Self::lay_out); a plain tree is given back as it is.
    pub(super) fn into_plain(self, ids: Vec<u32>, nodes: &mut [Bvh4Node]) -> (Vec<P>, Vec<u32>) {
        let blocks = match self {
            Self::Plain(prims) => return (prims, ids),
            Self::Blocks(blocks) => Self::Blocks(blocks),
        };
        let mut prims = Vec::with_capacity(ids.len());
        let mut dense_ids = Vec::with_capacity(ids.len());
        for (start, count, lane_start) in leaf_lanes(nodes) {
            *lane_start = u32::try_from(prims.len()).unwrap_or(u32::MAX);
            prims.extend((start..start + count).map(|slot| blocks.get(slot)));
            dense_ids.extend_from_slice(&ids[start..start + count]);
        }
        (prims, dense_ids)
    }

    /// The primitive in `slot`.
    #[inline]
    pub(super) fn get(&self, slot: usize) -> P {
        match self {
            Self::Plain(prims) => prims[slot],
            Self::Blocks(blocks) => as_prim(&blocks[slot / BLOCK].triangle(slot % BLOCK)),
        }
    }

    /// Puts `prim` in `slot`.
    pub(super) fn set(&mut self, slot: usize, prim: &P) {
        match self {
            Self::Plain(prims) => prims[slot] = *prim,
            Self::Blocks(blocks) => blocks[slot / BLOCK].set(slot % BLOCK, as_triangle(prim)),
        }
    }

    /// Appends a leaf of `prim` alone, with its `id` (and the padding after it) in `ids`;
    /// returns its slot.
    pub(super) fn push_leaf(&mut self, prim: &P, id: u32, ids: &mut Vec<u32>) -> u32 {
        let slot = u32::try_from(ids.len()).unwrap_or(u32::MAX);
        ids.push(id);
        match self {
            Self::Plain(prims) => prims.push(*prim),
            Self::Blocks(blocks) => {
                let mut block = TriangleBlock::UNUSED;
                block.set(0, as_triangle(prim));
                blocks.push(block);
                ids.resize(blocks.len() * BLOCK, PADDING);
            }
        }
        slot
    }

    /// How many slots there are (padding included).
    pub(super) fn slots(&self) -> usize {
        match self {
            Self::Plain(prims) => prims.len(),
            Self::Blocks(blocks) => blocks.len() * BLOCK,
        }
    }

    /// The heap memory held.
    pub(super) fn memory_bytes(&self) -> usize {
        match self {
            Self::Plain(prims) => prims.capacity() * size_of::<P>(),
            Self::Blocks(blocks) => blocks.capacity() * size_of::<TriangleBlock>(),
        }
    }

    /// Calls `visit(slot, primitive)` for the primitives of the leaf `slots` that may lie
    /// within `reach_sq` of `point`, in slot order: every one when they are kept one per
    /// slot; in blocks, those whose fitted box is in reach (`TriangleBlock::near_lanes`,
    /// the walks' own pruning rule), four boxes at a time. `visit` gives the new reach when
    /// the primitive improved the best.
    #[inline]
    pub(super) fn each_near(
        &self,
        slots: Range<usize>,
        point: &[f32; 3],
        reach_sq: &mut f32,
        mut visit: impl FnMut(usize, &P) -> Option<f32>,
    ) {
        let blocks = match self {
            Self::Plain(prims) => {
                for slot in slots {
                    if let Some(reach) = visit(slot, &prims[slot]) {
                        *reach_sq = reach;
                    }
                }
                return;
            }
            Self::Blocks(blocks) => blocks,
        };
        let first = slots.start / BLOCK;
        let leaf = &blocks[first..first + slots.len().div_ceil(BLOCK)];
        for (i, block) in leaf.iter().enumerate() {
            let mut lanes = block.near_lanes(point, *reach_sq, slots.len() - i * BLOCK);
            while lanes != 0 {
                let lane = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                let prim = as_prim(&block.triangle(lane));
                if let Some(reach) = visit(slots.start + i * BLOCK + lane, &prim) {
                    *reach_sq = reach;
                }
            }
        }
    }

    /// Offers the first hit of every primitive in the leaf `slots` to `best` (`ids` are the
    /// tree's, by slot); whether the best changed. Blocks are tested four triangles at a
    /// time, and only the lanes they do not prove missed one by one: the same hits, bit for
    /// bit.
    #[inline]
    pub(super) fn offer_first_hits(
        &self,
        slots: Range<usize>,
        ids: &[u32],
        ray: &Ray<P::Point>,
        best: &mut HitTracker,
    ) -> bool {
        let blocks = match self {
            Self::Plain(prims) => return best.offer_leaf(&prims[slots.clone()], &ids[slots], ray),
            Self::Blocks(blocks) => blocks,
        };
        let ray: &Ray3 = same(ray).expect("a Bvh4 has triangle blocks only over Triangle3");
        let mut changed = false;
        block_hits(blocks, slots, ray, |slot, t| {
            changed |= best.offer(ids[slot] as usize, t);
            false
        });
        changed
    }

    /// Calls `found(slot, t)` for every primitive in the leaf `slots` that the ray hits,
    /// in slot order, until `found` says to stop; whether it did.
    #[inline]
    pub(super) fn each_hit(
        &self,
        slots: Range<usize>,
        ray: &Ray<P::Point>,
        mut found: impl FnMut(usize, f32) -> bool,
    ) -> bool {
        match self {
            Self::Plain(prims) => slots
                .into_iter()
                .any(|slot| contract::ray_hit(&prims[slot], ray).is_some_and(|t| found(slot, t))),
            Self::Blocks(blocks) => {
                let ray: &Ray3 = same(ray).expect("a Bvh4 has triangle blocks only over Triangle3");
                block_hits(blocks, slots, ray, found)
            }
        }
    }
}

/// [`LeafPrims::each_hit`] over blocks.
#[inline]
fn block_hits(
    blocks: &[TriangleBlock],
    slots: Range<usize>,
    ray: &Ray3,
    mut found: impl FnMut(usize, f32) -> bool,
) -> bool {
    let first = slots.start / BLOCK;
    let leaf = &blocks[first..first + slots.len().div_ceil(BLOCK)];
    for (i, block) in leaf.iter().enumerate() {
        let mut lanes = block.may_hit(ray, slots.len() - i * BLOCK);
        while lanes != 0 {
            let lane = lanes.trailing_zeros() as usize;
            lanes &= lanes - 1;
            let hit = contract::ray_hit(&block.triangle(lane), ray);
            if hit.is_some_and(|t| found(slots.start + i * BLOCK + lane, t)) {
                return true;
            }
        }
    }
    false
}

/// Every leaf lane of `nodes`, in node and lane order: its first slot, its count, and its
/// `child` to rewrite.
fn leaf_lanes(nodes: &mut [Bvh4Node]) -> impl Iterator<Item = (usize, usize, &mut u32)> {
    nodes.iter_mut().flat_map(|node| {
        let Bvh4Node { child, count, .. } = node;
        child
            .iter_mut()
            .zip(count.iter())
            .take(WIDTH)
            .filter(|(_, count)| **count > 0)
            .map(|(child, &count)| (*child as usize, count as usize, child))
    })
}

impl<P: Primitive> Bvh4<P> {
    /// How full the leaves' blocks of four triangles are: the share of their lanes that
    /// hold a triangle (1 when every block is full; 0.95-0.96 for the bunny and the dragon
    /// built by [`Bvh4::build`]), or `None` when the tree keeps one primitive per slot (every
    /// primitive type but [`Triangle3`]).
    pub fn block_fill(&self) -> Option<f32> {
        match &self.leaf_prims {
            LeafPrims::Plain(_) => None,
            LeafPrims::Blocks(blocks) => {
                let lanes = (blocks.len() * BLOCK).max(1);
                Some(self.indexed_slots().count() as f32 / lanes as f32)
            }
        }
    }

    /// The box a leaf of `count` slots from `start` gets, as the builds fit one.
    pub(super) fn leaf_box(&self, start: usize, count: usize) -> Aabb<P::Point> {
        let bounds = (start..start + count).fold(Aabb::EMPTY, |bounds, slot| {
            bounds.merge(&self.leaf_prims.get(slot).bounds())
        });
        <Aabb<P::Point> as NodeVolume>::fit(&bounds, &[], &BvhOptions::default())
    }

    /// Every slot that holds a primitive (no padding), with the primitive's input index.
    pub(super) fn indexed_slots(&self) -> impl Iterator<Item = (usize, u32)> + '_ {
        self.leaf_ids
            .iter()
            .enumerate()
            .filter(|&(_, &id)| id != PADDING)
            .map(|(slot, &id)| (slot, id))
    }

    /// Takes the leaves out, one primitive per slot in node and lane order (each leaf lane
    /// moved to its first slot there), for the updates that rearrange slots; give them back
    /// with [`put_leaves`](Self::put_leaves).
    pub(super) fn take_leaves(&mut self) -> (Vec<P>, Vec<u32>) {
        let prims = std::mem::replace(&mut self.leaf_prims, LeafPrims::Plain(Vec::new()));
        prims.into_plain(std::mem::take(&mut self.leaf_ids), &mut self.nodes)
    }

    /// Puts back leaves taken by [`take_leaves`](Self::take_leaves) (or laid out as they
    /// are), triangles in blocks again.
    pub(super) fn put_leaves(&mut self, prims: Vec<P>, ids: Vec<u32>) {
        (self.leaf_prims, self.leaf_ids) = LeafPrims::lay_out(prims, ids, &mut self.nodes);
    }
}

#[cfg(test)]
mod tests {
    //! Trees that break the blocks' rules, made by hand: `validate` must refuse each.
    use super::{LeafPrims, PADDING};
    use crate::structure::bvh::Bvh4;
    use crate::{Triangle3, Vec3};

    fn fan(n: usize) -> Vec<Triangle3> {
        (0..n)
            .map(|i| {
                let x = i as f32;
                Triangle3::new(
                    Vec3::new(x, 0.0, 0.0),
                    Vec3::new(x + 1.0, 0.0, 0.0),
                    Vec3::new(x, 1.0, 0.0),
                )
            })
            .collect()
    }

    #[test]
    fn a_triangle_tree_keeps_blocks_and_passes_validate() {
        let tree = Bvh4::build(&fan(37));
        assert!(matches!(tree.leaf_prims, LeafPrims::Blocks(_)));
        assert_eq!(tree.leaf_ids.len() % 4, 0);
        assert!(
            tree.block_fill()
                .is_some_and(|fill| fill > 0.0 && fill <= 1.0)
        );
        tree.validate().expect("valid");
        assert_eq!(Bvh4::build(&[Vec3::ZERO, Vec3::X]).block_fill(), None);
    }

    #[test]
    fn a_leaf_starting_inside_a_block_is_refused() {
        let mut tree = Bvh4::build(&fan(3));
        let lane = (0..4)
            .find(|&l| tree.nodes[0].count[l] > 0)
            .expect("a leaf lane");
        tree.nodes[0].child[lane] += 1;
        let why = tree.validate().expect_err("refused").to_string();
        assert!(
            why.contains("inside a block") || why.contains("padding"),
            "{why}"
        );
    }

    #[test]
    fn a_leaf_reaching_into_padding_is_refused() {
        let mut tree = Bvh4::build(&fan(3));
        let lane = (0..4)
            .find(|&l| tree.nodes[0].count[l] == 3)
            .expect("one leaf of three");
        assert_eq!(tree.leaf_ids[3], PADDING);
        tree.nodes[0].count[lane] = 4;
        let why = tree.validate().expect_err("refused").to_string();
        assert!(why.contains("padding slot"), "{why}");
    }

    #[test]
    fn blocks_in_a_tree_of_another_primitive_are_refused() {
        let triangles = Bvh4::build(&fan(3));
        let mut points = Bvh4::build(&[Vec3::ZERO, Vec3::X, Vec3::Y]);
        points.leaf_prims = match triangles.leaf_prims {
            LeafPrims::Blocks(blocks) => LeafPrims::Blocks(blocks),
            LeafPrims::Plain(_) => unreachable!("triangles are kept in blocks"),
        };
        points.leaf_ids = triangles.leaf_ids;
        let why = points.validate().expect_err("refused").to_string();
        assert!(why.contains("triangle blocks"), "{why}");
    }
}
