//! The first hit in a [`Bvh4`]: one slab test for four boxes, then the boxes the ray enters,
//! nearest entry first.
//!
//! The four-lane test is the binary walk's slab test ([`NodeVolume::ray_entry`] of
//! [`Aabb`](crate::Aabb)) written over fixed-size arrays, one lane per child, so that the
//! compiler turns each line into one vector instruction (SSE natively, SIMD128 in
//! WebAssembly) and no `unsafe` is needed: per lane the same operations on the same values,
//! so the same entry `t` as the binary tree's test of that box.
//!
//! The answer is the binary walks' (fast and observed), bit for bit: the same boxes, the same
//! primitive test and the same pruning rule (a child is skipped only when the ray misses its
//! box or enters it beyond the best hit times [`GROW`]), and the best hit is the least
//! `(t, index)` over every primitive not pruned, whatever the order they are met in
//! ([`HitTracker`]).
//!
//! Tried and not kept (issue 19; bunny and dragon, primary, shadow, diffuse and random rays,
//! old and new walk timed in one run): a per-node child order for each ray octant, worked
//! out when the tree is made and pushed without sorting (tinybvh's ordered kernel): no gain
//! on primary and shadow rays, 0.88-0.95x on diffuse and random ones; the leaves' triangles
//! in blocks of four tested by a four-lane copy of the watertight test: 0.66-1.03x (random
//! rays 0.66-0.76x), and 0.70-1.00x with AVX-512, since the binned SAH leaves hold 1.8
//! triangles on average and a block costs more than two scalar tests; the same blocks over
//! a tree whose binned SAH costs leaves in groups of four (`ceil(n / 4)`, leaves of up to
//! 4, 8 or 16 triangles, a third of the wide nodes): 0.98-1.16x against this walk on its
//! own tree, for about 37 more bytes per triangle; testing a node's leaf lanes where it is
//! met (as `nearest.rs` does), or the whole triangle test inlined into the walk: no change.
//! Their code was on the branches `helper-walk-octant-experiment` and
//! `helper-walk-blocks-experiment` (not merged).
//!
//! Kept (issue 33): the leaves' triangles in blocks of four, tested four at a time
//! (`triangle_block.rs`, `leaves.rs`), over a tree whose binned SAH costs leaves by blocks.
//! First measured as an experiment (one binary timing four layouts alternately three times,
//! medians): the same blocks written with glam's
//! four-lane operations (the corners of four triangles in structure of arrays, 144 bytes;
//! moved and sheared as the scalar test does, with separate multiplies and subtractions so
//! that every lane is rounded alike; the edge values in `f32`, whose nonzero, non-NaN signs are
//! the exact ones, so a lane with two opposite signs is a miss the `f64` test would also find;
//! the lanes left are tested by the scalar test on a triangle read back from the block, not
//! from the leaf order's copy) over the binned SAH that costs a leaf `ceil(n / 4)` with
//! leaves of up to 16 triangles (blocks 95% full, a third of the wide nodes). Against this
//! walk on its own tree: 1.06x and 1.20x on primary rays (bunny, dragon), 1.16x and 1.49x on
//! shadow rays, 1.01x and 1.14x on diffuse rays, 1.12x and 1.39x on random rays, with the
//! same answers bit for bit on all 307,210 rays; leaves of up to 8: 1.01-1.32x. The same
//! tree tested one triangle at a time was 0.69-0.83x (random rays 1.04-1.07x), and blocks
//! over this walk's own tree (1.8 triangles a leaf) 0.74-1.08x: the gain needs both. A
//! plainly written loop over the lanes (which the compiler left half scalar) was 0.89-1.14x
//! of the scalar test on the same tree.
//! On that tree the closest point and the 8 nearest, one triangle at a time, were 0.80-0.91x
//! and 0.81-0.94x of this tree's: the other queries need their blocks too. Landed, the
//! blocks replace the leaf order's triangles (old and new binaries alternately three times
//! on one core, medians, bunny and dragon): first hits 1.10x and 1.27x on primary rays,
//! 1.25x and 1.31x on shadow rays, 1.25x and 1.52x on diffuse rays, 1.16x and 1.53x on random
//! rays, 0.92x and 1.30x on the overview camera; any hits on shadow rays 1.13x and 1.32x.
//! Read one triangle at a time from the blocks, the closest point fell to 0.62-0.65x; with
//! each block's four boxes bounded at once and only the lanes in reach tested
//! (`TriangleBlock::near_lanes`) it is 1.02x and 0.96x, the 8 nearest 0.92x and 0.96x.
//!
//! [`NodeVolume::ray_entry`]: crate::structure::bvh::NodeVolume::ray_entry

use glam::Vec4;

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::stack::{LaneStack, visit_nearest};
use crate::structure::bvh::volume::{GROW, PreparedRay};
use crate::structure::{Hit, HitTracker};
use crate::{Primitive, Ray, Vector};

/// The ray as the four-lane test reads it: per axis, the slack-shifted origins and the
/// inverse direction, and which planes it enters through (1, the `max` planes, where the
/// direction is negative).
pub(super) struct LaneRay {
    origin_near: [f32; 3],
    origin_far: [f32; 3],
    inv_dir: [f32; 3],
    entry_planes: [usize; 3],
}

