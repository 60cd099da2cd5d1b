//! The state of the algorithm after any number of its events.
//!
//! [`Snapshot::at`] folds the first `step` events of a [`Recording`] into what the student
//! sees: the current node, the nodes visited, culled and pruned so far, the traversal stack
//! (or priority queue, or the grid cells along the ray), the best answer so far, and the
//! counters. It is a pure function of the events, so stepping back is folding a shorter
//! prefix, and the same step of two structures can be shown side by side.

use std::collections::HashMap;

use bvhlab::glam::Vec2;
use bvhlab::structure::PrimitiveResult;
use bvhlab::{Event, NodeId, Vector};

use super::outcome::NodeMarks;
use super::playback::Playback;
use super::question::Task;
use super::recording::Recording;
use super::structures::StructureKind;

/// Node, bound and primitive counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Nodes (or cells) entered.
    pub nodes: u64,
    /// Bounding-volume, cell or plane tests.
    pub bound_tests: u64,
    /// Exact primitive tests.
    pub prim_tests: u64,
    /// Primitive tests skipped by mailboxing.
    pub mailbox_skips: u64,
}

impl Counters {
    /// What one event adds.
    pub fn of<V: Vector>(event: &Event<V>) -> Self {
        let mut c = Self::default();
        match event {
            Event::EnterNode { .. } | Event::CellEnter { .. } => c.nodes = 1,
            // A k-d or BSP tree's plane test is its bound test (the core counts it so).
            Event::RayBoundTest { .. }
            | Event::DistanceBoundTest { .. }
            | Event::PlaneCrossed { .. } => c.bound_tests = 1,
            Event::PrimitiveTest {
                result: PrimitiveResult::AlreadyTested,
                ..
            } => c.mailbox_skips = 1,
            Event::PrimitiveTest { .. } => c.prim_tests = 1,
            _ => {}
        }
        c
    }

    fn add(&mut self, other: Self) {
        self.nodes += other.nodes;
        self.bound_tests += other.bound_tests;
        self.prim_tests += other.prim_tests;
        self.mailbox_skips += other.mailbox_skips;
    }
}

/// A node waiting on the traversal stack or queue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pending {
    /// The node.
    pub node: NodeId,
    /// What it is ordered by: entry `t` or bound distance.
    pub key: f32,
    /// Which node queued it.
    pub parent: NodeId,
}

/// How the waiting nodes are kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frontier {
    /// A stack: the last queued is taken first (depth first, near child first).
    Stack,
    /// A priority queue: the smallest key is taken first (best first).
    Queue,
    /// Recursion: the slides' recursive pseudocode (the calls under way are
    /// [`Snapshot::calls`]).
    Calls,
}

/// A grid cell the ray entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellStep {
    /// The cell.
    pub cell: NodeId,
    /// Its integer coordinates.
    pub coords: [u32; 3],
    /// Where the ray enters it.
    pub t_enter: f32,
    /// Where it leaves it.
    pub t_exit: f32,
}

/// A build's split, as reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitStep<V: Vector = Vec2> {
    /// The node split.
    pub node: NodeId,
    /// The plane's normal.
    pub normal: V,
    /// The plane's offset.
    pub offset: f32,
    /// Primitives below the plane.
    pub left: u32,
    /// Primitives above.
    pub right: u32,
    /// The split's SAH cost, if the builder has a cost model.
    pub cost: Option<f32>,
}

