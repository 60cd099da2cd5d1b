//! Plane trees: what a BSP tree ([`super::bsp`]) and a k-d tree ([`super::kdtree`]) have in
//! common, a binary tree of half-spaces whose leaves list primitives. A k-d tree is a BSP
//! tree whose planes are axis-aligned (Fuchs, Kedem and Naylor 1980; Bentley 1975), so every
//! query is written once, here, against `PlaneTree`, and each tree only says how a ray
//! crosses one of its planes and how big a child's region is. The k-d tree answers
//! `PlaneTree::crossing` with one coordinate and the ray's precomputed `1/d` (its fast
//! axis-aligned path); the BSP tree with two dot products.
//!
//! - this file: the `PlaneTree` trait, plane crossings, the reference budget;
//! - [`ray`]: first hit, any hit, all hits, front to back by the split distance (the k-d
//!   traversal and the BSP traversal);
//! - [`nearest`]: the k nearest, by branch and bound;
//! - [`range`]: the range query; [`collide`]: tree against tree;
//! - [`validate`]: the checks and statistics both trees share.
//!
//! ## Rounding
//! The queries must find exactly the hits and neighbours that brute force finds. A split `t`
//! computed in floating point can be off by a few units in the last place, and a primitive's
//! own `t` too, so every crossing carries an error margin `err` and a child's `t`-interval is
//! widened by it on the side of the plane: near the plane both children are visited. Widening
//! only ever visits more, it never skips a primitive brute force would report.

pub mod collide;
pub mod nearest;
pub mod range;
pub mod ray;
pub mod validate;

use crate::structure::NodeId;
use crate::volume::Aabb;
use crate::{Primitive, Ray, Vector};

/// The vector type of a plane tree.
pub(crate) type PointOfTree<T> = <<T as PlaneTree>::Prim as Primitive>::Point;

/// The relative rounding margin of plane crossings and bound distances: 32 units in the last
/// place of `f32`, far more than the few the arithmetic loses, far less than a cell.
pub(crate) const SLACK: f32 = 32.0 * f32::EPSILON;

/// A node as the queries see it.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PlaneNode<'a> {
    /// An inner node: its children `[below, above]` the plane.
    Inner([u32; 2]),
    /// A leaf and the primitives it lists.
    Leaf(&'a [u32]),
}

/// Where a ray meets a node's plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Crossing {
    /// The ray crosses the plane at `t`, give or take `err`. With `below_first`, the ray runs
    /// from the below side (`t < t_split`) to the above side; otherwise the other way.
    At {
        /// Where the ray crosses the plane (may be negative: behind the origin).
        t: f32,
        /// The rounding margin of `t`.
        err: f32,
        /// Whether the part of the ray before `t` lies below the plane.
        below_first: bool,
    },
    /// The ray runs parallel to the plane, below it, above it, or inside it (both).
    Parallel {
        /// The ray is on the below side (or in the plane).
        below: bool,
        /// The ray is on the above side (or in the plane).
        above: bool,
    },
}

impl Crossing {
    /// The `t` to report in [`Event::PlaneCrossed`](crate::Event::PlaneCrossed): `inf` when
    /// parallel.
    pub(crate) fn t(self) -> f32 {
        match self {
            Crossing::At { t, .. } => t,
            Crossing::Parallel { .. } => f32::INFINITY,
        }
    }

    /// The children the ray visits, in visiting order (near child first), each with its
    /// `t`-interval, the part of `[t_enter, t_exit]` on the child's side (widened by `err`).
    pub(crate) fn split(self, t_enter: f32, t_exit: f32) -> [Option<(usize, f32, f32)>; 2] {
        match self {
            Crossing::At {
                t,
                err,
                below_first,
            } => {
                let (first, second) = if below_first { (0, 1) } else { (1, 0) };
                let first_exit = t_exit.min(t + err);
                let second_enter = t_enter.max(t - err);
                [
                    (t_enter <= first_exit).then_some((first, t_enter, first_exit)),
                    (second_enter <= t_exit).then_some((second, second_enter, t_exit)),
                ]
            }
            Crossing::Parallel { below, above } => [
                below.then_some((0, t_enter, t_exit)),
                above.then_some((1, t_enter, t_exit)),
            ],
        }
    }
}

