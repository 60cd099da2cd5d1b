//! What both k-d tree builders share: the node array, the build events, and how a split
//! plane sends a node's primitives to its children. The builders are [`median`] (the median
//! of the centres) and [`sah`] (the surface area heuristic, over the sorted edge events of
//! [`sah_events`]).
//!
//! A primitive goes to each child cell that it has points in, so that every point of a
//! primitive lies in the closed cell of some leaf that lists it, which is all the queries need:
//! - its bounds end at or below the plane: below only; start at or above: above only (a
//!   primitive that merely touches the plane is not copied to the other side: the plane's
//!   points belong to both closed cells, so the queries still meet it where it touches);
//! - it lies in the plane: the side the builder chose (both would be correct, one is cheaper);
//! - its bounds straddle the plane: the exact [`Primitive::intersects_aabb`] decides for each
//!   child cell, so that a thin diagonal primitive whose box straddles but whose points in the
//!   cell do not is not duplicated for nothing.
//!
//! A node becomes a leaf when it is small enough, deep enough, when no plane makes progress
//! (identical primitives, or all of them straddling), or when a split would exceed the
//! node's share of the reference budget ([`REFERENCE_BUDGET`] references per primitive,
//! shared out among children in proportion to their sizes).

pub mod median;
pub mod sah;
pub mod sah_events;

use glam::DVec3;

use super::layout::KdNode;
use super::options::{KdBuilder, KdTreeOptions};
use crate::structure::{Event, NodeId, Observer};
use crate::volume::Aabb;
use crate::{Primitive, Vector};

pub use crate::structure::plane_tree::REFERENCE_BUDGET;

/// The deepest a tree may grow, whatever the options say (the recursion depth).
pub const DEPTH_LIMIT: usize = 64;

/// Side flags of a primitive at a split.
pub(crate) const BELOW: u8 = 1;
/// It goes above.
pub(crate) const ABOVE: u8 = 2;
/// Its bounds straddle the plane (its clipped bounds change in the children).
pub(crate) const STRADDLES: u8 = 4;

/// Where a subtree is built: its cell, depth, parent and share of the reference budget.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Subtree<V: Vector> {
    pub cell: Aabb<V>,
    pub depth: usize,
    pub parent: Option<u32>,
    pub budget: usize,
}

impl<V: Vector> Subtree<V> {
    /// The whole tree over `n` primitives in `cell`.
    pub(crate) fn root(cell: Aabb<V>, n: usize) -> Self {
        Self {
            cell,
            depth: 0,
            parent: None,
            budget: REFERENCE_BUDGET * n,
        }
    }

    /// The children of node `id`, split at `x_axis = split`, with their budgets.
    pub(crate) fn children(
        &self,
        id: u32,
        axis: usize,
        split: f32,
        budgets: [usize; 2],
    ) -> [Self; 2] {
        let cells = split_cell(&self.cell, axis, split);
        [0, 1].map(|side| Self {
            cell: cells[side],
            depth: self.depth + 1,
            parent: Some(id),
            budget: budgets[side],
        })
    }
}

/// The node array under construction and everything the recursion needs.
pub(crate) struct Builder<'a, P: Primitive, O> {
    pub prims: &'a [P],
    /// Each primitive's bounds (only the finite ones are used).
    pub bounds: Vec<Aabb<P::Point>>,
    /// The same as `[min, max]` per axis, for quick access.
    extents: Vec<[[f32; 2]; 3]>,
    pub leaf_size: usize,
    pub max_depth: usize,
    pub nodes: Vec<KdNode>,
    pub indices: Vec<u32>,
    /// Per primitive, its [`BELOW`] / [`ABOVE`] / [`STRADDLES`] flags at the current split.
    pub sides: Vec<u8>,
    /// A reusable list of references (the SAH builder's per-node primitives).
    pub scratch: Vec<u32>,
    pub observer: &'a mut O,
}

