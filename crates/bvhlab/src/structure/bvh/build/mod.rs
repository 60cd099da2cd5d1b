//! Top-down construction (lecture §3, "Constructing a BVH"): fit a volume around a node's
//! primitives, split them in two by a plane, repeat on both halves until a node is small
//! enough.
//!
//! The builder sees only each primitive's box and centre (as madmann91/bvh's builders do);
//! the node volumes are fitted afterwards, per node, to that node's primitives: the union of
//! their boxes, or a sphere or OBB around their vertices. Fitting each node to all the
//! vertices below it reads every vertex once per level, `O(n)` per level, so the build stays
//! `O(n log n)` for every volume kind (the depth is capped by
//! [`MAX_DEPTH`](super::MAX_DEPTH)).
//!
//! Nodes are appended depth-first as they are created, so a node's index is final when it
//! is made (the id its `BuildNode` event reports), its first child is the next node, and the
//! second child's index is filled in when the second child is made.
//!
//! The lecture's recursion is unrolled into a [`Builder`]: a stack of primitive ranges
//! waiting for their node (a second child waits while the first child's subtree is built),
//! and the current node's work cut into stages (its boxes, its vertices, its fit, its split)
//! that stop when a budget of work is spent and resume where they stopped. Run with an
//! unlimited budget it is the one-shot build ([`build`]); [`BvhBuild`](super::BvhBuild) runs
//! it a budget at a time. Both make the tree, the events and the split log
//! of the recursion: the stack pops ranges in the recursion's order, and every stage reads
//! and writes the primitives in the order the recursion did.

mod fast;
mod fast_bins;
pub(super) mod job;
mod median;
mod node_stages;
pub(super) mod options;
#[cfg(feature = "parallel")]
mod parallel;
mod sah;
pub(super) mod split_log;

pub(super) use fast::{TreeParts, build_sah_box_parts, build_sah_boxes};
#[cfg(feature = "parallel")]
pub(super) use parallel::{build_sah_box_parts_parallel, build_sah_boxes_parallel};

use self::job::{BuildPhase, BuildProgress};
use self::sah::{SahBinning, SahCurve, SahScratch};
use self::split_log::SplitRecord;
use super::layout::BvhNode;
use super::volume::NodeVolume;
use super::volume::fit_sliced::SlicedFit;
use super::{Bvh, BvhOptions};
use crate::structure::Observer;
use crate::volume::Aabb;
use crate::{Primitive, Vector};

/// What the builder knows of a primitive: its box, its centre, its input index.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildPrim<V: Vector> {
    pub bounds: Aabb<V>,
    pub centroid: V,
    pub index: u32,
}

/// A chosen split: the plane, and how many primitives (now first in the node's range) lie
/// below it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    pub axis: usize,
    pub position: f32,
    pub left: usize,
    /// The SAH cost, for SAH splits.
    pub cost: Option<f32>,
}

/// Builds a tree in one go, reporting every node to `observer` and, when it
/// [wants them](Observer::wants_splits), every split decision.
pub(super) fn build<B, P, O>(prims: &[P], options: &BvhOptions, observer: &mut O) -> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    O: Observer<P::Point>,
{
    let mut builder = Builder::new(prims.len(), *options, Fits::Whole, observer.wants_splits());
    builder.run(prims, usize::MAX, observer);
    let (bvh, records) = builder.into_bvh(prims.to_vec());
    for record in &records {
        observer.on_split(record);
    }
    bvh
}

/// How node volumes are fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Fits {
    /// [`NodeVolume::fit`] on all the node's vertices at once.
    Whole,
    /// In resumable passes where there are ([`SlicedFit`]), with the same result.
    Sliced,
}

/// A range of primitives (in `items`) waiting for its node.
#[derive(Clone, Copy, Debug)]
struct Pending {
    start: usize,
    end: usize,
    parent: Option<u32>,
    depth: usize,
    /// Whether it is its parent's second child, whose index the parent stores.
    second: bool,
}

/// The node being made.
#[derive(Clone, Copy, Debug)]
struct NodeWork<V: Vector> {
    range: Pending,
    /// The union of its primitives' boxes (complete after [`Stage::Bounds`]).
    bounds: Aabb<V>,
    /// The box of its primitives' centres (complete after [`Stage::Bounds`]).
    centroids: Aabb<V>,
    /// Its index, set when it is pushed (after its fit).
    id: u32,
}

impl<V: Vector> NodeWork<V> {
    fn len(&self) -> usize {
        self.range.end - self.range.start
    }
}

/// How a partition sends a primitive to the first child.
#[derive(Clone, Copy, Debug)]
enum Cut {
    /// Its centre lies below `position` on `axis` (the spatial median).
    Below { axis: usize, position: f32 },
    /// Its centre's bin is at most the chosen one (the SAH).
    Sah(SahCurve),
}

