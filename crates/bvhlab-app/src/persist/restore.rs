//! Putting a [`SavedState`] back into the lab: every limit is checked and every value
//! converted first ([`Restored::from_state`]), and only a state that passed them all is
//! written into the app, so a bad file or link changes nothing.

use bvhlab::glam::Vec2;

use crate::app::{Display, LabApp, RayHandles};
use crate::lane::Lane;
use crate::playback::Playback;
use crate::presets::Preset;
use crate::pseudocode::{Task, Variant};
use crate::scene::{Scene, Shape, ShapeKind};
use crate::structures::BuildSettings;
use crate::tool::Interaction;
use crate::volumes::VolumeToggles;

use super::names::{Coord, StoredPoint};
use super::state::{FORMAT_VERSION, SavedState, SceneState, SettingsState, point};
use super::state3d::Restored3d;
use super::{
    MAX_COORD, MAX_GRID_CELLS, MAX_K, MAX_LEAF_SIZE, MAX_POINTS, MAX_QUADTREE_DEPTH, MAX_SCALE,
    MAX_SHAPES, MIN_SCALE, capitalized,
};

/// A state that passed every check, in the lab's own types.
struct Restored {
    preset: Preset,
    scene: Scene,
    selection: Vec<usize>,
    settings: BuildSettings,
    compare: Option<BuildSettings>,
    display: Display,
    volumes: VolumeToggles,
    ray: Option<RayHandles>,
    point: Option<Vec2>,
    k: usize,
    radius: f32,
    task: Task,
    variant: Variant,
    step: usize,
    live: bool,
    center: Vec2,
    scale: f32,
    three: Option<Restored3d>,
}

impl SavedState {
    /// Checks every limit (see [`SavedState`]'s "Limits") without touching any lab.
    ///
    /// # Errors
    /// What is wrong, naming the shape, point or field.
    pub fn check(&self) -> Result<(), String> {
        Restored::from_state(self).map(|_| ())
    }

    /// Replaces the lab's scene, structures, queries, playback and view with this state.
    /// Everything is checked first: on any error nothing changes.
    ///
    /// # Errors
    /// What is wrong, and that the current scene was kept.
    pub fn apply(self, app: &mut LabApp) -> Result<(), String> {
        self.restore(app)
            .map_err(|e| format!("{}. The current scene was kept.", capitalized(&e)))
    }

    /// [`apply`](Self::apply), with the bare reason as the error.
    pub(super) fn restore(self, app: &mut LabApp) -> Result<(), String> {
        Restored::from_state(&self)?.write(app);
        Ok(())
    }
}

impl Restored {
    /// Checks `state` and converts it, or says what is wrong.
    fn from_state(state: &SavedState) -> Result<Self, String> {
        if state.version != FORMAT_VERSION {
            return Err(format!(
                "this is version {} of the scene format; this lab reads version {FORMAT_VERSION}",
                state.version
            ));
        }
        let scene = match &state.scene {
            SceneState::Preset(p) => p.0.build().0,
            SceneState::Shapes(shapes) => {
                if shapes.len() > MAX_SHAPES {
                    return Err(format!(
                        "the scene has {} shapes; the lab takes at most {MAX_SHAPES}",
                        shapes.len()
                    ));
                }
                let total: usize = shapes.iter().map(|s| s.points.len()).sum();
                if total > MAX_POINTS {
                    return Err(format!(
                        "the scene has {total} points; the lab takes at most {MAX_POINTS}"
                    ));
                }
                let shapes = shapes
                    .iter()
                    .enumerate()
                    .map(|(i, s)| shape(i, s.kind.into(), &s.points))
                    .collect::<Result<Vec<_>, _>>()?;
                Scene::from_shapes(shapes)
            }
        };
        let n = scene.shapes().len();
        if let Some(&bad) = state.selection.iter().find(|&&i| i >= n) {
            return Err(format!(
                "the selection lists shape {bad}, but the scene has {n} shapes"
            ));
        }
        let mut selection = state.selection.clone();
        selection.sort_unstable();
        selection.dedup();
        if !(1..=MAX_K).contains(&state.k) {
            return Err(format!("k is {}; it must be 1 to {MAX_K}", state.k));
        }
        let radius = number("the radius", state.radius)?;
        if radius < 0.0 {
            return Err(format!("the radius is {radius}; it must be at least 0"));
        }
        let scale = number("the view's scale", state.view.scale)?;
        if !(MIN_SCALE..=MAX_SCALE).contains(&scale) {
            return Err(format!(
                "the view's scale is {scale}; it must be {MIN_SCALE} to {MAX_SCALE}"
            ));
        }
        Ok(Self {
            // A scene that is a preset is that preset in the menu too.
            preset: match &state.scene {
                SceneState::Preset(p) => p.0,
                SceneState::Shapes(_) => state.preset.0,
            },
            scene,
            selection,
            settings: settings("the structure", &state.structure)?,
            compare: state
                .compare
                .as_ref()
                .map(|c| settings("the comparison structure", c))
                .transpose()?,
            display: state.display.into(),
            volumes: state.volumes.into(),
            ray: state
                .ray
                .map(|r| -> Result<_, String> {
                    Ok(RayHandles {
                        origin: checked_point("the ray's origin", r.origin)?,
                        target: checked_point("the ray's target", r.target)?,
                    })
                })
                .transpose()?,
            point: state
                .point
                .map(|p| checked_point("the query point", p))
                .transpose()?,
            k: state.k,
            radius,
            task: state.task.into(),
            variant: state.variant.into(),
            step: state.playback.step,
            live: state.playback.live,
            center: checked_point("the view's centre", state.view.center)?,
            scale,
            three: state
                .three
                .as_ref()
                .map(|t| Restored3d::check(t, settings("the 3D structure", &t.structure)?))
                .transpose()?,
        })
    }

