//! Range queries in a [`Bvh4`]: every primitive that shares a point with a box or a ball,
//! four boxes tested at once.
//!
//! A box region is tested against a node's four lanes with the binary tree's box overlap
//! (closed intervals on every axis, written over the lanes); a ball region by the squared
//! distance bound of the closest-point walk ([`bound_lanes`]) against the square of the
//! ball's radius grown as the binary tree grows it ([`PreparedRange::grown_radius`]), with
//! room for rounding ([`reach_squared`]). Neither skips a box the binary tree's range walk
//! enters, and every primitive reached is tested exactly
//! ([`RangeShape::overlaps_primitive`]), so the answer is the binary tree's (and brute
//! force's). The order of visits does not matter to it: leaf lanes are tested where their
//! node is met, inner lanes wait in lane order, and the indices are sorted at the end.

use super::any_all_hits::push_lanes;
use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::nearest::{bound_lanes, leaf_lanes};
use super::stack::{MIDDLE_DEPTH, SHALLOW_DEPTH, capacity};
use crate::structure::RangeShape;
use crate::structure::bvh::MAX_DEPTH;
use crate::structure::bvh::volume::PreparedRange;
use crate::structure::bvh::walk::fast_nearest::reach_squared;
use crate::volume::BoundingVolume;
use crate::{Primitive, Vector};

/// How a node's lanes are tested against the region.
#[derive(Clone, Copy)]
enum LaneTest {
    /// The box's lower and upper corners, per axis.
    Box([f32; 3], [f32; 3]),
    /// The ball's centre and the squared reach of its grown radius.
    Ball([f32; 3], f32),
}

impl LaneTest {
    /// The used lanes of `node` whose boxes may share a point with the region.
    #[inline]
    fn lanes<const DIM: usize>(&self, node: &Bvh4Node) -> u32 {
        match self {
            LaneTest::Box(lo, hi) => box_lanes::<DIM>(node, lo, hi),
            LaneTest::Ball(center, reach_sq) => bound_lanes::<DIM>(node, center, *reach_sq).1,
        }
    }
}

/// The used lanes whose boxes overlap the closed box `lo..=hi` (which is not empty): the
/// binary tree's `Aabb::overlaps`, lane by lane.
#[inline]
fn box_lanes<const DIM: usize>(node: &Bvh4Node, lo: &[f32; 3], hi: &[f32; 3]) -> u32 {
    let mut overlap = [true; WIDTH];
    for axis in 0..DIM {
        let (min, max) = (&node.planes[0][axis], &node.planes[1][axis]);
        for lane in 0..WIDTH {
            overlap[lane] &= min[lane] <= hi[axis] && lo[axis] <= max[lane];
        }
    }
    let mut mask = 0;
    for (lane, &o) in overlap.iter().enumerate() {
        // An unused lane holds the empty box, which overlaps nothing.
        let used = node.planes[0][0][lane] <= node.planes[1][0][lane];
        mask |= u32::from(o && used) << lane;
    }
    mask
}

/// A point's coordinates as the lane tests read them (unused axes 0).
fn coords<V: Vector>(point: V) -> [f32; 3] {
    let mut c = [0.0; 3];
    for (axis, value) in c.iter_mut().enumerate().take(V::DIM) {
        *value = point.coord(axis);
    }
    c
}

impl<P: Primitive> Bvh4<P> {
    /// The primitives that share a point with `shape`, by input index, ascending: what the
    /// binary tree's [`range`](crate::SpatialQuery::range) answers. An empty
    /// box or ball (a NaN or negative radius) holds nothing.
    pub fn range(&self, shape: &RangeShape<P::Point>) -> Vec<usize> {
        let test = match shape {
            RangeShape::Box(b) if !b.is_empty() => LaneTest::Box(coords(b.min), coords(b.max)),
            RangeShape::Ball(s) if !s.is_empty() => {
                let grown = PreparedRange::new(shape).grown_radius().unwrap_or(s.radius);
                LaneTest::Ball(coords(s.center), reach_squared(grown))
            }
            _ => return Vec::new(),
        };
        if self.nodes.is_empty() {
            return Vec::new();
        }
        let mut found = if self.depth <= SHALLOW_DEPTH {
            self.range_walk::<{ capacity(SHALLOW_DEPTH) }>(shape, test)
        } else if self.depth <= MIDDLE_DEPTH {
            self.range_walk::<{ capacity(MIDDLE_DEPTH) }>(shape, test)
        } else {
            self.range_walk::<{ capacity(MAX_DEPTH + 1) }>(shape, test)
        };
        found.sort_unstable();
        found
    }

    /// The walk, with a stack of `CAP` node indices; the indices found, unsorted.
    fn range_walk<const CAP: usize>(
        &self,
        shape: &RangeShape<P::Point>,
        test: LaneTest,
    ) -> Vec<usize> {
        let mut found = Vec::new();
        let mut stack = [0u32; CAP];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[current as usize];
            let mask = if P::Point::DIM == 3 {
                test.lanes::<3>(node)
            } else {
                test.lanes::<2>(node)
            };
            let leaves = mask & leaf_lanes(node);
            let mut bits = leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let start = node.child[lane] as usize;
                for slot in start..start + node.count[lane] as usize {
                    if shape.overlaps_primitive(&self.leaf_prims[slot]) {
                        found.push(self.leaf_ids[slot] as usize);
                    }
                }
            }
            push_lanes(node, mask & !leaves, &mut stack, &mut len);
            if len == 0 {
                return found;
            }
            len -= 1;
            current = stack[len];
        }
    }
}
