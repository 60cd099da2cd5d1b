//! Building the 2^D tree top-down: split a cell into 2^D equal children while it holds too
//! many primitives, sending each primitive to every child it touches.

use super::layout::{
    INNER, MAX_DEPTH, Node, Orthtree, OrthtreeOptions, child_box_at, child_count, midpoint,
    split_point,
};
use crate::structure::grid::probe::finite_bounds;
use crate::structure::{Event, NodeId, Observer};
use crate::volume::Aabb;
use crate::{BoundingVolume, Primitive, Vector};

/// The children of `cell` that primitive `prim` shares a point with, as a bit mask over child
/// indices.
///
/// Its bounding box decides along each axis whether it reaches the lower half, the upper
/// half or both (touching the mid-plane counts: cells are closed). When that leaves one child,
/// the primitive lies in it and no exact test is needed (it shares a point with the parent
/// cell, and that point is in this child). A candidate holding one of the primitive's
/// vertices needs no test either. Otherwise the exact
/// [`Primitive::intersects_aabb`] decides among the candidates, so a triangle crossing a
/// corner is not copied into the children its box merely covers. Should the exact test refuse
/// every candidate (an exact test cannot), all are kept, so no primitive is lost. The build and
/// validation both call this.
pub(super) fn child_mask<P: Primitive>(prim: &P, split: &Split<P::Point>) -> u32 {
    let b = prim.bounds();
    let mut candidates = split.all;
    for i in 0..P::Point::DIM {
        let mid = split.mid.coord(i);
        if b.min.coord(i) > mid {
            candidates &= split.upper[i];
        }
        if b.max.coord(i) < mid {
            candidates &= !split.upper[i];
        }
    }
    if candidates.count_ones() <= 1 {
        return candidates;
    }
    // A child holding one of the vertices certainly shares a point with the primitive; only
    // the other candidates need the exact test.
    let mut certain = 0;
    for v in prim.vertices() {
        if split.cell.contains(v) {
            let mut holds = split.all;
            for i in 0..P::Point::DIM {
                let (x, mid) = (v.coord(i), split.mid.coord(i));
                if x > mid {
                    holds &= split.upper[i];
                } else if x < mid {
                    holds &= !split.upper[i];
                }
            }
            certain |= holds;
        }
    }
    certain &= candidates;
    let exact = (0..child_count::<P::Point>())
        .filter(|&k| {
            (candidates & !certain) >> k & 1 == 1
                && prim.intersects_aabb(&child_box_at(&split.cell, split.mid, k))
        })
        .fold(certain, |m, k| m | 1 << k);
    if exact == 0 { candidates } else { exact }
}

/// A cell about to be split: its box, its centre, and per axis the mask of the children on
/// the upper side.
pub(super) struct Split<V: Vector> {
    pub cell: Aabb<V>,
    pub mid: V,
    pub upper: [u32; 3],
    pub all: u32,
}

impl<V: Vector> Split<V> {
    pub(super) fn new(cell: &Aabb<V>) -> Self {
        let n = child_count::<V>();
        let mut upper = [0; 3];
        for (i, mask) in upper.iter_mut().enumerate().take(V::DIM) {
            *mask = (0..n)
                .filter(|k| k >> i & 1 == 1)
                .fold(0, |m, k| m | 1 << k);
        }
        Self {
            cell: *cell,
            mid: split_point(cell),
            upper,
            all: (1 << n) - 1,
        }
    }
}

/// Whether splitting a cell of `n` primitives into `children` is worth it.
///
/// Not when it would only copy the primitives: some child would receive all of them while
/// another child receives some too (they cannot be separated: many share a point, or are
/// identical). And not when the surface area heuristic (`MacDonald` and Booth, 1990) with unit
/// traversal and intersection costs says testing the `n` primitives is cheaper than visiting
/// the children: a child's boundary is `2^(1 - D)` of its parent's (a quarter of the surface
/// in 3D, half the perimeter in 2D), so the split pays only when
/// `1 + 2^(1 - D) · Σ n_child < n`. A cluster that falls into a single child is split further:
/// its cell shrinks around it.
fn split_pays<V: Vector>(n: usize, children: &[Vec<u32>]) -> bool {
    let non_empty = children.iter().filter(|c| !c.is_empty()).count();
    let only_copies = non_empty > 1 && children.iter().any(|c| c.len() == n);
    let references: usize = children.iter().map(Vec::len).sum();
    let split_cost = 1.0 + references as f64 / f64::from(1u32 << (V::DIM - 1));
    !only_copies && split_cost < n as f64
}

/// A square (cube) around `b`, centred on it, containing it despite rounding.
pub(super) fn cube_around<V: Vector>(b: &Aabb<V>) -> Aabb<V> {
    let side = (0..V::DIM)
        .map(|i| f64::from(b.max.coord(i)) - f64::from(b.min.coord(i)))
        .fold(0.0, f64::max);
    let mut cube = *b;
    for i in 0..V::DIM {
        let c = (f64::from(b.min.coord(i)) + f64::from(b.max.coord(i))) * 0.5;
        let lo = ((c - side * 0.5) as f32).max(f32::MIN).min(b.min.coord(i));
        let hi = ((c + side * 0.5) as f32).min(f32::MAX).max(b.max.coord(i));
        cube.min.set_coord(i, lo);
        cube.max.set_coord(i, hi);
    }
    cube
}

