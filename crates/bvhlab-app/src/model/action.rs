//! Every change of the lab, as a value: the panels' widgets, the canvas and the 3D view, the
//! keyboard, the embedding page's commands, a restored state and the tests all say what
//! they want as [`Action`]s, and [`Lab::apply`](super::Lab::apply) carries them out with the
//! rules that go with each.

use bvhlab::Ray3;
use bvhlab::glam::{Vec2, Vec3};

use super::camera2d::Camera2d;
use super::collision2d::Collision2d;
use super::collision3d::Collision3d;
use super::dimension::Dimension;
use super::heat::HeatSettings;
use super::lab2d::{Display, RayHandles};
use super::lab3d::Display3d;
use super::mesh::MeshSource;
use super::obb_pair3d::ObbPair3;
use super::orbit_camera::OrbitCamera;
use super::presets::Preset;
use super::question::{Task, Variant};
use super::refit::UpdateMode;
use super::restore::Restore;
use super::scene::ShapeKind;
use super::structures::BuildSettings;
use super::tools::{Tool, Tool3d};
use super::volumes::{ObbPair, VolumeToggles};
use super::volumes3d::Volumes3d;

/// A change of the lab.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Shows the 2D or the 3D half (each keeps its own state).
    Show(Dimension),
    /// Sets the status line's message (`None` clears it).
    SetMessage(Option<String>),
    /// A change of the 2D half.
    Two(Action2d),
    /// A change of the 3D half.
    Three(Action3d),
    /// A change of the structures, question or playback of the half shown.
    Half(HalfAction),
    /// Opens or closes a lesson, or moves to one of its steps.
    Lesson(super::lesson::LessonAction),
    /// Switches Predict on or off, or answers its question.
    Predict(super::predict::PredictAction),
    /// Replaces the whole state (a saved state, a scene file, a share link), already
    /// checked.
    Restore(Box<Restore>),
    /// A frame passed: `seconds` since the last one. Playback advances when playing; the 3D
    /// half loads a mesh asked for and gives a build under way about `build_ms`
    /// milliseconds.
    Tick {
        /// Seconds since the last frame.
        seconds: f64,
        /// Milliseconds of build work this frame may do.
        build_ms: f64,
    },
}

/// A change of the 2D half.
#[derive(Clone, Debug, PartialEq)]
pub enum Action2d {
    /// What a press on the canvas does.
    SetTool(Tool),
    /// Replaces the scene with a preset (and its structure), frames it and shows 2D.
    LoadPreset(Preset),
    /// Removes every shape.
    Clear,
    /// Undoes the last scene edit (a shape added, moved or deleted, the scene cleared, a
    /// preset loaded); refused when there is none.
    Undo,
    /// Redoes the last scene edit undone; refused when there is none (a new edit forgets
    /// what could be redone).
    Redo,
    /// Adds a shape.
    AddShape {
        /// What the points make.
        kind: ShapeKind,
        /// Its points.
        points: Vec<Vec2>,
    },
    /// Adds a point to the point cloud `cloud` (an index).
    AddToCloud {
        /// The cloud's shape index.
        cloud: usize,
        /// The point.
        point: Vec2,
    },
    /// Selects these shapes (by index).
    Select(Vec<usize>),
    /// Moves the selected shapes.
    MoveSelection(Vec2),
    /// Removes the selected shapes.
    DeleteSelection,
    /// Pans and zooms.
    SetCamera(Camera2d),
    /// Frames the scene in a canvas of this size (points).
    FrameScene(Vec2),
    /// Sets or clears the ray's handles (the task becomes a ray task).
    SetRay(Option<RayHandles>),
    /// Sets or clears the query point (the task becomes a point task).
    SetPoint(Option<Vec2>),
    /// What is drawn.
    SetDisplay(Display),
    /// Which bounding volumes are drawn.
    SetVolumes(VolumeToggles),
    /// The two boxes of the separating-axis demo.
    SetObbPair(ObbPair),
    /// The collision query of the selection against the other shapes; `None` ends it.
    SetCollision(Option<Collision2d>),
    /// Starts or stops the drifting preset's motion (refused on the other presets).
    SetAnimate(bool),
}

