//! Inserting, removing and moving primitives in an AABB tree without a rebuild (issue 20,
//! "Moving geometry"), and improving the tree in place.
//!
//! - `mod.rs`: the calls ([`Bvh::insert`], [`Bvh::remove`], [`Bvh::replace`]) and what they do
//!   to indices and leaves.
//! - `search.rs`: where a primitive goes, the branch-and-bound search for the place that
//!   raises the SAH cost least (Bittner, Hapala and Havran 2013).
//! - `splice.rs`: the edits of the depth-first arrays that put it there or take it out.
//! - `rotate.rs`: the tree rotations on the way back up after an insert (Catto 2019), which
//!   keep sorted input from growing a chain.
//! - `optimize.rs`: [`Bvh::optimize_by_reinsertion`], Bittner et al.'s in-place improvement.
//!
//! Only AABB trees: a box node is the union of its children's boxes, so a change refits its
//! ancestors from their children alone. A sphere or OBB node is fitted to every vertex
//! below it, so the same change would refit O(n) vertices at each ancestor: those trees
//! are refitted ([`Bvh::refit`]) or rebuilt. [`Bvh4`](super::Bvh4) has its own
//! [`insert`](super::Bvh4::insert) and [`remove`](super::Bvh4::remove) (`wide/update.rs`).
//!
//! What each call costs, beside the other structures' updates, is in
//! [`update`](crate::structure::update#what-an-update-costs-structure-by-structure).

mod optimize;
mod rotate;
mod search;
mod splice;
#[cfg(test)]
mod tests;

pub use optimize::OptimizeReport;

use search::{Item, Limits, Place};
use splice::Subtree;

use super::Bvh;
use crate::structure::update::{Removed, UpdateError, check_index};
use crate::volume::Aabb;
use crate::{Primitive, Vector};

