//! Numbers that let two structures be compared, and the well-formedness report.

use std::fmt;

use crate::Vector;
use crate::volume::{Aabb, BoundingVolume};

/// The shape and size of a built structure.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// Nodes (for a grid: cells), leaves included.
    pub nodes: usize,
    /// Leaves (for a grid: non-empty cells).
    pub leaves: usize,
    /// The deepest leaf's depth (the root is 0; 0 for a grid).
    pub max_depth: usize,
    /// `leaf_sizes[n]` leaves hold `n` primitive references; the last bucket also counts
    /// every larger leaf.
    pub leaf_sizes: Vec<usize>,
    /// Primitives the structure was built over.
    pub primitives: usize,
    /// Primitive references stored in leaves (cells). More than `primitives` when a
    /// primitive is listed in several leaves.
    pub references: usize,
    /// Heap memory the structure uses, in bytes (nodes, index lists, its copy of the
    /// primitives).
    pub memory_bytes: usize,
    /// The surface area heuristic cost with traversal and intersection costs 1, normalised by
    /// the root's area (`MacDonald` and Booth, 1990): `Σ_inner A(n)/A(root) + Σ_leaf
    /// |n| A(n)/A(root)`, with `A` the perimeter in 2D. `None` where it does not apply.
    pub sah_cost: Option<f32>,
}

impl Stats {
    /// References beyond one per primitive: the price of splitting space rather than objects.
    pub fn duplicated_references(&self) -> usize {
        self.references.saturating_sub(self.primitives)
    }

    /// The last bucket of [`leaf_sizes`](Self::leaf_sizes): it counts the leaves of this
    /// many primitives or more.
    pub const LEAF_SIZE_LAST: usize = 32;

    /// A histogram with buckets `0..=LEAF_SIZE_LAST` from leaf sizes.
    pub fn leaf_size_histogram(sizes: impl Iterator<Item = usize>) -> Vec<usize> {
        const LAST: usize = Stats::LEAF_SIZE_LAST;
        let mut histogram = vec![0; LAST + 1];
        for size in sizes {
            histogram[size.min(LAST)] += 1;
        }
        while histogram.len() > 1 && histogram.last() == Some(&0) {
            histogram.pop();
        }
        histogram
    }
}

/// The SAH cost of a tree from its nodes' bounding volumes: `(volume, leaf primitive count or
/// None for an inner node)` per node, root first. `None` when the root's boundary measure is
/// zero or not finite.
pub fn sah_cost<B: BoundingVolume>(nodes: impl Iterator<Item = (B, Option<usize>)>) -> Option<f32> {
    let mut root_area = None;
    let mut cost = 0.0f64;
    for (volume, leaf) in nodes {
        let area = f64::from(volume.boundary_measure());
        let root = *root_area.get_or_insert(area);
        // A flat root has no area to normalise by; a root whose area overflowed f32 (scenes
        // beyond ~1e19) has no meaningful ratio. Both: no SAH cost rather than inf or NaN.
        if root <= 0.0 || !root.is_finite() || !area.is_finite() {
            return None;
        }
        cost += area / root * leaf.map_or(1.0, |n| n as f64);
    }
    root_area.map(|_| cost as f32)
}

/// The SAH cost with axis-aligned boxes as node regions (k-d trees, octrees, BSP trees use
/// their cells' boxes).
pub fn sah_cost_boxes<V: Vector>(
    nodes: impl Iterator<Item = (Aabb<V>, Option<usize>)>,
) -> Option<f32> {
    sah_cost(nodes)
}

/// Why a structure is not well formed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValidationError {
    /// What is wrong, and where.
    pub message: String,
}

impl ValidationError {
    /// An error with this message.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "malformed structure: {}", self.message)
    }
}

impl std::error::Error for ValidationError {}