impl<P: Primitive> Orthtree<P> {
    /// A tree with the default options ([`OrthtreeOptions::default`]).
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &OrthtreeOptions::default())
    }

    /// A tree with the given options.
    pub fn build_with(prims: &[P], options: &OrthtreeOptions) -> Self {
        Self::build_observed(prims, options, &mut ())
    }

    /// Builds the tree depth first, reporting [`Event::BuildNode`] for every cell, `D`
    /// [`Event::BuildSplit`]s (one per mid-plane, with the primitives reaching each side) for
    /// every split and [`Event::BuildLeaf`] for every leaf.
    ///
    /// A cell becomes a leaf when it holds at most `leaf_size` primitives, is at
    /// `max_depth`, or when the split does not pay (it would only copy the
    /// primitives, or cost more than it saves by the surface area heuristic), which keeps
    /// inseparable input (identical primitives, many sharing a point) from splitting all the
    /// way down. Each split costs `O(n)` plus the exact tests of the primitives that straddle
    /// the cell's centre planes. Primitives with a NaN or infinite coordinate are left out
    /// ([`Primitive::has_finite_coordinates`]).
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        options: &OrthtreeOptions,
        observer: &mut O,
    ) -> Self {
        let options = OrthtreeOptions {
            leaf_size: options.leaf_size.max(1),
            max_depth: options.max_depth.min(MAX_DEPTH),
        };
        let (bounds, _) = finite_bounds(prims);
        let mut tree = Self {
            prims: prims.to_vec(),
            root: Aabb::EMPTY,
            nodes: Vec::new(),
            refs: Vec::new(),
            options,
        };
        if bounds.is_empty() {
            return tree;
        }
        tree.root = cube_around(&bounds);
        let all: Vec<u32> = (0..prims.len() as u32)
            .filter(|&i| prims[i as usize].has_finite_coordinates())
            .collect();
        tree.nodes.push(Node { first: 0, count: 0 });
        let mut stack = vec![(0u32, None, tree.root, 0usize, all)];
        while let Some((node, parent, cell, depth, list)) = stack.pop() {
            observer.on(Event::BuildNode {
                node: NodeId(node),
                parent: parent.map(NodeId),
                depth: depth as u32,
                prims: list.len() as u32,
            });
            let split = (list.len() > options.leaf_size && depth < options.max_depth)
                .then(|| tree.partition(&list, &cell))
                .filter(|(children, _)| split_pays::<P::Point>(list.len(), children));
            let Some((children, sides)) = split else {
                tree.nodes[node as usize] = Node {
                    first: tree.refs.len() as u32,
                    count: list.len() as u32,
                };
                tree.refs.extend_from_slice(&list);
                observer.on(Event::BuildLeaf {
                    node: NodeId(node),
                    prims: list.len() as u32,
                });
                continue;
            };
            for (i, (left, right)) in sides.iter().enumerate().take(P::Point::DIM) {
                observer.on(Event::BuildSplit {
                    node: NodeId(node),
                    normal: P::Point::unit_axis(i),
                    offset: midpoint(cell.min.coord(i), cell.max.coord(i)),
                    left: *left,
                    right: *right,
                    cost: None,
                });
            }
            let first = tree.nodes.len() as u32;
            tree.nodes[node as usize] = Node {
                first,
                count: INNER,
            };
            let n = children.len();
            tree.nodes
                .resize(tree.nodes.len() + n, Node { first: 0, count: 0 });
            let mid = split_point(&cell);
            for (k, child) in children.into_iter().enumerate().rev() {
                let child_cell = child_box_at(&cell, mid, k);
                stack.push((first + k as u32, Some(node), child_cell, depth + 1, child));
            }
        }
        tree
    }

    /// Each child's primitives (ascending, as `list` is), and per axis how many primitives
    /// reach the lower and the upper half.
    fn partition(&self, list: &[u32], cell: &Aabb<P::Point>) -> (Vec<Vec<u32>>, [(u32, u32); 3]) {
        let split = Split::new(cell);
        let mut children = vec![Vec::new(); child_count::<P::Point>()];
        let mut sides = [(0u32, 0u32); 3];
        for &i in list {
            let mask = child_mask(&self.prims[i as usize], &split);
            for (k, child) in children.iter_mut().enumerate() {
                if mask >> k & 1 == 1 {
                    child.push(i);
                }
            }
            for (axis, side) in sides.iter_mut().enumerate().take(P::Point::DIM) {
                side.0 += u32::from(mask & !split.upper[axis] != 0);
                side.1 += u32::from(mask & split.upper[axis] != 0);
            }
        }
        (children, sides)
    }
}