/// Where the build stands. Each stage that reads primitives keeps the index of the next one
/// (`next`, relative to the node's range), so that it can stop anywhere.
#[derive(Clone, Debug)]
enum Stage<V: Vector> {
    /// Computing each input primitive's box and centre (`Builder::scanned` so far).
    Scan,
    /// About to take the next pending range.
    NextNode,
    /// Merging the node's primitive boxes and centres.
    Bounds {
        node: NodeWork<V>,
        next: usize,
    },
    /// Copying the node's vertices into the scratch buffer.
    Gather {
        node: NodeWork<V>,
        next: usize,
    },
    /// Fitting the node's volume, in one go (`None`) or in passes.
    Fit {
        node: NodeWork<V>,
        sliced: Option<SlicedFit<V>>,
    },
    /// Binning the node's primitives for the SAH.
    Bin {
        node: NodeWork<V>,
        record: SplitRecord,
        binning: SahBinning,
        next: usize,
    },
    /// Moving the primitives below the plane to the front; `mid` of them so far.
    Partition {
        node: NodeWork<V>,
        record: SplitRecord,
        cut: Cut,
        next: usize,
        mid: usize,
    },
    /// The object median, in one go.
    Median {
        node: NodeWork<V>,
        record: SplitRecord,
    },
    /// Copying the primitives into leaf order (`Builder::leaf_ids` so far).
    Order,
    Done,
}

impl<V: Vector> Stage<V> {
    fn phase(&self) -> BuildPhase {
        match self {
            Self::Scan => BuildPhase::Preparing,
            Self::Bounds { .. } | Self::Gather { .. } | Self::Fit { .. } => BuildPhase::Fitting,
            Self::NextNode | Self::Bin { .. } | Self::Partition { .. } | Self::Median { .. } => {
                BuildPhase::Splitting
            }
            Self::Order => BuildPhase::Ordering,
            Self::Done => BuildPhase::Done,
        }
    }
}

/// The work a [`Builder::run`] may still do, in units of one primitive (or one vertex of a
/// fit) read in one pass.
#[derive(Clone, Copy, Debug)]
struct Budget {
    left: usize,
    used: usize,
    /// Set when an indivisible piece of work must wait for the next run.
    stopped: bool,
}

impl Budget {
    fn new(units: usize) -> Self {
        Self {
            left: units,
            used: 0,
            stopped: false,
        }
    }

    /// How much of a divisible piece with `remaining` units to do now: what is left, but
    /// at least one unit so that every run moves on.
    fn chunk(&self, remaining: usize) -> usize {
        remaining.min(self.left.max(1))
    }

    fn spend(&mut self, units: usize) {
        self.left = self.left.saturating_sub(units);
        self.used = self.used.saturating_add(units);
    }

    /// Whether an indivisible piece of `cost` units runs now (and spends it): at the start
    /// of a run always, later only if it fits in what is left, so that a run is never
    /// longer than its budget or one such piece.
    fn whole(&mut self, cost: usize) -> bool {
        if self.used > 0 && cost > self.left {
            self.stopped = true;
            return false;
        }
        self.spend(cost);
        true
    }

    fn is_spent(&self) -> bool {
        self.left == 0 || self.stopped
    }
}

/// The build in progress: everything the recursion kept on its call stack, kept here.
pub(super) struct Builder<B, P: Primitive> {
    options: BvhOptions,
    fits: Fits,
    /// The input's length; `run` is always given the same input.
    input_len: usize,
    /// Input primitives scanned so far.
    scanned: usize,
    /// Of those, how many were left out (a coordinate is NaN or infinite).
    skipped: usize,
    /// The indexed primitives, reordered by the splits into leaf order.
    items: Vec<BuildPrim<P::Point>>,
    nodes: Vec<BvhNode<B>>,
    /// Ranges waiting for their node; the last is made next.
    pending: Vec<Pending>,
    stage: Stage<P::Point>,
    /// Primitives in finished leaves.
    placed: usize,
    leaf_prims: Vec<P>,
    leaf_ids: Vec<u32>,
    /// The current node's vertices.
    scratch: Vec<P::Point>,
    /// Reused buffers for the SAH binning.
    sah: SahScratch<P::Point>,
    /// Every split decision, when asked for.
    log: Option<Vec<SplitRecord>>,
}

