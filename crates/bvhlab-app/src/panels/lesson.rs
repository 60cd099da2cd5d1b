//! The Lessons pane, at the top of the controls: the lessons to start, or the step open
//! (its sentences, its formula, its task with each goal's live mark, and why it matters
//! once reached), with buttons to move between steps, and Predict's question when "Step
//! through" is not on screen.
//!
//! The pane's height is the window's business, never its contents': opening, closing or
//! reaching a step, or a goal's mark changing while a field is typed in, moves nothing below
//! it (a click meant for "Reload preset" after Close landed on Undo). What does not fit
//! scrolls inside the pane.

use egui::{Color32, RichText};

use crate::model::{Action, Lab, LessonAction};
use crate::ui_state::Cx;

/// A goal met: its word and colour (readable on both themes; the word says it without the
/// colour).
const MET: (&str, Color32) = ("met", Color32::from_rgb(0x2e, 0x9d, 0x4e));
/// A goal not met yet.
const NOT_YET: &str = "not yet";

/// The pane's height for a window `window_height` points tall: a share of it, so that the
/// controls below keep room in a short (embedded) window.
pub fn pane_height(window_height: f32) -> f32 {
    (window_height * 0.45).clamp(140.0, 480.0)
}

/// The pane, at a fixed height. `with_question`: "Step through" is not on screen, so a
/// lesson's step shows Predict's question below its text (pinned, in view whatever the
/// text's scroll).
pub fn pane(cx: &mut Cx<'_>, ui: &mut egui::Ui, with_question: bool) {
    let window = ui.ctx().content_rect().height();
    // The writer has many fields: it takes most of the column (the controls below scroll).
    let height = if cx.writer.is_some() && !cx.ui.trying_lesson {
        (window * 0.7).max(pane_height(window))
    } else {
        pane_height(window)
    };
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(ui.available_width(), height),
        egui::Sense::hover(),
    );
    let question = with_question && cx.lab.lesson().is_some() && cx.lab.predict().on;
    // The question's height as last drawn (the text gets the rest).
    let question_id = ui.scope_id().with("lesson predict height");
    let question_height = if question {
        ui.ctx()
            .data(|d| d.get_temp::<f32>(question_id))
            .unwrap_or(90.0)
            .min(height * 0.6)
    } else {
        0.0
    };
    let text_rect = egui::Rect::from_min_max(
        rect.min,
        egui::pos2(rect.max.x, rect.max.y - question_height),
    );
    let mut text_ui = ui.new_child(egui::UiBuilder::new().max_rect(text_rect));
    text_ui.shrink_clip_rect(text_rect);
    // Each step opens at its top.
    let salt = cx.lab.lesson().map(|p| (p.lesson.name.clone(), p.step));
    egui::ScrollArea::vertical()
        .id_salt(("lesson pane", salt))
        .auto_shrink(false)
        .show(&mut text_ui, |ui| lessons(cx, ui));
    if question {
        let question_rect =
            egui::Rect::from_min_max(egui::pos2(rect.min.x, text_rect.max.y), rect.max);
        let mut q_ui = ui.new_child(egui::UiBuilder::new().max_rect(question_rect));
        q_ui.shrink_clip_rect(question_rect);
        q_ui.separator();
        let rule = q_ui.cursor().min.y - question_rect.min.y;
        let out = egui::ScrollArea::vertical()
            .id_salt("lesson predict")
            .max_height(height * 0.6 - rule)
            .auto_shrink([false, true])
            .show(&mut q_ui, |ui| {
                ui.label(RichText::new("Predict").strong());
                super::predict::question_block(cx, ui);
            });
        let used = out.inner_rect.max.y - question_rect.min.y;
        let stored = ui.ctx().data(|d| d.get_temp::<f32>(question_id));
        if stored.is_none_or(|h| (h - used).abs() > 0.5) {
            ui.ctx().data_mut(|d| d.insert_temp(question_id, used));
            ui.ctx()
                .request_discard("the lesson's Predict question changed height");
        }
    }
}

/// The lesson writer in the panel's place while it is open (true), unless the teacher tries
/// a step: then the lesson shows as a student sees it, under a way back to the writer.
fn writer_shown(cx: &mut Cx<'_>, ui: &mut egui::Ui) -> bool {
    let Some(writer) = cx.writer else {
        return false;
    };
    if !cx.ui.trying_lesson || cx.lab.lesson().is_none() {
        super::lesson_writer::writer(cx, ui, writer);
        return true;
    }
    if ui
        .button("Back to the lesson writer")
        .on_hover_text("The lesson stays open in the lab")
        .clicked()
    {
        cx.ui.trying_lesson = false;
    }
    false
}

/// The panel.
pub fn lessons(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    if writer_shown(cx, ui) {
        return;
    }
    let Some(progress) = cx.lab.lesson() else {
        choose(cx, ui);
        return;
    };
    let lesson = progress.lesson.clone();
    let step = progress.current();
    let count = lesson.steps.len();
    ui.label(RichText::new(format!("{} {}", lesson.section, lesson.title)).strong());
    teacher_mark(cx, ui, &lesson);
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
        super::formula::formula_block(ui, formula);
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
            // Wrapped: a narrow panel puts the mark on the next line rather than cut it.
            ui.horizontal_wrapped(|ui| {
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

/// Says that the lesson open is a teacher's (its text is not the lab's own), with a button
/// that opens it in the lesson writer.
fn teacher_mark(cx: &mut Cx<'_>, ui: &mut egui::Ui, lesson: &crate::model::Lesson) {
    let Some(teacher) = &lesson.teacher else {
        return;
    };
    // Said in words: a student must know this text is not the lab's own.
    ui.add(
        egui::Label::new(
            RichText::new(format!("A teacher's lesson, from {}", teacher.file))
                .small()
                .italics(),
        )
        .wrap(),
    );
    if ui
        .button("Edit this lesson")
        .on_hover_text("Opens it in the lesson writer")
        .clicked()
    {
        cx.write(crate::lessons::writer::WriterCommand::EditOpen);
        cx.ui.trying_lesson = false;
    }
}

/// The lessons to start, each a button.
fn choose(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.heading("bvh-lab");
    ui.label("Bounding volumes and spatial data structures, after the lecture's slides.");
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
    ui.separator();
    ui.label(RichText::new("Teachers").strong());
    if ui
        .button("Open a lesson file…")
        .on_hover_text("A lesson written as a .toml file (or drop the file on the lab)")
        .clicked()
        && let Some(said) = crate::persist::pick_lesson_file(ui.ctx())
    {
        cx.act(said);
    }
    if ui
        .button("Write a lesson")
        .on_hover_text("Turns what the lab shows into a lesson's steps, checked as you write")
        .clicked()
    {
        cx.write(crate::lessons::writer::WriterCommand::Start);
        cx.ui.trying_lesson = false;
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
