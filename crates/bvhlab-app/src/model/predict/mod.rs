//! Predict: while stepping through a query or a build, the student says what happens next
//! before each step that decides something, and the lab then shows the step and says whether
//! the prediction was right, and why ([`question`] reads each question from the recording).
//!
//! A wrong first answer gets a hint and a second try; a second wrong answer, or "show me",
//! shows the step with the answer. Each exercise (a structure and a task, e.g. "AABB tree:
//! first hit") keeps a score: right first time, right after a hint, shown. Scores are saved
//! with the lab's state and posted to the embedding page with the lesson's progress.
//!
//! While a question waits, stepping forward is refused (the student answers, or asks to be
//! shown), and playing is refused while Predict is on: it steps one decision at a time.
//! Going back, and jumping with the slider or to the end, are not refused: a student who
//! jumps simply is not asked about the steps jumped over.

mod build;
mod cell;
mod leaf;
pub mod question;
mod walk;

use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Obb, Sphere};

pub use self::question::{About, Choice, DISTINCT_ALONG_RAY, PredictQuestion, question_at};
use super::dimension::{Dimension, LabPrimitive};
use super::half::Half;
use super::question::{Task, Variant};
use super::{Lab, Note};

/// One exercise's score.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Score {
    /// Questions answered right at the first try.
    pub first_time: u32,
    /// Answered right after a hint.
    pub after_hint: u32,
    /// Shown (asked for, or after two wrong answers).
    pub shown: u32,
}

impl Score {
    /// How many questions were asked and settled.
    pub fn asked(&self) -> u32 {
        self.first_time + self.after_hint + self.shown
    }
}

/// How the last question went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Right at the first try.
    Right,
    /// Right after a hint.
    RightAfterHint,
    /// Wrong: a hint is shown and the question waits for a second try.
    Wrong,
    /// The answer was shown.
    Shown,
}

/// What the lab said about the last answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Feedback {
    /// How it went.
    pub verdict: Verdict,
    /// The playback step it belongs to (once the step moves on, it is no longer shown).
    pub step: usize,
    /// What the student reads: why the answer is right, or the hint.
    pub text: String,
}

/// Predict's state: whether it is on, the question's tries, the feedback and the scores.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PredictState {
    /// Whether the lab asks before each step.
    pub on: bool,
    /// The scores, by exercise, in the order first met.
    pub scores: Vec<(String, Score)>,
    /// The wrong answers given to the question waiting at a step.
    wrong: Option<(usize, Vec<Choice>)>,
    /// What the lab said about the last answer.
    pub feedback: Option<Feedback>,
}

impl PredictState {
    /// Predict as saved: on or off, with these scores (no question under way).
    pub fn saved(on: bool, scores: Vec<(String, Score)>) -> Self {
        Self {
            on,
            scores,
            wrong: None,
            feedback: None,
        }
    }

    /// The score of `exercise` (zero if never met).
    pub fn score(&self, exercise: &str) -> Score {
        self.scores
            .iter()
            .find(|(e, _)| e == exercise)
            .map(|(_, s)| *s)
            .unwrap_or_default()
    }

    fn score_mut(&mut self, exercise: &str) -> &mut Score {
        let found = self.scores.iter().position(|(e, _)| e == exercise);
        let at = found.unwrap_or_else(|| {
            self.scores.push((exercise.to_owned(), Score::default()));
            self.scores.len() - 1
        });
        &mut self.scores[at].1
    }

    /// The wrong answers already given at `step`.
    pub fn wrong_at(&self, step: usize) -> &[Choice] {
        match &self.wrong {
            Some((s, wrong)) if *s == step => wrong,
            _ => &[],
        }
    }

    /// The feedback for `step`, if the last answer was given there or revealed it.
    pub fn feedback_at(&self, step: usize) -> Option<&Feedback> {
        self.feedback.as_ref().filter(|f| f.step == step)
    }
}

/// A change of Predict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PredictAction {
    /// Switches it on (from the start when playback stands at the end) or off.
    On(bool),
    /// Answers the question waiting.
    Answer(Choice),
    /// Shows the answer of the question waiting (it counts as shown).
    Show,
}

/// The name of the exercise a half's main structure and task make ("AABB tree: first hit").
pub fn exercise_of<P: LabPrimitive>(half: &Half<P>) -> String {
    let dim = if P::DIMENSION == Dimension::Three {
        3
    } else {
        2
    };
    let task = match half.task {
        Task::FirstHit => "first hit",
        Task::AnyHit => "any hit",
        Task::AllHits => "all hits",
        Task::Nearest => "nearest",
        Task::Range => "range",
        Task::Build => "build",
    };
    let variant = match half.variant_for(half.lane.settings.kind) {
        Variant::Full => "",
        Variant::Lecture => ", the slides' version",
        Variant::LecturePruned => ", the slides' version with pruning",
    };
    format!(
        "{} {}: {task}{variant}",
        if dim == 3 { "3D" } else { "2D" },
        half.lane.settings.kind.label_in(dim)
    )
}

/// The question waiting at `half`'s playback step (its main structure's), if any.
pub fn question_of<P: LabPrimitive>(half: &Half<P>) -> Option<PredictQuestion>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    let recording = half.lane.recorded()?;
    let snapshot = half.lane.snapshot.as_ref()?;
    if snapshot.step != half.playback.shown(recording.events.len()) {
        return None;
    }
    question_at(recording, snapshot, half.lane.settings.kind)
}