impl LaneRay {
    pub(super) fn new<V: Vector>(prepared: &PreparedRay<V>) -> Self {
        let (mut origin_near, mut origin_far, mut inv_dir) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        for axis in 0..V::DIM {
            origin_near[axis] = prepared.origin_near.coord(axis);
            origin_far[axis] = prepared.origin_far.coord(axis);
            inv_dir[axis] = prepared.inv_dir.coord(axis);
        }
        Self {
            origin_near,
            origin_far,
            inv_dir,
            entry_planes: prepared.negative.map(usize::from),
        }
    }
}

/// The slab test of the four children's boxes: per lane the entry `t`, and a bit set for each
/// lane whose box the ray enters no later than `limit_grown`.
///
/// Line for line the scalar test: `>` and `<` with the running value second skip a NaN plane
/// (a ray lying in it), which is what SSE's `maxps`/`minps` do with their operands in this
/// order.
#[expect(
    clippy::inline_always,
    reason = "the hot step of the walk: left out of line it costs a call per node (measured)"
)]
#[inline(always)]
pub(super) fn enter_lanes<const DIM: usize>(
    node: &Bvh4Node,
    ray: &LaneRay,
    limit_grown: f32,
) -> ([f32; WIDTH], u32) {
    let mut t_enter = [0.0f32; WIDTH];
    let mut t_exit = [f32::INFINITY; WIDTH];
    for axis in 0..DIM {
        let entry = ray.entry_planes[axis] & 1;
        let (near, far) = (&node.planes[entry][axis], &node.planes[entry ^ 1][axis]);
        let (o_near, o_far, inv) = (
            ray.origin_near[axis],
            ray.origin_far[axis],
            ray.inv_dir[axis],
        );
        for lane in 0..WIDTH {
            let t_near = (near[lane] - o_near) * inv;
            let t_far = (far[lane] - o_far) * inv;
            t_enter[lane] = if t_near > t_enter[lane] {
                t_near
            } else {
                t_enter[lane]
            };
            t_exit[lane] = if t_far < t_exit[lane] {
                t_far
            } else {
                t_exit[lane]
            };
        }
    }
    // The lanes' verdicts as a bit mask: glam's four-lane compare and `bitmask` (one
    // `movmskps` with SSE), which the compiler does not find from a loop over the lanes
    // when AVX-512 is enabled (it shifts mask registers lane by lane).
    let enter = Vec4::from_array(t_enter);
    let enters =
        enter.cmple(Vec4::from_array(t_exit) * GROW) & enter.cmple(Vec4::splat(limit_grown));
    let mask = enters.bitmask();
    (t_enter, mask)
}

impl<P: Primitive> Bvh4<P> {
    /// The first hit with `0 <= t <= t_max` (none for a NaN `t_max`), ties broken by the
    /// lower primitive index: what the binary tree's
    /// [`ray_first_hit`](crate::RayCast::ray_first_hit) answers, bit for bit.
    pub fn ray_first_hit(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        if self.nodes.is_empty() || t_max.is_nan() {
            return None;
        }
        self.first_hit_walk(ray, t_max)
    }

    /// The walk.
    fn first_hit_walk(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        let prepared = PreparedRay::new(ray);
        let lanes = LaneRay::new(&prepared);
        // The root's boxes first: a ray that enters none of them (most rays of a camera
        // that sees the mesh small) leaves before the stack and the best hit are set up.
        // On the overview rays of the bunny and the dragon this made the walk 1.30-1.32x
        // as fast, and the other ray kinds no slower (issue 19, old and new walk in one
        // run, when the stack was still an array zeroed per ray).
        let root = &self.nodes[0];
        let (t_enter, mask) = if P::Point::DIM == 3 {
            enter_lanes::<3>(root, &lanes, t_max * GROW)
        } else {
            enter_lanes::<2>(root, &lanes, t_max * GROW)
        };
        if mask == 0 {
            return None;
        }
        let mut best = HitTracker::new(t_max);
        // `best.limit()`, kept in a local so that the hot loop reads a register.
        let mut limit = t_max;
        let mut stack = LaneStack::new();
        let mut current = visit_nearest(root, mask, &t_enter, &mut stack);
        // The leaf-order slot of the best hit's primitive, for its coordinates.
        let mut best_slot = 0;
        loop {
            if current.count > 0 {
                let range = current.child as usize..(current.child + current.count) as usize;
                let (prims, ids) = (&self.leaf_prims, &self.leaf_ids);
                if prims.offer_first_hits(range.clone(), ids, ray, &mut best) {
                    limit = best.limit();
                    let prim = best.best().map_or(0, |h| h.prim);
                    let ids = &ids[range.clone()];
                    best_slot =
                        range.start + ids.iter().position(|&id| id as usize == prim).unwrap_or(0);
                }
            } else {
                let node = &self.nodes[current.child as usize];
                let (t_enter, mask) = if P::Point::DIM == 3 {
                    enter_lanes::<3>(node, &lanes, limit * GROW)
                } else {
                    enter_lanes::<2>(node, &lanes, limit * GROW)
                };
                if mask != 0 {
                    current = visit_nearest(node, mask, &t_enter, &mut stack);
                    continue;
                }
            }
            // Pop the next waiting child the best hit has not moved in front of.
            loop {
                let Some(waiting) = stack.pop() else {
                    return best
                        .best()
                        .map(|h| Hit::on(h.prim, h.t, &self.leaf_prims.get(best_slot), ray));
                };
                if waiting.key <= limit * GROW {
                    current = waiting;
                    break;
                }
            }
        }
    }
}
