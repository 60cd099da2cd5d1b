//! The question a lane steps through: the task (which query, or the build), which version
//! of the algorithm, and its inputs (the ray or the point, k, the radius).

use bvhlab::Ray;
use bvhlab::Vector;
use bvhlab::glam::Vec2;

/// What is being stepped through.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Task {
    /// The first hit along a ray.
    FirstHit,
    /// Some hit along a ray, not necessarily the first (shadow rays): stops at the first
    /// one found.
    AnyHit,
    /// Every hit along a ray.
    AllHits,
    /// The k nearest primitives to a point (the lecture's distance query for k = 1).
    Nearest,
    /// Every primitive in a box or ball.
    Range,
    /// Building the structure.
    Build,
}

impl Task {
    /// Every task, queries first.
    pub const ALL: [Self; 6] = [
        Self::FirstHit,
        Self::AnyHit,
        Self::AllHits,
        Self::Nearest,
        Self::Range,
        Self::Build,
    ];
}

/// Which version of the algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// What the core runs: near-first order, pruning by the best so far.
    Full,
    /// The slides' pseudocode, literally (BVH first hit and BVH nearest only).
    Lecture,
    /// The slides' minDistance plus the pruning the slide leaves out (BVH nearest only).
    LecturePruned,
}

/// The question: everything a recording depends on besides the structure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Question<V: Vector = Vec2> {
    /// What to step through.
    pub task: Task,
    /// Which version of the algorithm.
    pub variant: Variant,
    /// The ray, for ray tasks.
    pub ray: Option<Ray<V>>,
    /// The query point, for point tasks.
    pub point: Option<V>,
    /// How many nearest primitives.
    pub k: usize,
    /// The range query's radius around the point.
    pub radius: f32,
}
