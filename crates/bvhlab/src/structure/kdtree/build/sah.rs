//! The SAH builder: at each node, the plane of least surface-area-heuristic cost among the
//! primitives' bound edges (pbrt-v3 §4.4.2), found by one sweep over the node's sorted edge
//! events per axis ([`super::sah_events`]; Wald and Havran 2006), in O(n) per node and
//! O(n log n) in all.
//!
//! Primitives lying in a candidate plane are costed on either side and put on the cheaper one
//! (Wald and Havran §3.3). The node becomes a leaf as pbrt decides: when the best split costs
//! more than four times the leaf for a small node, or after three splits in a row that cost
//! more than their leaves ("bad refines", which may still pay off further down).

use super::sah_events::{EventArena, Events};
use super::{Builder, Subtree};
use crate::structure::Observer;
use crate::structure::kdtree::options::SahCosts;
use crate::structure::plane_tree::share_budget;
use crate::volume::Aabb;
use crate::{Primitive, Vector};

/// The cheapest plane found.
#[derive(Clone, Copy, Debug)]
struct Best {
    axis: usize,
    pos: f32,
    planar_below: bool,
    cost: f64,
}

/// The surface area (perimeter in 2D) of a box with these extents, in `f64` so that huge
/// coordinates do not overflow. A cell flat in all but one dimension has no area in 3D: then
/// the sum of the extents stands in for it, so that such cells can still be split.
fn measure(extent: [f64; 3], dim: usize, flat: bool) -> f64 {
    let [x, y, z] = extent;
    if flat {
        x + y + z
    } else if dim == 2 {
        2.0 * (x + y)
    } else {
        2.0 * (x * y + y * z + z * x)
    }
}

/// One sweep per axis over the sorted events: the cheapest plane strictly inside the cell.
fn best_plane<V: Vector>(
    arena: &EventArena,
    events: &Events,
    n: usize,
    cell: &Aabb<V>,
    costs: &SahCosts,
) -> Option<Best> {
    let mut extent = [0.0f64; 3];
    for (axis, e) in extent.iter_mut().enumerate().take(V::DIM) {
        *e = f64::from(cell.max.coord(axis)) - f64::from(cell.min.coord(axis));
    }
    let flat = measure(extent, V::DIM, false) <= 0.0;
    let total = measure(extent, V::DIM, flat);
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let inv_total = 1.0 / total;
    let (trav, isect, bonus) = (
        f64::from(costs.traversal),
        f64::from(costs.intersection),
        f64::from(costs.empty_bonus),
    );
    let cost = |pb: f64, pa: f64, nb: usize, na: usize| {
        let discount = if nb == 0 || na == 0 { bonus } else { 0.0 };
        trav + isect * (1.0 - discount) * (pb * nb as f64 + pa * na as f64)
    };
    let mut best: Option<Best> = None;
    for axis in 0..V::DIM {
        let list = arena.axis(events, axis);
        let (lo, hi) = (cell.min.coord(axis), cell.max.coord(axis));
        if lo >= hi {
            continue;
        }
        // A child's measure is linear in its extent along the axis: k0 + k1 · extent.
        let mut part = extent;
        part[axis] = 0.0;
        let k0 = measure(part, V::DIM, flat);
        part[axis] = 1.0;
        let k1 = measure(part, V::DIM, flat) - k0;
        let (lo64, hi64) = (f64::from(lo), f64::from(hi));
        let (mut below, mut above) = (0usize, n);
        let mut i = 0;
        while i < list.len() {
            let pos = list[i].pos;
            // Ends, planars and starts at this position (indexed by kind: no branches).
            let mut count = [0usize; 3];
            while let Some(e) = list.get(i).filter(|e| e.pos == pos) {
                count[e.kind() as usize] += 1;
                i += 1;
            }
            let [ends, planars, starts] = count;
            above = above.saturating_sub(planars + ends);
            if lo < pos && pos < hi {
                let pos64 = f64::from(pos);
                let pb = (k0 + k1 * (pos64 - lo64)) * inv_total;
                let pa = (k0 + k1 * (hi64 - pos64)) * inv_total;
                let with_below = cost(pb, pa, below + planars, above);
                let with_above = cost(pb, pa, below, above + planars);
                let (c, planar_below) = if with_below <= with_above {
                    (with_below, true)
                } else {
                    (with_above, false)
                };
                if best.is_none_or(|b| c < b.cost) {
                    best = Some(Best {
                        axis,
                        pos,
                        planar_below,
                        cost: c,
                    });
                }
            }
            below += starts + planars;
        }
    }
    best
}

/// Builds the subtree over the primitives of `events` (on top of the arena) and returns its
/// root; the arena is left as it was found.
pub(crate) fn build_sah<P: Primitive, O: Observer<P::Point>>(
    b: &mut Builder<'_, P, O>,
    arena: &mut EventArena,
    costs: &SahCosts,
    events: Events,
    at: Subtree<P::Point>,
    bad_refines: usize,
) -> u32 {
    let mut refs = std::mem::take(&mut b.scratch);
    arena.prims(&events, &mut refs);
    let n = refs.len();
    let id = b.begin(at.parent, at.depth, n);
    let split = if b.must_stop(n, at.depth) {
        None
    } else {
        choose(b, arena, costs, &events, &refs, &at, bad_refines)
    };
    let Some((best, budgets, bad_refines)) = split else {
        b.leaf_from(id, &mut refs);
        b.scratch = refs;
        return id;
    };
    let [below, above] = arena.split(&events, &b.sides, &refs, best.axis, best.pos);
    b.scratch = refs;
    let [below_at, above_at] = at.children(id, best.axis, best.pos, budgets);
    build_sah(b, arena, costs, below, below_at, bad_refines);
    arena.release(&below);
    b.above_follows(id);
    build_sah(b, arena, costs, above, above_at, bad_refines);
    arena.release(&above);
    id
}

/// Picks the node's plane, or `None` for a leaf, as pbrt decides; on a split, classifies the
/// primitives, pushes the inner node and returns the plane, the children's budgets and the
/// bad-refine count.
fn choose<P: Primitive, O: Observer<P::Point>>(
    b: &mut Builder<'_, P, O>,
    arena: &EventArena,
    costs: &SahCosts,
    events: &Events,
    refs: &[u32],
    at: &Subtree<P::Point>,
    bad_refines: usize,
) -> Option<(Best, [usize; 2], usize)> {
    let n = refs.len();
    let best = best_plane(arena, events, n, &at.cell, costs)?;
    let leaf_cost = f64::from(costs.intersection) * n as f64;
    let bad_refines = bad_refines + usize::from(best.cost > leaf_cost);
    if (best.cost > 4.0 * leaf_cost && n < 16) || bad_refines >= 3 {
        return None;
    }
    let counts = b.classify(refs, &at.cell, best.axis, best.pos, best.planar_below);
    // Every primitive reaching both sides would only copy the node.
    let budgets = share_budget(at.budget, counts).filter(|_| counts != [n, n])?;
    let id = b.nodes.len() as u32;
    b.inner(id, best.axis, best.pos, counts, Some(best.cost as f32));
    Some((best, budgets, bad_refines))
}
