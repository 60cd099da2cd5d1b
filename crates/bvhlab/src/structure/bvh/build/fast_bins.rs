//! The SAH binning of the one-go build ([`fast`](super::fast)) in four-lane boxes: the
//! decisions of [`SahBinning`](super::sah::SahBinning) (Wald 2007;
//! pbrt-v4 §7.3.2), computed the same way, on boxes whose merge is one vector minimum and
//! one vector maximum.
//!
//! Bit for bit the same choice: the same bins (`((c - lo) * scale) as usize`, clamped), the
//! same boxes in each (a minimum and a maximum of finite numbers do not depend on the
//! order), the areas from the same `f32` side lengths summed in `f64` in the same order, the
//! same sweeps over the occupied bins and the same strict comparisons, axis by axis.
//!
//! Where a build spends its time (issue 33, `perf` of `Bvh4::build` on the three meshes,
//! before the sides' boxes came from the bins): 40% of the samples in the build's own loop,
//! into which the binning is inlined (most of them on the binning's loads and merges), 23%
//! in the partition, 17% in the sweeps. Tried on the binning and the sweep and not kept.
//! Each was timed against the build without it: old and new binaries in turn, three runs
//! of 15 builds each, on one core, on the bunny, the dragon and the ogre. Unless said
//! otherwise, each gave the same trees.
//!
//! | tried | build time, new ÷ old (below 1 is faster) |
//! |---|---|
//! | every other item of a node of 64 or more into a second set of bins, merged after the pass (to halve the chains of stores into one bin) | 1.05-1.09 |
//! | the three axes' bins from one four-lane product (glam's `as_uvec4`) | 1.02-1.03 |
//! | the bin clamped as an integer after the conversion | 1.17-1.20 |
//! | the three axes written out by hand for a node binned on all three | 1.12-1.13 |
//! | the sweep dividing by the node's area only when the sum of the sides' costs falls | slower: the sweep went from 18% to 23% of the samples |
//! | the sweep's `ceil(n / leaf_block)` as a shift for a power of two, and the cost above each plane multiplied out in the first pass (two integer divisions fewer per plane) | 0.99-1.00 |
//!
//! Binning only the axis along which the centres spread most, in nodes of at least 4,096
//! primitives (as Wald 2007 does everywhere), was 0.93-1.01 in one run. It changes the
//! tree: SAH costs were 0.1-1.2% higher. In nodes of at least 256 it was 0.88-0.97, with
//! SAH costs 0.4-1.4% higher. It would need an option that the resumable builder follows
//! too, so it was not kept.

use glam::Vec4;

use super::BvhOptions;
use super::sah::MAX_BINS;
use crate::Vector;
use crate::volume::Aabb;

/// A box in four lanes (`x`, `y`, `z`, and a lane that stays 0; `z` is 0 in 2D).
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneBox {
    pub min: Vec4,
    pub max: Vec4,
}

impl LaneBox {
    pub const EMPTY: Self = Self {
        min: Vec4::new(f32::INFINITY, f32::INFINITY, f32::INFINITY, 0.0),
        max: Vec4::new(f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY, 0.0),
    };

    /// The box around `self` and `other` (their coordinates are never NaN).
    #[inline]
    pub fn merge(&self, other: &Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The box around `self` and the point `p`.
    #[inline]
    pub fn grown(&self, p: Vec4) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// `sah.rs`'s `half_area`: half the surface area (3D) or half the perimeter (2D),
    /// from the `f32` side lengths, in `f64`.
    #[inline]
    pub fn half_area<V: Vector>(&self) -> f64 {
        let s = self.max - self.min;
        let (x, y, z) = (f64::from(s.x), f64::from(s.y), f64::from(s.z));
        if V::DIM == 2 {
            x + y
        } else {
            x * y + y * z + z * x
        }
    }

    pub fn of_aabb<V: Vector>(b: &Aabb<V>) -> Self {
        Self {
            min: lanes(b.min),
            max: lanes(b.max),
        }
    }

    pub fn to_aabb<V: Vector>(self) -> Aabb<V> {
        Aabb::new(point(self.min), point(self.max))
    }
}

/// A point's coordinates in lanes (0 beyond its dimension).
#[inline]
pub(super) fn lanes<V: Vector>(p: V) -> Vec4 {
    let c = |i: usize| if i < V::DIM { p.coord(i) } else { 0.0 };
    Vec4::new(c(0), c(1), c(2), 0.0)
}

/// The point of the first `V::DIM` lanes.
#[inline]
fn point<V: Vector>(l: Vec4) -> V {
    let mut p = V::ZERO;
    for (i, c) in l.to_array().into_iter().enumerate().take(V::DIM) {
        p.set_coord(i, c);
    }
    p
}

/// The bins of one axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct AxisBins {
    pub axis: usize,
    pub lo: f32,
    pub scale: f32,
    /// The last bin, `bins - 1`.
    pub last: f32,
}

