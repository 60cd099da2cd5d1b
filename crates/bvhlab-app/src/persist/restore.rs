//! Putting a [`SavedState`] back into the lab: every limit is checked and every value
//! converted first ([`SavedState::restore`]), into the model's own description of a whole
//! state ([`Restore`]), which one action then writes into the lab. So a bad file or link
//! changes nothing.

use bvhlab::glam::Vec2;

use crate::model::Action;
use crate::model::Dimension;
use crate::model::camera2d::{Camera2d, MAX_SCALE, MIN_SCALE};
use crate::model::half::MAX_K;
use crate::model::lab2d::RayHandles;
use crate::model::restore::{Restore, Restore2d, RestoreHalf};
use crate::model::scene::{Scene, Shape, ShapeKind};
use crate::model::structures::BuildSettings;

use super::names::{Coord, StoredPoint};
use super::state::{FORMAT_VERSION, SavedState, SceneState, SettingsState, point};
use super::state3d::Checked3d;
use super::{MAX_COORD, MAX_POINTS, MAX_SHAPES, capitalized};

impl SavedState {
    /// Checks every limit (see [`SavedState`]'s "Limits") without touching any lab.
    ///
    /// # Errors
    /// What is wrong, naming the shape, point or field.
    pub fn check(&self) -> Result<(), String> {
        self.restore().map(|_| ())
    }

    /// The action that puts this state into a lab (its scene, structures, queries,
    /// playback and view), once everything is checked.
    ///
    /// # Errors
    /// What is wrong, and that the current scene was kept.
    pub fn apply(&self) -> Result<Action, String> {
        self.restore()
            .map_err(|e| format!("{}. The current scene was kept.", capitalized(&e)))
    }

    /// [`apply`](Self::apply), with the bare reason as the error.
    ///
    /// # Errors
    /// What is wrong, naming the shape, point or field.
    pub fn restore(&self) -> Result<Action, String> {
        Ok(Action::Restore(Box::new(checked(self)?)))
    }
}

/// Checks `state` and converts it, or says what is wrong.
fn checked(state: &SavedState) -> Result<Restore, String> {
    if state.version != FORMAT_VERSION {
        return Err(format!(
            "this is version {} of the scene format; this lab reads version {FORMAT_VERSION}",
            state.version
        ));
    }
    let scene = scene(&state.scene)?;
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
    let half = RestoreHalf {
        settings: settings("the structure", &state.structure)?,
        compare: state
            .compare
            .as_ref()
            .map(|c| settings("the comparison structure", c))
            .transpose()?,
        update: [
            state.structure.update.into(),
            state
                .compare
                .map_or_else(Default::default, |c| c.update.into()),
        ],
        task: state.task.into(),
        variant: state.variant.into(),
        k: state.k,
        step: state.playback.step,
        live: state.playback.live,
    };
    let three = state
        .three
        .as_ref()
        .map(|t| three_half(t, &half))
        .transpose()?;
    let two = Restore2d {
        // A scene that is a preset is that preset in the menu too.
        preset: match &state.scene {
            SceneState::Preset(p) => p.0,
            SceneState::Shapes(_) => state.preset.0,
        },
        scene,
        selection,
        half,
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
        radius,
        camera: Camera2d {
            center: checked_point("the view's centre", state.view.center)?,
            scale,
        },
    };
    let shown = if three.as_ref().is_some_and(|t| t.shown) {
        Dimension::Three
    } else {
        Dimension::Two
    };
    let (lesson, note) = lesson_and_note(state, three.as_ref().and_then(|t| t.note.clone()));
    Ok(Restore {
        shown,
        two,
        three: three.map(|t| t.restore),
        note,
        lesson,
        predict: state.predict.as_ref().map(predict),
    })
}

/// The 3D half as saved, checked (`half`: the 2D half's, for what it shares).
fn three_half(t: &super::state3d::ThreeState, half: &RestoreHalf) -> Result<Checked3d, String> {
    let compare = t
        .compare
        .as_ref()
        .map(|c| settings("the 3D comparison structure", c))
        .transpose()?;
    Checked3d::check(
        t,
        settings("the 3D structure", &t.structure)?,
        compare,
        half,
    )
}

/// Predict as saved: on or off, and the scores.
fn predict(saved: &super::state::PredictSaved) -> crate::model::predict::PredictState {
    let scores = saved.scores.iter().map(|s| {
        let score = crate::model::predict::Score {
            first_time: s.first_time,
            after_hint: s.after_hint,
            shown: s.shown,
        };
        (s.exercise.clone(), score)
    });
    crate::model::predict::PredictState::saved(saved.on, scores.collect())
}

/// The saved lesson, if any and the lab has it, and what to tell the student: `note`, and
/// why a lesson this lab no longer has (or has changed) was closed (the rest comes back).
fn lesson_and_note(
    state: &SavedState,
    note: Option<String>,
) -> (Option<crate::model::LessonProgress>, Option<String>) {
    match state.lesson.as_ref().map(lesson) {
        Some(Ok(progress)) => (Some(progress), note),
        Some(Err(why)) => (
            None,
            Some(note.map_or(why.clone(), |n| format!("{n} {why}"))),
        ),
        None => (None, note),
    }
}

/// The saved lesson, found among the lab's, at a step it has.
fn lesson(saved: &super::state::LessonState) -> Result<crate::model::LessonProgress, String> {
    let closed = "; it was closed, and the rest of the state is back.";
    let lesson = match &saved.text {
        Some(text) => {
            let file = saved.file.as_deref().unwrap_or("the saved lesson");
            crate::lessons::format::read_teacher(file, text.as_bytes())
                .map(std::sync::Arc::new)
                .map_err(|e| format!("The saved teacher's lesson: {e}{closed}"))?
        }
        None => crate::lessons::find(&saved.name)
            .map_err(|e| format!("The saved lesson: {e}{closed}"))?,
    };
    let steps = lesson.steps.len();
    if saved.step >= steps || saved.reached.len() > steps {
        return Err(format!(
            "The saved lesson \"{}\" was at step {} of {}, and this lab's has {steps}{closed}",
            saved.name,
            saved.step + 1,
            saved.reached.len().max(saved.step + 1)
        ));
    }
    let mut reached = saved.reached.clone();
    reached.resize(steps, false);
    Ok(crate::model::LessonProgress {
        lesson,
        step: saved.step,
        reached,
    })
}

/// The scene, checked: at most [`MAX_SHAPES`] shapes and [`MAX_POINTS`] points, each shape
/// valid.
fn scene(scene: &SceneState) -> Result<Scene, String> {
    match scene {
        SceneState::Preset(p) => Ok(p.0.build().0),
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
            Ok(Scene::from_shapes(shapes))
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
    let settings = BuildSettings {
        kind: s.kind.into(),
        bvh_split: s.bvh_split.into(),
        sphere_fit: s.sphere_fit.into(),
        leaf_size: s.leaf_size,
        kd_split: s.kd_split.into(),
        grid_cells: s.grid_cells,
        quadtree_depth: s.quadtree_depth,
    };
    settings.check(what)?;
    Ok(settings)
}
