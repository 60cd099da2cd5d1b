//! [`SavedState`]: everything about the lab a student would miss after a reload, as plain data
//! that serde writes and reads, and [`SavedState::capture`], which reads it off the lab.
//!
//! The schema is flat on purpose: objects of fixed fields, lists of shapes and lists of
//! points, nothing that nests by itself, so hostile input cannot recurse (`serde_json`'s
//! recursion limit stays on as well). Every field but `version` may be left out of a
//! hand-written file and then takes the lab's default; an unknown field is an error, so a
//! typo is not silently ignored.

use bvhlab::glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::model::Lab;
use crate::model::camera2d::Camera2d;
use crate::model::lab2d::{Display, RayHandles};
use crate::model::lane::Lane;
use crate::model::structures::BuildSettings;
use crate::model::volumes::VolumeToggles;

use super::names::{
    Coord, KdSplitName, PresetSlug, ShapeName, SphereFitName, SplitName, StoredPoint,
    StructureName, TaskName, UpdateName, VariantName,
};
use super::state3d::ThreeState;

/// The version of the format this lab writes and reads.
pub const FORMAT_VERSION: u32 = 1;

/// The lab's state as a scene file, a share link and the browser's saved state hold it.
///
/// # Limits
/// What [`SavedState::apply`] (and so [`from_file`](super::from_file),
/// [`from_fragment`](super::from_fragment) and [`startup`](super::startup)) accepts; anything
/// else is refused with a message and the current scene is kept. Hostile input never panics.
///
/// - `version` must be [`FORMAT_VERSION`]; a file without one is not a scene file.
/// - A file is at most [`MAX_FILE_BYTES`](super::MAX_FILE_BYTES); a link's fragment at most
///   [`MAX_LINK_CHARS`](super::MAX_LINK_CHARS) characters, inflating to at most
///   [`MAX_LINK_JSON_BYTES`](super::MAX_LINK_JSON_BYTES) (inflation stops there: a deflate
///   bomb costs nothing).
/// - At most [`MAX_SHAPES`](super::MAX_SHAPES) shapes, [`MAX_POINTS`](super::MAX_POINTS)
///   points in all (one point cloud may have them all), and the points each kind needs (2
///   for a segment or polyline, 3 for a polygon, 1 for a cloud).
/// - Every coordinate, the radius and the view are finite numbers within
///   ±[`MAX_COORD`](super::MAX_COORD); the radius is at least 0; the view's scale lies in
///   the zoom range ([`MIN_SCALE`](super::MIN_SCALE) to [`MAX_SCALE`](super::MAX_SCALE)).
/// - `k` is 1 to [`MAX_K`](super::MAX_K); leaf sizes 1 to
///   [`MAX_LEAF_SIZE`](super::MAX_LEAF_SIZE); grid cells per axis 0 (automatic) to
///   [`MAX_GRID_CELLS`](super::MAX_GRID_CELLS); quadtree depth 1 to
///   [`MAX_QUADTREE_DEPTH`](super::MAX_QUADTREE_DEPTH); the selection lists shapes that exist.
/// - Names (structure, split, task, preset...) are the strings of the `*Name` enums and
///   [`PresetSlug`]; any other string is refused. A wrong type (a string for a number, a
///   number for a list) is refused by serde, naming the line and column.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SavedState {
    /// [`FORMAT_VERSION`].
    pub version: u32,
    /// The preset chosen in the menu (what "Reload preset" reloads); a scene stored as a
    /// preset's name sets it too.
    pub preset: PresetSlug,
    /// The shapes, or the preset they are (an unmodified preset is stored by name, so that
    /// even the 10,000-segment scene fits in a link).
    pub scene: SceneState,
    /// The selected shapes, by index.
    pub selection: Vec<usize>,
    /// The structure's build settings.
    pub structure: SettingsState,
    /// The comparison structure's, when two are shown side by side.
    pub compare: Option<SettingsState>,
    /// The drawing switches.
    pub display: DisplayState,
    /// Which bounding volumes are drawn.
    pub volumes: VolumeState,
    /// The query ray's handles.
    pub ray: Option<RayState>,
    /// The query point.
    pub point: Option<StoredPoint>,
    /// How many neighbours the point query finds.
    pub k: usize,
    /// The range query's radius.
    pub radius: Coord,
    /// What playback steps through.
    pub task: TaskName,
    /// Which version of the algorithm.
    pub variant: VariantName,
    /// Where playback is.
    pub playback: PlaybackState,
    /// Pan and zoom.
    pub view: ViewState,
    /// The 3D half: whether it is shown, its mesh, structure, camera, ray and point, and its
    /// own question and playback (absent in files from before the 3D view: the 2D half is
    /// shown).
    pub three: Option<ThreeState>,
    /// The lesson open (absent: none).
    pub lesson: Option<LessonState>,
    /// Predict, on or off, and its scores (absent in files from before Predict).
    pub predict: Option<PredictSaved>,
}

