//! The binned surface area heuristic (`MacDonald` and Booth, "Heuristics for ray tracing using
//! space subdivision", 1990; binning after Wald, "On fast Construction of SAH-based Bounding
//! Volume Hierarchies", 2007, and pbrt-v4 §7.3.2).
//!
//! The centres' box is cut into equal bins along each axis; each primitive falls into the
//! bin of its centre, and each bin keeps the box and count of its primitives. Every boundary
//! between bins is a candidate plane, costed as `C_trav + Σ A(child)/A(node) N(child)` with
//! `C_trav = C_isect = 1`: the probability that a ray through the node also passes through a
//! child is the ratio of their surface areas (perimeters in 2D). Two sweeps over the bins
//! cost every plane in `O(bins)`, so a node costs `O(n + bins)` per axis.
//!
//! Areas are summed in `f64`: with coordinates near 1e20 a surface area overflows `f32`.

use super::BuildPrim;
use crate::Vector;
use crate::volume::{Aabb, BoundingVolume};

/// The most bins per axis ([`BvhOptions::bins`] is clamped to it).
///
/// [`BvhOptions::bins`]: crate::structure::bvh::BvhOptions::bins
pub(super) const MAX_BINS: usize = 64;

/// The cheapest plane of the best axis; its cost curve is in the [`SahScratch`].
#[derive(Clone, Copy, Debug)]
pub(super) struct SahCurve {
    /// The axis whose cheapest plane is cheapest overall.
    pub axis: usize,
    /// The bin count.
    pub bins: usize,
    /// Where the bins start on `axis`.
    pub lo: f32,
    /// Bins per unit length.
    pub scale: f32,
    /// The cheapest plane (the boundary after this bin).
    pub best: usize,
    /// Its cost.
    pub best_cost: f32,
    /// Primitives on its low side.
    pub left: usize,
}

impl SahCurve {
    /// The position of the plane after bin `i`.
    #[inline]
    pub fn plane(&self, i: usize) -> f32 {
        self.lo + (i + 1) as f32 / self.scale
    }

    /// The bin of a centre coordinate; NaN and out-of-range values are clamped into range.
    #[inline]
    pub fn bin_of(&self, coord: f32) -> usize {
        (((coord - self.lo) * self.scale) as usize).min(self.bins - 1)
    }
}

/// The buffers of the binning, kept by the builder and reused for every node, so that a
/// node costs `O(n + bins)` and not a fresh `MAX_BINS`-sized array per axis.
#[derive(Clone, Debug, Default)]
pub(super) struct SahScratch<V: Vector> {
    /// Per axis, per bin: the box and count of its primitives.
    bins: Vec<(Aabb<V>, usize)>,
    /// Per plane: the area and count of everything above it.
    above: Vec<(f64, usize)>,
    /// Per axis, per plane: the cost (`+inf` where a side is empty), `bins - 1` per axis.
    costs: Vec<f32>,
    /// Per axis, which bins hold a primitive (bit `i`: bin `i`; [`MAX_BINS`] is 64). Only
    /// those bins differ from the empty bin, and only they are cleared after a node.
    occupied: [u64; 3],
}

impl<V: Vector> SahScratch<V> {
    /// The cost of each plane of the curve's axis.
    pub fn costs(&self, curve: &SahCurve) -> &[f32] {
        let per_axis = curve.bins - 1;
        &self.costs[curve.axis * per_axis..(curve.axis + 1) * per_axis]
    }
}

/// Half the surface area (3D) or half the perimeter (2D) of a box, in `f64`. Only called on
/// boxes that hold a primitive (never the empty box).
fn half_area<V: Vector>(b: &Aabb<V>) -> f64 {
    let s = (b.max - b.min).to_dvec3();
    if V::DIM == 2 {
        s.x + s.y
    } else {
        s.x * s.y + s.y * s.z + s.z * s.x
    }
}

