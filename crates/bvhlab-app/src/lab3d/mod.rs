//! The 3D half of the lab: a mesh, a structure built over it, a ray cast by clicking or a
//! query point placed with a gizmo, and the same recordings, playback and pseudocode as in
//! 2D, drawn with wgpu ([`crate::view3d`]).
//!
//! - [`mesh`]: loading built-in and dropped meshes; [`build`]: building without freezing the
//!   page; [`nodes`]: reading a structure's nodes at any size; [`wire`]: shapes as segments.
//! - [`draw`]: what the view shows, from the state and the playback snapshot; [`input`]:
//!   orbit, pan, zoom, click to cast, and the gizmo; [`panel`]: the 3D controls.

pub mod build;
pub mod draw;
pub mod heat;
pub mod input;
pub mod mesh;
pub mod nodes;
pub mod panel;
pub mod report;
pub mod view;
pub mod wire;

use bvhlab::glam::Vec3;
use bvhlab::{Ray3, Triangle3};

use self::build::{BuildJob, Built3d};
use self::mesh::{Mesh3d, MeshSource};
use crate::playback::{Playback, Snapshot};
use crate::recording::{Question, Recording};
use crate::structures::BuildSettings;
use crate::view3d::camera::OrbitCamera;

/// The largest mesh whose build can be stepped through (a build's recording holds a few
/// events per node).
pub const MAX_TRIANGLES_BUILD_STEPPING: usize = 30_000;

/// The built-in mesh the 3D view opens with.
pub const DEFAULT_MESH: &str = "bunny";

/// What a click on the mesh does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tool3d {
    /// Cast a ray from the camera through the clicked pixel.
    Ray,
    /// Put the query point where the click meets the mesh.
    Point,
}

/// What the 3D view shows besides the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Display3d {
    /// Draw the structure's nodes.
    pub structure: bool,
    /// Which level of nodes to draw (0 is the root).
    pub depth: u32,
    /// Draw the mesh translucent, so volumes inside show.
    pub xray: bool,
    /// Colour the nodes the query visited, culled and pruned.
    pub marks: bool,
}

impl Default for Display3d {
    fn default() -> Self {
        Self {
            structure: true,
            depth: 3,
            xray: true,
            marks: true,
        }
    }
}

/// The 3D lab's state.
pub struct Lab3d {
    /// The mesh shown, once one is loaded.
    pub mesh: Option<Mesh3d>,
    /// A mesh to load on the next frame (so "loading…" shows first).
    pub pending: Option<MeshSource>,
    /// The structure to build.
    pub settings: BuildSettings,
    /// A build under way.
    pub job: Option<BuildJob>,
    /// The structure built over the mesh.
    pub built: Option<Built3d>,
    /// The camera.
    pub camera: OrbitCamera,
    /// The ray, once cast.
    pub ray: Option<Ray3>,
    /// The query point, once placed.
    pub point: Option<Vec3>,
    /// The range query's radius.
    pub radius: f32,
    /// What a click does.
    pub tool: Tool3d,
    /// What is drawn.
    pub display: Display3d,
    /// The question being stepped through, recorded; or why it cannot be.
    pub recording: Option<Result<Recording<Vec3>, String>>,
    /// The recording's state at the playback step.
    pub snapshot: Option<Snapshot<Vec3>>,
    /// The last message for the student (a load or build that failed, and why).
    pub message: Option<String>,
    /// The gizmo handle being dragged, if any.
    pub dragging: Option<input::Handle>,
    /// The view's area on screen, set each frame.
    pub view_rect: egui::Rect,
    /// The traversal-cost heat map, when on.
    pub heat: heat::Heat,
    /// A saved camera, ray, point and radius to put back once the pending mesh has loaded,
    /// instead of framing it afresh (a reload, a scene file, a share link).
    pub placement: Option<Placement3d>,
    /// A mesh was loaded and the view has not framed it yet.
    framing: bool,
    last_question: Option<Question<Vec3>>,
    revisions: u64,
}