/// Predict: whether it is on, and each exercise's score.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PredictSaved {
    /// Whether the lab asks before each step.
    pub on: bool,
    /// The scores, in the order the exercises were first met.
    pub scores: Vec<ScoreSaved>,
}

/// One exercise's score.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScoreSaved {
    /// The exercise ("2D AABB tree: first hit").
    pub exercise: String,
    /// Right at the first try.
    pub first_time: u32,
    /// Right after a hint.
    pub after_hint: u32,
    /// Shown.
    pub shown: u32,
}

/// The lesson open, its step and which steps' goals were reached.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LessonState {
    /// The lesson's name (`slab-test`).
    pub name: String,
    /// The step shown (0 is the first).
    pub step: usize,
    /// For each step, whether its goal was reached.
    pub reached: Vec<bool>,
    /// A teacher's lesson (not one built into the lab): its file's name, or the address it
    /// came from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// A teacher's lesson: its file's text, read again on restore (the lab that restores
    /// may not have the file).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
}

/// The scene: `{"preset": "10k"}` (exactly that preset's shapes) or `{"shapes": [...]}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SceneState {
    /// A preset's shapes, unmodified.
    #[serde(rename = "preset")]
    Preset(PresetSlug),
    /// The shapes, in drawing order.
    #[serde(rename = "shapes")]
    Shapes(Vec<ShapeState>),
}

impl Default for SceneState {
    fn default() -> Self {
        Self::Preset(PresetSlug::default())
    }
}

/// One shape: `{"kind": "polygon", "points": [[x, y], ...]}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeState {
    /// What the points make.
    pub kind: ShapeName,
    /// Its points, in order.
    pub points: Vec<StoredPoint>,
}

/// A structure's build settings ([`BuildSettings`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SettingsState {
    /// Which structure.
    pub kind: StructureName,
    /// BVH split method.
    pub bvh_split: SplitName,
    /// Sphere-tree node fit.
    pub sphere_fit: SphereFitName,
    /// BVH, k-d, BSP and quadtree leaf size.
    pub leaf_size: usize,
    /// k-d tree planes.
    pub kd_split: KdSplitName,
    /// Grid cells per axis; 0 means automatic.
    pub grid_cells: u32,
    /// Quadtree depth limit.
    pub quadtree_depth: usize,
    /// What the lane does when the primitives move (left out when it rebuilds, as files
    /// from before refitting do).
    #[serde(skip_serializing_if = "UpdateName::is_default")]
    pub update: UpdateName,
}

impl SettingsState {
    /// A lane's build settings and update mode.
    pub fn of_lane<P: crate::model::dimension::LabPrimitive>(lane: &Lane<P>) -> Self {
        Self {
            update: lane.update.into(),
            ..lane.settings.into()
        }
    }
}

impl From<BuildSettings> for SettingsState {
    fn from(s: BuildSettings) -> Self {
        Self {
            kind: s.kind.into(),
            bvh_split: s.bvh_split.into(),
            sphere_fit: s.sphere_fit.into(),
            leaf_size: s.leaf_size,
            kd_split: s.kd_split.into(),
            grid_cells: s.grid_cells,
            quadtree_depth: s.quadtree_depth,
            update: UpdateName::default(),
        }
    }
}

impl Default for SettingsState {
    fn default() -> Self {
        BuildSettings::default().into()
    }
}

/// The drawing switches ([`Display`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
#[expect(
    clippy::struct_excessive_bools,
    reason = "one switch per checkbox, as in Display"
)]
pub struct DisplayState {
    /// Draw the structure's nodes.
    pub structure: bool,
    /// Draw nodes down to this depth.
    pub max_depth: u32,
    /// Colour primitives by the leaf that holds them.
    pub leaf_colours: bool,
    /// Mark the nodes the query visited, culled and pruned.
    pub query_marks: bool,
    /// Show the selection's bounding volumes.
    pub volumes: bool,
    /// Show the slab test of the ray against the selection's AABB.
    pub slab_test: bool,
}

impl From<Display> for DisplayState {
    fn from(d: Display) -> Self {
        Self {
            structure: d.structure,
            max_depth: d.max_depth,
            leaf_colours: d.leaf_colours,
            query_marks: d.query_marks,
            volumes: d.volumes,
            slab_test: d.slab_test,
        }
    }
}

impl From<DisplayState> for Display {
    fn from(d: DisplayState) -> Self {
        Self {
            structure: d.structure,
            max_depth: d.max_depth,
            leaf_colours: d.leaf_colours,
            query_marks: d.query_marks,
            volumes: d.volumes,
            slab_test: d.slab_test,
        }
    }
}

impl Default for DisplayState {
    fn default() -> Self {
        Display::default().into()
    }
}

