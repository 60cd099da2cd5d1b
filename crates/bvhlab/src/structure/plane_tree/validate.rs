//! Statistics and the well-formedness checks every plane tree shares: the depth-first node
//! layout, leaf contents, the nodes' boxes, and where each primitive must be stored.

use super::{PlaneNode, PlaneTree, PointOfTree, ROOT};
use crate::structure::stats::sah_cost_boxes;
use crate::structure::{Stats, ValidationError};
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// What the layout walk learns about one node.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeFacts<V: Vector> {
    /// The root is 0.
    pub depth: u32,
    /// The node's box, as the queries compute it.
    pub bound: Aabb<V>,
    /// One past the last node of its subtree: the subtree is `node..end`.
    pub end: u32,
}

/// Checks that every leaf's list (`None` for an inner node) lies inside the index list of
/// `len` entries: the walks slice it without a check, so a tree loaded from a file must pass
/// this before anything else reads its leaves.
pub(crate) fn check_leaf_ranges(
    leaves: impl Iterator<Item = Option<std::ops::Range<usize>>>,
    len: usize,
) -> Result<(), ValidationError> {
    for (node, range) in leaves.enumerate() {
        if let Some(range) = range.filter(|range| range.end > len) {
            return Err(ValidationError::new(format!(
                "leaf {node} lists entries {range:?} of {len}"
            )));
        }
    }
    Ok(())
}

/// Walks the tree in depth-first order and checks its layout: the nodes are numbered in
/// preorder (so every subtree is a contiguous range and the below child follows its parent),
/// every node is reached exactly once, and leaves list valid primitive indices without
/// repeats. Returns each node's facts.
pub(crate) fn check_layout<T: PlaneTree>(
    tree: &T,
) -> Result<Vec<NodeFacts<PointOfTree<T>>>, ValidationError> {
    let count = tree.node_count();
    let Some(root) = tree.root_bound() else {
        return if count == 0 {
            Ok(Vec::new())
        } else {
            Err(ValidationError::new("nodes without a root box"))
        };
    };
    let n_prims = tree.prims().len();
    let mut facts = Vec::with_capacity(count);
    let mut seen = vec![false; n_prims];
    // Preorder: the node popped next must be the next index.
    let mut stack = vec![(ROOT, 0u32, root)];
    while let Some((node, depth, bound)) = stack.pop() {
        if node as usize != facts.len() || node as usize >= count {
            return Err(ValidationError::new(format!(
                "node {node} reached out of depth-first order (expected {})",
                facts.len()
            )));
        }
        facts.push(NodeFacts {
            depth,
            bound,
            end: 0,
        });
        match tree.node(node) {
            PlaneNode::Leaf(list) => {
                for &prim in list {
                    let slot = seen.get_mut(prim as usize).ok_or_else(|| {
                        ValidationError::new(format!(
                            "leaf {node} lists primitive {prim} of {n_prims}"
                        ))
                    })?;
                    if std::mem::replace(slot, true) {
                        return Err(ValidationError::new(format!(
                            "leaf {node} lists primitive {prim} twice"
                        )));
                    }
                }
                for &prim in list {
                    seen[prim as usize] = false;
                }
            }
            PlaneNode::Inner([below, above]) => {
                // Both children must exist before `child_bounds` reads them.
                if below != node + 1 || above <= below || above as usize >= count {
                    return Err(ValidationError::new(format!(
                        "inner node {node} has children {below} and {above}; expected {} first",
                        node + 1
                    )));
                }
                let bounds = tree.child_bounds(node, &bound);
                stack.push((above, depth + 1, bounds[1]));
                stack.push((below, depth + 1, bounds[0]));
            }
        }
    }
    if facts.len() != count {
        return Err(ValidationError::new(format!(
            "{} of {count} nodes are reachable from the root",
            facts.len()
        )));
    }
    // Subtree ends, children before parents: a leaf ends after itself, an inner node where
    // its above child's subtree ends.
    for node in (0..count).rev() {
        facts[node].end = match tree.node(node as u32) {
            PlaneNode::Leaf(_) => node as u32 + 1,
            PlaneNode::Inner([_, above]) => facts[above as usize].end,
        };
    }
    for node in 0..count {
        if let PlaneNode::Inner([below, above]) = tree.node(node as u32)
            && facts[below as usize].end != above
        {
            return Err(ValidationError::new(format!(
                "node {node}: its above child {above} does not follow its below subtree"
            )));
        }
    }
    Ok(facts)
}

