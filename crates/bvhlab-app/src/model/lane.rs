//! One structure over one half's primitives, with everything derived from it: the build (in
//! slices for a big mesh), the live answers, the recording being stepped through and its
//! snapshot at the playback step.
//!
//! A half has one lane, or two when comparing side by side; both answer the same question
//! on the same primitives and step together. The same type serves 2D segments and 3D
//! triangles ([`LabPrimitive`]).

use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Bvh, Obb, SpatialIndex, Sphere};

use super::build_job::{BuildJob, Structure};
use super::dimension::{LabPrimitive, thousands};
use super::outcome::{NodeMarks, PointOutcome, RayOutcome};
use super::playback::Playback;
use super::question::Task;
use super::recording::{Question, Recording};
use super::refit::{EditEntry, EditKind, EditLog, UpdateMode};
use super::snapshot::Snapshot;
use super::structures::BuildSettings;

/// How much build work a refresh may do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BuildBudget {
    /// Start nothing and advance nothing (a change that is not a frame: the build goes on
    /// at the next frame).
    None,
    /// Work for about this many milliseconds.
    Millis(f64),
    /// Finish the build now (the 2D half, whose scenes build in milliseconds).
    All,
}

/// One structure and what the lab derived from it.
pub struct Lane<P: LabPrimitive> {
    /// The structure to build.
    pub settings: BuildSettings,
    /// A build under way.
    pub job: Option<BuildJob<P>>,
    /// The structure, once built (it may be of older settings or primitives while a new
    /// build runs: see [`Lane::current`]).
    pub structure: Option<Structure<P>>,
    /// Why the structure cannot be built (a structure not offered at this size).
    pub build_error: Option<String>,
    /// The live ray query (first hit), for the answer panel and markers.
    pub ray_outcome: Option<RayOutcome<P::Point>>,
    /// The live point query (k nearest).
    pub point_outcome: Option<PointOutcome<P::Point>>,
    /// The question being stepped through, recorded; or why it cannot be.
    pub recording: Option<Result<Recording<P::Point>, String>>,
    /// The recording's state at the playback step.
    pub snapshot: Option<Snapshot<P::Point>>,
    /// What it does when the primitives move: rebuild, or refit a BVH ([`super::refit`]).
    pub update: UpdateMode,
    /// The structure's updates (refits and builds): their times and SAH costs.
    pub log: EditLog,
    /// Why the last update in refit mode was a rebuild (a structure that is not a BVH, a
    /// changed primitive count); `None` after a refit, and in rebuild mode.
    pub refit_note: Option<String>,
    /// A rebuild was asked for ("Rebuild now"): the next refresh builds even in refit mode.
    rebuild_asked: bool,
    /// The question last recorded (also when recording failed, so that a failure is not
    /// retried every frame).
    last_question: Option<Question<P::Point>>,
}

impl<P: LabPrimitive> Lane<P> {
    /// A lane that will build `settings` on the next refresh.
    pub fn new(settings: BuildSettings) -> Self {
        Self {
            settings,
            job: None,
            structure: None,
            build_error: None,
            ray_outcome: None,
            point_outcome: None,
            recording: None,
            snapshot: None,
            update: UpdateMode::default(),
            log: EditLog::default(),
            refit_note: None,
            rebuild_asked: false,
            last_question: None,
        }
    }

    /// A lane that will build `settings` on the next refresh and update it by `update`.
    pub fn with_update(settings: BuildSettings, update: UpdateMode) -> Self {
        Self {
            update,
            ..Self::new(settings)
        }
    }

    /// Asks for a rebuild with the current settings at the next refresh, also in refit mode
    /// ("Rebuild now").
    pub fn rebuild_now(&mut self) {
        self.rebuild_asked = true;
    }

    /// The structure when it was built with the lane's settings on primitives of
    /// `revision`.
    pub fn current(&self, revision: u64) -> Option<&Structure<P>> {
        self.structure
            .as_ref()
            .filter(|s| s.revision == revision && s.settings == self.settings)
    }

    /// The recording, if there is one.
    pub fn recorded(&self) -> Option<&Recording<P::Point>> {
        self.recording.as_ref().and_then(|r| r.as_ref().ok())
    }

    /// Events in the recording (0 without one): its last playback step.
    pub fn steps(&self) -> usize {
        self.recorded().map_or(0, |r| r.events.len())
    }

    /// The marks at the playback step.
    pub fn marks(&self) -> Option<&NodeMarks> {
        self.snapshot.as_ref().map(|s| &s.marks)
    }

    /// The build under way's progress, 0 to 1.
    pub fn building(&self) -> Option<f32> {
        self.job.as_ref().map(BuildJob::fraction)
    }
}

