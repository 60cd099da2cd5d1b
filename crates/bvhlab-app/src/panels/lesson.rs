//! The Lessons panel, at the top of the controls: the lessons to start, or the step open
//! (its sentences, its formula, its task with each goal's live mark, and why it matters
//! once reached), with buttons to move between steps.

use egui::{Color32, RichText};

use crate::model::{Action, Lab, LessonAction};
use crate::ui_state::Cx;

/// A goal met: its word and colour (readable on both themes; the word says it without the
/// colour).
const MET: (&str, Color32) = ("met", Color32::from_rgb(0x2e, 0x9d, 0x4e));
/// A goal not met yet.
const NOT_YET: &str = "not yet";

/// The panel.
pub fn lessons(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let Some(progress) = cx.lab.lesson() else {
        choose(cx, ui);
        return;
    };
    let lesson = progress.lesson.clone();
    let step = progress.current();
    let count = lesson.steps.len();
    ui.label(RichText::new(format!("{} {}", lesson.section, lesson.title)).strong());
    ui.label(format!(
        "Step {} of {}: {}",
        progress.step + 1,
        count,
        step.title
    ));
    ui.horizontal_wrapped(|ui| {
        let open = |step: usize| {
            Action::Lesson(LessonAction::Open {
                lesson: lesson.clone(),
                step,
            })
        };
        if ui
            .add_enabled(progress.step > 0, egui::Button::new("Back"))
            .clicked()
        {
            cx.act(open(progress.step - 1));
        }
        if ui
            .add_enabled(progress.step + 1 < count, egui::Button::new("Next"))
            .clicked()
        {
            cx.act(open(progress.step + 1));
        }
        if ui
            .button("Start the step again")
            .on_hover_text("Puts the lab back where this step starts")
            .clicked()
        {
            cx.act(open(progress.step));
        }
        if ui
            .button("Close")
            .on_hover_text("Ends the lesson; the lab stays as it is")
            .clicked()
        {
            cx.act(Action::Lesson(LessonAction::Close));
        }
    });
    ui.label(
        RichText::new(
            "Keys: [ and ] move between steps; R and the arrow keys move the ray and point.",
        )
        .small()
        .weak(),
    );
    ui.add(egui::Label::new(&step.text).wrap());
    if let Some(formula) = &step.formula {
        // Formulas keep their lines (a wrapped formula misleads): a wide one scrolls.
        egui::Frame::group(ui.style()).show(ui, |ui| {
            egui::ScrollArea::horizontal()
                .id_salt("lesson formula")
                .show(ui, |ui| {
                    ui.add(egui::Label::new(RichText::new(formula).monospace()).extend());
                });
        });
    }
    if let Some(task) = &step.task {
        let reached = progress.reached_here();
        ui.horizontal_wrapped(|ui| {
            if reached {
                ui.label(RichText::new("Done:").color(MET.1).strong());
            } else {
                ui.label(RichText::new("Your task:").strong());
            }
            ui.add(egui::Label::new(task).wrap());
        });
        for goal in &step.goals {
            let holds = goal.holds(cx.lab);
            ui.horizontal(|ui| {
                ui.add_space(16.0);
                let (mark, color) = if holds {
                    MET
                } else {
                    (NOT_YET, ui.visuals().weak_text_color())
                };
                ui.label(RichText::new("•").color(color));
                ui.label(RichText::new(&goal.text).monospace());
                let now = crate::lessons::goal_text::now_text(goal, cx.lab);
                ui.label(RichText::new(format!("({now}: {mark})")).color(color));
            });
        }
        if reached && let Some(why) = &step.why {
            ui.add(egui::Label::new(RichText::new(format!("Why it matters: {why}"))).wrap());
        }
    }
}

/// The lessons to start, each a button.
fn choose(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.add(
        egui::Label::new(
            "New here? A lesson walks the lecture step by step: each step sets up the lab, \
             says what to look at, and checks a task as you do it.",
        )
        .wrap(),
    );
    for (i, lesson) in crate::lessons::lessons().enumerate() {
        let text = format!("{}. {} {}", i + 1, lesson.section, lesson.title);
        if ui.button(text).clicked() {
            cx.act(Action::Lesson(LessonAction::Open {
                lesson: lesson.clone(),
                step: 0,
            }));
        }
    }
}

/// The lesson's keys, when no widget has the keyboard focus: `]` the next step, `[` the one
/// before (a keyboard user moves through a lesson without finding its buttons).
pub fn lesson_keys(lab: &Lab, ctx: &egui::Context, actions: &mut Vec<Action>) {
    let Some(progress) = lab.lesson() else {
        return;
    };
    if ctx.text_edit_focused() || ctx.memory(|m| m.focused().is_some()) {
        return;
    }
    let (back, next) = ctx.input(|i| {
        (
            i.key_pressed(egui::Key::OpenBracket),
            i.key_pressed(egui::Key::CloseBracket),
        )
    });
    let step = if next && progress.step + 1 < progress.lesson.steps.len() {
        progress.step + 1
    } else if back && progress.step > 0 {
        progress.step - 1
    } else {
        return;
    };
    actions.push(Action::Lesson(LessonAction::Open {
        lesson: progress.lesson.clone(),
        step,
    }));
}
