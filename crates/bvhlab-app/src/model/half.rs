//! What the 2D and the 3D half share: the structure (and the one it is compared with), the
//! question stepped through, and the playback transport. Each half keeps its own, so that
//! switching halves leaves the other as it was.

use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Bvh, Obb, Ray, SpatialIndex, Sphere};

use super::dimension::LabPrimitive;
use super::lane::{BuildBudget, Lane};
use super::lane_name::lane_name;
use super::playback::Playback;
use super::question::{Task, Variant};
use super::recording::Question;
use super::refit::UpdateMode;
use super::structures::{BuildSettings, StructureKind};
use crate::pseudocode::variants;

/// The largest `k` of the k-nearest query.
pub const MAX_K: usize = 64;

/// One half's structures, question and playback.
pub struct Half<P: LabPrimitive> {
    /// The structure.
    pub lane: Lane<P>,
    /// A second structure on the same primitives and question, shown beside the first.
    pub compare: Option<Lane<P>>,
    /// What playback steps through.
    pub task: Task,
    /// Which version of the algorithm.
    pub variant: Variant,
    /// How many neighbours the point query finds.
    pub k: usize,
    /// The range query's radius.
    pub radius: f32,
    /// The transport.
    pub playback: Playback,
}

impl<P: LabPrimitive> Half<P> {
    /// A half with `settings`' structure, asking for the first hit along a ray.
    pub fn new(settings: BuildSettings, radius: f32) -> Self {
        Self {
            lane: Lane::new(settings),
            compare: None,
            task: Task::FirstHit,
            variant: Variant::Full,
            k: 1,
            radius,
            playback: Playback::default(),
        }
    }

    /// The lanes shown: the main one, and the comparison when on.
    pub fn lanes(&self) -> impl Iterator<Item = &Lane<P>> {
        std::iter::once(&self.lane).chain(self.compare.as_ref())
    }

    /// Lane `index`: 1 is the comparison when on; anything else the main lane.
    pub fn lane_at(&self, index: usize) -> &Lane<P> {
        match (index, &self.compare) {
            (1, Some(other)) => other,
            _ => &self.lane,
        }
    }

    /// What lane `index` is called beside the other (see [`lane_name`]).
    pub fn lane_name(&self, index: usize) -> String {
        let other = self
            .lanes()
            .nth(1 - index.min(1))
            .filter(|_| self.compare.is_some());
        let lane = self.lane_at(index);
        let mut name = lane_name(
            &lane.settings,
            other.map(|l| &l.settings),
            <P::Point as bvhlab::Vector>::DIM,
        );
        // Two lanes that differ in how they follow moving primitives (the drifting preset).
        if other.is_some_and(|o| o.update != lane.update) && lane.settings.kind.is_bvh() {
            name.push_str(match lane.update {
                UpdateMode::Refit => ", refitted",
                UpdateMode::Rebuild => ", rebuilt",
            });
        }
        name
    }

    /// How many lanes are shown.
    pub fn lane_count(&self) -> usize {
        1 + usize::from(self.compare.is_some())
    }

    /// The longest recording's length: the last step of playback.
    pub fn steps(&self) -> usize {
        self.lanes().map(Lane::steps).max().unwrap_or(0)
    }

    /// The variant a lane of `kind` runs: the chosen one where `kind` has it for the task,
    /// else the full algorithm.
    pub fn variant_for(&self, kind: StructureKind) -> Variant {
        if variants(kind, self.task).contains(&self.variant) {
            self.variant
        } else {
            Variant::Full
        }
    }

    /// The question a lane of `kind` steps through, about `ray` and `point`.
    pub fn question(
        &self,
        kind: StructureKind,
        ray: Option<Ray<P::Point>>,
        point: Option<P::Point>,
    ) -> Question<P::Point> {
        Question {
            task: self.task,
            variant: self.variant_for(kind),
            ray,
            point,
            k: self.k.clamp(1, MAX_K),
            radius: self.radius,
        }
    }

    /// Makes the question about the ray (first hit, unless another ray task is chosen).
    pub fn ask_about_ray(&mut self) {
        if !matches!(self.task, Task::FirstHit | Task::AnyHit | Task::AllHits) {
            self.set_task(Task::FirstHit);
        }
    }

    /// Makes the question about the point (nearest, unless the range task is chosen).
    pub fn ask_about_point(&mut self) {
        if !matches!(self.task, Task::Nearest | Task::Range) {
            self.set_task(Task::Nearest);
        }
    }

    /// Sets what lane `lane` (0: the structure, 1: the comparison) does when the
    /// primitives move.
    ///
    /// # Errors
    /// When there is no such lane.
    pub fn set_update_mode(&mut self, lane: usize, mode: UpdateMode) -> Result<(), String> {
        let target = match (lane, &mut self.compare) {
            (0, _) => &mut self.lane,
            (1, Some(other)) => other,
            (1, None) => {
                return Err("there is no comparison structure to set the update of".to_owned());
            }
            _ => {
                return Err(format!(
                    "there is no lane {lane}: 0 is the structure, 1 the comparison"
                ));
            }
        };
        target.update = mode;
        Ok(())
    }

    /// Rebuilds every lane's structure at the next refresh, also in refit mode.
    pub fn rebuild_now(&mut self) {
        self.lane.rebuild_now();
        if let Some(other) = &mut self.compare {
            other.rebuild_now();
        }
    }

    /// Changes the task; a variant the new task does not have goes back to the full
    /// algorithm, so that the panel always shows the one that runs.
    pub fn set_task(&mut self, task: Task) {
        self.task = task;
        if !variants(self.lane.settings.kind, task).contains(&self.variant) {
            self.variant = Variant::Full;
        }
    }
}

impl<P: LabPrimitive> Half<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
    Bvh<Sphere<P::Point>, P>: SpatialIndex,
    Bvh<Aabb<P::Point>, P>: SpatialIndex,
    Bvh<Obb<P::Point>, P>: SpatialIndex,
{
    /// Builds (within `budget`), re-records the question about `ray` and `point` when it
    /// changed, keeps playback inside the recordings and brings the snapshots to its step.
    pub fn refresh(
        &mut self,
        prims: &[P],
        revision: u64,
        ray: Option<Ray<P::Point>>,
        point: Option<P::Point>,
        budget: BuildBudget,
    ) {
        let question = self.question(self.lane.settings.kind, ray, point);
        let mut changed = self.lane.refresh(prims, revision, &question, budget);
        if let Some(kind) = self.compare.as_ref().map(|l| l.settings.kind) {
            let question = self.question(kind, ray, point);
            if let Some(other) = &mut self.compare {
                changed |= other.refresh(prims, revision, &question, budget);
            }
        }
        if changed {
            let len = self.steps();
            self.playback.fit(len);
        }
        self.lane.follow(&self.playback, revision);
        if let Some(other) = &mut self.compare {
            other.follow(&self.playback, revision);
        }
    }
}
