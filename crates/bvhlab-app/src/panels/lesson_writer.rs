//! "Write a lesson", in the Lessons pane: the lesson's title and file, the steps saved so far,
//! and the step being written (its title, setup, text, task, goals and solution), with the
//! buttons that check it, save it, and export the lesson as a file or a share link. Every
//! change goes through the writer's commands ([`crate::lessons::writer`]); this file only
//! draws it.

use egui::RichText;

use crate::lessons::writer::{
    LessonField, LessonWriter, StepField, WriterAction, WriterCommand, goals,
};
use crate::model::Lab;
use crate::ui_state::Cx;

/// The writer, in place of the lessons' list.
pub fn writer(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    ui.horizontal_wrapped(|ui| {
        ui.label(RichText::new("Writing a lesson").strong());
        if ui
            .button("Close the writer")
            .on_hover_text("What is not saved as a file is gone")
            .clicked()
        {
            cx.write(WriterCommand::Close);
        }
    });
    lesson_fields(cx, ui, writer);
    saved_steps(cx, ui, writer);
    ui.separator();
    step_fields(cx, ui, writer);
    ui.separator();
    export(cx, ui, writer);
}

/// Asks the writer to do `action`.
fn act(cx: &mut Cx<'_>, action: WriterAction) {
    cx.write(WriterCommand::Do(action));
}

/// A one-line or several-line text field named `name` for screen readers; the new text
/// when the teacher changed it.
fn field(ui: &mut egui::Ui, name: &str, value: &str, lines: usize) -> Option<String> {
    let label = ui.label(name);
    let mut text = value.to_owned();
    let edit = if lines > 1 {
        egui::TextEdit::multiline(&mut text).desired_rows(lines)
    } else {
        egui::TextEdit::singleline(&mut text)
    };
    let changed = ui
        .add(edit.desired_width(f32::INFINITY).id_salt(name))
        .labelled_by(label.id)
        .changed();
    changed.then_some(text)
}

/// The lesson's title, section and file name.
fn lesson_fields(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    let draft = &writer.draft;
    for (name, kind, value) in [
        ("Lesson title", LessonField::Title, draft.title.as_str()),
        ("Section", LessonField::Section, draft.section.as_str()),
        ("File name", LessonField::File, writer.file.as_str()),
    ] {
        if let Some(text) = field(ui, name, value, 1) {
            act(cx, WriterAction::SetLesson(kind, text));
        }
    }
}

/// The steps saved so far, each with buttons to try, edit and remove it.
fn saved_steps(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    let steps = &writer.draft.steps;
    ui.label(RichText::new(format!("Saved steps: {}", steps.len())).strong());
    for (i, step) in steps.iter().enumerate() {
        ui.horizontal_wrapped(|ui| {
            let editing = if writer.at == i { " (editing)" } else { "" };
            let goal = if step.goal.is_empty() {
                "to read"
            } else {
                "with a goal"
            };
            ui.label(format!("{}. {}: {goal}{editing}", i + 1, step.title));
            if ui
                .button(format!("Try step {}", i + 1))
                .on_hover_text("Opens the step as a student sees it")
                .clicked()
            {
                act(cx, WriterAction::Try(i));
                cx.ui.trying_lesson = true;
            }
            if ui.button(format!("Edit step {}", i + 1)).clicked() {
                act(cx, WriterAction::EditStep(i));
            }
            if ui.button(format!("Remove step {}", i + 1)).clicked() {
                act(cx, WriterAction::RemoveStep(i));
            }
        });
    }
}