/// The default depth limit. SAH: pbrt-v3's `8 + 1.3 log2 n`, rounded (the cost model stops
/// earlier where splitting does not pay). Median: `⌈log2(n / leaf_size)⌉ + 1`, one level more
/// than a balanced tree needs: a median split halves the count, so deeper splits only shave
/// copies off the primitives that no plane separates (the triangles around a mesh vertex),
/// at a high price in references and build time.
pub(crate) fn default_max_depth(n: usize, options: &KdTreeOptions) -> usize {
    let log2 = |x: f64| x.max(1.0).log2();
    let depth = match options.builder {
        KdBuilder::Sah(_) => (8.0 + 1.3 * log2(n as f64)).round(),
        KdBuilder::Median(_) => log2(n as f64 / options.leaf_size.max(1) as f64).ceil() + 1.0,
    };
    (depth as usize).min(DEPTH_LIMIT)
}

/// The cell cut at `x_axis = split`: `[below, above]`.
pub(crate) fn split_cell<V: Vector>(cell: &Aabb<V>, axis: usize, split: f32) -> [Aabb<V>; 2] {
    let (mut below, mut above) = (*cell, *cell);
    below.max.set_coord(axis, split);
    above.min.set_coord(axis, split);
    [below, above]
}

/// A box's corners in `f64` (exact), for comparisons without per-coordinate calls.
fn corners<V: Vector>(b: &Aabb<V>) -> [DVec3; 2] {
    [b.min.to_dvec3(), b.max.to_dvec3()]
}

/// Which of the two child cells (of `parent`, cut at `x_axis = split`) a straddling primitive
/// has points in. A vertex inside the parent cell settles the side it lies on cheaply (most
/// straddlers are small and have vertices on both sides); only the undecided cells get the
/// exact test. It returns at least one side.
fn reaches<P: Primitive>(
    prim: &P,
    parent: &[DVec3; 2],
    axis: usize,
    split: f32,
    cells: &[Aabb<P::Point>; 2],
) -> [bool; 2] {
    let mut reach = [false; 2];
    let split = f64::from(split);
    for v in prim.vertices() {
        let v = v.to_dvec3();
        if v.cmpge(parent[0]).all() && v.cmple(parent[1]).all() {
            reach[0] |= v[axis] <= split;
            reach[1] |= v[axis] >= split;
        }
    }
    match reach {
        // The primitive meets the parent cell (it was sent there), so if it misses the below
        // cell it meets the above one.
        [false, false] => {
            if prim.intersects_aabb(&cells[0]) {
                [true, prim.intersects_aabb(&cells[1])]
            } else {
                [false, true]
            }
        }
        [true, false] => [true, prim.intersects_aabb(&cells[1])],
        [false, true] => [prim.intersects_aabb(&cells[0]), true],
        [true, true] => reach,
    }
}

impl<'a, P: Primitive, O: Observer<P::Point>> Builder<'a, P, O> {
    /// A builder, the finite primitives' indices, and the root cell (their bounds' union).
    pub(crate) fn new(
        prims: &'a [P],
        options: &KdTreeOptions,
        observer: &'a mut O,
    ) -> (Self, Vec<u32>, Aabb<P::Point>) {
        let bounds: Vec<Aabb<P::Point>> = prims.iter().map(Primitive::bounds).collect();
        let refs: Vec<u32> = (0..prims.len() as u32)
            .filter(|&i| prims[i as usize].has_finite_coordinates())
            .collect();
        let cell = refs.iter().fold(Aabb::EMPTY, |c: Aabb<P::Point>, &r| {
            let b = &bounds[r as usize];
            Aabb::new(c.min.min(b.min), c.max.max(b.max))
        });
        let extents = bounds
            .iter()
            .map(|b| {
                let (min, max) = (b.min.to_dvec3().as_vec3(), b.max.to_dvec3().as_vec3());
                [[min.x, max.x], [min.y, max.y], [min.z, max.z]]
            })
            .collect();
        let builder = Self {
            prims,
            bounds,
            extents,
            leaf_size: options.leaf_size.max(1),
            max_depth: options
                .max_depth
                .unwrap_or_else(|| default_max_depth(refs.len(), options))
                .min(DEPTH_LIMIT),
            nodes: Vec::new(),
            indices: Vec::new(),
            sides: vec![0; prims.len()],
            scratch: Vec::new(),
            observer,
        };
        (builder, refs, cell)
    }

