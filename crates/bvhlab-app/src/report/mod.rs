//! What the lab reports about itself, as text for screen readers and as JSON for the page
//! (the browser test reads it; a course page embedding the lab can too).

pub mod motion;
pub mod predict;
pub mod speech;
pub mod update;

use std::fmt::Write as _;

use serde::Serialize;

use crate::model::Lab;
use crate::model::dimension::{Dimension, LabPrimitive};
use crate::model::lane::Lane;
use crate::model::recording::Answer;
use crate::ui_state::UiState;

/// The lab's state in brief.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Report {
    /// The lab has drawn at least one frame.
    pub ready: bool,
    /// The graphics backend.
    pub renderer: Option<String>,
    /// The drawing area, in points (CSS pixels on the web): `[x0, y0, x1, y1]`.
    pub canvas: [f32; 4],
    /// The scene.
    pub scene: SceneReport,
    /// The structure's name.
    pub structure: String,
    /// The ray query, if a ray is drawn.
    pub query: Option<RayReport>,
    /// The point query, if a point is placed.
    pub nearest: Option<NearestReport>,
    /// Playback: what is stepped through and where it is, per lane.
    pub playback: Vec<PlaybackReport>,
    /// The 3D view, when it is shown.
    pub three: Option<Report3d>,
    /// How the half shown's lanes follow moving primitives: refit or rebuild, and their
    /// times (lanes never updated are left out).
    pub updates: Vec<update::UpdateReport>,
    /// The status line's message, when there is one (a file or link that could not be
    /// opened, and what was kept).
    pub message: Option<String>,
    /// The lesson open, if any.
    pub lesson: Option<crate::lessons::report::LessonReport>,
    /// Predict, when it is on: the exercise, its score, the question waiting.
    pub predict: Option<predict::PredictReport>,
    /// The median interval between frames, in milliseconds.
    pub frame_ms: Option<f64>,
    /// The median CPU time per frame (UI, tessellation, draw calls), in milliseconds.
    pub cpu_ms: Option<f64>,
}

/// The scene's size.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SceneReport {
    /// Shapes drawn.
    pub shapes: usize,
    /// Primitives (segments and points) the structures are built on.
    pub primitives: usize,
}

/// The ray query's answer and cost.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayReport {
    /// Always "ray".
    pub kind: &'static str,
    /// Origin and direction.
    pub ray: [f32; 4],
    /// The first hit.
    pub hit: Option<HitReport>,
    /// Nodes (or cells) the query entered.
    pub nodes_visited: u64,
    /// Bounding-volume tests.
    pub bound_tests: u64,
    /// Exact primitive tests.
    pub primitive_tests: u64,
    /// Brute force's primitive tests.
    pub brute_force_tests: u64,
    /// Whether the structure's answer equals brute force's.
    pub agrees: bool,
}

/// A hit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HitReport {
    /// The primitive's index.
    pub primitive: usize,
    /// The ray parameter.
    pub t: f32,
    /// The hit point.
    pub point: [f32; 2],
}

/// The point query's answer and cost.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NearestReport {
    /// The query point.
    pub point: [f32; 2],
    /// The nearest primitive, its closest point and the distance.
    pub nearest: Option<(usize, [f32; 2], f32)>,
    /// Nodes entered.
    pub nodes_visited: u64,
    /// Bounding-volume distance tests.
    pub bound_tests: u64,
    /// Exact distance computations.
    pub primitive_tests: u64,
    /// Brute force's distance computations.
    pub brute_force_tests: u64,
    /// Whether the structure's answer equals brute force's.
    pub agrees: bool,
}

/// One lane's playback state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlaybackReport {
    /// The structure.
    pub structure: String,
    /// What is stepped through (`FirstHit`, `Nearest`, `Build`, ...).
    pub task: String,
    /// Which version (`Full`, `Lecture`, `LecturePruned`).
    pub variant: String,
    /// The step shown (events folded in).
    pub step: usize,
    /// The recording's length.
    pub steps: usize,
    /// The current node.
    pub current_node: Option<u32>,
    /// The highlighted pseudocode line (1-based), if any.
    pub line: Option<usize>,
    /// Nodes, bound tests and primitive tests so far.
    pub so_far: [u64; 3],
    /// The same for the whole query (the core's count).
    pub total: [u64; 3],
    /// Brute force's primitive tests.
    pub brute_force_tests: u64,
    /// Whether the answer equals brute force's.
    pub agrees: bool,
    /// Why there is no recording (no ray yet, a variant that does not exist...).
    pub error: Option<String>,
    /// The step shown, in words (the "Step through" panel's sentence), once one is.
    pub said: Option<String>,
    /// The nodes waiting on the stack or queue, next first.
    pub waiting: Vec<u32>,
}