/// Where a ray crosses the axis-aligned plane `x_axis = s`, with the rounding margin; `o`, `d`
/// and `inv` are the ray's origin, direction and `1/d` on that axis (`d != 0`).
///
/// `(s - o) · inv` is exact up to two roundings, relative to `(|s| + |o|) · |inv|`. When `d` is
/// subnormal, `1/d` overflows and `0 · inf` would give NaN, so the division is done instead.
#[inline]
pub(crate) fn axis_crossing(s: f32, o: f32, d: f32, inv: f32) -> (f32, f32) {
    let scale = s.abs() + o.abs();
    if inv.is_finite() {
        ((s - o) * inv, SLACK * scale * inv.abs())
    } else {
        ((s - o) / d, SLACK * (scale / d.abs()))
    }
}

/// The ray's interval inside `bound` (the slab test of lecture §2), widened by the rounding
/// margin and clamped to `t >= 0`; `None` when the ray misses the box. Axes the ray is parallel
/// to are decided exactly from the origin, as [`Aabb::slab_test`] does.
pub(crate) fn root_interval<V: Vector>(bound: &Aabb<V>, ray: &Ray<V>) -> Option<(f32, f32)> {
    let (origin, dir, inv) = (ray.origin(), ray.dir(), ray.inv_dir());
    let (mut enter, mut exit, mut err) = (0.0f32, f32::INFINITY, 0.0f32);
    for i in 0..V::DIM {
        let (o, d, lo, hi) = (
            origin.coord(i),
            dir.coord(i),
            bound.min.coord(i),
            bound.max.coord(i),
        );
        if d == 0.0 {
            if !(lo <= o && o <= hi) {
                return None;
            }
            continue;
        }
        let (t_lo, e_lo) = axis_crossing(lo, o, d, inv.coord(i));
        let (t_hi, e_hi) = axis_crossing(hi, o, d, inv.coord(i));
        let (near, far) = if d > 0.0 { (t_lo, t_hi) } else { (t_hi, t_lo) };
        enter = enter.max(near);
        exit = exit.min(far);
        err = err.max(e_lo).max(e_hi);
    }
    // `f32::max` ignores a NaN (from `inf - inf`), so an infinite margin gives `[0, inf]`.
    let enter = (enter - err).max(0.0);
    let exit = if err.is_finite() {
        exit + err
    } else {
        f32::INFINITY
    };
    (enter <= exit).then_some((enter, exit))
}

/// The largest absolute coordinate of a point or box corner: the scale of the rounding error
/// of distances computed near it.
pub(crate) fn magnitude<V: Vector>(v: V) -> f32 {
    v.abs().max_element()
}

/// How many references a build may store per primitive: a subtree's budget is shared out
/// among its children in proportion to their sizes, so that a node whose every plane cuts many
/// primitives cannot blow up the tree, and no part of the tree spends another's share.
pub const REFERENCE_BUDGET: usize = 8;

/// The children's budgets when a node with `budget` splits into `counts` references, or
/// `None` when the split would store more than the budget allows. Each child's budget is at
/// least its count.
pub(crate) fn share_budget(budget: usize, counts: [usize; 2]) -> Option<[usize; 2]> {
    let total = counts[0] + counts[1];
    if total > budget {
        return None;
    }
    let below = (budget as u128 * counts[0] as u128 / total.max(1) as u128) as usize;
    Some([below, budget - below])
}

/// The node id of the root.
pub(crate) const ROOT: u32 = 0;

/// `NodeId` from a node index.
pub(crate) fn node_id(node: u32) -> NodeId {
    NodeId(node)
}

/// A binary tree of half-spaces, as the queries in this folder see it. Nodes are numbered
/// from the root, 0.
pub(crate) trait PlaneTree {
    /// What the leaves list.
    type Prim: Primitive;

    /// The primitives, in input order.
    fn prims(&self) -> &[Self::Prim];

    /// How many nodes the tree has (0 when empty).
    fn node_count(&self) -> usize;

    /// The root's region (a box around every stored primitive); `None` for an empty tree.
    fn root_bound(&self) -> Option<Aabb<PointOfTree<Self>>>;

    /// The node's kind and contents.
    fn node(&self, node: u32) -> PlaneNode<'_>;

    /// Where the ray crosses the inner node's plane.
    fn crossing(&self, node: u32, ray: &Ray<PointOfTree<Self>>) -> Crossing;

    /// The boxes that bound the inner node's children, given the box that bounds the node:
    /// cells for a k-d tree, the stored boxes of their primitives for a BSP tree. Every
    /// primitive point that a query can find under a child lies in its box.
    fn child_bounds(
        &self,
        node: u32,
        bound: &Aabb<PointOfTree<Self>>,
    ) -> [Aabb<PointOfTree<Self>>; 2];

    /// Which side of the inner node's plane a point lies on: 0 below, 1 above.
    fn side_of(&self, node: u32, point: PointOfTree<Self>) -> usize;
}