impl AxisBins {
    /// The bin of a centre coordinate; NaN and out-of-range values are clamped into range
    /// (`sah.rs`'s `as usize` then `min`: the same bin, through a cheaper conversion).
    /// `bins` is at most [`MAX_BINS`], so the mask only tells the compiler the index fits.
    #[inline]
    pub fn bin_of(&self, coord: f32) -> usize {
        // `max` and `min` take NaN to 0 and bound the value, so the conversion needs no
        // saturation of its own.
        ((((coord - self.lo) * self.scale).max(0.0).min(self.last)) as u32) as usize
            & (MAX_BINS - 1)
    }
}

/// The cheapest plane: after bin `best` on `axis`, with `left` primitives below it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cheapest {
    pub bins: AxisBins,
    pub best: usize,
    pub cost: f32,
    pub left: usize,
    /// The boxes of the primitives below and above the plane: the merged boxes of its
    /// bins, so that the partition need not merge them again (the same primitives, so the
    /// same minimum and maximum, up to the sign of a zero, which the node's fit removes and
    /// the areas do not see, as with the bins merged across threads).
    pub sides: [LaneBox; 2],
}

/// What a node's binning is planned on: its area, and the `k` axes along which its centres
/// differ (the first `k` of `axes`).
#[derive(Clone, Copy, Debug)]
struct Plan {
    node_area: f64,
    axes: [AxisBins; 3],
    k: usize,
}

impl Plan {
    fn axes(&self) -> &[AxisBins] {
        &self.axes[..self.k]
    }
}

/// The per-bin boxes and counts of every axis, reused from node to node: only the bins a
/// node filled are cleared after it.
#[derive(Clone, Debug)]
pub(super) struct Binner {
    bins: usize,
    /// The SAH counts a side's primitives in groups of this many
    /// ([`BvhOptions::leaf_block`]).
    leaf_block: usize,
    boxes: [[LaneBox; MAX_BINS]; 3],
    counts: [[u32; MAX_BINS]; 3],
    occupied: [u64; 3],
    /// The sweep's area and count above each occupied bin (no need to clear between uses).
    above: [(f64, usize); MAX_BINS],
}

impl Binner {
    pub fn new(options: &BvhOptions) -> Box<Self> {
        Self::with_sizes(options.bin_count(), options.leaf_block)
    }

    fn with_sizes(bins: usize, leaf_block: usize) -> Box<Self> {
        Box::new(Self {
            bins: bins.clamp(2, MAX_BINS),
            leaf_block: leaf_block.max(1),
            boxes: [[LaneBox::EMPTY; MAX_BINS]; 3],
            counts: [[0; MAX_BINS]; 3],
            occupied: [0; 3],
            above: [(0.0, 0); MAX_BINS],
        })
    }

    /// The node's cheapest plane over `items` (their boxes, centres, in order), or `None`
    /// when the SAH says nothing (no area, or no axis along which the centres differ).
    #[inline]
    pub fn cheapest<V: Vector>(
        &mut self,
        bounds: &LaneBox,
        centroids: &LaneBox,
        items: &[super::fast::Item],
    ) -> Option<Cheapest> {
        let plan = self.plan::<V>(bounds, centroids)?;
        if let [a, b] = items {
            return self.cheapest_of_two::<V>(plan.axes(), [a, b], plan.node_area);
        }
        self.fill_planned(&plan, items);
        self.finish::<V>(&plan)
    }

    /// The bins of a node: its area and the axes along which its centres differ, or `None`
    /// when it has no area to cost splits by.
    #[inline]
    fn plan<V: Vector>(&self, bounds: &LaneBox, centroids: &LaneBox) -> Option<Plan> {
        let node_area = bounds.half_area::<V>();
        if !(node_area > 0.0 && node_area.is_finite()) {
            return None;
        }
        // The axes along which the centres differ, in axis order.
        let mut axes = [AxisBins {
            axis: 0,
            lo: 0.0,
            scale: 0.0,
            last: 0.0,
        }; 3];
        let mut k = 0;
        for axis in 0..V::DIM {
            let lo = centroids.min[axis];
            let extent = centroids.max[axis] - lo;
            if extent > 0.0 && extent.is_finite() {
                axes[k] = AxisBins {
                    axis,
                    lo,
                    scale: self.bins as f32 / extent,
                    last: (self.bins - 1) as f32,
                };
                k += 1;
            }
        }
        Some(Plan { node_area, axes, k })
    }

