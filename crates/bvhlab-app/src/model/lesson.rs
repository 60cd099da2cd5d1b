//! A lesson walks the lecture in the lab: each step puts the lab in a state ([`Setup`]), says
//! a few sentences and the formula or pseudocode it is about, and gives the student a task
//! whose goal the lab checks live ([`Goal`]). Lessons are data, written by hand in
//! `crates/bvhlab-app/lessons/` and read by [`crate::lessons`]; here is what the model keeps
//! of them: the lesson open, its step, and which steps' goals were reached.

use std::sync::Arc;

use super::goal::Goal;
use super::setup::Setup;
use super::{Lab, Note};

/// A lesson, read from its file.
#[derive(Clone, Debug, PartialEq)]
pub struct Lesson {
    /// Its name in addresses and files (`slab-test` for `lessons/03-slab-test.toml`).
    pub name: String,
    /// Its title.
    pub title: String,
    /// The lecture's section it follows ("§2").
    pub section: String,
    /// Its steps, in order.
    pub steps: Vec<LessonStep>,
    /// Where a teacher's lesson came from (a file opened in the lab, not one built in): kept
    /// so that the lab can save it with the student's state and show it as the teacher's.
    pub teacher: Option<TeacherFile>,
}

/// A lesson file a teacher gave the lab while it runs (dropped, picked, sent by the
/// embedding page or named by the address's `lesson-url=`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TeacherFile {
    /// The file's name (`my-lesson.toml`), or the address it came from.
    pub file: String,
    /// The file's text, as given.
    pub text: Arc<str>,
}

/// One step of a lesson.
#[derive(Clone, Debug, PartialEq)]
pub struct LessonStep {
    /// Its title.
    pub title: String,
    /// Where the lab starts for it.
    pub setup: Setup,
    /// What it says: a few sentences.
    pub text: String,
    /// The formula or pseudocode it is about, shown in a monospace block.
    pub formula: Option<String>,
    /// What the student is asked to do (shown with a mark that fills in when reached).
    pub task: Option<String>,
    /// The goal: reached when every comparison holds at once (none: nothing to check).
    pub goals: Vec<Goal>,
    /// Why the goal matters, shown once it is reached.
    pub why: Option<String>,
    /// A state that reaches the goal, put in place on top of the step's and followed by
    /// playback to the end: the tests check that it does, and a teacher reads it as the
    /// answer.
    pub solution: Option<Setup>,
}

/// The lesson open and where the student is in it.
#[derive(Clone, Debug, PartialEq)]
pub struct LessonProgress {
    /// The lesson.
    pub lesson: Arc<Lesson>,
    /// The step shown (0 is the first).
    pub step: usize,
    /// For each step, whether its goal was reached (it stays reached).
    pub reached: Vec<bool>,
}

impl LessonProgress {
    /// The step shown.
    pub fn current(&self) -> &LessonStep {
        &self.lesson.steps[self.step]
    }

    /// Whether the step shown's goal was reached.
    pub fn reached_here(&self) -> bool {
        self.reached.get(self.step).copied().unwrap_or(false)
    }
}

/// A change of the lesson.
#[derive(Clone, Debug, PartialEq)]
pub enum LessonAction {
    /// Opens `lesson` at `step` (0 is the first) and puts the lab in that step's state;
    /// opening the step shown again starts it afresh (its goal stays reached).
    Open {
        /// The lesson.
        lesson: Arc<Lesson>,
        /// The step.
        step: usize,
    },
    /// Marks steps of the lesson open as reached (0 is the first), as the student reached
    /// them in an earlier session: what an LMS keeps for a student (SCORM's
    /// `suspend_data`) brought back on another computer. Steps it does not have are refused.
    MarkReached(Vec<usize>),
    /// Closes the lesson; the lab stays as it is.
    Close,
}

impl Lab {
    /// The lesson open, if any.
    pub fn lesson(&self) -> Option<&LessonProgress> {
        self.lesson.as_ref()
    }

    /// Carries out a lesson action.
    pub(super) fn apply_lesson(&mut self, action: LessonAction) -> Result<Note, String> {
        let (lesson, step) = match action {
            LessonAction::Open { lesson, step } => (lesson, step),
            LessonAction::MarkReached(steps) => return self.mark_reached(&steps),
            LessonAction::Close => {
                self.lesson = None;
                return Ok(Note::Clear);
            }
        };
        let Some(shown) = lesson.steps.get(step) else {
            return Err(format!(
                "the lesson \"{}\" has {} steps; there is no step {}",
                lesson.name,
                lesson.steps.len(),
                step + 1
            ));
        };
        let reached = match self.lesson.take() {
            // The same lesson: a teacher's file opened again with changes starts over.
            Some(open) if Arc::ptr_eq(&open.lesson, &lesson) || open.lesson == lesson => {
                open.reached
            }
            _ => vec![false; lesson.steps.len()],
        };
        // The lesson is put back only once the step's state is in place: its actions must
        // not count as reaching the goal of the step the student is leaving.
        let source = format!("the lesson \"{}\", step {}", lesson.name, step + 1);
        let mut problems = self.start_afresh(&shown.setup, &source);
        problems.extend(self.apply_setup(&shown.setup, &source));
        self.lesson = Some(LessonProgress {
            lesson,
            step,
            reached,
        });
        Ok(if problems.is_empty() {
            Note::Clear
        } else {
            Note::Say(problems.join("; "))
        })
    }

    /// Puts the half `setup` shows back to how it starts (the preset's or the mesh's
    /// defaults: one structure, no comparison, no ray or point, the first playback step,
    /// the default drawing switches and camera), so that a step starts the same whatever
    /// came before it: a comparison or a leaf size left by an earlier step must not show
    /// in this one, nor an answer recorded before it count as this step's. The 2D scene's
    /// undo history stays (the student's own drawing is one Undo away), and so does
    /// Predict's switch (the student's choice). Returns what could not be done.
    fn start_afresh(&mut self, setup: &Setup, source: &str) -> Vec<String> {
        if let Some(preset) = setup.preset {
            // Loading the preset by its action records the student's scene for Undo.
            if let Err(e) = self.apply(super::Action2d::LoadPreset(preset).into()) {
                return vec![format!("{source}: {e}")];
            }
            self.two.start_afresh();
        }
        if setup.mesh.is_some() {
            self.three.start_afresh();
        }
        Vec::new()
    }

    /// Marks `steps` of the lesson open reached ([`LessonAction::MarkReached`]).
    fn mark_reached(&mut self, steps: &[usize]) -> Result<Note, String> {
        let open = self
            .lesson
            .as_mut()
            .ok_or("no lesson is open: there is nothing to mark reached")?;
        let count = open.reached.len();
        if let Some(&beyond) = steps.iter().find(|&&s| s >= count) {
            return Err(format!(
                "the lesson \"{}\" has steps 1 to {count}; step {} cannot be marked reached",
                open.lesson.name,
                beyond + 1
            ));
        }
        for &step in steps {
            open.reached[step] = true;
        }
        Ok(Note::Clear)
    }

    /// Marks the step shown's goal reached once all its comparisons hold (after every
    /// action; a reached goal stays reached).
    pub(super) fn check_goal(&mut self) {
        let Some(progress) = &self.lesson else {
            return;
        };
        let goals = &progress.current().goals;
        if progress.reached_here() || goals.is_empty() || !goals.iter().all(|g| g.holds(self)) {
            return;
        }
        let step = progress.step;
        if let Some(open) = &mut self.lesson {
            open.reached[step] = true;
        }
    }
}
