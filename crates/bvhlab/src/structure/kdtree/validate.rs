//! Checking a k-d tree: the depth-first layout, cells nested in their parents, and every
//! primitive stored in every leaf whose cell it reaches into.

use super::KdTree;
use super::build::DEPTH_LIMIT;
use super::layout::KdNode;
use crate::structure::ValidationError;
use crate::structure::check_primitives_contract;
use crate::structure::contract_rounding;
use crate::structure::plane_tree::validate::{
    check_coverage, check_layout, check_leaf_ranges, check_nesting,
};
use crate::structure::plane_tree::{PlaneNode, PlaneTree};
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// Up to this many primitives the coverage check is exact (one exact primitive-box test per
/// primitive and cell it reaches); above, it only checks that every primitive is stored.
pub const EXACT_COVERAGE_LIMIT: usize = 100_000;

/// The cell's interior, approximated from inside by moving each face that is a split plane
/// inwards by `rounding` (at least one `f32` step); `None` when the cell is too thin to have
/// one. Faces on the root cell's boundary stay: no neighbouring cell holds the points on
/// them, so the cell must.
fn interior<V: Vector>(cell: &Aabb<V>, root: &Aabb<V>, rounding: f32) -> Option<Aabb<V>> {
    let mut inner = *cell;
    for axis in 0..V::DIM {
        let (min, max) = (cell.min.coord(axis), cell.max.coord(axis));
        let (lo, hi) = (
            if min == root.min.coord(axis) {
                min
            } else {
                (min + rounding).max(min.next_up())
            },
            if max == root.max.coord(axis) {
                max
            } else {
                (max - rounding).min(max.next_down())
            },
        );
        if lo > hi {
            return None;
        }
        inner.min.set_coord(axis, lo);
        inner.max.set_coord(axis, hi);
    }
    Some(inner)
}

/// Checks the tree's invariants:
/// - the nodes form one tree in depth-first order, leaves list valid indices once each, no
///   leaf is deeper than [`DEPTH_LIMIT`], split axes exist in this dimension;
/// - the root cell is the box of the primitives with finite coordinates, and every split
///   lies inside its node's cell (so children's cells lie inside their parent's);
/// - every such primitive is stored, and (up to [`EXACT_COVERAGE_LIMIT`] primitives) in
///   every leaf whose cell's interior it reaches, checked with the exact
///   [`Primitive::intersects_aabb`]. A primitive that only touches a cell's boundary may be
///   stored on the other side of it: the closed neighbouring cell holds the touching points.
///
/// # Errors
/// The first violation found.
pub fn validate<P: Primitive>(tree: &KdTree<P>) -> Result<(), ValidationError> {
    check_primitives_contract(tree.prims())?;
    let finite = tree
        .prims()
        .iter()
        .filter(|prim| prim.has_finite_coordinates())
        .map(Primitive::bounds)
        .fold(Aabb::EMPTY, |c: Aabb<P::Point>, b| c.merge(&b));
    if !tree.nodes().is_empty() && finite != tree.root_cell() {
        return Err(ValidationError::new(format!(
            "the root cell {:?} is not the box of the primitives {finite:?}",
            tree.root_cell()
        )));
    }
    check_leaf_ranges(
        tree.nodes().iter().map(|n| n.is_leaf().then(|| n.range())),
        tree.indices.len(),
    )?;
    // The layout walk cuts cells along the split axes: an axis must exist before it runs.
    if let Some(node) = tree
        .nodes()
        .iter()
        .position(|n| !n.is_leaf() && n.axis() >= P::Point::DIM)
    {
        return Err(ValidationError::new(format!(
            "node {node} splits axis {}, not one of {} axes",
            tree.nodes()[node].axis(),
            P::Point::DIM
        )));
    }
    let facts = check_layout(tree)?;
    check_nesting(tree, &facts)?;
    for (node, fact) in facts.iter().enumerate() {
        let n: &KdNode = &tree.nodes()[node];
        if fact.depth as usize > DEPTH_LIMIT {
            return Err(ValidationError::new(format!(
                "node {node} is at depth {}",
                fact.depth
            )));
        }
        if !n.is_leaf() {
            let (lo, hi) = (
                fact.bound.min.coord(n.axis()),
                fact.bound.max.coord(n.axis()),
            );
            if n.axis() >= P::Point::DIM || !(lo <= n.split() && n.split() <= hi) {
                return Err(ValidationError::new(format!(
                    "node {node} splits axis {} at {} outside its cell [{lo}, {hi}]",
                    n.axis(),
                    n.split()
                )));
            }
        }
    }
    // A leaf lists only primitives whose box meets its closed cell: the coverage check below
    // lets a primitive on a split plane be stored on either side, and this keeps it from
    // being stored in a leaf no query near it visits.
    for (node, fact) in facts.iter().enumerate() {
        if let PlaneNode::Leaf(list) = PlaneTree::node(tree, node as u32)
            && let Some(&prim) = list
                .iter()
                .find(|&&prim| !tree.prims()[prim as usize].bounds().overlaps(&fact.bound))
        {
            return Err(ValidationError::new(format!(
                "leaf {node} lists primitive {prim}, whose box misses its cell"
            )));
        }
    }
    let exact = tree.prims().len() <= EXACT_COVERAGE_LIMIT;
    check_coverage(tree, &facts, |_, children, prim, facts| {
        // The rounding the primitive contract allows the primitive's own tests: a few units
        // in the last place of its coordinates ([`contract_rounding`]). A
        // ball whose box starts on a plane may touch the cell beyond it by its exact test
        // (its `center - radius` rounded), and the builder rightly sends it to one side only.
        let rounding = contract_rounding(prim);
        children.map(|child| {
            exact
                && interior(&facts[child as usize].bound, &tree.root_cell(), rounding)
                    .is_some_and(|inside| prim.intersects_aabb(&inside))
        })
    })
}
