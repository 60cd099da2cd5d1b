//! The lesson writer's check of a step, the same as `tests/lessons.rs` runs on the lab's own
//! lessons: the step reads as a lesson file would; opened in a fresh lab, its goal is not met
//! where it starts (a student has something to do); and its recorded solution, put in place
//! and played to the end, meets it. A step without a goal is checked only for reading.

use std::sync::Arc;

use super::text::{DraftStep, LessonDraft, to_toml};
use crate::model::goal::Quantity;
use crate::model::predict::PredictAction;
use crate::model::{Action, Lab, LessonAction, LessonProgress, PlaybackAction};

/// What the check found: what to tell the teacher when the step passes.
///
/// # Errors
/// Why the step cannot be saved, in a sentence.
pub fn check_step(file: &str, draft: &LessonDraft, step: &DraftStep) -> Result<String, String> {
    let alone = LessonDraft {
        steps: vec![step.clone()],
        ..draft.clone()
    };
    let text = to_toml(&alone);
    let lesson = super::super::format::read_teacher(file, text.as_bytes())
        // Without the line: it is of a one-step file the teacher never sees.
        .map_err(|e| {
            let why = e.split_once(": ").map_or(e.as_str(), |(_, why)| why);
            format!("The step does not read: {why}")
        })?;
    let lesson = Arc::new(lesson);
    let mut lab = Lab::default();
    lab.apply(Action::Lesson(LessonAction::Open {
        lesson: lesson.clone(),
        step: 0,
    }))?;
    settle(&mut lab);
    if let Some(problem) = lab.message() {
        return Err(format!("The step's setup does not apply: {problem}"));
    }
    let shown = &lesson.steps[0];
    let Some(solution) = &shown.solution else {
        return Ok("The step reads; it has no goal to check.".to_owned());
    };
    if lab.lesson().is_some_and(LessonProgress::reached_here) {
        return Err(format!(
            "The goal is met where the step starts, so a student has nothing to do: {}",
            goals_now(&lab)
        ));
    }
    let problems = lab.apply_setup(solution, "the solution");
    if !problems.is_empty() {
        return Err(format!(
            "The solution does not apply: {}",
            problems.join("; ")
        ));
    }
    if shown
        .goals
        .iter()
        .any(|g| g.quantity == Quantity::Predicted)
    {
        answer_every_question(&mut lab);
    }
    lab.apply(PlaybackAction::End.into())?;
    settle(&mut lab);
    if lab.lesson().is_some_and(LessonProgress::reached_here) {
        Ok(
            "Checked: the goal is not met where the step starts, and the solution meets it."
                .to_owned(),
        )
    } else {
        Err(format!(
            "The solution does not meet the goal: {}",
            goals_now(&lab)
        ))
    }
}

/// Frames' worth of ticks without a window: builds finish, a held step takes effect.
fn settle(lab: &mut Lab) {
    for _ in 0..3 {
        let _ = lab.apply(Action::Tick {
            seconds: 0.0,
            build_ms: 1e6,
        });
    }
}

/// Switches Predict on and answers each of the recording's questions right.
fn answer_every_question(lab: &mut Lab) {
    let _ = lab.apply(PredictAction::On(true).into());
    for _ in 0..=lab.steps() {
        let _ = match lab.predict_question() {
            Some(q) => lab.apply(PredictAction::Answer(q.answer).into()),
            None => lab.apply(PlaybackAction::StepBy(1).into()),
        };
    }
}

/// Each goal with its value now: "`nodes-visited < 14` is now 20".
fn goals_now(lab: &Lab) -> String {
    let Some(progress) = lab.lesson() else {
        return String::new();
    };
    progress
        .current()
        .goals
        .iter()
        .map(|g| {
            let now = super::super::goal_text::now_text(g, lab);
            let holds = if g.holds(lab) { "met" } else { "not met" };
            format!("`{}` ({now}: {holds})", g.text)
        })
        .collect::<Vec<_>>()
        .join(", ")
}
