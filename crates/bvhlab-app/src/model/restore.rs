//! A whole state of the lab, checked, in the model's own types: what a saved state, a scene
//! file or a share link put back ([`Action::Restore`](super::Action::Restore)). The checks
//! (limits, finite numbers, known names) happen where the state is read
//! ([`crate::persist`]); writing it replaces everything it names and drops what was derived
//! from what it replaces.

use bvhlab::glam::Vec2;

use super::camera2d::Camera2d;
use super::collision3d::Collision3d;
use super::dimension::Dimension;
use super::half::Half;
use super::lab2d::{Display, Lab2d, RayHandles};
use super::lab3d::{Lab3d, Placement3d};
use super::lane::Lane;
use super::mesh::MeshSource;
use super::obb_pair3d::ObbPair3;
use super::playback::Playback;
use super::presets::Preset;
use super::question::{Task, Variant};
use super::refit::UpdateMode;
use super::scene::Scene;
use super::structures::BuildSettings;
use super::volumes::VolumeToggles;
use super::volumes3d::Volumes3d;

/// The question and playback of one half.
#[derive(Clone, Debug, PartialEq)]
pub struct RestoreHalf {
    /// The structure's build settings.
    pub settings: BuildSettings,
    /// The comparison structure's, when two are shown.
    pub compare: Option<BuildSettings>,
    /// What the structure and the comparison do when the primitives move.
    pub update: [UpdateMode; 2],
    /// What is stepped through.
    pub task: Task,
    /// Which version of the algorithm.
    pub variant: Variant,
    /// How many neighbours.
    pub k: usize,
    /// The playback step.
    pub step: usize,
    /// Whether playback stays at the end (live).
    pub live: bool,
}

/// The 2D half's state.
#[derive(Clone, Debug)]
pub struct Restore2d {
    /// The preset in the menu.
    pub preset: Preset,
    /// The scene.
    pub scene: Scene,
    /// The selected shapes.
    pub selection: Vec<usize>,
    /// Structures, question and playback.
    pub half: RestoreHalf,
    /// Drawing switches.
    pub display: Display,
    /// Which bounding volumes are drawn.
    pub volumes: VolumeToggles,
    /// The ray's handles.
    pub ray: Option<RayHandles>,
    /// The query point.
    pub point: Option<Vec2>,
    /// The range radius.
    pub radius: f32,
    /// Pan and zoom.
    pub camera: Camera2d,
}

/// The 3D half's state.
#[derive(Clone, Debug, PartialEq)]
pub struct Restore3d {
    /// The mesh to open.
    pub mesh: MeshSource,
    /// Structures, question and playback.
    pub half: RestoreHalf,
    /// The camera, ray, point and radius to put back over the mesh once it has loaded.
    pub placement: Placement3d,
    /// §2's volumes.
    pub volumes: Volumes3d,
    /// The two boxes of the separating-axis test, if it is on.
    pub obb_pair: Option<ObbPair3>,
    /// The collision query's copy, if it is on.
    pub collision: Option<Collision3d>,
}

/// A whole state of the lab.
#[derive(Clone, Debug)]
pub struct Restore {
    /// The half shown.
    pub shown: Dimension,
    /// The 2D half.
    pub two: Restore2d,
    /// The 3D half (absent in files from before the 3D view: it stays as it is).
    pub three: Option<Restore3d>,
    /// What to tell the student (a mesh that was a file, shown as the bunny meanwhile).
    pub note: Option<String>,
    /// The lesson open, its step and the goals reached (none: no lesson is open).
    pub lesson: Option<super::lesson::LessonProgress>,
    /// Predict, on or off, with its scores (none: from before Predict; it stays as it is).
    pub predict: Option<super::predict::PredictState>,
}

impl PartialEq for Restore2d {
    fn eq(&self, other: &Self) -> bool {
        self.preset == other.preset
            && self.scene.shapes() == other.scene.shapes()
            && self.selection == other.selection
            && self.half == other.half
            && self.display == other.display
            && self.volumes == other.volumes
            && self.ray == other.ray
            && self.point == other.point
            && self.radius == other.radius
            && self.camera == other.camera
    }
}

impl PartialEq for Restore {
    fn eq(&self, other: &Self) -> bool {
        self.shown == other.shown
            && self.two == other.two
            && self.three == other.three
            && self.note == other.note
            && self.lesson == other.lesson
            && self.predict == other.predict
    }
}

impl RestoreHalf {
    /// Writes the structures, question and playback into `half` (keeping its speed).
    fn write<P: super::dimension::LabPrimitive>(self, half: &mut Half<P>) {
        let [update, compare_update] = self.update;
        half.lane = Lane::with_update(self.settings, update);
        half.compare = self
            .compare
            .map(|settings| Lane::with_update(settings, compare_update));
        half.task = self.task;
        half.variant = self.variant;
        // A file may name a version the task lacks: the full one runs, and is shown.
        half.set_task(self.task);
        half.k = self.k;
        let speed = half.playback.speed;
        half.playback = Playback::default();
        half.playback.step = self.step;
        half.playback.at_end = self.live;
        half.playback.speed = speed;
    }
}

impl Restore2d {
    pub(super) fn write(self, lab: &mut Lab2d) {
        lab.preset = self.preset;
        lab.scene = self.scene;
        lab.selection = self.selection;
        self.half.write(&mut lab.half);
        lab.half.radius = self.radius;
        lab.display = self.display;
        lab.volumes = self.volumes;
        lab.ray = self.ray;
        lab.point = self.point;
        lab.camera = self.camera;
        lab.fit_pending = false;
        // A saved drifting scene comes back still ("Animate" starts it again).
        lab.animation = (lab.preset == Preset::Drifting).then(Default::default);
        // Undoing an edit made before would bring back a scene of another state.
        lab.history = super::history::History::default();
    }
}

impl Restore3d {
    pub(super) fn write(self, lab: &mut Lab3d) {
        self.half.write(&mut lab.half);
        lab.placement = Some(self.placement);
        lab.pending = Some(self.mesh);
        // As the volumes' rule has it: the trees' nodes are put away while they are shown.
        if self.volumes.shown || self.obb_pair.is_some() {
            lab.display.structure = false;
            lab.display.marks = false;
        }
        lab.volumes = self.volumes;
        lab.obb_pair = self.obb_pair;
        lab.collision = self.collision;
    }
}
