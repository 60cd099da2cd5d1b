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
//! # The order of events
//!
//! Each event says what it is without the events around it: a [`Event::Prune`] says where in
//! the walk it happened ([`PruneAt`]), a [`Event::ChildQueued`] names its parent and its place
//! among its siblings. The order in which a structure reports them is fixed, and written
//! below as a small grammar per structure: `a b` is `a` then `b`, `a | b` one of them, `[a]`
//! `a` or nothing, `{a}` zero or more `a`s, `end` that nothing follows. `n` is the node being
//! walked, `c` a child of it, `p` a primitive. Walks with a stack take their next `n` from
//! its top, where a node's children are pushed so that `rank` 0 is on top; a priority queue
//! gives the nearest. Some queries end before they begin and report nothing (beyond the
//! tests of a grid's unplaced primitives, below): on an empty tree or grid, for `k = 0` or a
//! non-finite query point, and for a NaN `t_max` in a BVH, k-d or BSP tree (or a negative one
//! in the last two). `tests/event_order.rs` (in the `bvhlab-tests` crate) checks every
//! structure's events against these grammars, query by query.
//!
//! **Brute force** (`brute_force.rs`): every primitive `p` in input order.
//!
//! ```text
//! first hit, nearest    = {PrimitiveTest(p) [NewBest(p)]}
//! any hit               = {PrimitiveTest(p)}            end at the first hit
//! all hits, range       = {PrimitiveTest(p)}
//! collide               = {PairTest(a, b)}              every pair, a then b in input order
//! ```
//!
//! **BVH** (sphere, AABB and OBB trees: `bvh/walk/ray.rs`, `nearest.rs`, `range.rs`,
//! `collide.rs`). A refused node is not queued; `test` is
//! `RayBoundTest` for rays, `DistanceBoundTest` for the nearest query, and nothing (a silent
//! test) for a range.
//!
//! ```text
//! query    = test(root) [Prune(root, at Test)] {pop}
//! pop      = Prune(n, at Pop) | EnterNode(n) (leaf | inner)      no Pop prune in a range
//! inner    = test(c1) [Prune(c1, at Test)] test(c2) [Prune(c2, at Test)]
//!            {ChildQueued(n, c)}          the children not refused, nearer first
//! leaf     = {PrimitiveTest(p) [NewBest(p)]} [stop]   NewBest: first hit and nearest
//! stop     = {Prune(m, at Stop)} end      any hit, at its first hit: every m left, top first
//! collide  = {NodePairTest(a, b) {PairTest}}
//! ```
//!
//! Prune reasons: `RayMissed` or `BeyondBestHit` (the best hit, or `t_max`) for rays,
//! `AlreadyHit` at a stop, `NoNearer` for the nearest query, `NoOverlap` for a range. In
//! `collide`, the node pairs come from a stack, the roots first; two overlapping leaves test
//! their primitive pairs; of any other overlapping pair the larger node (or the inner one) is
//! opened and each of its children paired with the other node, first child first.
//!
//! **The slides' recursions** (`bvh/walk/lecture.rs`): `c1` and `c2` are the left and right
//! child, and `call` is the query's own recursion.
//!
//! ```text
//! intersect(n)   = EnterNode(n) RayBoundTest(n) (Prune(n, at Test) | leaf | calls)
//! minDistance(n) = EnterNode(n) (leaf | calls)
//! pruned(n)      = DistanceBoundTest(n) (Prune(n, at Test) | EnterNode(n) (leaf | calls))
//! calls          = ChildQueued(n, c1, rank 0) call(c1) ChildQueued(n, c2, rank 1) call(c2)
//! leaf           = {PrimitiveTest(p) [NewBest(p)]}
//! ```
//!
//! **k-d and BSP trees** (`plane_tree/ray.rs`, `nearest.rs`, `range.rs`, `collide.rs`,
//! shared through `plane_tree/mod.rs`). A primitive listed in several
//! leaves is reported `AlreadyTested` after its first test (mailboxing), and gets no
//! `NewBest` then.
//!
//! ```text
//! ray      = RayBoundTest(root) (Prune(root, at Test) | {pop})    the root's box
//! pop      = Prune(n, at Pop) | EnterNode(n) (leaf | inner)
//! inner    = PlaneCrossed(n) {ChildQueued(n, c)} {Prune(c, at Test)}
//!                         the children the ray reaches, near first; then those it does not
//! leaf     = first hit:   {PrimitiveTest(p) [NewBest(p)]} (stop | [HitBeyondRegion(best)])
//!            any hit:     {PrimitiveTest(p)} [stop]      stop right after the first hit
//!            all hits:    {PrimitiveTest(p)}
//! stop     = {Prune(m, at Stop)} end      every m left on the stack, top first
//!
//! nearest  = DistanceBoundTest(root) {pop}
//! pop      = Prune(n, at Pop) | EnterNode(n) (leaf | inner)
//! inner    = {DistanceBoundTest(c) (Prune(c, at Test) | ChildQueued(n, c))}
//!                         both children, the point's side first
//! leaf     = {PrimitiveTest(p) [NewBest(p)]}
//!
//! range    = Prune(root, at Test) | {EnterNode(n) (leaf | inner)}
//! inner    = {Prune(c, at Test) | ChildQueued(n, c)}        below child, then above
//! leaf     = {PrimitiveTest(p)}
//!
//! collide  = {NodePairTest(a, b) {PairTest}}      as the BVH's, the larger box opened; a
//!                                                 pair of primitives met again is skipped
//! ```
//!
//! The first hit stops (`BeyondBestHit`) once its best hit lies before every region left on
//! the stack; the any-hit query stops (`AlreadyHit`) at its first hit; `RayMissed` refuses
//! the root's box or a child the ray does not reach; a popped region is pruned
//! `BeyondBestHit` (the best hit, or `t_max`); the nearest query prunes `NoNearer`, the range
//! `NoOverlap`.
//!
//! **Quadtrees and octrees** (`quadtree/ray.rs`, `nearest.rs`, `range.rs`, `collide.rs`).
//! Primitives listed in several cells are mailboxed, as in the k-d tree.
//!
//! ```text
//! ray      = RayBoundTest(root) (Prune(root, at Test) | {pop})
//! pop      = Prune(n, at Pop) | EnterNode(n) (leaf | inner)
//! inner    = {RayBoundTest(c) [Prune(c, at Test)]}    every child, in stored order
//!            {ChildQueued(n, c)}    the children the ray meets that are not empty leaves,
//!                                   by entry t
//! leaf     = first hit:   {PrimitiveTest(p) [HitBeyondRegion(p)] [NewBest(p)]}
//!            any hit:     {PrimitiveTest(p)}     end at the first hit
//!            all hits:    {PrimitiveTest(p)}
//!
//! nearest  = DistanceBoundTest(root) {EnterNode(n) (leaf | inner)}
//!            [Prune(n, at Pop) end]      n: the nearest cell queued; the first one no nearer
//!                                        than the k-th best ends the search
//! inner    = {DistanceBoundTest(c)}     every child, in stored order
//!            {ChildQueued(n, c) | Prune(c, at Test)}    the non-empty ones, nearest first
//! leaf     = {PrimitiveTest(p) [NewBest(p)]}
//!
//! range    = {Prune(n, at Pop) | EnterNode(n) [leaf]}
//!                     an inner node's children are pushed silently, the first on top
//! leaf     = {PrimitiveTest(p)}
//!
//! collide  = {NodePairTest(a, b) {PairTest}}   as the BVH's, the larger cell
//!                     opened; pairs met again, or whose boxes are apart, are skipped
//! ```
//!
//! A range that is not a finite box or ball tests every primitive, and reports nothing else.
//!
//! **Uniform grid** (`grid/ray.rs`, `nearest.rs`, `range.rs`, `collide.rs`). The primitives
//! that updates moved out of the grid's box sit in no cell: each query tests them first
//! (`unplaced`, the cell's grammar over them; an any-hit query that hits one ends there).
//! Mailboxing as in the quadtree; cells are named by their linear index.
//!
//! ```text
//! ray      = unplaced {CellEnter(c) cell} [Prune(c, at Stop)]
//!                  the cells along the ray, front to back; the first one that begins
//!                  after the best hit (or t_max) ends the walk
//! cell     = first hit:   {PrimitiveTest(p) [HitBeyondRegion(p)] [NewBest(p)]}
//!            any hit:     {PrimitiveTest(p)}     end at the first hit
//!            all hits:    {PrimitiveTest(p)}
//!
//! nearest  = unplaced {cell}     the rings of cells around the point's cell, outward
//! cell     = DistanceBoundTest(c) (Prune(c, at Test) | EnterNode(c) {PrimitiveTest(p)
//!            [NewBest(p)]})            a cell that lists primitives
//!          | EnterNode(c)              an empty one
//!
//! range    = unplaced {Prune(c, at Test) | EnterNode(c) {PrimitiveTest(p)}}
//!                  the cells the region's box covers, in index order; a ball prunes
//!                  those it misses
//! collide  = unplaced {NodePairTest(a, b) {PairTest}}
//!                  a: each non-empty cell of the first grid, in order; b: the non-empty
//!                  cells of the second that a's box covers, in order
//! ```
//!
//! **Builds** (`build_observed` of each structure): trees report their nodes depth first,
//! first child first; a BVH, k-d or BSP node that splits has two children, a quadtree cell
//! four (an octree cell eight), with one `BuildSplit` per axis.
//!
//! ```text
//! tree     = node(root)
//! node(n)  = BuildNode(n, parent) (BuildSplit(n) {BuildSplit(n)} {node(c)} | BuildLeaf(n))
//! grid     = {BuildLeaf(c)}       each non-empty cell, in index order
//! ```
//!
//! [`SpatialIndex`]: super::SpatialIndex

