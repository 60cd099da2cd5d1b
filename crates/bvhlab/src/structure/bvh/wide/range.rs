//! Range queries in a [`Bvh4`]: every primitive that shares a point with a box or a ball,
//! four boxes tested at once, and every box wholly inside the region taken whole.
//!
//! One walk answers the three forms ([`Bvh4::range`], [`Bvh4::range_count`],
//! [`Bvh4::range_for_each`]); what it finds goes to a [`Found`], which collects, counts or
//! calls back. A node's lanes are tested by [`LaneTest`] (`range_lanes.rs`): a lane that may
//! share a point with the region is entered, and one wholly inside it is taken whole: a
//! leaf lane hands its slice of input indices over at once, an inner lane is pushed marked
//! [`WHOLE`], and a marked node's lanes are all taken without a test. Leaf lanes are met
//! where their node is met; inner lanes wait in lane order.

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::nearest::leaf_lanes;
use super::range_lanes::{LaneMasks, LaneTest};
use super::stack::{MIDDLE_DEPTH, SHALLOW_DEPTH, capacity};
use crate::structure::RangeShape;
use crate::structure::bvh::MAX_DEPTH;
use crate::structure::index_sort::sort_indices;
use crate::{Primitive, Vector};

/// The mark of a waiting node wholly inside the region, in its index's top bit. A node is
/// 128 bytes, so a tree would need 256 GiB of nodes before an index reached this bit; a
/// tree that large (or a loaded file that claims it) takes no inner lane whole.
const WHOLE: u32 = 1 << 31;

/// Where the range walk puts what it finds.
trait Found {
    /// A primitive that was tested and shares a point with the region.
    fn one(&mut self, id: u32);
    /// The primitives of a leaf lane wholly inside the region.
    fn all(&mut self, ids: &[u32]);
}

/// Counts, without looking at the indices of a whole lane.
struct Count(usize);

impl Found for Count {
    #[inline]
    fn one(&mut self, _id: u32) {
        self.0 += 1;
    }
    #[inline]
    fn all(&mut self, ids: &[u32]) {
        self.0 += ids.len();
    }
}

impl Found for Vec<usize> {
    #[inline]
    fn one(&mut self, id: u32) {
        self.push(id as usize);
    }
    #[inline]
    fn all(&mut self, ids: &[u32]) {
        self.extend(ids.iter().map(|&id| id as usize));
    }
}

/// Calls back once per index.
struct Each<F>(F);

impl<F: FnMut(usize)> Found for Each<F> {
    #[inline]
    fn one(&mut self, id: u32) {
        (self.0)(id as usize);
    }
    #[inline]
    fn all(&mut self, ids: &[u32]) {
        for &id in ids {
            (self.0)(id as usize);
        }
    }
}

/// Every lane of `node` that is used, for a node wholly inside the region.
#[inline]
fn used_lanes(node: &Bvh4Node) -> LaneMasks {
    let mut used = 0;
    for lane in 0..WIDTH {
        used |= u32::from(node.is_used(lane)) << lane;
    }
    LaneMasks {
        touch: used,
        inside: used,
    }
}

impl<P: Primitive> Bvh4<P> {
    /// The primitives that share a point with `shape`, by input index, ascending: what the
    /// binary tree's [`range`](crate::SpatialQuery::range) and
    /// [`BruteForce`](crate::BruteForce) answer. An empty box or ball (a NaN or negative
    /// radius) holds nothing.
    ///
    /// Each node's four lane boxes are tested at once. A lane whose box may share a point
    /// with the region is entered: its primitives are tested one by one with the exact
    /// [`RangeShape::overlaps_primitive`], as brute force tests them. A lane whose box lies
    /// wholly inside the region is taken whole, every primitive below it without a test.
    /// (The build gives 200k uniform points leaves of one point each, so 50 balls holding
    /// 3,780 of them each tested 18 points in all, where the walk had tested every point
    /// it reported.) The answer stays
    /// exact because a primitive lies in its bounds and its lane's box holds those bounds
    /// ([`validate`](Self::validate) checks it): a box region takes a lane whose box lies
    /// inside it on every axis (exact comparisons of the same `f32` planes), and a ball one
    /// whose farthest corner lies within the radius shrunk by more than the rounding of the
    /// corner's distance and of the primitives' own distance (`SLACK` of the radius and of
    /// the ball's coordinates; `range_lanes.rs`). A box that is inside but within that
    /// margin of the surface is entered and tested. Every primitive is in one leaf slot
    /// and non-finite ones are in none, so nothing is reported twice or off the geometry.
    ///
    /// [`range_count`](Self::range_count) counts the same primitives and
    /// [`range_for_each`](Self::range_for_each) visits them, without the list.
    pub fn range(&self, shape: &RangeShape<P::Point>) -> Vec<usize> {
        let mut found = Vec::new();
        self.range_into(shape, &mut found);
        sort_indices(&mut found);
        found
    }

