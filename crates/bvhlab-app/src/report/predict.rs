//! What the lab reports about Predict: the exercise and its score, the question waiting with
//! its answers (numbered as the keys and the `answer` command count them), and what the lab
//! said about the last answer. A screen reader hears the question and the verdict in the
//! page's live region; a course page receives the score with the progress message.

use std::fmt::Write as _;

use serde::Serialize;

use crate::model::Lab;
use crate::model::predict::Verdict;

/// Predict's state, when it is on.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PredictReport {
    /// The exercise: the structure and task of the half shown ("2D AABB tree: first hit").
    pub exercise: String,
    /// Its score.
    pub score: ScoreReport,
    /// The question waiting at the step, if any.
    pub question: Option<QuestionReport>,
    /// What the lab said about the last answer, while its step is shown.
    pub feedback: Option<FeedbackReport>,
}

/// One exercise's score.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct ScoreReport {
    /// Right at the first try.
    pub first_time: u32,
    /// Right after a hint.
    pub after_hint: u32,
    /// Shown.
    pub shown: u32,
}

/// The question waiting.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct QuestionReport {
    /// The playback step it is asked at.
    pub step: usize,
    /// The question.
    pub prompt: String,
    /// The answers offered, in order (the first is answer 1).
    pub choices: Vec<String>,
}

/// What the lab said about the last answer.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FeedbackReport {
    /// "right", "right after a hint", "wrong" or "shown".
    pub verdict: &'static str,
    /// The words shown: why, or the hint.
    pub text: String,
}

impl PredictReport {
    /// The report, when Predict is on.
    pub fn of(lab: &Lab) -> Option<Self> {
        let state = lab.predict();
        if !state.on {
            return None;
        }
        let exercise = lab.exercise();
        let score = state.score(&exercise);
        let step = lab.shown_step();
        Some(Self {
            exercise,
            score: ScoreReport {
                first_time: score.first_time,
                after_hint: score.after_hint,
                shown: score.shown,
            },
            question: lab.predict_question().map(|q| QuestionReport {
                step: q.step,
                prompt: q.prompt,
                choices: q.choices.into_iter().map(|(_, label)| label).collect(),
            }),
            feedback: state.feedback_at(step).map(|f| FeedbackReport {
                verdict: match f.verdict {
                    Verdict::Right => "right",
                    Verdict::RightAfterHint => "right after a hint",
                    Verdict::Wrong => "wrong",
                    Verdict::Shown => "shown",
                },
                text: f.text.clone(),
            }),
        })
    }

    /// In words, for the live region: the verdict, then the question and its answers.
    pub fn text(&self) -> String {
        let mut s = String::new();
        if let Some(f) = &self.feedback {
            s.push_str(&f.text);
        }
        if let Some(q) = &self.question {
            let answers: Vec<String> = q
                .choices
                .iter()
                .enumerate()
                .map(|(i, c)| format!("{} {c}", i + 1))
                .collect();
            if !s.is_empty() {
                s.push(' ');
            }
            let _ = write!(s, "Predict: {} Answers: {}.", q.prompt, answers.join("; "));
        }
        s
    }
}

/// The `{bvhlab: "progress", ...}` message for an embedding page: the lesson's step and goals
/// (when a lesson is open) and Predict's exercise and score (when it is on); none when
/// neither.
pub fn progress_message(
    lesson: Option<&crate::lessons::report::LessonReport>,
    predict: Option<&PredictReport>,
) -> Option<String> {
    if lesson.is_none() && predict.is_none() {
        return None;
    }
    let mut message = serde_json::json!({ "bvhlab": "progress" });
    if let Some(lesson) = lesson {
        message["lesson"] = lesson.lesson.clone().into();
        message["step"] = lesson.step.into();
        message["steps"] = lesson.steps.into();
        message["goal_reached"] = lesson.goal_reached.into();
        message["goals_reached"] = lesson.goals_reached.into();
        message["goals"] = lesson.goals.into();
    }
    if let Some(predict) = predict {
        message["exercise"] = predict.exercise.clone().into();
        message["score"] = serde_json::json!({
            "first_time": predict.score.first_time,
            "after_hint": predict.score.after_hint,
            "shown": predict.score.shown,
        });
    }
    Some(message.to_string())
}
