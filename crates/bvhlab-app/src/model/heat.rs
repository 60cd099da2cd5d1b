//! The traversal-cost heat map's settings: whether it is shown, what a pixel counts and
//! where it is computed. The map itself (the tracing, the textures) belongs to the 3D view
//! ([`crate::lab3d::heat`]); the model keeps what the student chose.

use bvhlab::structure::QueryCost;

/// Where the map is computed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Device {
    /// The GPU when it can, else the CPU.
    #[default]
    Auto,
    /// Always the CPU.
    Cpu,
}

/// The heat map's settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct HeatSettings {
    /// Whether it is shown.
    pub on: bool,
    /// What a pixel counts.
    pub metric: Metric,
    /// Where it is computed.
    pub device: Device,
}

/// What a pixel's count counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Metric {
    /// Nodes visited: [`QueryCost::nodes_visited`], the nodes the traversal entered (popped
    /// and not pruned), the work the ray needed to reach its first hit. Children whose
    /// volume was tested and refused are not counted (they are bound tests).
    #[default]
    Nodes,
    /// Primitive tests: [`QueryCost::prim_tests`], the triangles tested.
    PrimitiveTests,
}

impl Metric {
    /// The count this metric reads from a query's cost (saturating at `u32::MAX`).
    pub fn count(self, cost: &QueryCost) -> u32 {
        let n = match self {
            Metric::Nodes => cost.nodes_visited,
            Metric::PrimitiveTests => cost.prim_tests,
        };
        u32::try_from(n).unwrap_or(u32::MAX)
    }

    /// A short label for the legend.
    pub fn label(self) -> &'static str {
        match self {
            Metric::Nodes => "nodes visited per ray",
            Metric::PrimitiveTests => "triangle tests per ray",
        }
    }

    /// The index the shaders use (0: nodes, 1: primitive tests).
    pub fn index(self) -> u32 {
        match self {
            Metric::Nodes => 0,
            Metric::PrimitiveTests => 1,
        }
    }
}