    /// Writes the state into `app`, dropping everything derived from what it replaces.
    fn write(self, app: &mut LabApp) {
        app.preset = self.preset;
        app.scene = self.scene;
        app.selection = self.selection;
        app.lane = Lane::new(self.settings);
        app.compare = self.compare.map(Lane::new);
        app.display = self.display;
        app.volume_toggles = self.volumes;
        app.ray = self.ray;
        app.point = self.point;
        app.k = self.k;
        app.radius = self.radius;
        app.task = self.task;
        app.variant = self.variant;
        let mut playback = Playback::default();
        playback.step = self.step;
        playback.at_end = self.live;
        playback.speed = app.playback.speed;
        app.playback = playback;
        app.view.center = self.center;
        app.view.scale = self.scale;
        app.fit_pending = false;
        app.interaction = Interaction::None;
        app.hovered = None;
        app.linked = None;
        app.fits_cache = None;
        match self.three {
            Some(three) => {
                if let Some(note) = three.write(app) {
                    app.message = Some(note);
                }
            }
            None => app.dimension = crate::app::Dimension::Two,
        }
    }
}

/// Shape `index`, checked: every coordinate finite and within range, then what
/// [`Shape::new`] checks (enough points for the kind).
fn shape(index: usize, kind: ShapeKind, points: &[StoredPoint]) -> Result<Shape, String> {
    let points: Vec<Vec2> = points.iter().copied().map(point).collect();
    if let Some((i, p)) = points
        .iter()
        .enumerate()
        .find(|(_, p)| !p.is_finite() || p.abs().max_element() > MAX_COORD)
    {
        return Err(format!(
            "point {i} of shape {index} is {p}: coordinates must be finite numbers within ±{MAX_COORD:e}"
        ));
    }
    Shape::new(kind, points).map_err(|e| format!("shape {index}: {e}"))
}

/// A number of the state, or why it cannot be used.
fn number(what: &str, value: Coord) -> Result<f32, String> {
    let v = value.0;
    if v.is_finite() && v.abs() <= MAX_COORD {
        Ok(v)
    } else {
        Err(format!(
            "{what} is {v}; it must be a finite number within ±{MAX_COORD:e}"
        ))
    }
}

/// A point of the state, or why it cannot be used.
fn checked_point(what: &str, p: StoredPoint) -> Result<Vec2, String> {
    Ok(Vec2::new(number(what, p[0])?, number(what, p[1])?))
}

/// Build settings, or why they cannot be used.
fn settings(what: &str, s: &SettingsState) -> Result<BuildSettings, String> {
    if !(1..=MAX_LEAF_SIZE).contains(&s.leaf_size) {
        return Err(format!(
            "{what}'s leaf size is {}; it must be 1 to {MAX_LEAF_SIZE}",
            s.leaf_size
        ));
    }
    if s.grid_cells > MAX_GRID_CELLS {
        return Err(format!(
            "{what}'s grid has {} cells per axis; at most {MAX_GRID_CELLS} (0: automatic)",
            s.grid_cells
        ));
    }
    if !(1..=MAX_QUADTREE_DEPTH).contains(&s.quadtree_depth) {
        return Err(format!(
            "{what}'s quadtree depth is {}; it must be 1 to {MAX_QUADTREE_DEPTH}",
            s.quadtree_depth
        ));
    }
    Ok(BuildSettings {
        kind: s.kind.into(),
        bvh_split: s.bvh_split.into(),
        sphere_fit: s.sphere_fit.into(),
        leaf_size: s.leaf_size,
        kd_split: s.kd_split.into(),
        grid_cells: s.grid_cells,
        quadtree_depth: s.quadtree_depth,
    })
}
