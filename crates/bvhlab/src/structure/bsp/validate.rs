//! Checking a BSP tree: the depth-first layout, planes, boxes, and that every primitive is
//! stored on each side of a plane that it certainly reaches.

use super::BspTree;
use super::build::{DEPTH_LIMIT, bounds_of};
use super::plane::Plane;
use crate::structure::ValidationError;
use crate::structure::check_primitives_contract;
use crate::structure::plane_tree::validate::{
    check_coverage, check_layout, check_leaf_ranges, check_nesting,
};
use crate::structure::plane_tree::{PlaneNode, PlaneTree};
use crate::volume::BoundingVolume;
use crate::{Primitive, Vector as _};

/// Checks the tree's invariants:
/// - the nodes form one tree in depth-first order, leaves list valid indices once each, no
///   leaf is deeper than [`DEPTH_LIMIT`];
/// - every inner node's plane has a finite unit normal and a finite offset;
/// - every node's box is the box of the primitives below it (so children lie inside parents);
/// - every primitive with finite coordinates is stored, under each side of a plane on which
///   it has a vertex clearly off the plane, all the way down to the leaves.
///
/// # Errors
/// The first violation found.
pub fn validate<P: Primitive>(tree: &BspTree<P>) -> Result<(), ValidationError> {
    check_primitives_contract(tree.prims())?;
    check_leaf_ranges(
        tree.nodes().iter().map(|n| n.is_leaf().then(|| n.range())),
        tree.indices.len(),
    )?;
    let facts = check_layout(tree)?;
    check_nesting(tree, &facts)?;
    let prims = tree.prims();
    for (node, fact) in facts.iter().enumerate() {
        if fact.depth as usize > DEPTH_LIMIT {
            return Err(ValidationError::new(format!(
                "node {node} is at depth {}",
                fact.depth
            )));
        }
        let stored = &tree.nodes()[node];
        match PlaneTree::node(tree, node as u32) {
            PlaneNode::Leaf(list) => {
                if bounds_of(prims, list) != stored.bounds() {
                    return Err(ValidationError::new(format!(
                        "leaf {node}'s box is not the box of its primitives"
                    )));
                }
            }
            PlaneNode::Inner([below, above]) => {
                let merged = facts[below as usize]
                    .bound
                    .merge(&facts[above as usize].bound);
                if merged != stored.bounds() {
                    return Err(ValidationError::new(format!(
                        "node {node}'s box is not the box of its children's"
                    )));
                }
                let n = stored.normal();
                let unit = (n.length() - 1.0).abs() < 1e-5;
                if !(n.is_finite() && stored.offset().is_finite() && unit) {
                    return Err(ValidationError::new(format!(
                        "node {node} has the plane {n:?} · x = {}",
                        stored.offset()
                    )));
                }
            }
        }
    }
    check_coverage(tree, &facts, |node, _, prim, _| {
        let stored = &tree.nodes()[node as usize];
        let plane = Plane {
            normal: stored.normal(),
            offset: stored.offset(),
        };
        let sides = plane.certain_sides(prim);
        [sides.below, sides.above]
    })
}
