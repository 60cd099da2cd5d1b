//! Choosing a BSP node's splitting plane.
//!
//! Autopartition (Fuchs, Kedem and Naylor, "On Visible Surface Generation by A Priori Tree
//! Structures", SIGGRAPH 1980): the splitter is the supporting plane (line, in 2D) of one of
//! the node's own primitives. Paterson and Yao ("Efficient Binary Space Partitions for
//! Hidden-Surface Removal and Solid Modeling", 1990) show that a *random* choice gives small
//! trees in expectation; here a few random candidates are scored by `straddle_weight ·
//! straddlers + |below - above|` (straddlers are listed on both sides, imbalance makes the tree
//! deep) and the best one that separates something wins.
//!
//! Points have no supporting plane, and some primitive sets cannot be separated by their own
//! planes (all segments on one line, all triangles in one plane): then the plane through the
//! median of the centroids, perpendicular to their principal axis (PCA), splits instead.

use super::plane::Plane;
use crate::structure::plane_tree::share_budget;
use crate::{Primitive, Vector};

/// Scores are estimated on at most this many of the node's primitives, so that choosing a
/// plane costs O(candidates · SAMPLE) per node however large the node is.
const SAMPLE: usize = 256;

/// A small deterministic random generator (`SplitMix64`, Steele, Lea and Flood, OOPSLA 2014):
/// the builds must not depend on a dependency's stream, and seeded builds must repeat.
#[derive(Clone, Debug)]
pub(crate) struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from a seed.
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A random index below `n` (`n > 0`).
    pub(crate) fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }
}

/// A plane and the node's primitives sorted to its two sides.
pub(crate) struct Split<V: Vector> {
    /// The plane.
    pub plane: Plane<V>,
    /// The primitives reaching the below side.
    pub below: Vec<u32>,
    /// The primitives reaching the above side.
    pub above: Vec<u32>,
}

/// Sorts `refs` to the sides of `plane`; `None` unless both sides get fewer than all and the
/// copies fit in the budget.
fn partition<P: Primitive>(
    prims: &[P],
    refs: &[u32],
    plane: Plane<P::Point>,
    budget: usize,
) -> Option<Split<P::Point>> {
    let (mut below, mut above) = (Vec::new(), Vec::new());
    for &r in refs {
        let sides = plane.sides(&prims[r as usize]);
        if sides.below {
            below.push(r);
        }
        if sides.above {
            above.push(r);
        }
    }
    let progress = below.len() < refs.len() && above.len() < refs.len();
    let affordable = share_budget(budget, [below.len(), above.len()]).is_some();
    (progress && affordable).then_some(Split {
        plane,
        below,
        above,
    })
}

/// The plane through the median centroid, perpendicular to the centroids' principal axis.
fn median_plane<P: Primitive>(prims: &[P], refs: &[u32]) -> Option<Plane<P::Point>> {
    let centroids: Vec<P::Point> = refs.iter().map(|&r| prims[r as usize].centroid()).collect();
    let axis = P::Point::principal_axes(&centroids).axes.as_ref()[0];
    let mut along: Vec<f32> = centroids.iter().map(|c| c.dot(axis)).collect();
    let mid = along.len() / 2;
    let (_, median, _) = along.select_nth_unstable_by(mid, f32::total_cmp);
    Plane::through(axis * *median, axis)
}

/// Chooses the split of a node with primitives `refs` (at least two), or `None` when no plane
/// tried separates them within the node's reference budget (the node becomes a leaf).
pub(crate) fn choose_split<P: Primitive>(
    prims: &[P],
    refs: &[u32],
    candidates: usize,
    straddle_weight: f32,
    median_candidate: bool,
    budget: usize,
    rng: &mut SplitMix64,
) -> Option<Split<P::Point>> {
    let sample: Vec<u32> = if refs.len() <= SAMPLE {
        refs.to_vec()
    } else {
        (0..SAMPLE).map(|_| refs[rng.below(refs.len())]).collect()
    };
    let mut scored: Vec<(f32, Plane<P::Point>)> = Vec::with_capacity(candidates);
    for _ in 0..candidates {
        let prim = &prims[refs[rng.below(refs.len())] as usize];
        let Some(plane) = Plane::through(prim.centroid(), prim.normal()) else {
            continue;
        };
        if scored.iter().any(|(_, p)| *p == plane) {
            continue;
        }
        let (mut below, mut above) = (0usize, 0usize);
        for &r in &sample {
            let sides = plane.sides(&prims[r as usize]);
            below += usize::from(sides.below);
            above += usize::from(sides.above);
        }
        if below == sample.len() || above == sample.len() {
            continue;
        }
        let straddlers = (below + above).saturating_sub(sample.len());
        let score = straddle_weight * straddlers as f32 + below.abs_diff(above) as f32;
        scored.push((score, plane));
    }
    if median_candidate && let Some(plane) = median_plane(prims, refs) {
        let (mut below, mut above) = (0usize, 0usize);
        for &r in &sample {
            let sides = plane.sides(&prims[r as usize]);
            below += usize::from(sides.below);
            above += usize::from(sides.above);
        }
        let straddlers = (below + above).saturating_sub(sample.len());
        let score = straddle_weight * straddlers as f32 + below.abs_diff(above) as f32;
        scored.push((score, plane));
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    scored
        .into_iter()
        .find_map(|(_, plane)| partition(prims, refs, plane, budget))
        .or_else(|| {
            median_plane(prims, refs).and_then(|plane| partition(prims, refs, plane, budget))
        })
}
