//! Predict, in the "Step through" panel: a switch, the question waiting at the step with its
//! answers as buttons (P switches it, keys 1 to 9 answer too; a node can be clicked in the tree diagram),
//! what the lab said about the last answer, and the exercise's score.

use egui::{Color32, RichText};

use crate::model::predict::{Choice, PredictAction, Verdict};
use crate::model::{Action, Lab};
use crate::ui_state::Cx;

/// Right: green, readable on both themes (the words say it without the colour).
const RIGHT: Color32 = Color32::from_rgb(0x2e, 0x9d, 0x4e);
/// Wrong or shown: orange.
const NOT_RIGHT: Color32 = Color32::from_rgb(0xd0, 0x70, 0x10);

/// The switch and, when on, the question, the feedback and the score.
pub fn predict_block(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab;
    let state = lab.predict();
    let mut on = state.on;
    if ui
        .checkbox(&mut on, "Predict each step (P)")
        .on_hover_text(
            "Before each step that decides something, say what happens next: the lab then \
             shows the step and says whether you were right, and why.",
        )
        .changed()
    {
        cx.act(PredictAction::On(on));
    }
    if !state.on {
        return;
    }
    question_block(cx, ui);
    let exercise = lab.exercise();
    let score = state.score(&exercise);
    ui.label(
        RichText::new(format!(
            "{exercise}: {} right first time, {} after a hint, {} shown",
            score.first_time, score.after_hint, score.shown
        ))
        .small(),
    );
}

/// What Predict says at the step shown: the feedback on the last answer, and the question
/// waiting with its answers as buttons (or why there is none). Also in the lesson's pane when
/// "Step through" is not on screen: a step and its question belong together.
pub fn question_block(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab;
    let state = lab.predict();
    let steps = lab.steps();
    let step = lab.shown_step();
    if let Some(feedback) = state.feedback_at(step) {
        // The words say how it went ("Right: ...", "Not quite. Hint: ...", "The answer:
        // ..."); the colour repeats it.
        let color = match feedback.verdict {
            Verdict::Right | Verdict::RightAfterHint => RIGHT,
            Verdict::Wrong | Verdict::Shown => NOT_RIGHT,
        };
        ui.add(egui::Label::new(RichText::new(&feedback.text).color(color)).wrap());
    }
    match lab.predict_question() {
        Some(question) => {
            ui.add(egui::Label::new(RichText::new(&question.prompt).strong()).wrap());
            let tried = state.wrong_at(question.step);
            ui.horizontal_wrapped(|ui| {
                for (i, (choice, label)) in question.choices.iter().enumerate() {
                    let text = if i < 9 {
                        format!("{} {label}", i + 1)
                    } else {
                        label.clone()
                    };
                    let button = egui::Button::new(text);
                    let response = ui.add_enabled(!tried.contains(choice), button);
                    if response.clicked() {
                        cx.act(PredictAction::Answer(*choice));
                    }
                }
            });
            ui.horizontal_wrapped(|ui| {
                if ui
                    .button("Show the answer")
                    .on_hover_text("Shows the step and why (it counts as shown)")
                    .clicked()
                {
                    cx.act(PredictAction::Show);
                }
                let nodes = question
                    .choices
                    .iter()
                    .any(|(c, _)| matches!(c, Choice::Node(_)));
                let how = if nodes {
                    "Keys 1 to 9 answer; so does a click on the node in the tree diagram."
                } else {
                    "Keys 1 to 9 answer."
                };
                ui.label(RichText::new(how).small().weak());
            });
        }
        None if step < steps => {
            ui.label("Nothing to predict at this step: step on (> or the . key).");
        }
        None => {
            ui.label(
                "The end of the recording. |< (or Home) starts it again; a new ray, point or \
                 structure starts a new one.",
            );
        }
    }
}

/// The keys that answer, in the order of the answers.
const KEYS: [egui::Key; 9] = [
    egui::Key::Num1,
    egui::Key::Num2,
    egui::Key::Num3,
    egui::Key::Num4,
    egui::Key::Num5,
    egui::Key::Num6,
    egui::Key::Num7,
    egui::Key::Num8,
    egui::Key::Num9,
];

/// Predict's keys, when no text field has the focus: P switches it on or off, and 1 to 9
/// answer the question waiting.
pub fn predict_keys(lab: &Lab, ctx: &egui::Context, actions: &mut Vec<Action>) {
    if ctx.text_edit_focused() {
        return;
    }
    if ctx.input(|i| i.key_pressed(egui::Key::P)) {
        actions.push(PredictAction::On(!lab.predict().on).into());
        return;
    }
    let Some(question) = lab.predict_question() else {
        return;
    };
    let pressed = ctx.input(|i| KEYS.iter().position(|k| i.key_pressed(*k)));
    if let Some((choice, _)) = pressed.and_then(|n| question.choices.get(n)) {
        actions.push(PredictAction::Answer(*choice).into());
    }
}