/// The binning of one node, filled a chunk of primitives at a time so that a resumable
/// build can spread a large node over several steps: [`start`](Self::start), then
/// [`add`](Self::add) over the node's primitives in order, then [`finish`](Self::finish).
/// Adding in chunks merges the same boxes in the same order as adding all at once.
#[derive(Clone, Copy, Debug)]
pub(super) struct SahBinning {
    /// One curve per axis that can be binned (a non-zero, finite extent of the centres).
    curves: [Option<SahCurve>; 3],
    /// Half the node's surface area (perimeter in 2D).
    node_area: f64,
    /// A side's primitives are counted in groups of this many
    /// ([`BvhOptions::leaf_block`](super::BvhOptions::leaf_block)).
    leaf_block: usize,
}

impl SahBinning {
    /// Prepares the bins of every axis with a non-zero, finite extent of the centres' box.
    /// `None` when the node's area is zero or infinite: the heuristic says nothing then.
    pub fn start<V: Vector>(
        bounds: &Aabb<V>,
        centroids: &Aabb<V>,
        bins: usize,
        leaf_block: usize,
        scratch: &mut SahScratch<V>,
    ) -> Option<Self> {
        let node_area = half_area(bounds);
        if !(node_area > 0.0 && node_area.is_finite()) {
            return None;
        }
        let bins = bins.clamp(2, MAX_BINS);
        let curves = std::array::from_fn(|axis| {
            let lo = centroids.min.coord(axis.min(V::DIM - 1));
            let extent = centroids.max.coord(axis.min(V::DIM - 1)) - lo;
            (axis < V::DIM && extent > 0.0 && extent.is_finite()).then_some(SahCurve {
                axis,
                bins,
                lo,
                scale: bins as f32 / extent,
                best: 0,
                best_cost: f32::INFINITY,
                left: 0,
            })
        });
        // Every bin is empty between nodes (`finish` clears the bins it used), so only a
        // change of the bin count needs fresh bins.
        if scratch.bins.len() != V::DIM * bins {
            scratch.bins.clear();
            scratch.bins.resize(V::DIM * bins, (Aabb::EMPTY, 0));
            scratch.occupied = [0; 3];
        }
        Some(Self {
            curves,
            node_area,
            leaf_block: leaf_block.max(1),
        })
    }

    /// What the SAH counts for a side of `n` primitives: `n` tests in groups of
    /// `leaf_block` (exact in `f64`).
    #[inline]
    fn units(&self, n: usize) -> f64 {
        n.div_ceil(self.leaf_block) as f64
    }

    /// Puts each primitive into its bin on every binned axis.
    pub fn add<V: Vector>(&self, items: &[BuildPrim<V>], scratch: &mut SahScratch<V>) {
        for item in items {
            for curve in self.curves.iter().flatten() {
                let axis = curve.axis;
                let index = curve.bin_of(item.centroid.coord(axis));
                scratch.occupied[axis] |= 1 << index;
                let bin = &mut scratch.bins[axis * curve.bins + index];
                bin.0 = bin.0.merge(&item.bounds);
                bin.1 += 1;
            }
        }
    }

    /// Costs every plane and returns the cheapest axis's (its curve stays in `scratch`).
    /// `None` when no axis could be binned (the centres coincide).
    pub fn finish<V: Vector>(&self, scratch: &mut SahScratch<V>) -> Option<SahCurve> {
        let best = self.finish_dense(scratch);
        self.clear(scratch);
        best
    }