use crate::Vector;
use crate::structure::bvh::SplitRecord;

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

/// Where in the walk a node (or cell) was skipped: which line of the algorithm skipped it.
///
/// The same reason can be given at different places (a node the ray enters beyond the best
/// hit is refused at its own test, or later when it is taken from the stack), and the lab
/// highlights a different line for each, so the event says which it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PruneAt {
    /// At the node's own test, before it was ever queued: the root's (the query is over before
    /// it began), a child's as its parent is expanded (a child a k-d or BSP ray does not reach
    /// is refused there too), a grid cell's, or, in the slides' recursions, at the start of the
    /// call.
    Test,
    /// When the node is taken from the stack or queue: the best so far has moved since it was
    /// queued (a quadtree's range query tests its cells only then).
    Pop,
    /// Once the answer is final: the node is skipped with everything else still waiting (an
    /// any-hit query found its hit; a k-d or BSP first hit lies before every region left; the
    /// grid's walk reached a cell that begins after the best hit).
    Stop,
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
    /// A node is entered: popped from the traversal stack or queue (in the slides'
    /// recursions: a call begins).
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
    /// A node was skipped: why, and where in the walk.
    Prune {
        /// The node.
        node: NodeId,
        /// Why.
        reason: PruneReason,
        /// Where: at its own test, when taken from the stack or queue, or when the query
        /// stops.
        at: PruneAt,
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
///
/// Besides the events, a builder that weighs candidate planes reports each node's decision
/// with its whole cost curve to an observer that [asks for them](Self::wants_splits) (the
/// BVH's builders: [`SplitRecord`]); the curve is a vector per node, so builders compute it
/// only then.
pub trait Observer<V: Vector> {
    /// One step.
    fn on(&mut self, event: Event<V>);

    /// Whether this observer keeps split decisions ([`on_split`](Self::on_split)). `false`
    /// by default, and builders then skip the cost curves.
    #[inline]
    fn wants_splits(&self) -> bool {
        false
    }

    /// One node's split decision, with the cost of every candidate plane, after the
    /// [`Event::BuildSplit`] or [`Event::BuildLeaf`] of the same node. Called only when
    /// [`wants_splits`](Self::wants_splits) says so.
    #[inline]
    fn on_split(&mut self, record: &SplitRecord) {
        let _ = record;
    }
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

/// An observer that keeps every event in order, for playback and for tests, and every split
/// decision of a build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recorder<V: Vector> {
    /// The events, in the order they happened.
    pub events: Vec<Event<V>>,
    /// A build's split decisions with their cost curves, node by node.
    pub splits: Vec<SplitRecord>,
}

impl<V: Vector> Observer<V> for Recorder<V> {
    fn on(&mut self, event: Event<V>) {
        self.events.push(event);
    }

    fn wants_splits(&self) -> bool {
        true
    }

    fn on_split(&mut self, record: &SplitRecord) {
        self.splits.push(record.clone());
    }
}