    /// Announces the next node; it is pushed by [`Builder::leaf`] or [`Builder::inner`].
    pub(crate) fn begin(&mut self, parent: Option<u32>, depth: usize, prims: usize) -> u32 {
        let id = self.nodes.len() as u32;
        self.observer.on(Event::BuildNode {
            node: NodeId(id),
            parent: parent.map(NodeId),
            depth: depth as u32,
            prims: prims as u32,
        });
        id
    }

    /// Whether a node of `n` references at `depth` must be a leaf before any plane is tried.
    pub(crate) fn must_stop(&self, n: usize, depth: usize) -> bool {
        n <= self.leaf_size || depth >= self.max_depth
    }

    /// Pushes node `id` as a leaf over `refs`.
    pub(crate) fn leaf(&mut self, id: u32, mut refs: Vec<u32>) -> u32 {
        self.leaf_from(id, &mut refs);
        id
    }

    /// Pushes node `id` as a leaf over `refs` (sorted here).
    pub(crate) fn leaf_from(&mut self, id: u32, refs: &mut [u32]) {
        debug_assert_eq!(self.nodes.len(), id as usize);
        refs.sort_unstable();
        self.observer.on(Event::BuildLeaf {
            node: NodeId(id),
            prims: refs.len() as u32,
        });
        self.nodes
            .push(KdNode::leaf(self.indices.len() as u32, refs.len() as u32));
        self.indices.extend_from_slice(refs);
    }

    /// Pushes node `id` as an inner node; its children are built next.
    pub(crate) fn inner(
        &mut self,
        id: u32,
        axis: usize,
        split: f32,
        counts: [usize; 2],
        cost: Option<f32>,
    ) {
        debug_assert_eq!(self.nodes.len(), id as usize);
        self.observer.on(Event::BuildSplit {
            node: NodeId(id),
            normal: P::Point::unit_axis(axis),
            offset: split,
            left: counts[0] as u32,
            right: counts[1] as u32,
            cost,
        });
        self.nodes.push(KdNode::inner(axis, split));
    }

    /// Records that node `id`'s above child is the next node.
    pub(crate) fn above_follows(&mut self, id: u32) {
        let above = self.nodes.len() as u32;
        self.nodes[id as usize].set_above(above);
    }

    /// Sends `refs` to the sides of the plane `x_axis = split` (strictly inside `cell`):
    /// records each one's flags in [`Builder::sides`] and returns how many go below and
    /// above. Primitives lying in the plane go below when `planar_below`, else above.
    pub(crate) fn classify(
        &mut self,
        refs: &[u32],
        cell: &Aabb<P::Point>,
        axis: usize,
        split: f32,
        planar_below: bool,
    ) -> [usize; 2] {
        let cells = split_cell(cell, axis, split);
        let parent = corners(cell);
        let mut counts = [0; 2];
        for &r in refs {
            let [lo, hi] = self.extents[r as usize][axis];
            let flags = if lo == split && hi == split {
                if planar_below { BELOW } else { ABOVE }
            } else if hi <= split {
                BELOW
            } else if lo >= split {
                ABOVE
            } else {
                let flags = match reaches(&self.prims[r as usize], &parent, axis, split, &cells) {
                    [true, false] => BELOW,
                    [false, true] => ABOVE,
                    // Both, or (rounding in an inexact test) neither: keep it on both sides.
                    _ => BELOW | ABOVE,
                };
                flags | STRADDLES
            };
            self.sides[r as usize] = flags;
            counts[0] += usize::from(flags & BELOW != 0);
            counts[1] += usize::from(flags & ABOVE != 0);
        }
        counts
    }

    /// The references that [`Builder::classify`] sent to the side with this flag.
    pub(crate) fn on_side(&self, refs: &[u32], flag: u8, count: usize) -> Vec<u32> {
        let mut out = Vec::with_capacity(count);
        out.extend(
            refs.iter()
                .copied()
                .filter(|&r| self.sides[r as usize] & flag != 0),
        );
        out
    }
}