/// The state of the algorithm after the first `step` events (in 2D by default).
#[derive(Clone, Debug)]
pub struct Snapshot<V: Vector = Vec2> {
    /// How many events are folded in.
    pub step: usize,
    /// Nodes visited, culled and pruned, and primitives tested, so far.
    pub marks: NodeMarks,
    /// The node the last event concerned.
    pub current: Option<NodeId>,
    /// The last event.
    pub event: Option<Event<V>>,
    /// The nodes waiting, next first.
    pub frontier: Vec<Pending>,
    /// How they are kept.
    pub frontier_kind: Option<Frontier>,
    /// The path from the root to the current node: for the slides' recursive versions, the
    /// calls under way.
    pub calls: Vec<NodeId>,
    /// Grid: the cells the ray entered so far, in order.
    pub cells: Vec<CellStep>,
    /// The best answers so far, best first: (primitive, t or distance).
    pub best: Vec<(u32, f32)>,
    /// Counters so far.
    pub so_far: Counters,
    /// What the last event added.
    pub this_step: Counters,
    /// Builds: which nodes exist so far (indexed by node id).
    pub existing: Vec<bool>,
    /// Builds: the current node's split, once chosen.
    pub split: Option<SplitStep<V>>,
}

impl<V: Vector> Default for Snapshot<V> {
    fn default() -> Self {
        Self {
            step: 0,
            marks: NodeMarks::default(),
            current: None,
            event: None,
            frontier: Vec::new(),
            frontier_kind: None,
            calls: Vec::new(),
            cells: Vec::new(),
            best: Vec::new(),
            so_far: Counters::default(),
            this_step: Counters::default(),
            existing: Vec::new(),
            split: None,
        }
    }
}

impl<V: Vector> Snapshot<V> {
    /// Brings `snapshot` to the playback's step of `recording` (over a structure of
    /// `node_count` nodes of `kind`), folding again only when the step changed; clears it
    /// without a recording.
    pub fn follow(
        snapshot: &mut Option<Self>,
        recording: Option<&Recording<V>>,
        kind: StructureKind,
        node_count: usize,
        playback: &Playback,
    ) {
        let Some(rec) = recording else {
            *snapshot = None;
            return;
        };
        let step = playback.shown(rec.events.len());
        if snapshot.as_ref().is_none_or(|s| s.step != step) {
            *snapshot = Some(Self::at(rec, kind, step, node_count));
        }
    }

    /// Folds the first `step` events of `recording` over a structure of `node_count` nodes.
    pub fn at(
        recording: &Recording<V>,
        kind: StructureKind,
        step: usize,
        node_count: usize,
    ) -> Self {
        let events = &recording.events[..step.min(recording.events.len())];
        let task = recording.question.task;
        let mut s = Self {
            step: events.len(),
            marks: NodeMarks::from_events(events, node_count),
            frontier_kind: frontier_kind(kind, task, recording.question.variant),
            ..Self::default()
        };
        if task == Task::Build {
            s.existing = vec![false; node_count];
        }
        let k = match task {
            Task::Nearest => recording.question.k.max(1),
            Task::AllHits | Task::Range => usize::MAX,
            _ => 1,
        };
        // A stack walk queues a node's children together, right after entering it: the later
        // a parent's children were queued, the nearer the top they are, and among them rank
        // 0 is on top. Each event names its parent, so the children of each parent form one
        // group, numbered in the order the parents first queued. (group, rank, entry)
        let mut groups: HashMap<NodeId, usize> = HashMap::new();
        let mut waiting: Vec<(usize, u32, Pending)> = Vec::new();
        for event in events {
            s.so_far.add(Counters::of(event));
            s.current = node_of(event).or(s.current);
            match *event {
                Event::ChildQueued {
                    parent,
                    child,
                    key,
                    rank,
                } => {
                    let next = groups.len();
                    let group = *groups.entry(parent).or_insert(next);
                    waiting.push((
                        group,
                        rank,
                        Pending {
                            node: child,
                            key,
                            parent,
                        },
                    ));
                }
                Event::EnterNode { node, depth } => {
                    s.calls.truncate(depth as usize);
                    s.calls.push(node);
                    waiting.retain(|w| w.2.node != node);
                }
                Event::Prune { node, .. } => waiting.retain(|w| w.2.node != node),
                Event::CellEnter {
                    cell,
                    coords,
                    t_enter,
                    t_exit,
                } => s.cells.push(CellStep {
                    cell,
                    coords,
                    t_enter,
                    t_exit,
                }),
                // The best so far, from the tests themselves (brute force reports no
                // NewBest for every query): the nearest hits, the k smallest distances,
                // everything inside the range.
                Event::PrimitiveTest { prim, result } => match result {
                    PrimitiveResult::Hit(t) => offer(&mut s.best, prim, t, k),
                    PrimitiveResult::Distance(d) => offer(&mut s.best, prim, d, k),
                    PrimitiveResult::Overlap => offer(&mut s.best, prim, 0.0, k),
                    _ => {}
                },
                Event::BuildNode { .. } | Event::BuildSplit { .. } | Event::BuildLeaf { .. } => {
                    s.apply_build(event);
                }
                _ => {}
            }
        }
        if task == Task::AllHits {
            // All hits are offered as they are found; the answer is every one of them.
            s.best
                .sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        }
        s.this_step = events.last().map(Counters::of).unwrap_or_default();
        s.event = events.last().copied();
        s.frontier = order(waiting, s.frontier_kind);
        s
    }