impl Lab {
    /// Predict's state.
    pub fn predict(&self) -> &PredictState {
        &self.predict
    }

    /// The question waiting in the half shown, when Predict is on.
    pub fn predict_question(&self) -> Option<PredictQuestion> {
        if !self.predict.on {
            return None;
        }
        match self.dimension {
            Dimension::Two => question_of(&self.two.half),
            Dimension::Three => question_of(&self.three.half),
        }
    }

    /// What the question waiting is about (nothing when none waits): the views light it in
    /// the main structure's lane while it is asked.
    pub fn predict_about(&self) -> About {
        self.predict_question().map(|q| q.about).unwrap_or_default()
    }

    /// The exercise of the half shown.
    pub fn exercise(&self) -> String {
        match self.dimension {
            Dimension::Two => exercise_of(&self.two.half),
            Dimension::Three => exercise_of(&self.three.half),
        }
    }

    /// Moves the half shown's playback to `step` (a question answered reveals its step).
    fn reveal(&mut self, step: usize) {
        match self.dimension {
            Dimension::Two => {
                let len = self.two.half.steps();
                self.two.half.playback.playing = false;
                self.two.half.playback.go(step, len);
            }
            Dimension::Three => {
                let len = self.three.half.steps();
                self.three.half.playback.playing = false;
                self.three.half.playback.go(step, len);
            }
        }
    }

    /// Why a playback action is refused while Predict is on, if it is: stepping forward
    /// past a question waiting, and playing.
    pub(super) fn predict_refuses(&self, forward: bool, plays: bool) -> Option<String> {
        if !self.predict.on {
            return None;
        }
        if plays {
            return Some(
                "Predict is on: step one at a time and answer each question (switch Predict \
                 off to play)."
                    .to_owned(),
            );
        }
        (forward && self.predict_question().is_some()).then(|| {
            "Predict is on: answer the question first, or ask to be shown the answer.".to_owned()
        })
    }

    /// A change of Predict.
    pub(super) fn apply_predict(&mut self, action: PredictAction) -> Result<Note, String> {
        match action {
            PredictAction::On(on) => {
                if on == self.predict.on {
                    return Ok(Note::Keep);
                }
                self.predict.on = on;
                self.predict.wrong = None;
                self.predict.feedback = None;
                if !on {
                    return Ok(Note::Clear);
                }
                // From the start when at the end; else where it stands, no longer playing.
                let shown = self.shown_step();
                self.reveal(if shown >= self.steps() { 0 } else { shown });
                Ok(Note::Say(
                    "Predict is on: before each step that decides something, say what happens \
                     next."
                        .to_owned(),
                ))
            }
            PredictAction::Answer(choice) => {
                let question = self.waiting()?;
                if question.label(choice).is_none() {
                    return Err("That is not one of the answers offered.".to_owned());
                }
                let exercise = self.exercise();
                let step = question.step;
                let tried = self.predict.wrong_at(step).to_vec();
                if choice == question.answer {
                    let verdict = if tried.is_empty() {
                        self.predict.score_mut(&exercise).first_time += 1;
                        Verdict::Right
                    } else {
                        self.predict.score_mut(&exercise).after_hint += 1;
                        Verdict::RightAfterHint
                    };
                    let text = match verdict {
                        Verdict::Right => format!("Right: {}.", question.why),
                        _ => format!("Right, after the hint: {}.", question.why),
                    };
                    Ok(self.settle(&question, verdict, text))
                } else if tried.contains(&choice) || tried.is_empty() {
                    let mut wrong = tried;
                    if !wrong.contains(&choice) {
                        wrong.push(choice);
                    }
                    self.predict.wrong = Some((step, wrong));
                    self.predict.feedback = Some(Feedback {
                        verdict: Verdict::Wrong,
                        step,
                        text: format!("Not quite. Hint: {}", question.hint),
                    });
                    Ok(Note::Keep)
                } else {
                    self.predict.score_mut(&exercise).shown += 1;
                    let text = shown_text(&question);
                    Ok(self.settle(&question, Verdict::Shown, text))
                }
            }
            PredictAction::Show => {
                let question = self.waiting()?;
                let exercise = self.exercise();
                self.predict.score_mut(&exercise).shown += 1;
                let text = shown_text(&question);
                Ok(self.settle(&question, Verdict::Shown, text))
            }
        }
    }

    /// The question waiting, or why there is none.
    fn waiting(&self) -> Result<PredictQuestion, String> {
        if !self.predict.on {
            return Err("Predict is off: switch it on in \"Step through\" first.".to_owned());
        }
        self.predict_question()
            .ok_or_else(|| "There is no question at this step: step on to the next.".to_owned())
    }

    /// Reveals `question`'s step and says how it went.
    fn settle(&mut self, question: &PredictQuestion, verdict: Verdict, text: String) -> Note {
        let step = question.step + question.reveal;
        self.predict.wrong = None;
        self.predict.feedback = Some(Feedback {
            verdict,
            step,
            text,
        });
        self.reveal(step);
        Note::Keep
    }
}

/// What is said when the answer is shown.
fn shown_text(question: &PredictQuestion) -> String {
    let label = question.label(question.answer).unwrap_or("?");
    format!("The answer: {label}. Why: {}.", question.why)
}
