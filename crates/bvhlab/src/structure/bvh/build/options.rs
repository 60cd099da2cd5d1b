//! What a BVH build can be told: how to split, when to stop, how to fit spheres.

/// The deepest a tree may grow (the root is depth 0). Builds stop splitting here and make a
/// leaf of whatever is left, so traversal stacks have a fixed size and build recursion a fixed
/// depth. A balanced tree over 2^32 primitives is 32 deep; only degenerate inputs come near.
/// The app's heat map shader sizes its stack from it (`STACK` in `trace.wgsl`, checked
/// against this by the app's shader test).
pub const MAX_DEPTH: usize = 64;

/// How a node's primitives are divided between its two children. Every method picks a plane
/// across one axis and sends each primitive to the side its centre lies on (pbrt-v4's
/// `SplitMethod`: `Middle`, `EqualCounts`, `SAH`).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SplitMethod {
    /// The lecture's split: the middle of the longest axis of the primitive centres' box
    /// (the spatial median). When every centre lands on one side it falls back to
    /// [`ObjectMedian`](Self::ObjectMedian).
    SpatialMedian,
    /// Half the primitives on each side: the median of the centres along the longest axis.
    /// Always splits, so the tree is balanced (depth `⌈log2(n / leaf size)⌉`).
    ObjectMedian,
    /// The surface area heuristic, evaluated at the boundaries of equal-width bins over the
    /// centres' box on every axis (Wald, "On fast Construction of SAH-based Bounding Volume
    /// Hierarchies", 2007; pbrt-v4 §7.3.2). Makes a leaf when no split is cheaper than
    /// testing every primitive; falls back to [`ObjectMedian`](Self::ObjectMedian) when the
    /// centres all coincide.
    #[default]
    BinnedSah,
}

/// How the sphere of a sphere-tree node is fitted to the vertices below it.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SphereFit {
    /// Ritter's two-pass sphere ([`Sphere::ritter_fit`](crate::Sphere::ritter_fit)): linear
    /// time with a small constant, typically 5-20% larger than the minimum. The default: a
    /// tree fits every node to all the vertices below it, so the fit runs over the whole
    /// input once per level, and the topology, not the last few percent of radius, decides
    /// most of a query's cost.
    #[default]
    Ritter,
    /// Welzl's minimal sphere ([`Sphere::welzl_fit`](crate::Sphere::welzl_fit)): the
    /// tightest, in expected linear time, with a larger constant (`f64`, a shuffled copy).
    Welzl,
}

/// Options of a BVH build. [`BvhOptions::default`] is a binned-SAH build with leaves of at
/// most 4 primitives.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhOptions {
    /// How nodes are split.
    pub method: SplitMethod,
    /// A node with more primitives than this is always split (unless it is at `max_depth`
    /// or its primitives cannot be told apart); one with at most this many becomes a leaf
    /// (median methods) or is split only when the SAH says it pays. At least 1.
    pub leaf_size: usize,
    /// Nodes at this depth become leaves whatever their size. Clamped to [`MAX_DEPTH`].
    pub max_depth: usize,
    /// SAH bins per axis, clamped to `2..=64`; pbrt-v4 uses 12, Wald 16-32.
    pub bins: usize,
    /// How sphere-tree nodes are fitted (ignored by the other node volumes).
    pub sphere_fit: SphereFit,
    /// How many primitives a leaf tests at once, for the SAH's cost of a leaf:
    /// `ceil(n / leaf_block)` instead of `n`. 1 (the default) is the lecture's cost, one test
    /// per primitive; 4 is what a [`Bvh4`](crate::structure::bvh::Bvh4) over triangles tests
    /// at once (its leaves hold them in blocks of four), so its build makes leaves whose
    /// blocks come out full ([`BvhOptions::for_triangle_blocks`]). The binned-SAH builds
    /// read it, the stepped one included; the lab builds with the default, one per primitive.
    /// At least 1.
    pub leaf_block: usize,
}

impl Default for BvhOptions {
    fn default() -> Self {
        Self {
            method: SplitMethod::BinnedSah,
            leaf_size: 4,
            max_depth: MAX_DEPTH,
            bins: 16,
            sphere_fit: SphereFit::Ritter,
            leaf_block: 1,
        }
    }
}

impl BvhOptions {
    /// The default options with another split method.
    #[must_use]
    pub fn with_method(method: SplitMethod) -> Self {
        Self {
            method,
            ..Self::default()
        }
    }

    /// The options [`Bvh4::build`](crate::structure::bvh::Bvh4::build) uses over triangles:
    /// the binned SAH costing leaves by blocks of four triangles, with leaves of up to 16.
    ///
    /// Measured on the bunny and the dragon (issue 33), against the default options'
    /// tree with the same four-triangle test: first hits 1.01-1.49x as fast by ray kind, and
    /// a third as many wide nodes; the blocks came out 95-96% full.
    #[must_use]
    pub fn for_triangle_blocks() -> Self {
        Self {
            leaf_size: 16,
            leaf_block: 4,
            ..Self::default()
        }
    }

    /// The SAH's cost of testing a leaf of `n` primitives: `n` in groups of `leaf_block`.
    pub(in crate::structure::bvh) fn leaf_cost(&self, n: usize) -> f32 {
        n.div_ceil(self.leaf_block.max(1)) as f32
    }

    /// `leaf_size`, at least 1.
    pub(in crate::structure::bvh) fn leaf_limit(&self) -> usize {
        self.leaf_size.max(1)
    }

    /// `max_depth`, at most [`MAX_DEPTH`].
    pub(in crate::structure::bvh) fn depth_limit(&self) -> usize {
        self.max_depth.min(MAX_DEPTH)
    }

    /// `bins`, within `2..=64`.
    pub(super) fn bin_count(&self) -> usize {
        self.bins.clamp(2, 64)
    }
}
