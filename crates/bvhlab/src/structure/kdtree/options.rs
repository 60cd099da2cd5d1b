//! How a k-d tree is built: which builder, and when to stop splitting.

use crate::Primitive;

/// How the median builder picks a node's split axis.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AxisRule {
    /// The longest axis of the node's cell (the lecture's choice for top-down builds).
    #[default]
    LongestAxis,
    /// `depth mod dimension`: x, y, (z,) x, ... as in Bentley's original k-d tree (1975).
    RoundRobin,
}

/// The cost model of the surface area heuristic, pbrt-v3's (§4.4.2, after `MacDonald` and
/// Booth 1990): splitting costs `traversal + intersection · (1 - bonus) · (p_below n_below +
/// p_above n_above)`, where `p` is the child cell's surface area (perimeter in 2D) over the
/// node's, and `bonus` is `empty_bonus` when one child is empty; a leaf costs
/// `intersection · n`.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SahCosts {
    /// The cost of visiting an inner node.
    pub traversal: f32,
    /// The cost of one primitive test.
    pub intersection: f32,
    /// The discount, in `[0, 1]`, on a split that leaves one child empty: cutting off empty
    /// space lets rays skip it.
    pub empty_bonus: f32,
}

impl Default for SahCosts {
    /// pbrt-v3's defaults: 1, 80, 0.5.
    fn default() -> Self {
        Self {
            traversal: 1.0,
            intersection: 80.0,
            empty_bonus: 0.5,
        }
    }
}

/// Which algorithm chooses the splitting planes.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KdBuilder {
    /// Split at the median of the primitives' centres (Bentley 1975), along the axis the rule
    /// picks; the spatial midpoint when the median lies on the cell's boundary.
    Median(AxisRule),
    /// The plane of least SAH cost among all primitive bound edges, found by a sweep over
    /// sorted edge events kept sorted from node to node: O(n log n) in total (Wald and
    /// Havran, "On building fast kd-Trees for Ray Tracing, and on doing that in O(N log N)",
    /// 2006).
    Sah(SahCosts),
}

/// How a [`KdTree`](super::KdTree) is built.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KdTreeOptions {
    /// The split algorithm.
    pub builder: KdBuilder,
    /// A node with at most this many primitive references becomes a leaf (at least 1).
    pub leaf_size: usize,
    /// The deepest a leaf may be; `None`: pbrt's `8 + 1.3 log2 n` for the SAH builder,
    /// `⌈log2(n / leaf_size)⌉ + 1` for the median builder. Never more than
    /// [`DEPTH_LIMIT`](super::build::DEPTH_LIMIT).
    pub max_depth: Option<usize>,
}

impl Default for KdTreeOptions {
    /// The SAH builder with pbrt's costs, splitting down to one primitive where it pays
    /// (for segments and triangles: [`KdTree::build`](super::KdTree::build) picks by the
    /// primitives, [`for_primitives`](Self::for_primitives)).
    fn default() -> Self {
        Self::sah()
    }
}

impl KdTreeOptions {
    /// The options [`KdTree::build`](super::KdTree::build) uses for `prims`: the median
    /// builder with leaves of up to 4 ([`median`](Self::median), longest axis) when every
    /// primitive is a point (its box a single point), the SAH builder ([`sah`](Self::sah))
    /// otherwise.
    ///
    /// A point cloud is searched for nearest neighbours, and the median split on the longest
    /// axis with small buckets is the k-d tree built for that (Friedman, Bentley and Finkel,
    /// "An Algorithm for Finding Best Matches in Logarithmic Expected Time", ACM TOMS 1977).
    /// The SAH's cost model is one of rays (a cell's surface area is the chance a ray meets
    /// it), and over points its empty-space bonus misleads it: every cell has a gap between
    /// each face and its nearest point, and cutting that gap off as an empty child earns the
    /// bonus (half the cost), more than a real split can save (at most a third of a cube's
    /// area). So the SAH tree over 200k random points cut empty slivers off its cells until
    /// the depth limit (31 levels): 2908 empty leaves and 852 of 32 points or more, a mean
    /// of 228 points per non-empty leaf, and closest points about 20 times slower than the
    /// [`Bvh4`](crate::structure::bvh::Bvh4)'s. The median tree has leaves of 2 to 4.
    pub fn for_primitives<P: Primitive>(prims: &[P]) -> Self {
        // A primitive with a non-finite coordinate is not stored: it does not count.
        let is_point = |p: &P| {
            let b = p.bounds();
            b.min == b.max || !p.has_finite_coordinates()
        };
        if !prims.is_empty() && prims.iter().all(is_point) {
            Self::median(AxisRule::LongestAxis)
        } else {
            Self::sah()
        }
    }

    /// The SAH builder with pbrt-v3's costs and leaf size 1 (the cost model decides).
    pub fn sah() -> Self {
        Self {
            builder: KdBuilder::Sah(SahCosts::default()),
            leaf_size: 1,
            max_depth: None,
        }
    }

    /// The median builder with the given axis rule and leaves of up to 4 primitives.
    pub fn median(rule: AxisRule) -> Self {
        Self {
            builder: KdBuilder::Median(rule),
            leaf_size: 4,
            max_depth: None,
        }
    }
}
