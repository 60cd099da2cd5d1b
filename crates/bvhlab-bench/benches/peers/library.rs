//! One small interface that every library of the comparison is put behind, so that the
//! measurement code is written once and a new entry point (a faster traversal of bvhlab, say)
//! is a few lines in one adapter.

use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use bvhlab_bench::workload::BenchRay;

/// What a query cost, as far as a library reports it.
#[derive(Clone, Copy, Debug, Default)]
pub struct RayCost {
    /// Nodes visited (tinybvh: its traversal "steps").
    pub nodes: Option<u64>,
    /// Primitive (triangle) tests.
    pub prims: Option<u64>,
}

/// The shape of a built tree, computed the same way for every library that shows its nodes.
#[derive(Clone, Copy, Debug, Default)]
pub struct TreeFacts {
    /// Nodes, leaves included.
    pub nodes: Option<usize>,
    /// SAH cost with `C_trav = C_tri = 1`, normalised by the root's area ([`sah_cost`]).
    pub sah: Option<f64>,
    /// Bytes the built structure holds (nodes, index lists, its copy of the triangles).
    pub bytes: Option<usize>,
}

/// A library under test. Implemented by a marker type per library; the tree may borrow the
/// library's input (tinybvh keeps a pointer to its vertices).
pub trait Library {
    /// The name in the tables.
    const NAME: &'static str;
    /// Whether [`closest_distance`](Self::closest_distance) is implemented.
    const HAS_CLOSEST: bool;
    /// Whether [`occluded`](Self::occluded) is the library's own occlusion (any-hit) call;
    /// when not, the shadow rays are only timed as first hits.
    const HAS_OCCLUSION: bool = false;
    /// The triangles in the library's own format (converted before timing).
    type Input;
    /// The built structure.
    type Tree<'a>
    where
        Self: 'a;
    /// A ray in the library's own format (converted before timing).
    type Ray;

    /// Converts the triangles (not timed).
    fn input(tris: &[Triangle3]) -> Self::Input;
    /// Builds the structure (timed).
    fn build(input: &Self::Input) -> Self::Tree<'_>;
    /// Converts a ray (not timed).
    fn ray(ray: &BenchRay) -> Self::Ray;
    /// The distance to the first hit with `t <= t_max`, if any (timed).
    fn first_hit(tree: &Self::Tree<'_>, ray: &Self::Ray) -> Option<f32>;
    /// What the first-hit query of `ray` cost (not timed; may run an instrumented variant).
    fn first_hit_cost(_tree: &Self::Tree<'_>, _ray: &Self::Ray) -> RayCost {
        RayCost::default()
    }
    /// Whether anything blocks the ray within its `t_max` (timed; shadow rays). Called only
    /// when [`HAS_OCCLUSION`](Self::HAS_OCCLUSION) is set.
    fn occluded(_tree: &Self::Tree<'_>, _ray: &Self::Ray) -> bool {
        unreachable!("occluded is only called when HAS_OCCLUSION is set")
    }
    /// The distance from `point` to the nearest triangle (timed; `None` when not supported).
    fn closest_distance(_tree: &Self::Tree<'_>, _point: Vec3) -> Option<f32> {
        None
    }
    /// Nodes, SAH cost and memory of the built tree.
    fn facts(tree: &Self::Tree<'_>) -> TreeFacts;
}

/// Accumulates the SAH cost of a binary tree node by node: `Σ_inner A(n)/A(root) +
/// Σ_leaf |n| · A(n)/A(root)` (`MacDonald` and Booth, 1990), with `A` the box's surface area
/// and traversal and triangle costs both 1: the formula bvhlab's own `Stats::sah_cost` uses.
#[derive(Clone, Copy, Debug, Default)]
pub struct SahSum {
    root_area: Option<f64>,
    cost: f64,
    nodes: usize,
}

impl SahSum {
    /// Adds one node with box `(min, max)` and `prims` triangles (0 for an inner node). The
    /// first node added must be the root.
    pub fn add(&mut self, min: [f32; 3], max: [f32; 3], prims: usize) {
        let d = [0, 1, 2].map(|i| f64::from(max[i] - min[i]).max(0.0));
        let area = 2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
        let root = *self.root_area.get_or_insert(area);
        self.cost += area / root * if prims == 0 { 1.0 } else { prims as f64 };
        self.nodes += 1;
    }

    /// The cost and the node count; no cost when the root is flat.
    pub fn finish(self) -> (Option<f64>, usize) {
        let cost = self.root_area.filter(|&a| a > 0.0).map(|_| self.cost);
        (cost, self.nodes)
    }
}

/// The triangles as one vertex list with equal corners merged (compared bit for bit) and an
/// index triple per triangle: the input of the peers that take an indexed mesh (parry3d,
/// Embree).
pub fn indexed_mesh(tris: &[Triangle3]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut index = std::collections::HashMap::new();
    let mut vertices = Vec::new();
    let mut corner = |p: Vec3| {
        *index
            .entry(p.to_array().map(f32::to_bits))
            .or_insert_with(|| {
                vertices.push(p);
                vertices.len() as u32 - 1
            })
    };
    let indices = tris
        .iter()
        .map(|t| [corner(t.a), corner(t.b), corner(t.c)])
        .collect();
    (vertices, indices)
}