impl Default for Lab3d {
    fn default() -> Self {
        Self {
            mesh: None,
            pending: Some(MeshSource::Builtin(DEFAULT_MESH.to_owned())),
            settings: BuildSettings {
                kind: crate::structures::StructureKind::AabbTree,
                bvh_split: bvhlab::structure::SplitMethod::BinnedSah,
                leaf_size: 4,
                ..BuildSettings::default()
            },
            job: None,
            built: None,
            camera: OrbitCamera::default(),
            ray: None,
            point: None,
            radius: 0.1,
            tool: Tool3d::Ray,
            display: Display3d::default(),
            recording: None,
            snapshot: None,
            message: None,
            dragging: None,
            view_rect: egui::Rect::NOTHING,
            heat: heat::Heat::default(),
            placement: None,
            framing: false,
            last_question: None,
            revisions: 0,
        }
    }
}

/// What to put back over a mesh once it has loaded, instead of the defaults: a saved state's
/// camera, ray, point and radius, or the ray and point the page's address asks for (the
/// camera then frames the mesh as usual).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Placement3d {
    /// The camera; `None` frames the mesh.
    pub camera: Option<OrbitCamera>,
    /// The ray; `None` leaves none (or, when the camera frames the mesh, one through the
    /// middle of the view).
    pub ray: Option<Ray3>,
    /// The query point; `None` as for the ray.
    pub point: Option<Vec3>,
    /// The range query's radius; `None` takes a tenth of the mesh's size.
    pub radius: Option<f32>,
}

/// Milliseconds of build work per frame: enough to finish a small mesh at once, little
/// enough that the page stays responsive during a big one.
const BUILD_BUDGET_MS: f64 = 25.0;
/// The most build work per frame when frames are slow anyway (software rendering of a big
/// mesh takes hundreds of milliseconds a frame): half the frame time, up to this.
const SLOW_FRAME_BUILD_BUDGET_MS: f64 = 250.0;

/// The build work to do this frame, given the median frame interval: 25 ms, or half a slow
/// frame, so that a build keeps pace with a view that takes long to draw.
pub fn build_budget_ms(frame_ms: Option<f64>) -> f64 {
    frame_ms.map_or(BUILD_BUDGET_MS, |ms| {
        (ms * 0.5).clamp(BUILD_BUDGET_MS, SLOW_FRAME_BUILD_BUDGET_MS)
    })
}

impl Lab3d {
    /// Loads `source` on the next frame.
    pub fn open(&mut self, source: MeshSource) {
        self.pending = Some(source);
    }

    /// Whether a load or a build is under way (the caller keeps repainting).
    pub fn busy(&self) -> bool {
        self.pending.is_some() || self.job.is_some()
    }

    /// Loads a pending mesh, advances a build (for [`build_budget_ms`] of the median frame
    /// interval `frame_ms`), re-records the question when it changed and brings the snapshot
    /// to the playback step. Returns whether the recording changed.
    pub fn refresh(&mut self, question: &Question<Vec3>, frame_ms: Option<f64>) -> bool {
        if let Some(source) = self.pending.take() {
            self.load(&source);
        }
        self.advance_build(build_budget_ms(frame_ms));
        let Some(mesh) = &self.mesh else {
            return false;
        };
        let Some(built) = self.built.as_ref().filter(|b| b.revision == mesh.revision) else {
            return false;
        };
        let changed = self.recording.is_none() || self.last_question.as_ref() != Some(question);
        if changed {
            self.recording = Some(record(built, mesh, *question));
            self.last_question = Some(*question);
            self.snapshot = None;
        }
        changed
    }

    fn load(&mut self, source: &MeshSource) {
        self.revisions += 1;
        match mesh::load(source, self.revisions) {
            Ok(mesh) => {
                let saved = self.placement.take().unwrap_or_default();
                self.radius = saved.radius.unwrap_or(mesh.size() * 0.1);
                self.ray = saved.ray;
                self.point = saved.point;
                match saved.camera {
                    Some(camera) => {
                        self.camera = camera;
                        self.framing = false;
                    }
                    // The camera (and a missing ray and point) are placed by the view, which
                    // knows its shape.
                    None => self.framing = true,
                }
                self.message = (!mesh.warnings.is_empty()).then(|| mesh.warnings.join(" "));
                self.mesh = Some(mesh);
                self.built = None;
                self.job = None;
                self.recording = None;
                self.snapshot = None;
            }
            Err(e) => {
                self.placement = None;
                let kept = self
                    .mesh
                    .as_ref()
                    .map_or(String::new(), |m| format!(" {} stays open.", m.name));
                self.message = Some(format!("{e}{kept}"));
            }
        }
    }