    /// A build event: nodes come into existence, and the current node's split is shown
    /// until its first child is made.
    fn apply_build(&mut self, event: &Event<V>) {
        let s = self;
        match *event {
            Event::BuildNode { node, .. } => {
                if let Some(slot) = s.existing.get_mut(node.index()) {
                    *slot = true;
                }
                s.split = None;
            }
            Event::BuildSplit {
                node,
                normal,
                offset,
                left,
                right,
                cost,
            } => {
                s.split = Some(SplitStep {
                    node,
                    normal,
                    offset,
                    left,
                    right,
                    cost,
                });
            }
            Event::BuildLeaf { node, .. } => {
                // A grid reports its cells as leaves only.
                if let Some(slot) = s.existing.get_mut(node.index()) {
                    *slot = true;
                }
                s.split = None;
            }
            _ => {}
        }
    }
}

/// The node an event is about.
fn node_of<V: Vector>(event: &Event<V>) -> Option<NodeId> {
    match *event {
        Event::EnterNode { node, .. }
        | Event::RayBoundTest { node, .. }
        | Event::DistanceBoundTest { node, .. }
        | Event::Prune { node, .. }
        | Event::PlaneCrossed { node, .. }
        | Event::BuildNode { node, .. }
        | Event::BuildSplit { node, .. }
        | Event::BuildLeaf { node, .. } => Some(node),
        Event::CellEnter { cell, .. } => Some(cell),
        _ => None,
    }
}

/// How `kind` keeps the nodes it has yet to visit for `task`.
fn frontier_kind(
    kind: StructureKind,
    task: Task,
    variant: super::question::Variant,
) -> Option<Frontier> {
    use super::question::Variant;
    match (kind, task) {
        (_, Task::Build) | (StructureKind::BruteForce | StructureKind::Grid, _) => None,
        _ if variant != Variant::Full => Some(Frontier::Calls),
        (StructureKind::Quadtree, Task::Nearest) => Some(Frontier::Queue),
        _ => Some(Frontier::Stack),
    }
}

/// The waiting nodes, next first.
fn order(mut waiting: Vec<(usize, u32, Pending)>, kind: Option<Frontier>) -> Vec<Pending> {
    match kind {
        Some(Frontier::Queue) => {
            waiting.sort_by(|a, b| a.2.key.total_cmp(&b.2.key));
        }
        // Later groups are on top of the stack; within a group, rank 0 is taken first.
        _ => waiting.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1))),
    }
    waiting.into_iter().map(|w| w.2).collect()
}

/// Keeps the `k` best (smallest value, then primitive) distinct primitives.
fn offer(best: &mut Vec<(u32, f32)>, prim: u32, value: f32, k: usize) {
    best.retain(|b| b.0 != prim);
    let at = best
        .iter()
        .position(|b| value.total_cmp(&b.1).then(prim.cmp(&b.0)).is_lt())
        .unwrap_or(best.len());
    best.insert(at, (prim, value));
    best.truncate(k);
}
