//! The drifting preset's motion: while it plays, each [`Action::Tick`](super::Action::Tick)
//! moves the shapes to where [`drifting_shapes`] puts them at the animation's time, and the
//! lanes update (the preset shows an AABB tree refitted beside the same tree rebuilt every
//! frame, each with its time: [`super::refit`]).
//!
//! The motion is a function of the animation's time alone, so a test that ticks the same
//! seconds sees the same shapes. It stops when the student edits the scene (drawing, moving
//! or deleting a shape, undo, another preset), and "Animate" starts it again from where it
//! was.

use super::Note;
use super::half::Half;
use super::lab2d::Lab2d;
use super::lane::Lane;
use super::presets::{Preset, drifting_shapes};
use super::refit::UpdateMode;
use super::scene::Scene;
use bvhlab::Segment2;

/// The longest step one frame moves the animation (a frame after the tab was hidden would
/// otherwise jump the shapes across the square).
pub const MAX_FRAME_SECONDS: f64 = 0.1;

/// The drifting preset's animation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Animation {
    /// Whether the shapes move on each frame.
    pub on: bool,
    /// Seconds of motion so far: the shapes are [`drifting_shapes`] of it.
    pub time: f64,
}

impl Animation {
    /// The animation `preset` starts with: moving, for the drifting preset; none for the
    /// others.
    pub fn for_preset(preset: Preset) -> Option<Self> {
        (preset == Preset::Drifting).then_some(Self {
            on: true,
            time: 0.0,
        })
    }
}

/// What loading `preset` does to the lanes: the drifting preset compares a refitted tree
/// (the structure) with the same tree rebuilt every frame (the comparison); leaving it ends
/// that comparison and goes back to rebuilding.
pub(super) fn preset_lanes(half: &mut Half<Segment2>, old: Preset, new: Preset) {
    if new == Preset::Drifting {
        half.lane.update = UpdateMode::Refit;
        half.compare = Some(Lane::with_update(half.lane.settings, UpdateMode::Rebuild));
    } else if old == Preset::Drifting {
        half.lane.update = UpdateMode::Rebuild;
        half.compare = None;
    }
}

impl Lab2d {
    /// Whether the shapes are moving.
    pub fn animating(&self) -> bool {
        self.animation.is_some_and(|a| a.on)
    }

    /// Moves the shapes `seconds` further (at most [`MAX_FRAME_SECONDS`]) when animating;
    /// whether they moved.
    pub(super) fn animate(&mut self, seconds: f64) -> bool {
        let Some(animation) = self.animation.as_mut().filter(|a| a.on) else {
            return false;
        };
        if !(seconds.is_finite() && seconds > 0.0) {
            return false;
        }
        animation.time += seconds.min(MAX_FRAME_SECONDS);
        let shapes = drifting_shapes(animation.time as f32);
        self.scene = Scene::from_shapes(shapes);
        true
    }

    /// "Animate": starts or stops the drifting preset's motion.
    ///
    /// # Errors
    /// When the scene is not the drifting preset's.
    pub(super) fn set_animate(&mut self, on: bool) -> Result<Note, String> {
        if self.preset != Preset::Drifting {
            return Err(format!(
                "only the preset \"{}\" moves; this scene is \"{}\"",
                Preset::Drifting.label(),
                self.preset.label()
            ));
        }
        let animation = self.animation.get_or_insert_with(Animation::default);
        animation.on = on;
        if on {
            // Back to the moving shapes, from where they were (edits made meanwhile go).
            self.scene = Scene::from_shapes(drifting_shapes(animation.time as f32));
            self.selection.clear();
        }
        Ok(Note::Clear)
    }

    /// Stops the motion (the student edits the scene); "Animate" resumes it.
    pub(super) fn stop_animation(&mut self) {
        if let Some(a) = &mut self.animation {
            a.on = false;
        }
    }
}