/// The step being written.
fn step_fields(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    let step = &writer.step;
    let heading = if writer.at < writer.draft.steps.len() {
        format!("Step {} (saving replaces it)", writer.at + 1)
    } else {
        format!("New step {}", writer.at + 1)
    };
    ui.label(RichText::new(heading).strong());
    if let Some(text) = field(ui, "Step title", &step.title, 1) {
        act(cx, WriterAction::SetStep(StepField::Title, text));
    }
    if let Some(text) = field(ui, "Setup (the address's words)", &step.setup, 2) {
        act(cx, WriterAction::SetStep(StepField::Setup, text));
    }
    if ui
        .button("Use what is on screen as the setup")
        .on_hover_text("The scene or mesh, structures, task, ray, point and playback step")
        .clicked()
    {
        act(cx, WriterAction::CaptureSetup);
    }
    for unsaid in &writer.unsaid {
        ui.add(
            egui::Label::new(RichText::new(format!("Not in the setup: {unsaid}.")).small()).wrap(),
        );
    }
    let optional = |value: &Option<String>| value.clone().unwrap_or_default();
    for (name, kind, value, lines) in [
        ("Text", StepField::Text, step.text.clone(), 4),
        (
            "Formula or pseudocode (optional)",
            StepField::Formula,
            optional(&step.formula),
            2,
        ),
        (
            "Task (what the student does)",
            StepField::Task,
            optional(&step.task),
            2,
        ),
        (
            "Why it matters (optional)",
            StepField::Why,
            optional(&step.why),
            2,
        ),
    ] {
        if let Some(text) = field(ui, name, &value, lines) {
            act(cx, WriterAction::SetStep(kind, text));
        }
    }
    goal_list(cx, ui, writer);
    let lab = cx.lab;
    offers(cx, ui, lab);
    if let Some(text) = field(
        ui,
        "Solution (the address's words)",
        &optional(&step.solution),
        1,
    ) {
        act(cx, WriterAction::SetStep(StepField::Solution, text));
    }
    if ui
        .button("Record what is on screen as the solution")
        .on_hover_text("Do the task in the lab first; the words that differ from the setup")
        .clicked()
    {
        act(cx, WriterAction::RecordSolution);
    }
    ui.horizontal_wrapped(|ui| {
        if ui.button("Check the step").clicked() {
            act(cx, WriterAction::Check);
        }
        let checked = matches!(writer.verdict, Some(Ok(_)));
        if ui
            .add_enabled(checked, egui::Button::new("Save the step"))
            .on_disabled_hover_text("Check the step first: it is saved once it passes")
            .clicked()
        {
            act(cx, WriterAction::SaveStep);
        }
    });
    let (verdict, strong) = match &writer.verdict {
        None => ("Not checked since the last change.".to_owned(), false),
        Some(Ok(passed)) => (format!("Passed: {passed}"), true),
        Some(Err(why)) => (format!("Not yet: {why}"), true),
    };
    let text = RichText::new(verdict);
    ui.add(egui::Label::new(if strong { text.strong() } else { text }).wrap());
}

/// The step's goals, each with a button to remove it.
fn goal_list(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    ui.label(format!("Goals (all must hold): {}", writer.step.goal.len()));
    for (i, goal) in writer.step.goal.iter().enumerate() {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(goal).monospace());
            if ui.button(format!("Remove goal {}", i + 1)).clicked() {
                act(cx, WriterAction::RemoveGoal(i));
            }
        });
    }
}

/// The quantities the lab knows now, each with the goals it offers.
fn offers(cx: &mut Cx<'_>, ui: &mut egui::Ui, lab: &Lab) {
    egui::CollapsingHeader::new("Add a goal from what the lab shows now")
        .id_salt("writer goals")
        .show(ui, |ui| {
            for offer in goals::offers(lab) {
                ui.horizontal_wrapped(|ui| {
                    ui.label(format!("{}: now {}", offer.quantity, offer.now))
                        .on_hover_text(offer.meaning);
                    for goal in offer.goals {
                        if ui
                            .button(RichText::new(&goal).monospace())
                            .on_hover_text("Add this goal")
                            .clicked()
                        {
                            act(cx, WriterAction::AddGoal(goal));
                        }
                    }
                });
            }
        });
}

/// Saving the lesson as a file, trying it, and its share link.
fn export(cx: &mut Cx<'_>, ui: &mut egui::Ui, writer: &LessonWriter) {
    let has_steps = !writer.draft.steps.is_empty();
    ui.horizontal_wrapped(|ui| {
        if ui
            .add_enabled(has_steps, egui::Button::new("Save the lesson file"))
            .on_hover_text("The saved steps, as a .toml lesson file")
            .clicked()
        {
            let name = writer.file_name();
            let said =
                match crate::export::save_file(&name, "application/toml", writer.toml().as_bytes())
                {
                    Ok(done) => format!("Lesson saved: {done}"),
                    Err(e) => format!("The lesson could not be saved: {e}."),
                };
            cx.act(crate::model::Action::SetMessage(Some(said)));
        }
        if ui
            .add_enabled(has_steps, egui::Button::new("Copy the lesson's share link"))
            .on_hover_text("A link that opens the lab on this lesson's first step")
            .clicked()
        {
            match share_lab(writer) {
                Ok(lab) => {
                    if let Some(said) = crate::persist::copy_share_link(&lab, ui.ctx()) {
                        cx.act(said);
                    }
                }
                Err(e) => cx.act(crate::model::Action::SetMessage(Some(e))),
            }
        }
    });
    if let Some(link) = crate::persist::share_link_text(ui.ctx()) {
        let label = ui.label("Share link");
        ui.add(
            egui::TextEdit::singleline(&mut &*link)
                .desired_width(f32::INFINITY)
                .id_salt("writer share link"),
        )
        .labelled_by(label.id);
    }
}

/// A fresh lab with the lesson open at its first step: what its share link opens.
fn share_lab(writer: &LessonWriter) -> Result<Lab, String> {
    let lesson = writer.lesson()?;
    let mut lab = Lab::default();
    lab.apply(crate::model::Action::Lesson(
        crate::model::LessonAction::Open { lesson, step: 0 },
    ))?;
    Ok(lab)
}