    /// How many primitives share a point with `shape`: `range(shape).len()`, without
    /// building the list (a whole lane adds its count; nothing is allocated).
    ///
    /// ```
    /// use bvhlab::glam::Vec3;
    /// use bvhlab::prelude::*;
    /// use bvhlab::{RangeShape, Sphere3};
    ///
    /// let points: Vec<Vec3> = (0..1000).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    /// let wide = Bvh4::build(&points);
    /// let ball = RangeShape::Ball(Sphere3::new(Vec3::new(500.0, 0.0, 0.0), 100.0));
    /// assert_eq!(wide.range_count(&ball), 201);
    /// assert_eq!(wide.range_count(&ball), wide.range(&ball).len());
    /// ```
    pub fn range_count(&self, shape: &RangeShape<P::Point>) -> usize {
        let mut count = Count(0);
        self.range_into(shape, &mut count);
        count.0
    }

    /// Calls `visit` with the input index of every primitive that shares a point with
    /// `shape`, once each, in the tree's order (not sorted): the indices of
    /// [`range`](Self::range), without collecting them.
    ///
    /// ```
    /// use bvhlab::glam::Vec2;
    /// use bvhlab::prelude::*;
    /// use bvhlab::{Aabb2, RangeShape};
    ///
    /// let points: Vec<Vec2> = (0..100).map(|i| Vec2::new((i % 10) as f32, (i / 10) as f32)).collect();
    /// let wide = Bvh4::build(&points);
    /// let square = RangeShape::Box(Aabb2::new(Vec2::ZERO, Vec2::splat(2.0)));
    /// let mut sum_x = 0.0;
    /// wide.range_for_each(&square, |i| sum_x += points[i].x);
    /// assert_eq!(sum_x, 3.0 * (0.0 + 1.0 + 2.0));
    /// ```
    pub fn range_for_each(&self, shape: &RangeShape<P::Point>, visit: impl FnMut(usize)) {
        self.range_into(shape, &mut Each(visit));
    }

    /// The walk for `shape`, with the stack its depth needs, into `found`.
    fn range_into(&self, shape: &RangeShape<P::Point>, found: &mut impl Found) {
        let Some(test) = LaneTest::new(shape) else {
            return;
        };
        if self.nodes.is_empty() {
            return;
        }
        if self.depth <= SHALLOW_DEPTH {
            self.range_walk::<{ capacity(SHALLOW_DEPTH) }>(shape, test, found);
        } else if self.depth <= MIDDLE_DEPTH {
            self.range_walk::<{ capacity(MIDDLE_DEPTH) }>(shape, test, found);
        } else {
            self.range_walk::<{ capacity(MAX_DEPTH + 1) }>(shape, test, found);
        }
    }

    /// The walk, with a stack of `CAP` node indices (those marked [`WHOLE`] lie inside the
    /// region). A marked node pushes at most as many lanes as a tested one, so the stack's
    /// bound holds.
    fn range_walk<const CAP: usize>(
        &self,
        shape: &RangeShape<P::Point>,
        test: LaneTest,
        found: &mut impl Found,
    ) {
        // Whole inner lanes need their index's top bit free.
        let whole_inner = if self.nodes.len() <= WHOLE as usize {
            u32::MAX
        } else {
            0
        };
        let mut stack = [0u32; CAP];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            let node = &self.nodes[(current & !WHOLE) as usize];
            let lanes = if current & WHOLE != 0 {
                used_lanes(node)
            } else if P::Point::DIM == 3 {
                test.lanes::<3>(node)
            } else {
                test.lanes::<2>(node)
            };
            let leaves = lanes.touch & leaf_lanes(node);
            let mut bits = leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let start = node.child[lane] as usize;
                let slots = start..start + node.count[lane] as usize;
                if lanes.inside & (1 << lane) != 0 {
                    found.all(&self.leaf_ids[slots]);
                } else {
                    for slot in slots {
                        if shape.overlaps_primitive(&self.leaf_prims.get(slot)) {
                            found.one(self.leaf_ids[slot]);
                        }
                    }
                }
            }
            let mut bits = lanes.touch & !leaves;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let whole = (lanes.inside & whole_inner) & (1 << lane) != 0;
                stack[len] = node.child[lane] | if whole { WHOLE } else { 0 };
                len += 1;
            }
            if len == 0 {
                return;
            }
            len -= 1;
            current = stack[len];
        }
    }
}