impl<P: LabPrimitive> Lane<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
    Bvh<Sphere<P::Point>, P>: SpatialIndex,
    Bvh<Aabb<P::Point>, P>: SpatialIndex,
    Bvh<Obb<P::Point>, P>: SpatialIndex,
{
    /// Builds when the primitives (`prims`, of `revision`) or the settings changed, as far as
    /// `budget` allows; reruns the live queries and re-records `question` when anything it
    /// depends on changed. Returns whether the recording changed.
    pub fn refresh(
        &mut self,
        prims: &[P],
        revision: u64,
        question: &Question<P::Point>,
        budget: BuildBudget,
    ) -> bool {
        let mut changed = self.advance_build(prims, revision, budget);
        let Some(structure) = self
            .structure
            .as_ref()
            .filter(|s| s.revision == revision && s.settings == self.settings)
        else {
            return changed;
        };
        if self.recording.is_none() || self.last_question.as_ref() != Some(question) {
            self.recording = Some(record(structure, prims, *question));
            self.last_question = Some(*question);
            self.snapshot = None;
            changed = true;
        }
        // The live answers: read from the recording when it asks the same question.
        let recorded = self.recording.as_ref().and_then(|r| r.as_ref().ok());
        match question.ray {
            Some(ray) if self.ray_outcome.as_ref().is_none_or(|o| o.ray != ray) => {
                self.ray_outcome = Some(
                    recorded
                        .and_then(Recording::ray_outcome)
                        .filter(|o| o.ray == ray)
                        .unwrap_or_else(|| {
                            RayOutcome::run(&structure.built, &structure.brute, ray)
                        }),
                );
            }
            None => self.ray_outcome = None,
            Some(_) => {}
        }
        match question.point {
            Some(p) => {
                let k = question.k.max(1);
                if self
                    .point_outcome
                    .as_ref()
                    .is_none_or(|o| o.point != p || o.k != k)
                {
                    self.point_outcome = Some(
                        recorded
                            .and_then(Recording::point_outcome)
                            .filter(|o| o.point == p && o.k == k)
                            .unwrap_or_else(|| {
                                PointOutcome::run(&structure.built, &structure.brute, p, k)
                            }),
                    );
                }
            }
            None => self.point_outcome = None,
        }
        changed
    }

    /// Starts a build when the primitives or settings changed, and gives a build under way
    /// its budget. Returns whether the recording was dropped (a new structure, or a build
    /// that cannot be made).
    fn advance_build(&mut self, prims: &[P], revision: u64, budget: BuildBudget) -> bool {
        if budget == BuildBudget::None {
            return false;
        }
        let settings = self.settings;
        let current = |s: &BuildSettings, r: u64| *s == settings && r == revision;
        let built_ok = self
            .structure
            .as_ref()
            .is_some_and(|s| current(&s.settings, s.revision));
        let job_ok = self
            .job
            .as_ref()
            .is_some_and(|j| current(&j.settings, j.revision));
        let mut dropped = false;
        let rebuild = std::mem::take(&mut self.rebuild_asked);
        if !built_ok && !job_ok && !rebuild && self.try_refit(prims, revision) {
            return true;
        }
        if (!built_ok && !job_ok) || rebuild {
            match BuildJob::start(prims, revision, settings) {
                Ok(job) => {
                    self.job = Some(job);
                    self.build_error = None;
                }
                Err(e) => {
                    self.job = None;
                    self.structure = None;
                    self.ray_outcome = None;
                    self.point_outcome = None;
                    self.recording = Some(Err(e.clone()));
                    self.snapshot = None;
                    self.last_question = None;
                    self.build_error = Some(e);
                    return true;
                }
            }
        }
        let ms = match budget {
            BuildBudget::Millis(ms) => ms,
            _ => f64::INFINITY,
        };
        if let Some(job) = &mut self.job
            && let Some(structure) = job.run(prims, ms)
        {
            self.log.push(EditEntry {
                how: EditKind::Rebuild,
                sah_cost: structure.stats.sah_cost,
                millis: structure.build_ms,
            });
            self.structure = Some(structure);
            self.job = None;
            self.ray_outcome = None;
            self.point_outcome = None;
            self.recording = None;
            self.snapshot = None;
            dropped = true;
        }
        dropped
    }

    /// In refit mode, refits the structure built with the lane's settings on older
    /// primitives to `prims` (of `revision`) instead of building; whether it did (the
    /// recording is then dropped). When it cannot, [`Lane::refit_note`] says why.
    fn try_refit(&mut self, prims: &[P], revision: u64) -> bool {
        if self.update != UpdateMode::Refit {
            self.refit_note = None;
            return false;
        }
        let settings = self.settings;
        let Some(structure) = self
            .structure
            .as_mut()
            .filter(|s| s.settings == settings && s.revision != revision)
        else {
            return false;
        };
        match structure.refit(prims, revision) {
            Ok(millis) => {
                self.log.push(EditEntry {
                    how: EditKind::Refit,
                    sah_cost: structure.stats.sah_cost,
                    millis,
                });
                self.refit_note = None;
                self.job = None;
                self.build_error = None;
                self.ray_outcome = None;
                self.point_outcome = None;
                self.recording = None;
                self.snapshot = None;
                true
            }
            Err(why) => {
                self.refit_note = Some(why);
                false
            }
        }
    }

    /// Updates the snapshot to the playback's step (in live mode: this lane's end).
    pub fn follow(&mut self, playback: &Playback, revision: u64) {
        let current = self
            .structure
            .as_ref()
            .filter(|s| s.revision == revision && s.settings == self.settings);
        let recording = self
            .recording
            .as_ref()
            .and_then(|r| r.as_ref().ok())
            .filter(|_| current.is_some());
        let (kind, nodes) =
            current.map_or((self.settings.kind, 0), |s| (s.settings.kind, s.node_count));
        Snapshot::follow(&mut self.snapshot, recording, kind, nodes, playback);
    }
}

/// Records `question` on `structure`, refusing a build recording of more primitives than
/// [`LabPrimitive::MAX_BUILD_STEPPING`].
fn record<P: LabPrimitive>(
    structure: &Structure<P>,
    prims: &[P],
    question: Question<P::Point>,
) -> Result<Recording<P::Point>, String>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    if question.task == Task::Build && prims.len() > P::MAX_BUILD_STEPPING {
        return Err(format!(
            "Stepping through a build is offered up to {} {} (this mesh has {}): load a smaller mesh, such as the bunny.",
            thousands(P::MAX_BUILD_STEPPING),
            P::NAME,
            thousands(prims.len())
        ));
    }
    Recording::record_on(structure.subject(prims), question)
}