    /// Puts every item in its bin on each planned axis.
    #[inline]
    fn fill_planned(&mut self, plan: &Plan, items: &[super::fast::Item]) {
        match plan.k {
            3 => self.fill::<3>(&plan.axes, items),
            2 => self.fill::<2>(&plan.axes, items),
            1 => self.fill::<1>(&plan.axes, items),
            _ => {}
        }
    }

    /// The cheapest plane of the filled bins, axis by axis (the first of equal costs); the
    /// bins are emptied for the next node.
    #[inline]
    fn finish<V: Vector>(&mut self, plan: &Plan) -> Option<Cheapest> {
        let mut best: Option<Cheapest> = None;
        for &bins in plan.axes() {
            let curve = self.sweep::<V>(bins, plan.node_area);
            if best.is_none_or(|b| curve.cost < b.cost) {
                best = Some(curve);
            }
        }
        if let Some(best) = &mut best {
            best.sides = self.sides(best.bins.axis, best.best);
        }
        self.clear();
        best.filter(|b| b.cost.is_finite())
    }

    /// [`cheapest`](Self::cheapest) with the items binned on every core: each thread fills
    /// bins of its own over consecutive chunks of at least `chunk` items, and the bins are
    /// merged. A bin's count is a sum of integers and its box a minimum and a maximum, so
    /// the merged bins equal those one pass fills, whatever the chunks (up to the sign of a
    /// zero, which the sweep's areas do not see: a zero side makes a zero product, and the
    /// costs add it to `1.0`), and the sweep over them is the same sweep.
    #[cfg(feature = "parallel")]
    pub fn cheapest_parallel<V: Vector>(
        &mut self,
        bounds: &LaneBox,
        centroids: &LaneBox,
        items: &[super::fast::Item],
        chunk: usize,
    ) -> Option<Cheapest> {
        use rayon::prelude::*;
        let plan = self.plan::<V>(bounds, centroids)?;
        if plan.k == 0 || items.len() <= 2 {
            return self.cheapest::<V>(bounds, centroids, items);
        }
        let filled = items
            .par_chunks(chunk.max(1))
            .map(|part| {
                let mut binner = Self::with_sizes(self.bins, self.leaf_block);
                binner.fill_planned(&plan, part);
                binner
            })
            .reduce_with(|mut a, b| {
                a.absorb(&b);
                a
            });
        if let Some(filled) = filled {
            self.absorb(&filled);
        }
        self.finish::<V>(&plan)
    }

    /// Adds `other`'s bins to these.
    #[cfg(feature = "parallel")]
    fn absorb(&mut self, other: &Self) {
        for axis in 0..3 {
            let mut mask = other.occupied[axis];
            self.occupied[axis] |= mask;
            while mask != 0 {
                let i = mask.trailing_zeros() as usize;
                self.boxes[axis][i] = self.boxes[axis][i].merge(&other.boxes[axis][i]);
                self.counts[axis][i] += other.counts[axis][i];
                mask &= mask - 1;
            }
        }
    }

    /// [`cheapest`](Self::cheapest) of a node of two items (a third of the calls on a mesh),
    /// without the bins: on each axis either both fall in one bin (no plane) or the one
    /// plane after the lower bin has that item's box below it and the other's above, and
    /// the sweeps' merges with the empty box give each box itself.
    fn cheapest_of_two<V: Vector>(
        &self,
        axes: &[AxisBins],
        items: [&super::fast::Item; 2],
        node_area: f64,
    ) -> Option<Cheapest> {
        let mut best: Option<Cheapest> = None;
        for &axis_bins in axes {
            let axis = axis_bins.axis;
            let [i, j] = items.map(|item| axis_bins.bin_of(item.centroid[axis]));
            let mut curve = Cheapest {
                bins: axis_bins,
                best: 0,
                cost: f32::INFINITY,
                left: 0,
                sides: [LaneBox::EMPTY; 2],
            };
            if i != j {
                let (low, high) = if i < j { (0, 1) } else { (1, 0) };
                let area_low = items[low].bounds.half_area::<V>();
                let area_high = items[high].bounds.half_area::<V>();
                let one = self.units(1);
                curve.cost = (1.0 + (area_low * one + area_high * one) / node_area) as f32;
                curve.best = i.min(j);
                curve.left = 1;
                curve.sides = [items[low].bounds, items[high].bounds];
            }
            if best.is_none_or(|b| curve.cost < b.cost) {
                best = Some(curve);
            }
        }
        best.filter(|b| b.cost.is_finite())
    }