/// Which bounding volumes are drawn ([`VolumeToggles`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
#[expect(
    clippy::struct_excessive_bools,
    reason = "one switch per volume, as in VolumeToggles"
)]
pub struct VolumeState {
    /// The centroid sphere.
    pub centroid: bool,
    /// Ritter's sphere.
    pub ritter: bool,
    /// Welzl's sphere.
    pub welzl: bool,
    /// The AABB.
    pub aabb: bool,
    /// The OBB.
    pub obb: bool,
    /// The convex hull.
    pub hull: bool,
}

impl From<VolumeToggles> for VolumeState {
    fn from(t: VolumeToggles) -> Self {
        Self {
            centroid: t.centroid,
            ritter: t.ritter,
            welzl: t.welzl,
            aabb: t.aabb,
            obb: t.obb,
            hull: t.hull,
        }
    }
}

impl From<VolumeState> for VolumeToggles {
    fn from(t: VolumeState) -> Self {
        Self {
            centroid: t.centroid,
            ritter: t.ritter,
            welzl: t.welzl,
            aabb: t.aabb,
            obb: t.obb,
            hull: t.hull,
        }
    }
}

impl Default for VolumeState {
    fn default() -> Self {
        VolumeToggles::default().into()
    }
}

/// The ray's handles ([`RayHandles`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RayState {
    /// Where the ray starts.
    pub origin: StoredPoint,
    /// A point it passes through.
    pub target: StoredPoint,
}

/// Where playback is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlaybackState {
    /// How many events are shown (clamped to the recording when it is made).
    pub step: usize,
    /// Whether playback stays at the end as the question changes (live mode).
    pub live: bool,
}

impl Default for PlaybackState {
    fn default() -> Self {
        Self {
            step: 0,
            live: true,
        }
    }
}

/// Which part of the world the canvas shows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewState {
    /// The world point at the canvas centre.
    pub center: StoredPoint,
    /// Screen points per world unit.
    pub scale: Coord,
}

impl Default for ViewState {
    fn default() -> Self {
        let camera = Camera2d::default();
        Self {
            center: stored(camera.center),
            scale: Coord(camera.scale),
        }
    }
}

impl Default for SavedState {
    fn default() -> Self {
        Self::capture(&Lab::default())
    }
}

impl SavedState {
    /// The lab's state, with the scene stored as its preset's name when it is that preset
    /// unmodified (for links and the browser's saved state, which must stay small).
    pub fn capture(lab: &Lab) -> Self {
        let mut state = Self::capture_full(lab);
        let two = lab.two();
        if two.scene.shapes() == two.preset.build().0.shapes() {
            state.scene = SceneState::Preset(PresetSlug(two.preset));
        }
        state
    }

    /// The lab's state with every shape written out (for files, which should open the same
    /// even if a preset changes one day).
    pub fn capture_full(lab: &Lab) -> Self {
        let two = lab.two();
        let half = &two.half;
        Self {
            version: FORMAT_VERSION,
            preset: PresetSlug(two.preset),
            scene: SceneState::Shapes(
                two.scene
                    .shapes()
                    .iter()
                    .map(|s| ShapeState {
                        kind: s.kind.into(),
                        points: s.points.iter().copied().map(stored).collect(),
                    })
                    .collect(),
            ),
            selection: two.selection.clone(),
            structure: SettingsState::of_lane(&half.lane),
            compare: half.compare.as_ref().map(SettingsState::of_lane),
            display: two.display.into(),
            volumes: two.volumes.into(),
            ray: two.ray.map(|r: RayHandles| RayState {
                origin: stored(r.origin),
                target: stored(r.target),
            }),
            point: two.point.map(stored),
            k: half.k,
            radius: Coord(half.radius),
            task: half.task.into(),
            variant: half.variant.into(),
            playback: PlaybackState {
                step: half.playback.step,
                live: half.playback.at_end,
            },
            view: ViewState {
                center: stored(two.camera.center),
                scale: Coord(two.camera.scale),
            },
            three: Some(ThreeState::capture(lab)),
            lesson: lab.lesson().map(|p| LessonState {
                name: p.lesson.name.clone(),
                step: p.step,
                reached: p.reached.clone(),
                file: p.lesson.teacher.as_ref().map(|t| t.file.clone()),
                text: p.lesson.teacher.as_ref().map(|t| t.text.to_string()),
            }),
            predict: Some(PredictSaved {
                on: lab.predict().on,
                scores: lab
                    .predict()
                    .scores
                    .iter()
                    .map(|(exercise, s)| ScoreSaved {
                        exercise: exercise.clone(),
                        first_time: s.first_time,
                        after_hint: s.after_hint,
                        shown: s.shown,
                    })
                    .collect(),
            }),
        }
    }
}

/// A point as stored.
pub(super) fn stored(p: Vec2) -> StoredPoint {
    [Coord(p.x), Coord(p.y)]
}

/// A stored point.
pub(super) fn point(p: StoredPoint) -> Vec2 {
    Vec2::new(p[0].0, p[1].0)
}