impl PlaybackReport {
    /// While stepping (not at the end), the step in words, for the live region: " Step 4
    /// of 31: ray meets node 2's volume for t in [1.2, 3.4]. Waiting: node 6, then node 3."
    pub fn text(&self) -> String {
        let Some(said) = self.said.as_ref().filter(|_| self.step < self.steps) else {
            return String::new();
        };
        let mut s = format!(" Step {} of {}: {said}.", self.step, self.steps);
        if !self.waiting.is_empty() {
            let nodes: Vec<String> = self.waiting.iter().map(|n| format!("node {n}")).collect();
            let _ = write!(s, " Waiting: {}.", nodes.join(", then "));
        }
        s
    }

    /// The report of a lane in either half.
    pub fn of<P: LabPrimitive>(lane: &Lane<P>) -> Option<Self> {
        let dim = if P::DIMENSION == Dimension::Three {
            3
        } else {
            2
        };
        Self::of_recording(
            lane.settings.kind.label_in(dim),
            lane.settings.kind,
            lane.recording.as_ref(),
            lane.snapshot.as_ref(),
        )
    }

    /// The report of a recording at its snapshot, in either dimension.
    pub fn of_recording<V: bvhlab::Vector>(
        structure: &str,
        kind: crate::model::structures::StructureKind,
        recording: Option<&Result<crate::model::recording::Recording<V>, String>>,
        snapshot: Option<&crate::model::snapshot::Snapshot<V>>,
    ) -> Option<Self> {
        let structure = structure.to_owned();
        let rec = match recording? {
            Ok(rec) => rec,
            Err(why) => {
                return Some(Self {
                    structure,
                    task: String::new(),
                    variant: String::new(),
                    step: 0,
                    steps: 0,
                    current_node: None,
                    line: None,
                    so_far: [0; 3],
                    total: [0; 3],
                    brute_force_tests: 0,
                    agrees: false,
                    error: Some(why.clone()),
                    said: None,
                    waiting: Vec::new(),
                });
            }
        };
        let snap = snapshot?;
        let q = rec.question;
        let line = snap
            .step
            .checked_sub(1)
            .and_then(|i| crate::pseudocode::line_of(kind, q.task, q.variant, &rec.events, i));
        Some(Self {
            structure,
            task: format!("{:?}", q.task),
            variant: format!("{:?}", q.variant),
            step: snap.step,
            steps: rec.events.len(),
            current_node: snap.current.map(|n| n.0),
            line: line.map(|l| l + 1),
            so_far: [
                snap.so_far.nodes,
                snap.so_far.bound_tests,
                snap.so_far.prim_tests,
            ],
            total: [
                rec.cost.nodes_visited,
                rec.cost.bound_tests,
                rec.cost.prim_tests,
            ],
            brute_force_tests: rec.brute_cost.prim_tests,
            agrees: rec.agrees(),
            error: None,
            said: snap
                .event
                .map(|e| crate::pseudocode::describe(&e, kind, q.task, q.variant)),
            waiting: snap.frontier.iter().map(|p| p.node.0).collect(),
        })
    }
}

impl Report {
    /// The report of the lab's state, as the UI shows it.
    pub fn of(lab: &Lab, ui: &UiState) -> Self {
        let two = lab.two();
        let r = ui.canvas.screen(two).rect;
        let lane = &two.half.lane;
        let three = lab.dimension() == Dimension::Three;
        Self {
            ready: true,
            renderer: ui.renderer.clone(),
            message: lab.message().map(str::to_owned),
            lesson: crate::lessons::report::LessonReport::of(lab),
            predict: predict::PredictReport::of(lab),
            canvas: [r.min.x, r.min.y, r.max.x, r.max.y],
            scene: SceneReport {
                shapes: two.scene.shapes().len(),
                primitives: two.prims().segments.len(),
            },
            structure: lane.settings.kind.label().to_owned(),
            query: lane.ray_outcome.as_ref().map(|o| RayReport {
                kind: "ray",
                ray: [
                    o.ray.origin().x,
                    o.ray.origin().y,
                    o.ray.dir().x,
                    o.ray.dir().y,
                ],
                hit: o.hit.map(|h| {
                    let p = o.ray.at(h.t);
                    HitReport {
                        primitive: h.prim,
                        t: h.t,
                        point: [p.x, p.y],
                    }
                }),
                nodes_visited: o.cost.nodes_visited,
                bound_tests: o.cost.bound_tests,
                primitive_tests: o.cost.prim_tests,
                brute_force_tests: o.brute_cost.prim_tests,
                agrees: o.agrees(),
            }),
            nearest: lane.point_outcome.as_ref().map(|o| NearestReport {
                point: [o.point.x, o.point.y],
                nearest: o
                    .nearest
                    .first()
                    .map(|n| (n.prim, [n.point.x, n.point.y], n.distance)),
                nodes_visited: o.cost.nodes_visited,
                bound_tests: o.cost.bound_tests,
                primitive_tests: o.cost.prim_tests,
                brute_force_tests: o.brute_cost.prim_tests,
                agrees: o.agrees(),
            }),
            playback: if three {
                lab.three()
                    .half
                    .lanes()
                    .filter_map(PlaybackReport::of)
                    .collect()
            } else {
                two.half.lanes().filter_map(PlaybackReport::of).collect()
            },
            three: three.then(|| Report3d::of(lab, ui)),
            updates: if three {
                update::UpdateReport::of_half(&lab.three().half)
            } else {
                update::UpdateReport::of_half(&two.half)
            },
            frame_ms: ui.clock.median_ms(),
            cpu_ms: ui.clock.median_cpu_ms(),
        }
    }