    /// Puts every item in its bin on each of the first `K` axes.
    #[inline]
    fn fill<const K: usize>(&mut self, axes: &[AxisBins; 3], items: &[super::fast::Item]) {
        // The occupied bits stay in registers through the loop (in `self` each item would
        // read back the previous item's store).
        let mut occupied = [0u64; K];
        for item in items {
            for (bin_axis, occupied) in axes[..K].iter().zip(&mut occupied) {
                let axis = bin_axis.axis;
                let i = bin_axis.bin_of(item.centroid[axis]);
                *occupied |= 1 << i;
                let b = &mut self.boxes[axis][i];
                *b = b.merge(&item.bounds);
                self.counts[axis][i] += 1;
            }
        }
        for (bin_axis, occupied) in axes[..K].iter().zip(occupied) {
            self.occupied[bin_axis.axis] = occupied;
        }
    }

    /// The cheapest plane of one axis, costed after each occupied bin but the last (a plane
    /// after an empty bin costs what the one before it costs and never wins the strict
    /// comparison, as `finish_best` explains).
    fn sweep<V: Vector>(&mut self, bins: AxisBins, node_area: f64) -> Cheapest {
        let axis = bins.axis;
        let mut occupied = [0u8; MAX_BINS];
        let mut m = 0;
        let mut mask = self.occupied[axis];
        while mask != 0 {
            occupied[m] = mask.trailing_zeros() as u8;
            mask &= mask - 1;
            m += 1;
        }
        let occupied = &occupied[..m];
        let (boxes, counts) = (&self.boxes[axis], &self.counts[axis]);
        let block = self.leaf_block;
        let units = |n: usize| n.div_ceil(block) as f64;
        // Sweep from the right: `above[j]` is everything after occupied bin `j`.
        let above = &mut self.above;
        let (mut acc, mut n) = (LaneBox::EMPTY, 0usize);
        for j in (1..m).rev() {
            let i = usize::from(occupied[j]);
            acc = acc.merge(&boxes[i]);
            n += counts[i] as usize;
            above[j - 1] = (acc.half_area::<V>(), n);
        }
        let mut best = Cheapest {
            bins,
            best: 0,
            cost: f32::INFINITY,
            left: 0,
            sides: [LaneBox::EMPTY; 2],
        };
        let (mut acc, mut n) = (LaneBox::EMPTY, 0usize);
        for (j, &i) in occupied.iter().enumerate().take(m.saturating_sub(1)) {
            let i = usize::from(i);
            acc = acc.merge(&boxes[i]);
            n += counts[i] as usize;
            let (area_above, n_above) = above[j];
            let cost = (1.0
                + (acc.half_area::<V>() * units(n) + area_above * units(n_above)) / node_area)
                as f32;
            if cost < best.cost {
                best.best = i;
                best.cost = cost;
                best.left = n;
            }
        }
        best
    }

    /// What the SAH counts for a side of `n` primitives: `n` tests in groups of
    /// `leaf_block` (exact in `f64`).
    #[inline]
    fn units(&self, n: usize) -> f64 {
        n.div_ceil(self.leaf_block) as f64
    }

    /// The merged boxes of the occupied bins of `axis` up to `best` and after it.
    fn sides(&self, axis: usize, best: usize) -> [LaneBox; 2] {
        let mut sides = [LaneBox::EMPTY; 2];
        let mut mask = self.occupied[axis];
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            let side = &mut sides[usize::from(i > best)];
            *side = side.merge(&self.boxes[axis][i]);
            mask &= mask - 1;
        }
        sides
    }

    /// Empties the bins the node used.
    fn clear(&mut self) {
        for axis in 0..3 {
            let mut mask = std::mem::take(&mut self.occupied[axis]);
            while mask != 0 {
                let i = mask.trailing_zeros() as usize;
                self.boxes[axis][i] = LaneBox::EMPTY;
                self.counts[axis][i] = 0;
                mask &= mask - 1;
            }
        }
    }
}
