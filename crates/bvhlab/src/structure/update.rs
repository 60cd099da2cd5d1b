//! Changing a built structure (issue 20, "Moving geometry"): insert, remove and move one
//! primitive without building again, and what each structure pays for it.
//!
//! Queries name primitives by their index in [`primitives`](super::SpatialIndex::primitives)
//! ([`Hit::prim`](super::Hit::prim), [`Nearest::prim`](super::Nearest::prim)), so every
//! update says what it does to indices, the same way in every structure that has one:
//!
//! - `insert(prim) -> usize` appends: the new primitive's index is the old length, and no
//!   other index changes.
//! - `replace(index, prim)` moves (or reshapes) one primitive in place: every index stays.
//! - `remove(index)` is a swap-remove ([`Vec::swap_remove`]): the last primitive takes the
//!   removed one's index, and [`Removed::moved_from`] says so; every other index stays. A
//!   caller that keeps its own handles renames one of them per removal, not all.
//!
//! After each of them [`validate`](super::SpatialIndex::validate) holds and every query
//! answers as [`BruteForce`](super::BruteForce) does on the primitives now held. A
//! primitive with a NaN or infinite coordinate may be inserted: it is kept, and placed
//! where the structure keeps such primitives at build time (left out of a BVH's leaves, in
//! a grid's list of unplaced primitives).
//!
//! ## What an update costs, structure by structure
//!
//! | structure | moving every primitive | one insert, remove or move | quality over time |
//! | --- | --- | --- | --- |
//! | [`Bvh`](super::Bvh) (any volume) | [`refit`](super::Bvh::refit): O(nodes), topology kept (Wald, Boulos and Shirley 2007) | not for sphere and OBB trees (their volumes are fitted to every vertex below, so a change would refit O(n) vertices per ancestor): refit or rebuild | decays as primitives drift; [`needs_rebuild`](super::Bvh::needs_rebuild) says when |
//! | AABB tree (`Bvh<Aabb<V>, P>`) | the same refit | [`Bvh::insert`](super::Bvh::insert), [`remove`](super::Bvh::remove), [`replace`](super::Bvh::replace): a branch-and-bound search for the cheapest place that visits O(log n) nodes on typical scenes (Bittner, Hapala and Havran 2013), then a splice into the depth-first arrays, which moves the nodes and leaf slots after the place (a memory move and one pass over the nodes, O(n) with a small constant) | SAH-greedy inserts; [`optimize_by_reinsertion`](super::Bvh::optimize_by_reinsertion) lowers the SAH cost in place and never raises it |
//! | [`Bvh4`](crate::Bvh4) | [`refit`](crate::Bvh4::refit): O(nodes), wide topology kept | [`Bvh4::insert`](crate::Bvh4::insert): down the lanes whose boxes grow least into the first free lane (a full node's leaf lane becomes a node), appended to the leaf order, O(depth); [`Bvh4::remove`](crate::Bvh4::remove): the leaf order and nodes laid out again, O(n), as a refit | inserts by least growth, not by SAH search; [`needs_rebuild`](crate::Bvh4::needs_rebuild) says when a rebuild pays |
//! | [`Grid`](super::Grid) | replace each primitive (below), or rebuild | [`Grid::insert`](super::Grid::insert), [`remove`](super::Grid::remove), [`replace`](super::Grid::replace): only the cells the primitive covered and now covers are edited, each list in place, so the cost is proportional to those cells and their lists (amortised: a list that outgrows its room moves to the end of the list array with twice the room, and the lists are packed again when the spare entries outnumber the listed ones and the cells) | the grid's box and cells are fixed at build time: a primitive that leaves the box is kept in the unplaced list, which every query tests, so a grid whose primitives wander out should be rebuilt |
//! | [`KdTree`](super::KdTree), [`BspTree`](super::BspTree), [`Orthtree`](super::Orthtree) (quadtree, octree) | rebuild: O(n log n) | rebuild | every build is fresh |
//!
//! Why the AABB tree's splice is O(n): the tree keeps the layout the queries walk, nodes
//! depth-first with the first child next to its parent and each subtree's primitives
//! contiguous (pbrt-v4's `LinearBVHNode`). A new leaf must sit right after its sibling's
//! subtree, so the nodes and leaf slots after it move and the links past them are
//! renumbered. A pointer-linked tree (`Box2D`'s dynamic tree; Catto, "Dynamic Bounding
//! Volume Hierarchies", GDC 2019) avoids the move, at the price of the flat layout every
//! walk here reads.
//!
//! What that means in time (`cargo bench -p bvhlab --bench updates`: 10 000 triangles of
//! the Stanford bunny, medians of one run on a shared two-core machine, where builds
//! varied from 5 to 13 ms between runs): a binned SAH build took 5.1 ms, moving one
//! triangle by [`replace`](super::Bvh::replace) about 0.2 ms (the memory moves dominate:
//! a twentieth of a build), and inserting all 10 000 one by one 0.52 s, a hundred builds;
//! the grid's build took about 4 ms and moving one triangle about 1 µs. So: a few
//! primitives move by updates, all of them by a refit, and after many updates a rebuild
//! pays.

use std::fmt;

/// What a `remove` ([`Bvh::remove`](super::Bvh::remove), [`Grid::remove`](super::Grid::remove))
/// took out, and which primitive took its index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Removed<P> {
    /// The primitive removed.
    pub prim: P,
    /// `Some(old)` when the primitive that was last, at index `old`, now has the removed
    /// primitive's index (a swap-remove); `None` when the removed one was last.
    pub moved_from: Option<usize>,
}

/// Why an update was refused; the structure is then unchanged.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum UpdateError {
    /// There is no primitive at that index.
    NoSuchPrimitive {
        /// The index given.
        index: usize,
        /// How many primitives the structure holds.
        len: usize,
    },
}

impl fmt::Display for UpdateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoSuchPrimitive { index, len } => write!(
                f,
                "there is no primitive {index}: the structure holds {len} (indices 0..{len})"
            ),
        }
    }
}

impl std::error::Error for UpdateError {}

/// Checks that `index` names one of `len` primitives.
pub(crate) fn check_index(index: usize, len: usize) -> Result<(), UpdateError> {
    if index < len {
        Ok(())
    } else {
        Err(UpdateError::NoSuchPrimitive { index, len })
    }
}