    /// The report as JSON.
    pub fn json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
    }
}

/// The 3D view's state in brief.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Report3d {
    /// The mesh's name, once loaded.
    pub mesh: Option<String>,
    /// Its triangles.
    pub triangles: usize,
    /// The structure.
    pub structure: String,
    /// A build under way: how far it is, 0 to 1.
    pub building: Option<f32>,
    /// How long the finished build took, in milliseconds.
    pub build_ms: Option<f64>,
    /// The view's area on the page, in points: `[x0, y0, x1, y1]`.
    pub view: [f32; 4],
    /// The ray: origin and direction.
    pub ray: Option<[f32; 6]>,
    /// The first hit: triangle, t, point.
    pub hit: Option<Hit3dReport>,
    /// The query point.
    pub point: Option<[f32; 3]>,
    /// Whether the recorded answer equals brute force's.
    pub agrees: Option<bool>,
    /// The recorded query's nodes, bound tests and triangle tests.
    pub cost: Option<[u64; 3]>,
    /// Brute force's triangle tests.
    pub brute_force_tests: Option<u64>,
    /// The last message (a refused file, a structure not offered for this size).
    pub message: Option<String>,
    /// The heat map, when shown: "gpu" or "cpu", its progress and its largest count.
    pub heat_map: Option<HeatReport>,
    /// The mesh's motion, when it moves (the twisting torus).
    pub motion: Option<motion::MotionReport>,
}

/// A first hit in 3D.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Hit3dReport {
    /// The triangle's index.
    pub triangle: usize,
    /// The ray parameter.
    pub t: f32,
    /// The hit point.
    pub point: [f32; 3],
}

/// The heat map's state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HeatReport {
    /// Where it is computed: "gpu" or "cpu".
    pub device: String,
    /// How far it is, 0 to 1.
    pub progress: f32,
    /// The largest count in the image.
    pub max: u32,
    /// What a pixel's colour counts ("nodes visited per ray").
    pub metric: &'static str,
}

impl Report3d {
    /// The report of the 3D half's state.
    pub fn of(lab: &Lab, ui: &UiState) -> Self {
        let three = lab.three();
        let lane = &three.half.lane;
        let rec = lane.recorded();
        let hit = rec.and_then(|r| match (&r.answer, r.question.ray) {
            (Answer::Hit(Some(h)), Some(ray)) => Some(Hit3dReport {
                triangle: h.prim,
                t: h.t,
                point: ray.at(h.t).to_array(),
            }),
            _ => None,
        });
        let view = ui.view3d.rect;
        Self {
            mesh: three.mesh.as_ref().map(|m| m.name.clone()),
            triangles: three.triangles().len(),
            structure: lane.settings.kind.label_in(3).to_owned(),
            building: lane.building(),
            build_ms: lane.structure.as_ref().map(|b| b.build_ms),
            view: [view.min.x, view.min.y, view.max.x, view.max.y],
            ray: three.ray.map(|r| {
                let (o, d) = (r.origin(), r.dir());
                [o.x, o.y, o.z, d.x, d.y, d.z]
            }),
            hit,
            point: three.point.map(|p| p.to_array()),
            agrees: rec.map(crate::model::recording::Recording::agrees),
            cost: rec.map(|r| [r.cost.nodes_visited, r.cost.bound_tests, r.cost.prim_tests]),
            brute_force_tests: rec.map(|r| r.brute_cost.prim_tests),
            message: three.message.clone(),
            heat_map: ui.view3d.heat.report(three.heat.on),
            motion: motion::MotionReport::of(lab, ui),
        }
    }
}
