//! The stages of one node, in the recursion's order: merge its primitives' boxes, gather
//! their vertices, fit its volume, push it, then decide between a leaf and a split (SAH
//! binning, a partition, or the object median) and queue its children.
//!
//! Each stage takes the node's state by value and returns the next stage: the same stage
//! with its position when the budget ran out, the following one when it is finished.

use super::median::{object_median, spatial_median_plane};
use super::sah::{SahBinning, SahCurve};
use super::split_log::SplitRecord;
use super::{Budget, BuildPrim, Builder, Cut, Fits, NodeWork, Pending, Split, Stage};
use crate::structure::bvh::SplitMethod;
use crate::structure::bvh::layout::BvhNode;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::bvh::volume::fit_sliced::SlicedFit;
use crate::structure::{Event, NodeId, Observer};
use crate::volume::BoundingVolume;
use crate::{Primitive, Vector};

type NodeStage<P> = Stage<<P as Primitive>::Point>;

impl<B, P> Builder<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Merges the next primitives' boxes and centres into the node's.
    pub(super) fn bounds(
        &mut self,
        mut node: NodeWork<P::Point>,
        next: usize,
        budget: &mut Budget,
    ) -> NodeStage<P> {
        let end = next + budget.chunk(node.len() - next);
        let start = node.range.start;
        for item in &self.items[start + next..start + end] {
            node.bounds = node.bounds.merge(&item.bounds);
            node.centroids = node.centroids.grown(item.centroid);
        }
        budget.spend(end - next);
        if end < node.len() {
            return Stage::Bounds { node, next: end };
        }
        self.scratch.clear();
        if B::NEEDS_VERTICES {
            Stage::Gather { node, next: 0 }
        } else {
            Stage::Fit { node, sliced: None }
        }
    }

    /// Copies the next primitives' vertices into the scratch buffer.
    pub(super) fn gather(
        &mut self,
        node: NodeWork<P::Point>,
        next: usize,
        prims: &[P],
        budget: &mut Budget,
    ) -> NodeStage<P> {
        let end = next + budget.chunk(node.len() - next);
        let start = node.range.start;
        if next == 0 {
            // Room for the whole node at once (exact when every primitive has as many
            // vertices as the first), so that no step pays for copying a grown buffer.
            let per_prim = prims[self.items[start].index as usize].vertices().count();
            self.scratch.reserve(per_prim * node.len());
        }
        for item in &self.items[start + next..start + end] {
            self.scratch.extend(prims[item.index as usize].vertices());
        }
        budget.spend(end - next);
        if end < node.len() {
            return Stage::Gather { node, next: end };
        }
        let sliced = (self.fits == Fits::Sliced && !self.scratch.is_empty())
            .then(|| SlicedFit::for_volume::<B>(&node.bounds, &self.options))
            .flatten();
        Stage::Fit { node, sliced }
    }

    /// Fits the node's volume, in one go or a pass at a time; then makes the node.
    pub(super) fn fit<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        sliced: Option<SlicedFit<P::Point>>,
        budget: &mut Budget,
        observer: &mut O,
    ) -> NodeStage<P> {
        let volume = match sliced {
            None => {
                if !budget.whole(self.scratch.len().max(1)) {
                    return Stage::Fit { node, sliced };
                }
                B::fit(&node.bounds, &self.scratch, &self.options)
            }
            Some(mut fit) => {
                budget.spend(fit.advance(&self.scratch, budget.chunk(usize::MAX)));
                if !fit.is_done() {
                    return Stage::Fit {
                        node,
                        sliced: Some(fit),
                    };
                }
                // `for_volume` chose the fit by `B`, so the volume is a `B`.
                fit.volume::<B>()
                    .unwrap_or_else(|| B::fit(&node.bounds, &self.scratch, &self.options))
            }
        };
        self.make_node(node, volume, observer)
    }

    /// Pushes the node (completing its parent if it is a second child), reports it, and
    /// starts its split, or makes it a leaf.
    fn make_node<O: Observer<P::Point>>(
        &mut self,
        mut node: NodeWork<P::Point>,
        volume: B,
        observer: &mut O,
    ) -> NodeStage<P> {
        let id = self.nodes.len() as u32;
        node.id = id;
        let Pending {
            start,
            end,
            parent,
            depth,
            second,
        } = node.range;
        let count = (end - start) as u32;
        // A leaf until a split is chosen.
        self.nodes.push(BvhNode {
            volume,
            start: start as u32,
            count,
        });
        if let (true, Some(parent)) = (second, parent) {
            let parent = &mut self.nodes[parent as usize];
            parent.start = id;
            parent.count = 0;
        }
        observer.on(Event::BuildNode {
            node: NodeId(id),
            parent: parent.map(NodeId),
            depth: depth as u32,
            prims: count,
        });
        let n = node.len();
        if n <= 1 || depth >= self.options.depth_limit() {
            return self.leaf(&node, observer);
        }
        let record = SplitRecord {
            node: NodeId(id),
            method: self.options.method,
            axis: 0,
            position: 0.0,
            planes: Vec::new(),
            bin_costs: Vec::new(),
            chosen_bin: None,
            leaf_cost: self.options.leaf_cost(n),
            left: 0,
            right: 0,
            made_leaf: false,
        };
        match self.options.method {
            SplitMethod::SpatialMedian | SplitMethod::ObjectMedian
                if n <= self.options.leaf_limit() =>
            {
                self.leaf(&node, observer)
            }
            SplitMethod::SpatialMedian => {
                let (axis, position) = spatial_median_plane(&node.centroids);
                Stage::Partition {
                    node,
                    record,
                    cut: Cut::Below { axis, position },
                    next: 0,
                    mid: 0,
                }
            }
            SplitMethod::ObjectMedian => Stage::Median { node, record },
            SplitMethod::BinnedSah => {
                let (bins, block) = (self.options.bin_count(), self.options.leaf_block);
                match SahBinning::start(&node.bounds, &node.centroids, bins, block, &mut self.sah) {
                    Some(binning) => Stage::Bin {
                        node,
                        record,
                        binning,
                        next: 0,
                    },
                    None => self.no_sah_curve(node, record, observer),
                }
            }
        }
    }

    /// Bins the next primitives; once all are binned, decides by the cheapest plane.
    pub(super) fn bin<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        mut record: SplitRecord,
        binning: SahBinning,
        next: usize,
        budget: &mut Budget,
        observer: &mut O,
    ) -> NodeStage<P> {
        let end = next + budget.chunk(node.len() - next);
        let start = node.range.start;
        binning.add(&self.items[start + next..start + end], &mut self.sah);
        budget.spend(end - next);
        if end < node.len() {
            return Stage::Bin {
                node,
                record,
                binning,
                next: end,
            };
        }
        // Only a logged build keeps every plane's cost.
        let curve = if self.log.is_some() {
            binning.finish(&mut self.sah)
        } else {
            binning.finish_best(&mut self.sah)
        };
        let Some(curve) = curve else {
            return self.no_sah_curve(node, record, observer);
        };
        if self.log.is_some() {
            record.planes = (0..curve.bins - 1).map(|i| curve.plane(i)).collect();
            record.bin_costs = self.sah.costs(&curve).to_vec();
        }
        record.chosen_bin = Some(curve.best);
        let n = node.len();
        // Splitting does not pay: a leaf, if it is small enough.
        if n <= self.options.leaf_limit() && curve.best_cost >= self.options.leaf_cost(n) {
            record.made_leaf = true;
            self.log_decision(record, &sah_split(&curve), n);
            return self.leaf(&node, observer);
        }
        Stage::Partition {
            node,
            record,
            cut: Cut::Sah(curve),
            next: 0,
            mid: 0,
        }
    }

    /// The SAH could not cost a plane (nothing to bin, or no area to weigh): a leaf if the
    /// node is small enough, else the object median.
    fn no_sah_curve<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        record: SplitRecord,
        observer: &mut O,
    ) -> NodeStage<P> {
        if node.len() <= self.options.leaf_limit() {
            self.leaf(&node, observer)
        } else {
            fall_back(node, record)
        }
    }

    /// Moves the next primitives below the cut to the front of the node's range; once all
    /// are moved, splits there (or falls back to the object median when a spatial median
    /// left one side empty).
    pub(super) fn partition<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        record: SplitRecord,
        (cut, next, mut mid): (Cut, usize, usize),
        budget: &mut Budget,
        observer: &mut O,
    ) -> NodeStage<P> {
        let n = node.len();
        let end = next + budget.chunk(n - next);
        let items = &mut self.items[node.range.start..node.range.end];
        for i in next..end {
            if cut.below(&items[i]) {
                items.swap(i, mid);
                mid += 1;
            }
        }
        budget.spend(end - next);
        if end < n {
            return Stage::Partition {
                node,
                record,
                cut,
                next: end,
                mid,
            };
        }
        match cut {
            Cut::Below { axis, position } if mid > 0 && mid < n => {
                let split = Split {
                    axis,
                    position,
                    left: mid,
                    cost: None,
                };
                self.split(node, record, &split, observer)
            }
            Cut::Below { .. } => fall_back(node, record),
            Cut::Sah(curve) => {
                debug_assert_eq!(mid, curve.left, "binning and partition disagree");
                self.split(node, record, &sah_split(&curve), observer)
            }
        }
    }

    /// Splits at the object median, in one go (a selection cannot stop halfway).
    pub(super) fn median<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        record: SplitRecord,
        budget: &mut Budget,
        observer: &mut O,
    ) -> NodeStage<P> {
        if !budget.whole(node.len()) {
            return Stage::Median { node, record };
        }
        let items = &mut self.items[node.range.start..node.range.end];
        let split = object_median(items, &node.centroids);
        self.split(node, record, &split, observer)
    }

    /// Logs and reports the split, and queues both children, the first on top.
    fn split<O: Observer<P::Point>>(
        &mut self,
        node: NodeWork<P::Point>,
        record: SplitRecord,
        split: &Split,
        observer: &mut O,
    ) -> NodeStage<P> {
        let n = node.len();
        self.log_decision(record, split, n);
        observer.on(Event::BuildSplit {
            node: NodeId(node.id),
            normal: P::Point::unit_axis(split.axis),
            offset: split.position,
            left: split.left as u32,
            right: (n - split.left) as u32,
            cost: split.cost,
        });
        let Pending {
            start, end, depth, ..
        } = node.range;
        let mid = start + split.left;
        for (start, end, second) in [(mid, end, true), (start, mid, false)] {
            self.pending.push(Pending {
                start,
                end,
                parent: Some(node.id),
                depth: depth + 1,
                second,
            });
        }
        Stage::NextNode
    }

    /// Reports the node as a leaf.
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        node: &NodeWork<P::Point>,
        observer: &mut O,
    ) -> NodeStage<P> {
        observer.on(Event::BuildLeaf {
            node: NodeId(node.id),
            prims: node.len() as u32,
        });
        self.placed += node.len();
        Stage::NextNode
    }

    fn log_decision(&mut self, mut record: SplitRecord, split: &Split, n: usize) {
        if let Some(log) = self.log.as_mut() {
            record.axis = split.axis;
            record.position = split.position;
            record.left = split.left as u32;
            record.right = (n - split.left) as u32;
            log.push(record);
        }
    }
}

/// The object median where the chosen method could not split: logged as such.
fn fall_back<V: Vector>(node: NodeWork<V>, mut record: SplitRecord) -> Stage<V> {
    record.method = SplitMethod::ObjectMedian;
    record.chosen_bin = None;
    record.planes.clear();
    record.bin_costs.clear();
    Stage::Median { node, record }
}

/// The split at the curve's cheapest plane.
fn sah_split(curve: &SahCurve) -> Split {
    Split {
        axis: curve.axis,
        position: curve.plane(curve.best),
        left: curve.left,
        cost: Some(curve.best_cost),
    }
}

impl Cut {
    /// Whether the primitive goes to the first child.
    fn below<V: Vector>(&self, item: &BuildPrim<V>) -> bool {
        match self {
            Self::Below { axis, position } => item.centroid.coord(*axis) < *position,
            Self::Sah(curve) => curve.bin_of(item.centroid.coord(curve.axis)) <= curve.best,
        }
    }
}