impl<V, P> Bvh<Aabb<V>, P>
where
    V: Vector,
    P: Primitive<Point = V>,
{
    /// Adds a primitive and returns its index, the old length of
    /// [`primitives`](crate::SpatialIndex::primitives); no other index changes.
    ///
    /// The primitive goes where it raises the tree's SAH cost least (a branch-and-bound
    /// search, `update/search.rs`): into a leaf that holds fewer than
    /// [`leaf_size`](super::BvhOptions::leaf_size) primitives, or into a leaf of
    /// its own beside any node, under a new parent. A full leaf is never grown; the search
    /// puts the primitive beside it instead, which splits it into a new inner node. Then,
    /// on the way back up, each ancestor may swap a child with a grandchild when that
    /// shrinks the node between them (a tree rotation, `update/rotate.rs`). The tree stays
    /// within [`max_depth`](super::BvhOptions::max_depth): only when no new leaf fits there
    /// does a leaf grow past `leaf_size`, as the builds make leaves of any size at that
    /// depth. The volumes above the change are fitted again, so
    /// [`validate`](crate::SpatialIndex::validate) holds and every query answers as brute
    /// force on the primitives now held.
    ///
    /// A primitive with a NaN or infinite coordinate is kept, left out of the tree, as the
    /// builds leave it out ([`skipped`](Bvh::skipped) counts it).
    ///
    /// ```
    /// use bvhlab::glam::Vec3;
    /// use bvhlab::prelude::*;
    ///
    /// let floor = Triangle3::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
    /// let mut tree = AabbTree3::build(&[floor]);
    /// let roof = Triangle3::new(Vec3::Z, Vec3::Z + Vec3::X * 4.0, Vec3::Z + Vec3::Y * 4.0);
    /// assert_eq!(tree.insert(roof), 1);
    /// tree.validate()?;
    /// let down = Ray3::new(Vec3::new(1.0, 1.0, 3.0), -Vec3::Z)?;
    /// assert_eq!(tree.ray_first_hit(&down, f32::INFINITY).map(|h| h.prim), Some(1));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn insert(&mut self, prim: P) -> usize {
        let index = self.prims.len();
        self.prims.push(prim);
        self.link(index);
        index
    }

    /// Removes primitive `index` and returns it. The last primitive takes its index (a
    /// swap-remove): [`Removed::moved_from`] says which one moved, and no other index
    /// changes.
    ///
    /// The primitive's leaf loses it; a leaf left empty is removed with its parent, whose
    /// other child takes the parent's place. The volumes above are fitted again (they only
    /// shrink). Removing the last primitive leaves an empty tree that answers every query
    /// with nothing.
    ///
    /// # Errors
    /// [`UpdateError::NoSuchPrimitive`] when `index` is out of range; the tree is unchanged.
    pub fn remove(&mut self, index: usize) -> Result<Removed<P>, UpdateError> {
        check_index(index, self.prims.len())?;
        self.unlink(index);
        let last = self.prims.len() - 1;
        let prim = self.prims.swap_remove(index);
        if index == last {
            return Ok(Removed {
                prim,
                moved_from: None,
            });
        }
        if let Some(id) = self.leaf_ids.iter_mut().find(|id| **id as usize == last) {
            *id = index as u32;
        }
        Ok(Removed {
            prim,
            moved_from: Some(last),
        })
    }

    /// Moves (or reshapes) primitive `index` to `prim` and returns what it was; every index
    /// stays. The primitive is taken out of its leaf and placed again as
    /// [`insert`](Self::insert) places a new one, so a primitive that moved far lands
    /// among its new neighbours (a [`refit`](Bvh::refit) would keep it in its old leaf and
    /// stretch the boxes above).
    ///
    /// # Errors
    /// [`UpdateError::NoSuchPrimitive`] when `index` is out of range; the tree is unchanged.
    pub fn replace(&mut self, index: usize, prim: P) -> Result<P, UpdateError> {
        check_index(index, self.prims.len())?;
        self.unlink(index);
        let old = std::mem::replace(&mut self.prims[index], prim);
        self.link(index);
        Ok(old)
    }

    /// Puts primitive `id` (already in `prims`) into the tree, if it can be indexed.
    fn link(&mut self, id: usize) {
        let prim = self.prims[id];
        if !prim.has_finite_coordinates() {
            return;
        }
        let leaf = Subtree::leaf(self.leaf_volume(&[prim]), prim, id as u32);
        if self.nodes.is_empty() {
            self.attach(leaf, 0);
            return;
        }
        let item = Item {
            volume: leaf.volume(),
            prims: Some(1),
            height: 0,
        };
        // Then rotations on the way up, from the node that changed.
        let path = match self.place(&item) {
            Some(Place::IntoLeaf(node)) => {
                self.grow_leaf(node, prim, id as u32);
                self.path_to(node)
            }
            Some(Place::Sibling(node)) => {
                self.attach(leaf, node);
                let mut path = self.path_to(node);
                path.push(node); // the new parent
                path
            }
            None => unreachable!("a leaf may always grow past its size"),
        };
        self.rotate_path(&path);
    }

    /// Takes primitive `id` out of the tree, if it is in it; `prims` is left alone.
    fn unlink(&mut self, id: usize) {
        let Some(slot) = self.leaf_ids.iter().position(|&i| i as usize == id) else {
            return;
        };
        let (leaf, path) = self.leaf_of_slot(slot);
        if self.nodes[leaf].count > 1 {
            self.shrink_leaf(leaf, &path, slot);
        } else if leaf == 0 {
            self.nodes.clear();
            self.leaf_prims.clear();
            self.leaf_ids.clear();
        } else {
            self.detach(leaf);
        }
    }

    /// The cheapest place for `item` that keeps the tree within its depth limit.
    ///
    /// First the search ignores depth, which is cheap and almost always lands within it;
    /// if not, it runs again knowing every node's height; a leaf item may then, as a last
    /// resort, grow a leaf past its size. `None` only for a subtree with no place.
    fn place(&self, item: &Item<V>) -> Option<Place> {
        let mut limits = Limits {
            depth: self.options.depth_limit(),
            heights: None,
            leaf_size: self.options.leaf_limit(),
            full_leaves: false,
        };
        let found = self.cheapest_place(item, &limits)?;
        match found.place {
            Place::IntoLeaf(_) => return Some(found.place),
            Place::Sibling(node) => {
                if found.depth + 1 + self.height_of(node).max(item.height) <= limits.depth {
                    return Some(found.place);
                }
            }
        }
        let heights = self.heights();
        limits.heights = Some(&heights);
        if let Some(found) = self.cheapest_place(item, &limits) {
            return Some(found.place);
        }
        limits.full_leaves = item.prims.is_some();
        self.cheapest_place(item, &limits).map(|found| found.place)
    }
}
