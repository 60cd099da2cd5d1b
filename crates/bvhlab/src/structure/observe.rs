//! Watching a build or a query step by step: the single interface between the core and the
//! lab's playback, pseudocode highlighting and counters.
//!
//! Every builder and query takes an [`Observer`] and reports each step as an [`Event`]. The
//! no-op observer `()` has an empty, always inlined [`Observer::on`], and events are small
//! `Copy` values built from numbers the algorithm computes anyway, so passing `()` costs
//! nothing: the reports vanish from the walk it is passed to (tinybvh and madmann91/bvh use
//! the same pattern for their traversal callbacks). By default the plain queries of
//! [`SpatialIndex`] (`ray_first_hit`, `k_nearest`, ...) are their `_observed` walks with `()`.
//!
//! What `()` does not remove is the bookkeeping of a walk written to be watched: the depth
//! of each waiting node, the order of its pushes, the counters of its
//! [`QueryCost`](super::QueryCost). So a BVH's plain `ray_first_hit` and `closest_point`,
//! the two queries asked most often, take walks of their own without it, which answer
//! exactly as the observed walks do ([`bvh`](super::bvh) has the table of which call runs
//! which walk).
//!
//! [`SpatialIndex`]: super::SpatialIndex

use crate::Vector;

/// A node of a structure, by its index in the structure's node array (for a grid: a cell, by
/// its linear index).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(pub u32);

impl NodeId {
    /// The index as a `usize`.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Why a node (or cell) was skipped without visiting its contents.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PruneReason {
    /// The ray misses the node's bounding volume (or region).
    RayMissed,
    /// The ray enters the node only after the best hit found so far.
    BeyondBestHit {
        /// Where the ray enters the node.
        t_enter: f32,
        /// The best hit so far.
        best_t: f32,
    },
    /// The node's bound is no nearer to the query point than the best distance so far
    /// (branch and bound).
    NoNearer {
        /// Distance from the query point to the node's bound.
        distance: f32,
        /// The best (k-th best, for k nearest) distance so far.
        best: f32,
    },
    /// The node does not overlap the range or the other tree's node.
    NoOverlap,
    /// Any-hit query: a hit was already found.
    AlreadyHit,
}

/// What testing one primitive gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PrimitiveResult {
    /// The ray hits it at this `t` (within `[0, t_max]`).
    Hit(f32),
    /// The ray misses it (or hits beyond `t_max`).
    Miss,
    /// Its distance to the query point.
    Distance(f32),
    /// It overlaps the range or the other primitive.
    Overlap,
    /// It does not overlap.
    NoOverlap,
    /// Already tested during this query (mailboxing): not tested again.
    AlreadyTested,
}

