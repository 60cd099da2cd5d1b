//! Top-down construction (lecture §3, "Constructing a BVH"): fit a volume around a node's
//! primitives, split them in two by a plane, recurse until a node is small enough.
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
//! second child's index is filled in once the first subtree is built.

use super::build_log::SplitRecord;
use super::split_median::{object_median, spatial_median};
use super::split_sah::{SahScratch, binned_sah};
use super::tree::{BvhNode, is_indexable};
use super::volume::NodeVolume;
use super::{Bvh, BvhOptions, SplitMethod};
use crate::structure::{Event, NodeId, Observer};
use crate::volume::{Aabb, BoundingVolume};
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

/// What the SAH decided for a node.
enum Sah {
    /// Split here (the items are partitioned).
    Split(Split),
    /// Make a leaf.
    Leaf,
    /// The SAH cannot decide: take the object median.
    Fallback,
}

/// Moves the items satisfying `below` to the front, in place; returns how many there are.
pub(super) fn partition<T>(items: &mut [T], below: impl Fn(&T) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..items.len() {
        if below(&items[i]) {
            items.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

/// Builds a tree, reporting every node to `observer` and, when `log` is given, every split
/// decision to it.
pub(super) fn build<B, P, O>(
    prims: &[P],
    options: &BvhOptions,
    observer: &mut O,
    log: Option<&mut Vec<SplitRecord>>,
) -> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    O: Observer<P::Point>,
{
    let items: Vec<BuildPrim<P::Point>> = prims
        .iter()
        .enumerate()
        .filter(|(_, p)| is_indexable(*p))
        .map(|(i, p)| BuildPrim {
            bounds: p.bounds(),
            centroid: p.centroid(),
            index: i as u32,
        })
        .collect();
    let mut builder = Builder {
        prims,
        // A binary tree with at least one primitive per leaf has fewer than 2n nodes.
        nodes: Vec::with_capacity(items.len().saturating_mul(2).min(1 << 24)),
        items,
        options: *options,
        observer,
        log,
        scratch: Vec::new(),
        sah: SahScratch::default(),
    };
    if !builder.items.is_empty() {
        builder.node(0, builder.items.len(), None, 0);
    }
    let Builder { items, nodes, .. } = builder;
    let mut nodes = nodes;
    nodes.shrink_to_fit();
    Bvh {
        prims: prims.to_vec(),
        nodes,
        leaf_prims: items
            .iter()
            .map(|item| prims[item.index as usize])
            .collect(),
        leaf_ids: items.iter().map(|item| item.index).collect(),
        options: *options,
    }
}

struct Builder<'a, B, P: Primitive, O> {
    prims: &'a [P],
    items: Vec<BuildPrim<P::Point>>,
    nodes: Vec<BvhNode<B>>,
    options: BvhOptions,
    observer: &'a mut O,
    log: Option<&'a mut Vec<SplitRecord>>,
    /// Reused buffer for a node's vertices.
    scratch: Vec<P::Point>,
    /// Reused buffers for the SAH binning.
    sah: SahScratch<P::Point>,
}

impl<B, P, O> Builder<'_, B, P, O>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    O: Observer<P::Point>,
{
    /// Creates the node over `items[start..end]` and, recursively, its subtree; returns its
    /// index.
    fn node(&mut self, start: usize, end: usize, parent: Option<u32>, depth: usize) -> u32 {
        let id = self.nodes.len() as u32;
        let (bounds, centroids) = self.items[start..end].iter().fold(
            (Aabb::EMPTY, Aabb::EMPTY),
            |(b, c): (Aabb<P::Point>, Aabb<P::Point>), item| {
                (b.merge(&item.bounds), c.grown(item.centroid))
            },
        );
        let volume = self.fit(start, end, &bounds);
        let count = (end - start) as u32;
        // A leaf until a split is chosen.
        self.nodes.push(BvhNode {
            volume,
            start: start as u32,
            count,
        });
        self.observer.on(Event::BuildNode {
            node: NodeId(id),
            parent: parent.map(NodeId),
            depth: depth as u32,
            prims: count,
        });
        let split = if end - start <= 1 || depth >= self.options.depth_limit() {
            None
        } else {
            self.choose_split(id, start, end, &bounds, &centroids)
        };
        let Some(split) = split else {
            self.observer.on(Event::BuildLeaf {
                node: NodeId(id),
                prims: count,
            });
            return id;
        };
        self.observer.on(Event::BuildSplit {
            node: NodeId(id),
            normal: P::Point::unit_axis(split.axis),
            offset: split.position,
            left: split.left as u32,
            right: (end - start - split.left) as u32,
            cost: split.cost,
        });
        let mid = start + split.left;
        self.node(start, mid, Some(id), depth + 1);
        let right = self.node(mid, end, Some(id), depth + 1);
        let node = &mut self.nodes[id as usize];
        node.start = right;
        node.count = 0;
        id
    }

    /// The node's volume, fitted to its primitives.
    fn fit(&mut self, start: usize, end: usize, bounds: &Aabb<P::Point>) -> B {
        self.scratch.clear();
        if B::NEEDS_VERTICES {
            for item in &self.items[start..end] {
                for v in self.prims[item.index as usize].vertices() {
                    self.scratch.push(v);
                }
            }
        }
        B::fit(bounds, &self.scratch, &self.options)
    }

    /// Decides how to split `items[start..end]` (at least two primitives, above the depth
    /// limit), partitions them, and logs the decision; `None` makes a leaf.
    fn choose_split(
        &mut self,
        id: u32,
        start: usize,
        end: usize,
        bounds: &Aabb<P::Point>,
        centroids: &Aabb<P::Point>,
    ) -> Option<Split> {
        let n = end - start;
        let leaf_size = self.options.leaf_size();
        let mut record = SplitRecord {
            node: NodeId(id),
            method: self.options.method,
            axis: 0,
            position: 0.0,
            planes: Vec::new(),
            bin_costs: Vec::new(),
            chosen_bin: None,
            leaf_cost: n as f32,
            left: 0,
            right: 0,
            made_leaf: false,
        };
        let split = match self.options.method {
            SplitMethod::SpatialMedian | SplitMethod::ObjectMedian if n <= leaf_size => {
                return None;
            }
            SplitMethod::SpatialMedian => spatial_median(&mut self.items[start..end], centroids),
            SplitMethod::ObjectMedian => None,
            SplitMethod::BinnedSah => {
                match self.sah_split(start, end, bounds, centroids, &mut record) {
                    Sah::Split(split) => Some(split),
                    Sah::Leaf => return None,
                    Sah::Fallback => None,
                }
            }
        };
        let split = split.unwrap_or_else(|| {
            record.method = SplitMethod::ObjectMedian;
            record.chosen_bin = None;
            record.planes.clear();
            record.bin_costs.clear();
            object_median(&mut self.items[start..end], centroids)
        });
        self.log_decision(record, &split, n);
        Some(split)
    }

    /// The binned SAH's decision for `items[start..end]`; a split has partitioned them. A
    /// leaf chosen because no split pays is logged here.
    fn sah_split(
        &mut self,
        start: usize,
        end: usize,
        bounds: &Aabb<P::Point>,
        centroids: &Aabb<P::Point>,
        record: &mut SplitRecord,
    ) -> Sah {
        let n = end - start;
        let bins = self.options.bin_count();
        let items = &mut self.items[start..end];
        let Some(curve) = binned_sah(items, bounds, centroids, bins, &mut self.sah) else {
            // Nothing to bin (the centres coincide) or no area to weigh.
            return if n <= self.options.leaf_size() {
                Sah::Leaf
            } else {
                Sah::Fallback
            };
        };
        if self.log.is_some() {
            record.planes = (0..curve.bins - 1).map(|i| curve.plane(i)).collect();
            record.bin_costs = self.sah.costs(&curve).to_vec();
        }
        record.chosen_bin = Some(curve.best);
        let split = Split {
            axis: curve.axis,
            position: curve.plane(curve.best),
            left: curve.left,
            cost: Some(curve.best_cost),
        };
        // Splitting does not pay: a leaf, if it is small enough.
        if n <= self.options.leaf_size() && curve.best_cost >= n as f32 {
            record.made_leaf = true;
            self.log_decision(record.clone(), &split, n);
            return Sah::Leaf;
        }
        let axis = curve.axis;
        let left = partition(items, |item| {
            curve.bin_of(item.centroid.coord(axis)) <= curve.best
        });
        debug_assert_eq!(left, curve.left, "binning and partition disagree");
        Sah::Split(split)
    }

    fn log_decision(&mut self, mut record: SplitRecord, split: &Split, n: usize) {
        if let Some(log) = self.log.as_deref_mut() {
            record.axis = split.axis;
            record.position = split.position;
            record.left = split.left as u32;
            record.right = (n - split.left) as u32;
            log.push(record);
        }
    }
}
