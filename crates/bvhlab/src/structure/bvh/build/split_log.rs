//! What the builder decided at each node, kept for the lab to plot: the SAH cost of every
//! candidate plane, the plane it chose, and the cost of not splitting at all.

use crate::structure::NodeId;
use crate::structure::bvh::SplitMethod;

/// One node's split decision.
///
/// For a SAH split, `planes[i]` is the position of the boundary after bin `i` along `axis`
/// and `bin_costs[i]` the estimated cost of splitting there: `1 + (A(left) N(left) +
/// A(right) N(right)) / A(node)`, in units of one primitive test, with `A` the surface area
/// (perimeter in 2D) of each side's box and `N` its primitive count; an empty side costs
/// `+inf`. Not splitting costs `leaf_cost = N(node)` (counted in groups of `leaf_block`, 1 by
/// default). Median splits have no curve.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitRecord {
    /// The node.
    pub node: NodeId,
    /// The method that made the decision: [`SplitMethod::ObjectMedian`] where a spatial
    /// median or the SAH had to fall back to it.
    pub method: SplitMethod,
    /// The axis of the split plane.
    pub axis: usize,
    /// Where the plane crosses `axis`.
    pub position: f32,
    /// SAH only: the candidate planes along `axis`, one per bin boundary.
    pub planes: Vec<f32>,
    /// SAH only: the cost of splitting at each of `planes`.
    pub bin_costs: Vec<f32>,
    /// SAH only: the index of the cheapest plane.
    pub chosen_bin: Option<usize>,
    /// The cost of making the node a leaf: its primitive count.
    pub leaf_cost: f32,
    /// Primitives on the low side of the plane.
    pub left: u32,
    /// Primitives on the high side.
    pub right: u32,
    /// Whether the node became a leaf after all (the SAH found no split cheaper than the
    /// leaf, and the node was small enough to stay one).
    pub made_leaf: bool,
}