/// One step of a build or a query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event<V: Vector> {
    // ---- queries ----
    /// A node is entered: popped from the traversal stack or queue.
    EnterNode {
        /// The node.
        node: NodeId,
        /// Its depth (the root is 0).
        depth: u32,
    },
    /// The ray was tested against the node's bounding volume (or region).
    RayBoundTest {
        /// The node.
        node: NodeId,
        /// Where the ray is inside the volume, or `None` for a miss.
        interval: Option<(f32, f32)>,
    },
    /// The distance from the query point to the node's bounding volume was computed.
    DistanceBoundTest {
        /// The node.
        node: NodeId,
        /// The distance (0 inside).
        distance: f32,
    },
    /// A child was put on the stack or queue; children of one node are reported in the order
    /// they will be visited (`rank` 0 first: near child first).
    ChildQueued {
        /// The parent.
        parent: NodeId,
        /// The child.
        child: NodeId,
        /// The key it was ordered by: entry `t` or bound distance.
        key: f32,
        /// Its place in the visiting order among its siblings.
        rank: u32,
    },
    /// A node was skipped, and why.
    Prune {
        /// The node.
        node: NodeId,
        /// Why.
        reason: PruneReason,
    },
    /// A primitive was tested.
    PrimitiveTest {
        /// The primitive's index in the input slice.
        prim: u32,
        /// What the test gave.
        result: PrimitiveResult,
    },
    /// Two primitives were tested against each other (collision query).
    PairTest {
        /// The primitive of the first structure.
        a: u32,
        /// The primitive of the second structure.
        b: u32,
        /// Whether they overlap.
        overlap: bool,
    },
    /// Two nodes, one of each structure, were tested against each other (collision query).
    NodePairTest {
        /// The first structure's node.
        a: NodeId,
        /// The second structure's node.
        b: NodeId,
        /// Whether their volumes overlap.
        overlap: bool,
    },
    /// The best answer improved: a nearer hit (`value` is its `t`) or, for nearest-neighbour
    /// queries, a primitive entered the k nearest so far (`value` is its distance).
    NewBest {
        /// The primitive.
        prim: u32,
        /// The new best `t` or distance.
        value: f32,
    },
    /// A hit was found in a leaf or cell but lies beyond it, so it does not end the search
    /// yet: a nearer hit may lie in a later cell (space partitions only).
    HitBeyondRegion {
        /// The primitive.
        prim: u32,
        /// Where the ray hits it.
        t: f32,
        /// Where the ray leaves the current region.
        t_exit: f32,
    },
    /// Grid traversal: the ray enters a cell.
    CellEnter {
        /// The cell, by linear index.
        cell: NodeId,
        /// Its integer coordinates (unused axes are 0).
        coords: [u32; 3],
        /// Where the ray enters it.
        t_enter: f32,
        /// Where the ray leaves it.
        t_exit: f32,
    },
    /// k-d tree or BSP traversal: the ray crosses the node's split plane at `t`.
    PlaneCrossed {
        /// The node whose plane it is.
        node: NodeId,
        /// Where the ray crosses it (`inf` when parallel).
        t: f32,
    },

    // ---- builds ----
    /// A node was created with `prims` primitives (references) under it.
    BuildNode {
        /// The node.
        node: NodeId,
        /// Its parent, `None` for the root.
        parent: Option<NodeId>,
        /// Its depth.
        depth: u32,
        /// How many primitive references it holds.
        prims: u32,
    },
    /// A node was split by the plane `normal · x = offset` (an axis-aligned plane has a unit
    /// axis as its normal).
    BuildSplit {
        /// The node.
        node: NodeId,
        /// The plane's normal.
        normal: V,
        /// The plane's offset.
        offset: f32,
        /// Primitives sent to the first child (below the plane).
        left: u32,
        /// Primitives sent to the second child.
        right: u32,
        /// The split's cost under the builder's cost model (SAH), if it has one.
        cost: Option<f32>,
    },
    /// A node was made a leaf.
    BuildLeaf {
        /// The node.
        node: NodeId,
        /// How many primitive references it holds.
        prims: u32,
    },
}

/// Receives the steps of a build or a query.
///
/// Implemented for `()` (does nothing, costs nothing), for [`Recorder`] (keeps every event,
/// for playback) and for any `FnMut(Event<V>)`.
pub trait Observer<V: Vector> {
    /// One step.
    fn on(&mut self, event: Event<V>);
}

impl<V: Vector> Observer<V> for () {
    #[inline(always)]
    fn on(&mut self, _event: Event<V>) {}
}

impl<V: Vector, F: FnMut(Event<V>)> Observer<V> for F {
    #[inline]
    fn on(&mut self, event: Event<V>) {
        self(event);
    }
}

/// An observer that keeps every event in order, for playback and for tests.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recorder<V: Vector> {
    /// The events, in the order they happened.
    pub events: Vec<Event<V>>,
}

impl<V: Vector> Observer<V> for Recorder<V> {
    fn on(&mut self, event: Event<V>) {
        self.events.push(event);
    }
}