/// A change of the 3D half.
#[derive(Clone, Debug, PartialEq)]
pub enum Action3d {
    /// What a click on the view does (the task follows: a ray task or a point task).
    SetTool(Tool3d),
    /// Opens a mesh (it loads on the next frame) and shows 3D.
    OpenMesh(MeshSource),
    /// Orbits, pans or zooms.
    SetCamera(OrbitCamera),
    /// Frames the mesh just loaded in a view of this aspect ratio (width / height), and puts
    /// a first ray and point in it.
    Frame {
        /// Width over height.
        aspect: f32,
    },
    /// Sets or clears the ray (the task becomes a ray task).
    SetRay(Option<Ray3>),
    /// Sets or clears the query point (the task becomes a point task).
    SetPoint(Option<Vec3>),
    /// What is drawn.
    SetDisplay(Display3d),
    /// The heat map's settings.
    SetHeat(HeatSettings),
    /// Starts or stops the motion of a mesh that moves (the twisting torus): while on, each
    /// frame moves it on and its structures follow.
    Animate(bool),
    /// The bounding volumes of the mesh or a part of it (lecture §2): shown or not, which,
    /// fitted to which triangles, and the slab test.
    SetVolumes(Volumes3d),
    /// The two boxes of the separating-axis test and the axis looked at; `None` ends it.
    SetObbPair(Option<ObbPair3>),
    /// The collision query of the volumes' part against a moved copy of it; `None` ends it.
    SetCollision(Option<Collision3d>),
}

/// A change of the structures, question or playback of the half shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HalfAction {
    /// The structure and its build options.
    SetStructure(BuildSettings),
    /// A second structure (or the same with other options) beside the first; `None` ends
    /// the comparison.
    SetCompare(Option<BuildSettings>),
    /// What is stepped through (a variant the task lacks goes back to the full algorithm).
    SetTask(Task),
    /// Which version of the algorithm.
    SetVariant(Variant),
    /// How many nearest neighbours.
    SetK(usize),
    /// The range query's radius.
    SetRadius(f32),
    /// What lane `lane` (0: the structure; 1: the comparison) does when the primitives
    /// move: rebuild, or refit a BVH ([`super::refit`]).
    SetUpdateMode {
        /// 0 for the structure, 1 for the comparison.
        lane: usize,
        /// Rebuild or refit.
        mode: UpdateMode,
    },
    /// Rebuilds every lane's structure with its settings now, also in refit mode.
    RebuildNow,
    /// Moves playback.
    Playback(PlaybackAction),
}

/// Moves playback.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlaybackAction {
    /// To step `n` (0: the start; past the end: the end, live).
    GoTo(usize),
    /// To the end, live (it follows the question as it changes).
    End,
    /// To step `n` once there is a recording that long (not live): where a page's address
    /// or a saved state asks playback to be before the structure is built.
    Hold(usize),
    /// Forward (or back, negative) by this many steps; stops playing.
    StepBy(isize),
    /// Starts (from the start when at the end) or stops.
    Play(bool),
    /// Plays or pauses.
    Toggle,
    /// Steps per second while playing.
    SetSpeed(f32),
}

impl Action2d {
    /// Whether the action edits the scene's shapes (which also stops the drifting preset's
    /// motion).
    pub fn edits_scene(&self) -> bool {
        matches!(
            self,
            Self::Clear
                | Self::Undo
                | Self::Redo
                | Self::AddShape { .. }
                | Self::AddToCloud { .. }
                | Self::MoveSelection(_)
                | Self::DeleteSelection
        )
    }
}

impl Action {
    /// Whether the action asks a new question: it changes what is recorded (the scene or
    /// mesh, the structures, the task, variant, k, radius, the ray or the point). Playback
    /// then shows the new answer, at the end ([`super::playback`]'s rule). Framing a mesh
    /// just loaded is not one: opening it was.
    pub fn asks_new_question(&self) -> bool {
        match self {
            Self::Two(a) => {
                a.edits_scene()
                    || matches!(
                        a,
                        Action2d::LoadPreset(_) | Action2d::SetRay(_) | Action2d::SetPoint(_)
                    )
            }
            Self::Three(a) => matches!(
                a,
                Action3d::SetTool(_)
                    | Action3d::OpenMesh(_)
                    | Action3d::SetRay(_)
                    | Action3d::SetPoint(_)
            ),
            Self::Half(a) => !matches!(a, HalfAction::Playback(_)),
            Self::Show(_)
            | Self::SetMessage(_)
            | Self::Lesson(_)
            | Self::Predict(_)
            | Self::Restore(_)
            | Self::Tick { .. } => false,
        }
    }
}

impl From<super::predict::PredictAction> for Action {
    fn from(a: super::predict::PredictAction) -> Self {
        Self::Predict(a)
    }
}

impl From<Action2d> for Action {
    fn from(a: Action2d) -> Self {
        Self::Two(a)
    }
}

impl From<Action3d> for Action {
    fn from(a: Action3d) -> Self {
        Self::Three(a)
    }
}

impl From<HalfAction> for Action {
    fn from(a: HalfAction) -> Self {
        Self::Half(a)
    }
}

impl From<PlaybackAction> for Action {
    fn from(a: PlaybackAction) -> Self {
        Self::Half(HalfAction::Playback(a))
    }
}