impl<B, P> Builder<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// A build of `input_len` primitives that has not started.
    pub fn new(input_len: usize, options: BvhOptions, fits: Fits, keep_log: bool) -> Self {
        Self {
            options,
            fits,
            input_len,
            scanned: 0,
            skipped: 0,
            items: Vec::with_capacity(input_len),
            nodes: Vec::new(),
            pending: Vec::new(),
            // Nothing to build: complete from the start.
            stage: if input_len == 0 {
                Stage::Done
            } else {
                Stage::Scan
            },
            placed: 0,
            leaf_prims: Vec::new(),
            leaf_ids: Vec::new(),
            scratch: Vec::new(),
            sah: SahScratch::default(),
            log: keep_log.then(Vec::new),
        }
    }

    /// Whether the tree is complete.
    pub fn is_done(&self) -> bool {
        matches!(self.stage, Stage::Done)
    }

    /// How far the build is, in units of primitives: each input primitive counts three
    /// times, once scanned, once in a finished leaf and once copied into leaf order (a
    /// primitive left out counts all three when scanned), so `done` only grows and reaches
    /// `total` exactly when the tree is complete.
    pub fn progress(&self) -> BuildProgress {
        BuildProgress {
            done: self.scanned + 2 * self.skipped + self.placed + self.leaf_ids.len(),
            total: self.input_len.saturating_mul(3),
            phase: self.stage.phase(),
        }
    }

    /// Works on the build until about `units` units (see [`Budget`]) are spent or the tree
    /// is complete. `prims` must be the same input every time.
    pub fn run<O: Observer<P::Point>>(&mut self, prims: &[P], units: usize, observer: &mut O) {
        debug_assert_eq!(prims.len(), self.input_len, "a build runs on one input");
        let mut budget = Budget::new(units);
        while !budget.is_spent() && !self.is_done() {
            let stage = std::mem::replace(&mut self.stage, Stage::Done);
            self.stage = match stage {
                Stage::Scan => self.scan(prims, &mut budget),
                Stage::NextNode => self.next_node(),
                Stage::Bounds { node, next } => self.bounds(node, next, &mut budget),
                Stage::Gather { node, next } => self.gather(node, next, prims, &mut budget),
                Stage::Fit { node, sliced } => self.fit(node, sliced, &mut budget, observer),
                Stage::Bin {
                    node,
                    record,
                    binning,
                    next,
                } => self.bin(node, record, binning, next, &mut budget, observer),
                Stage::Partition {
                    node,
                    record,
                    cut,
                    next,
                    mid,
                } => self.partition(node, record, (cut, next, mid), &mut budget, observer),
                Stage::Median { node, record } => self.median(node, record, &mut budget, observer),
                Stage::Order => self.order(prims, &mut budget),
                Stage::Done => Stage::Done,
            };
        }
    }

    /// The finished tree over `prims` (the input, owned) and the split log (empty unless
    /// asked for).
    pub fn into_bvh(self, prims: Vec<P>) -> (Bvh<B, P>, Vec<SplitRecord>) {
        debug_assert!(self.is_done(), "the tree is complete");
        let mut nodes = self.nodes;
        nodes.shrink_to_fit();
        let bvh = Bvh {
            prims,
            nodes,
            leaf_prims: self.leaf_prims,
            leaf_ids: self.leaf_ids,
            options: self.options,
            build_sah_cost: None,
        }
        .with_build_cost();
        (bvh, self.log.unwrap_or_default())
    }

    /// Computes the next input primitives' boxes and centres, leaving out those that cannot
    /// be indexed; then queues the root.
    fn scan(&mut self, prims: &[P], budget: &mut Budget) -> Stage<P::Point> {
        let start = self.scanned;
        let end = start + budget.chunk(prims.len() - start);
        for (index, prim) in prims[start..end].iter().enumerate() {
            if prim.has_finite_coordinates() {
                self.items.push(BuildPrim {
                    bounds: prim.bounds(),
                    centroid: prim.centroid(),
                    index: (start + index) as u32,
                });
            } else {
                self.skipped += 1;
            }
        }
        budget.spend(end - start);
        self.scanned = end;
        if end < prims.len() {
            return Stage::Scan;
        }
        let n = self.items.len();
        // A binary tree with at least one primitive per leaf has fewer than 2n nodes.
        self.nodes = Vec::with_capacity(n.saturating_mul(2).min(1 << 24));
        self.leaf_prims = Vec::with_capacity(n);
        self.leaf_ids = Vec::with_capacity(n);
        if n == 0 {
            return Stage::Done;
        }
        self.pending.push(Pending {
            start: 0,
            end: n,
            parent: None,
            depth: 0,
            second: false,
        });
        Stage::NextNode
    }

    /// Takes the range the recursion would build next, or moves on to the leaf order.
    fn next_node(&mut self) -> Stage<P::Point> {
        let Some(range) = self.pending.pop() else {
            // Every node is made: the buffers of the node stages are not needed any more.
            self.scratch = Vec::new();
            self.sah = SahScratch::default();
            return Stage::Order;
        };
        Stage::Bounds {
            node: NodeWork {
                range,
                bounds: Aabb::EMPTY,
                centroids: Aabb::EMPTY,
                id: 0,
            },
            next: 0,
        }
    }

    /// Copies the next primitives, now in leaf order, after the previous ones.
    fn order(&mut self, prims: &[P], budget: &mut Budget) -> Stage<P::Point> {
        let start = self.leaf_ids.len();
        let end = start + budget.chunk(self.items.len() - start);
        for item in &self.items[start..end] {
            self.leaf_prims.push(prims[item.index as usize]);
            self.leaf_ids.push(item.index);
        }
        budget.spend(end - start);
        if end < self.items.len() {
            return Stage::Order;
        }
        self.items = Vec::new();
        Stage::Done
    }
}
