//! The lab's state, with no egui in it: one [`Lab`], changed only by [`Lab::apply`] with an
//! [`Action`].
//!
//! The panels, the canvas and the 3D view read the lab and say what they want as actions;
//! so do the keyboard, the embedding page's commands, a restored state and the tests. Each
//! action is one match arm in [`Lab::apply`] (and in the half it concerns:
//! [`Lab2d::apply`](lab2d::Lab2d), [`Lab3d::apply`](lab3d::Lab3d)), so the rules that go with
//! a change (a new preset clears the ray, a ray makes the task a ray task, a comparison
//! reframes the canvas, ...) sit in one place, and a refused action changes nothing.
//!
//! What is derived from the state (the scene's primitives, the built structures, the
//! recordings and the snapshot at the playback step) is brought up to date after every
//! action; a big 3D build advances a slice per frame ([`Action::Tick`]).
//!
//! - [`lab2d`] and [`lab3d`]: the two halves, mirrors of each other around one generic
//!   [`half::Half`] (structures, question, playback) over the primitive of each
//!   ([`dimension::LabPrimitive`]).
//! - [`lane`]: one structure and what is derived from it; [`build_job`]: building in slices.
//! - [`question`]: what is stepped through; [`recording`]: a question asked with an observer; [`snapshot`]: its events folded at
//!   any step; [`playback`]: the transport; [`outcome`]: the live answers beside brute
//!   force's; [`structures`]: one dispatch over the core's structures.
//! - [`scene`], [`presets`], [`volumes`], [`camera2d`]: the 2D half's data; [`mesh`],
//!   [`motion`], [`orbit_camera`], [`heat`]: the 3D half's; [`tools`]: what a press does in each.
//! - [`predict`]: the student predicts each step before it is shown, and is scored.
//! - [`lesson`]: the lesson open and its goals reached; [`goal`]: a goal read live;
//!   [`setup`]: a starting state in a few words (the address's and each lesson step's).
//! - [`action`]: every change; [`restore`]: a whole state, checked; [`history`]: the 2D
//!   scene's edits, to undo and redo.

pub mod action;
pub mod animation;
mod apply;
pub mod build_job;
pub mod camera2d;
pub mod clock;
pub mod collision;
pub mod collision2d;
pub mod collision3d;
pub mod dimension;
pub mod goal;
pub mod half;
pub mod heat;
pub mod history;
pub mod lab2d;
pub mod lab3d;
pub mod lane;
pub mod lane_name;
pub mod lesson;
pub mod mesh;
pub mod motion;
pub mod obb_pair3d;
pub mod orbit_camera;
pub mod outcome;
pub mod playback;
pub mod predict;
pub mod presets;
pub mod question;
pub mod recording;
pub mod refit;
pub mod restore;
pub mod scene;
pub mod setup;
pub mod snapshot;
pub mod structures;
pub mod tools;
pub mod volumes;
pub mod volumes3d;

pub use action::{Action, Action2d, Action3d, HalfAction, PlaybackAction};
pub use dimension::Dimension;
pub use lab2d::Lab2d;
pub use lab3d::Lab3d;
pub use lesson::{Lesson, LessonAction, LessonProgress, LessonStep, TeacherFile};
pub use setup::Setup;

/// What the status line says after an action.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Note {
    /// Whatever it said.
    Keep,
    /// Nothing: the last message no longer applies.
    Clear,
    /// This.
    Say(String),
}

/// The whole lab: the half shown, both halves, and the status line's message.
#[derive(Default)]
pub struct Lab {
    dimension: Dimension,
    two: Lab2d,
    three: Lab3d,
    message: Option<String>,
    /// The lesson open, if any ([`lesson`]).
    lesson: Option<LessonProgress>,
    /// Predict: on or off, the question's tries and the scores ([`predict`]).
    predict: predict::PredictState,
    /// Counts the changes: equal counts mean an unchanged state (the autosave compares it).
    changes: u64,
}

impl Lab {
    /// A lab whose 2D half opens on `preset` (the default lab opens on [`Preset::default`]),
    /// with nothing to undo.
    ///
    /// [`Preset::default`]: presets::Preset
    pub fn with_preset(preset: presets::Preset) -> Self {
        let mut lab = Self {
            two: Lab2d::with_preset(preset),
            ..Self::default()
        };
        lab.refresh();
        lab
    }

    /// The half shown.
    pub fn dimension(&self) -> Dimension {
        self.dimension
    }

    /// The 2D half.
    pub fn two(&self) -> &Lab2d {
        &self.two
    }

    /// The 3D half.
    pub fn three(&self) -> &Lab3d {
        &self.three
    }

    /// The status line's message: what went wrong and what was kept, or what was done.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// How many changes the lab has seen: it grows with every action that applied.
    pub fn changes(&self) -> u64 {
        self.changes
    }

    /// Whether the 3D half is shown and loading or building (the caller keeps repainting
    /// and holds replies to the embedding page until it is done).
    pub fn busy(&self) -> bool {
        self.dimension == Dimension::Three && self.three.busy()
    }

    /// Whether the half shown moves: the 2D drifting preset's shapes, or the 3D mesh that
    /// moves. The caller keeps repainting; replies to the embedding page do not wait for it
    /// to stop.
    pub fn animating(&self) -> bool {
        match self.dimension {
            Dimension::Two => self.two.animating(),
            Dimension::Three => self.three.moving(),
        }
    }

    /// Whether playback runs in the half shown.
    pub fn playing(&self) -> bool {
        match self.dimension {
            Dimension::Two => self.two.half.playback.playing,
            Dimension::Three => self.three.half.playback.playing,
        }
    }

    /// The last playback step of the half shown (its longest recording's length).
    pub fn steps(&self) -> usize {
        match self.dimension {
            Dimension::Two => self.two.half.steps(),
            Dimension::Three => self.three.half.steps(),
        }
    }

    /// The playback step shown in the half shown (its recordings' length in live mode).
    pub fn shown_step(&self) -> usize {
        match self.dimension {
            Dimension::Two => self.two.half.playback.shown(self.two.half.steps()),
            Dimension::Three => self.three.half.playback.shown(self.three.half.steps()),
        }
    }

    /// Applies every action in order, stopping at the first refused one; returns its error.
    ///
    /// # Errors
    /// The first refusal; the actions before it stay applied.
    pub fn apply_all(&mut self, actions: impl IntoIterator<Item = Action>) -> Result<(), String> {
        for action in actions {
            self.apply(action)?;
        }
        Ok(())
    }
}
