//! What the lab says about the lesson open: in its report (for the page and the browser
//! test), in words for the page's live region (a screen reader reads the step and its task),
//! and as the `{bvhlab: "progress", ...}` message an embedding course page receives whenever
//! the student moves to another step or reaches a goal.

use serde::Serialize;

use crate::model::Lab;

/// The lesson open, in brief.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LessonReport {
    /// The lesson's name (`slab-test`).
    pub lesson: String,
    /// Its title.
    pub title: String,
    /// The step shown, from 1.
    pub step: usize,
    /// How many steps it has.
    pub steps: usize,
    /// The step's title.
    pub step_title: String,
    /// What the student is asked to do, if anything.
    pub task: Option<String>,
    /// Whether the step shown's goal was reached.
    pub goal_reached: bool,
    /// How many of the lesson's steps with a goal have it reached.
    pub goals_reached: usize,
    /// How many of its steps have a goal.
    pub goals: usize,
}

impl LessonReport {
    /// The lesson open in `lab`, if any.
    pub fn of(lab: &Lab) -> Option<Self> {
        let progress = lab.lesson()?;
        let step = progress.current();
        let with_goal = |i: &usize| !progress.lesson.steps[*i].goals.is_empty();
        Some(Self {
            lesson: progress.lesson.name.clone(),
            title: progress.lesson.title.clone(),
            step: progress.step + 1,
            steps: progress.lesson.steps.len(),
            step_title: step.title.clone(),
            task: step.task.clone(),
            goal_reached: progress.reached_here(),
            goals_reached: (0..progress.reached.len())
                .filter(with_goal)
                .filter(|&i| progress.reached[i])
                .count(),
            goals: (0..progress.lesson.steps.len()).filter(with_goal).count(),
        })
    }

    /// The step in words: "Lesson The AABB and the slab test, step 2 of 2: When does this
    /// fail? Task: ... Not done yet."
    pub fn text(&self) -> String {
        let mut s = format!(
            "Lesson {}, step {} of {}: {}.",
            self.title, self.step, self.steps, self.step_title
        );
        if let Some(task) = &self.task {
            s.push_str(" Task: ");
            s.push_str(task);
            s.push_str(if self.goal_reached {
                " Done."
            } else {
                " Not done yet."
            });
        }
        s
    }

    /// The message a course page receives: `{bvhlab: "progress", lesson, step, steps,
    /// goal_reached, goals_reached, goals}`.
    #[cfg(feature = "gui")]
    pub fn progress_message(&self) -> String {
        crate::report::predict::progress_message(Some(self), None).unwrap_or_default()
    }
}