/// For each primitive, the leaves that list it, ascending (leaves are numbered in preorder, so
/// "is the primitive under node `n`" is a range search).
pub(crate) fn leaves_of_prims<T: PlaneTree>(tree: &T) -> Vec<Vec<u32>> {
    let mut leaves = vec![Vec::new(); tree.prims().len()];
    for node in 0..tree.node_count() as u32 {
        if let PlaneNode::Leaf(list) = tree.node(node) {
            for &prim in list {
                leaves[prim as usize].push(node);
            }
        }
    }
    leaves
}

/// Checks that every primitive is stored wherever it must be: starting from the root (for
/// primitives with finite bounds; the others must not be stored at all), `must_enter(node,
/// children, prim, facts)` says which children of an inner node must hold the primitive
/// somewhere below them.
pub(crate) fn check_coverage<T: PlaneTree>(
    tree: &T,
    facts: &[NodeFacts<PointOfTree<T>>],
    mut must_enter: impl FnMut(u32, [u32; 2], &T::Prim, &[NodeFacts<PointOfTree<T>>]) -> [bool; 2],
) -> Result<(), ValidationError> {
    let leaves = leaves_of_prims(tree);
    for (index, prim) in tree.prims().iter().enumerate() {
        let under = |node: u32| {
            // A tree without nodes (a damaged saved file) stores nothing.
            let Some(end) = facts.get(node as usize).map(|fact| fact.end) else {
                return false;
            };
            let at = leaves[index].partition_point(|&leaf| leaf < node);
            leaves[index].get(at).is_some_and(|&leaf| leaf < end)
        };
        if !prim.has_finite_coordinates() {
            if !leaves[index].is_empty() {
                return Err(ValidationError::new(format!(
                    "primitive {index} has non-finite coordinates but is stored"
                )));
            }
            continue;
        }
        let mut stack = vec![ROOT];
        while let Some(node) = stack.pop() {
            if !under(node) {
                return Err(ValidationError::new(format!(
                    "primitive {index} must be stored under node {node} but is not"
                )));
            }
            if let PlaneNode::Inner(children) = tree.node(node) {
                let must = must_enter(node, children, prim, facts);
                stack.extend((0..2).filter(|&side| must[side]).map(|side| children[side]));
            }
        }
    }
    Ok(())
}

/// Checks that every child's box lies inside its parent's.
pub(crate) fn check_nesting<T: PlaneTree>(
    tree: &T,
    facts: &[NodeFacts<PointOfTree<T>>],
) -> Result<(), ValidationError> {
    for (node, fact) in facts.iter().enumerate() {
        if let PlaneNode::Inner(children) = tree.node(node as u32) {
            for child in children {
                let inner = &facts[child as usize].bound;
                let inside = inner.is_empty()
                    || (fact.bound.contains(inner.min) && fact.bound.contains(inner.max));
                if !inside {
                    return Err(ValidationError::new(format!(
                        "child {child}'s box {inner:?} is not inside node {node}'s {:?}",
                        fact.bound
                    )));
                }
            }
        }
    }
    Ok(())
}

/// Node and leaf counts, depth, leaf sizes, references and the SAH cost of the nodes' boxes.
pub(crate) fn plane_tree_stats<T: PlaneTree>(tree: &T, memory_bytes: usize) -> Stats {
    let mut stats = Stats {
        primitives: tree.prims().len(),
        memory_bytes,
        leaf_sizes: vec![0],
        ..Stats::default()
    };
    let Some(root) = tree.root_bound() else {
        return stats;
    };
    let mut sizes = Vec::new();
    let mut regions = Vec::with_capacity(tree.node_count());
    let mut stack = vec![(ROOT, 0usize, root)];
    while let Some((node, depth, bound)) = stack.pop() {
        stats.nodes += 1;
        match tree.node(node) {
            PlaneNode::Leaf(list) => {
                stats.leaves += 1;
                stats.max_depth = stats.max_depth.max(depth);
                stats.references += list.len();
                sizes.push(list.len());
                regions.push((bound, Some(list.len())));
            }
            PlaneNode::Inner(children) => {
                regions.push((bound, None));
                let bounds = tree.child_bounds(node, &bound);
                stack.push((children[1], depth + 1, bounds[1]));
                stack.push((children[0], depth + 1, bounds[0]));
            }
        }
    }
    stats.leaf_sizes = Stats::leaf_size_histogram(sizes.into_iter());
    stats.sah_cost = sah_cost_boxes(regions.into_iter());
    stats
}
