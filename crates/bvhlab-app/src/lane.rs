//! One structure on the scene, with everything derived from it: the build, the live query
//! answers, the recording being stepped through and its snapshot, and the cached drawing.
//!
//! The lab has one lane, or two when comparing structures side by side; both answer the same
//! question on the same scene and step together.

use bvhlab::glam::Vec2;
use bvhlab::{BruteForce, NodeOutline, Segment2, SpatialIndex, Stats};
use web_time::Instant;

use crate::canvas::StaticLayer;
use crate::playback::{Playback, Snapshot};
use crate::query::{NodeMarks, PointOutcome, RayOutcome};
use crate::recording::{Question, Recording};
use crate::scene::{Primitives, Scene};
use crate::structures::{BuildSettings, Built};

/// The structure built on the current scene, and everything read from it once.
pub struct Built2d {
    /// The settings it was built with.
    pub settings: BuildSettings,
    /// The scene revision it was built on.
    pub revision: u64,
    /// The primitives and their shapes.
    pub prims: Primitives,
    /// The structure.
    pub structure: Built,
    /// The baseline.
    pub brute: BruteForce<Segment2>,
    /// Its nodes, for drawing.
    pub outline: Vec<NodeOutline<Vec2>>,
    /// Its statistics.
    pub stats: Stats,
    /// How long the build took, in milliseconds.
    pub build_ms: f64,
    /// For leaf colouring: the first leaf listing each primitive.
    pub leaf_of: Vec<Option<u32>>,
}

impl Built2d {
    /// What a recording asks questions of.
    pub fn subject(&self) -> crate::recording::Subject<'_, Segment2> {
        crate::recording::Subject {
            structure: &self.structure,
            brute: &self.brute,
            prims: &self.prims.segments,
            settings: self.settings,
            revision: self.revision,
            node_count: self.outline.len(),
        }
    }

    /// Builds `settings`' structure on `scene`.
    pub fn new(scene: &Scene, settings: BuildSettings) -> Self {
        let prims = scene.primitives();
        let start = Instant::now();
        let structure = Built::build(&prims.segments, &settings);
        let build_ms = start.elapsed().as_secs_f64() * 1e3;
        let outline = structure.outline();
        let mut leaf_of = vec![None; prims.segments.len()];
        for node in outline.iter().filter(|n| n.is_leaf()) {
            for &p in &node.primitives {
                let slot = &mut leaf_of[p as usize];
                if slot.is_none() {
                    *slot = Some(node.id.0);
                }
            }
        }
        Self {
            settings,
            revision: scene.revision(),
            stats: structure.stats(),
            brute: BruteForce::build(&prims.segments),
            prims,
            structure,
            outline,
            build_ms,
            leaf_of,
        }
    }
}

/// One structure and what the lab derived from it.
pub struct Lane {
    /// The structure to build.
    pub settings: BuildSettings,
    /// The structure built on the scene.
    pub built: Option<Built2d>,
    /// The live ray query (first hit), for the answer panel and markers.
    pub ray_outcome: Option<RayOutcome>,
    /// The live point query (k nearest).
    pub point_outcome: Option<PointOutcome>,
    /// The question being stepped through, recorded; or why it cannot be.
    pub recording: Option<Result<Recording, String>>,
    /// The recording's state at the playback step.
    pub snapshot: Option<Snapshot>,
    /// The structure and scene, tessellated for the current view.
    pub static_layer: Option<StaticLayer>,
    /// The question last recorded (also when recording failed, so a failure is not retried
    /// every frame).
    last_question: Option<Question>,
}

impl Lane {
    /// A lane that will build `settings` on the next refresh.
    pub fn new(settings: BuildSettings) -> Self {
        Self {
            settings,
            built: None,
            ray_outcome: None,
            point_outcome: None,
            recording: None,
            snapshot: None,
            static_layer: None,
            last_question: None,
        }
    }

    /// Rebuilds when the scene or settings changed, reruns the live queries and re-records
    /// the question when anything it depends on changed. Returns whether the recording
    /// changed.
    pub fn refresh(&mut self, scene: &Scene, question: &Question) -> bool {
        let stale = self
            .built
            .as_ref()
            .is_none_or(|b| b.revision != scene.revision() || b.settings != self.settings);
        if stale {
            self.built = Some(Built2d::new(scene, self.settings));
            self.ray_outcome = None;
            self.point_outcome = None;
            self.recording = None;
        }
        let Some(built) = &self.built else {
            return false;
        };
        let changed = self.recording.is_none() || self.last_question.as_ref() != Some(question);
        if changed {
            self.recording = Some(Recording::record(built, *question));
            self.last_question = Some(*question);
            self.snapshot = None;
        }
        // The live answers: read from the recording when it asks the same question.
        let recorded = self.recording.as_ref().and_then(|r| r.as_ref().ok());
        match question.ray {
            Some(ray) if self.ray_outcome.as_ref().is_none_or(|o| o.ray != ray) => {
                self.ray_outcome = Some(
                    recorded
                        .and_then(Recording::ray_outcome)
                        .filter(|o| o.ray == ray)
                        .unwrap_or_else(|| RayOutcome::run(&built.structure, &built.brute, ray)),
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
                                PointOutcome::run(&built.structure, &built.brute, p, k)
                            }),
                    );
                }
            }
            None => self.point_outcome = None,
        }
        changed
    }

    /// The recording, if there is one.
    pub fn recorded(&self) -> Option<&Recording> {
        self.recording.as_ref().and_then(|r| r.as_ref().ok())
    }

    /// Events in the recording (0 without one): its last playback step.
    pub fn steps(&self) -> usize {
        self.recorded().map_or(0, |r| r.events.len())
    }

    /// Updates the snapshot to the playback's step (in live mode: this lane's end).
    pub fn follow(&mut self, playback: &Playback) {
        let recording = self.recording.as_ref().and_then(|r| r.as_ref().ok());
        let (kind, nodes) = self.built.as_ref().map_or((self.settings.kind, 0), |b| {
            (b.settings.kind, b.outline.len())
        });
        Snapshot::follow(
            &mut self.snapshot,
            recording.filter(|_| self.built.is_some()),
            kind,
            nodes,
            playback,
        );
    }

    /// The marks at the playback step.
    pub fn marks(&self) -> Option<&NodeMarks> {
        self.snapshot.as_ref().map(|s| &s.marks)
    }
}