    /// [`finish`](Self::finish) without the cost curve (`scratch`'s costs are left
    /// unset): only the planes just after an occupied bin can be cheapest, so only they are
    /// costed, `O(occupied bins)` instead of `O(bins)` per axis, which is most of a small
    /// node's work. The cheapest plane, its cost and its count are those of `finish`, bit
    /// for bit: a plane after an empty bin has the same boxes and counts on both sides as
    /// the plane before it (merging an empty box changes nothing), so it costs the same and
    /// never wins the strict comparison; the occupied bins are merged in the same order.
    pub fn finish_best<V: Vector>(&self, scratch: &mut SahScratch<V>) -> Option<SahCurve> {
        let mut best: Option<SahCurve> = None;
        for mut curve in self.curves.into_iter().flatten() {
            let axis = curve.axis;
            let axis_bins = &scratch.bins[axis * curve.bins..(axis + 1) * curve.bins];
            let mut occupied = [0u8; MAX_BINS];
            let mut m = 0;
            let mut mask = scratch.occupied[axis];
            while mask != 0 {
                occupied[m] = mask.trailing_zeros() as u8;
                mask &= mask - 1;
                m += 1;
            }
            let occupied = &occupied[..m];
            // Sweep from the right: above[j] is everything after occupied bin j.
            let mut above = [(0.0f64, 0usize); MAX_BINS];
            let (mut acc, mut n) = (Aabb::<V>::EMPTY, 0);
            for j in (1..m).rev() {
                let bin = &axis_bins[usize::from(occupied[j])];
                acc = acc.merge(&bin.0);
                n += bin.1;
                above[j - 1] = (half_area(&acc), n);
            }
            // Sweep from the left, costing the plane after each occupied bin but the last.
            let (mut acc, mut n) = (Aabb::<V>::EMPTY, 0);
            for (j, &index) in occupied.iter().enumerate().take(m.saturating_sub(1)) {
                let bin = &axis_bins[usize::from(index)];
                acc = acc.merge(&bin.0);
                n += bin.1;
                let (area_above, n_above) = above[j];
                let cost = (1.0
                    + (half_area(&acc) * self.units(n) + area_above * self.units(n_above))
                        / self.node_area) as f32;
                if cost < curve.best_cost {
                    curve.best = usize::from(index);
                    curve.best_cost = cost;
                    curve.left = n;
                }
            }
            if best.is_none_or(|b| curve.best_cost < b.best_cost) {
                best = Some(curve);
            }
        }
        self.clear(scratch);
        best.filter(|curve| curve.best_cost.is_finite())
    }

    /// Empties the bins this node used, for the next node.
    fn clear<V: Vector>(&self, scratch: &mut SahScratch<V>) {
        for curve in self.curves.iter().flatten() {
            let axis = curve.axis;
            let mut mask = std::mem::take(&mut scratch.occupied[axis]);
            while mask != 0 {
                let index = mask.trailing_zeros() as usize;
                scratch.bins[axis * curve.bins + index] = (Aabb::EMPTY, 0);
                mask &= mask - 1;
            }
        }
    }

    /// Costs every plane of every binned axis into `scratch`'s cost curve; the cheapest.
    fn finish_dense<V: Vector>(&self, scratch: &mut SahScratch<V>) -> Option<SahCurve> {
        let bins = self.curves.iter().flatten().map(|c| c.bins).next()?;
        scratch.costs.clear();
        scratch.costs.resize(V::DIM * (bins - 1), f32::INFINITY);
        let mut best: Option<SahCurve> = None;
        for mut curve in self.curves.into_iter().flatten() {
            let axis = curve.axis;
            let axis_bins = &scratch.bins[axis * bins..(axis + 1) * bins];
            // Sweep from the right: the area and count above each plane.
            scratch.above.clear();
            scratch.above.resize(bins - 1, (0.0, 0));
            let (mut acc, mut n) = (Aabb::<V>::EMPTY, 0);
            for i in (1..bins).rev() {
                acc = acc.merge(&axis_bins[i].0);
                n += axis_bins[i].1;
                scratch.above[i - 1] = (half_area(&acc), n);
            }
            // Sweep from the left, costing each plane.
            let costs = &mut scratch.costs[axis * (bins - 1)..(axis + 1) * (bins - 1)];
            let (mut acc, mut n) = (Aabb::<V>::EMPTY, 0);
            for i in 0..bins - 1 {
                acc = acc.merge(&axis_bins[i].0);
                n += axis_bins[i].1;
                let (area_above, n_above) = scratch.above[i];
                if n == 0 || n_above == 0 {
                    continue;
                }
                let cost = 1.0
                    + (half_area(&acc) * self.units(n) + area_above * self.units(n_above))
                        / self.node_area;
                costs[i] = cost as f32;
                if costs[i] < curve.best_cost {
                    curve.best = i;
                    curve.best_cost = costs[i];
                    curve.left = n;
                }
            }
            if best.is_none_or(|b| curve.best_cost < b.best_cost) {
                best = Some(curve);
            }
        }
        best.filter(|curve| curve.best_cost.is_finite())
    }
}
