//! The median builder: split at the median of the primitives' centres (Bentley, "Multidimensional
//! Binary Search Trees Used for Associative Searching", 1975), along the longest axis of the
//! node's cell or round robin by depth.
//!
//! The median is found by selection, O(n) per node, so the build is O(n log n). When the median
//! lies on the cell's boundary (many centres there) the spatial midpoint is used instead; when
//! neither separates the primitives on any axis (every one straddles, or all are identical) the
//! node is a leaf.

use super::{ABOVE, BELOW, Builder, Subtree};
use crate::structure::Observer;
use crate::structure::kdtree::options::AxisRule;
use crate::structure::plane_tree::share_budget;
use crate::volume::Aabb;
use crate::{Primitive, Vector};

/// The order in which axes are tried at a node.
fn axis_order<V: Vector>(cell: &Aabb<V>, rule: AxisRule, depth: usize) -> Vec<usize> {
    let size = cell.max - cell.min;
    match rule {
        AxisRule::LongestAxis => {
            let mut axes: Vec<usize> = (0..V::DIM).collect();
            axes.sort_by(|&a, &b| size.coord(b).total_cmp(&size.coord(a)));
            axes
        }
        AxisRule::RoundRobin => (0..V::DIM).map(|i| (depth + i) % V::DIM).collect(),
    }
}

/// Where to split `cell` on `axis`: the median centre, or the midpoint when the median is not
/// strictly inside the cell; `None` when the cell is too thin to split there.
fn split_position<P: Primitive>(
    prims: &[P],
    refs: &[u32],
    cell: &Aabb<P::Point>,
    axis: usize,
) -> Option<f32> {
    let (lo, hi) = (cell.min.coord(axis), cell.max.coord(axis));
    let inside = |s: f32| lo < s && s < hi;
    let mut centres: Vec<f32> = refs
        .iter()
        .map(|&r| prims[r as usize].centroid().coord(axis))
        .collect();
    let mid = centres.len() / 2;
    let (_, median, _) = centres.select_nth_unstable_by(mid, f32::total_cmp);
    let midpoint = lo * 0.5 + hi * 0.5;
    [*median, midpoint].into_iter().find(|&s| inside(s))
}

/// Builds the subtree over `refs` and returns its root.
pub(crate) fn build_median<P: Primitive, O: Observer<P::Point>>(
    b: &mut Builder<'_, P, O>,
    rule: AxisRule,
    refs: Vec<u32>,
    at: Subtree<P::Point>,
) -> u32 {
    let n = refs.len();
    let id = b.begin(at.parent, at.depth, n);
    if b.must_stop(n, at.depth) {
        return b.leaf(id, refs);
    }
    for axis in axis_order(&at.cell, rule, at.depth) {
        let Some(split) = split_position(b.prims, &refs, &at.cell, axis) else {
            continue;
        };
        let counts = b.classify(&refs, &at.cell, axis, split, true);
        if counts[0] == n || counts[1] == n {
            continue;
        }
        let Some(budgets) = share_budget(at.budget, counts) else {
            continue;
        };
        b.inner(id, axis, split, counts, None);
        let below = b.on_side(&refs, BELOW, counts[0]);
        let above = b.on_side(&refs, ABOVE, counts[1]);
        drop(refs);
        let [below_at, above_at] = at.children(id, axis, split, budgets);
        build_median(b, rule, below, below_at);
        b.above_follows(id);
        build_median(b, rule, above, above_at);
        return id;
    }
    b.leaf(id, refs)
}