    /// Starts a build when the mesh or settings changed, and gives a build under way this
    /// frame's time.
    fn advance_build(&mut self, budget_ms: f64) {
        let Some(mesh) = &self.mesh else { return };
        let current = |s: &BuildSettings, r: u64| *s == self.settings && r == mesh.revision;
        let built_ok = self
            .built
            .as_ref()
            .is_some_and(|b| current(&b.settings, b.revision));
        let job_ok = self
            .job
            .as_ref()
            .is_some_and(|j| current(&j.settings, j.revision));
        if !built_ok && !job_ok {
            match BuildJob::start(mesh, self.settings) {
                Ok(job) => self.job = Some(job),
                Err(e) => {
                    self.job = None;
                    self.built = None;
                    self.recording = Some(Err(e.clone()));
                    self.message = Some(e);
                }
            }
        }
        if let Some(job) = &mut self.job
            && let Some(built) = job.run(mesh, budget_ms)
        {
            self.built = Some(built);
            self.job = None;
            self.recording = None;
            self.snapshot = None;
        }
    }

    /// Frames the camera on the mesh for a view of `aspect` (width / height), and puts a
    /// first ray through the middle of the view and the point beside the mesh, so the view
    /// has answers to show straight away. Done once per loaded mesh, by the view.
    pub fn place_defaults(&mut self, aspect: f32) {
        let Some(mesh) = &self.mesh else { return };
        if !std::mem::take(&mut self.framing) {
            return;
        }
        self.camera.frame_in(&mesh.bounds(), aspect);
        let size = mesh.size();
        if self.ray.is_none() {
            self.ray = Ray3::new(self.camera.eye(), self.camera.basis().forward).ok();
        }
        if self.point.is_none() {
            // Beside the mesh, to the right in the view, where the gizmo is on screen.
            self.point = Some(self.camera.target + self.camera.basis().right * size * 0.35);
        }
    }

    /// Whether the camera, ray and point belong to the mesh shown: it has loaded, nothing else
    /// is loading, and the view has framed it.
    pub fn placed(&self) -> bool {
        self.mesh.is_some() && self.pending.is_none() && !self.framing
    }

    /// Events in the recording (0 without one).
    pub fn steps(&self) -> usize {
        self.recorded().map_or(0, |r| r.events.len())
    }

    /// The recording, if there is one.
    pub fn recorded(&self) -> Option<&Recording<Vec3>> {
        self.recording.as_ref().and_then(|r| r.as_ref().ok())
    }

    /// Updates the snapshot to the playback's step.
    pub fn follow(&mut self, playback: &Playback) {
        let recording = self.recording.as_ref().and_then(|r| r.as_ref().ok());
        let (kind, nodes) = self
            .built
            .as_ref()
            .map_or((self.settings.kind, 0), |b| (b.settings.kind, b.node_count));
        Snapshot::follow(
            &mut self.snapshot,
            recording.filter(|_| self.built.is_some()),
            kind,
            nodes,
            playback,
        );
    }

    /// The mesh's triangle `index`.
    pub fn triangle(&self, index: u32) -> Option<Triangle3> {
        self.mesh
            .as_ref()?
            .mesh
            .triangles()
            .get(index as usize)
            .copied()
    }
}

/// Records `question` on `built`, refusing a build recording of a big mesh.
fn record(
    built: &Built3d,
    mesh: &Mesh3d,
    question: Question<Vec3>,
) -> Result<Recording<Vec3>, String> {
    if question.task == crate::pseudocode::Task::Build
        && mesh.triangle_count() > MAX_TRIANGLES_BUILD_STEPPING
    {
        return Err(format!(
            "Stepping through a build is offered up to {} triangles ({} has {}): load a smaller mesh, such as the bunny.",
            build::thousands(MAX_TRIANGLES_BUILD_STEPPING),
            mesh.name,
            build::thousands(mesh.triangle_count())
        ));
    }
    Recording::record_on(built.subject(mesh), question)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_frames_give_the_build_more_time_up_to_a_cap() {
        assert_eq!(build_budget_ms(None), BUILD_BUDGET_MS);
        assert_eq!(build_budget_ms(Some(16.0)), BUILD_BUDGET_MS);
        assert_eq!(build_budget_ms(Some(300.0)), 150.0);
        assert_eq!(build_budget_ms(Some(5_000.0)), SLOW_FRAME_BUILD_BUDGET_MS);
    }
}
