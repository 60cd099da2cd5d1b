//! The "Step through" panel: what to step through (task and variant), a second structure to
//! compare with, the transport, export, and each lane's recording at the step
//! ([`super::recording`]). The same panel serves both halves.

use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Obb, Sphere};
use egui::RichText;

use super::recording::recording_state;
use super::structure::settings_editor;
use crate::model::dimension::{Dimension, LabPrimitive};
use crate::model::half::Half;
use crate::model::structures::StructureKind;
use crate::model::{HalfAction, PlaybackAction};
use crate::paint::colors;
use crate::pseudocode::{Task, Variant};
use crate::ui_state::Cx;

/// Every task, in menu order, with its label.
pub const TASKS: [(Task, &str); 6] = [
    (Task::FirstHit, "ray: first hit"),
    (Task::AnyHit, "ray: any hit"),
    (Task::AllHits, "ray: all hits"),
    (Task::Nearest, "point: k nearest"),
    (Task::Range, "point: within a radius"),
    (Task::Build, "build the structure"),
];

/// A variant's label.
pub fn variant_label(v: Variant) -> &'static str {
    match v {
        Variant::Full => "full (near first, pruning)",
        Variant::Lecture => "the slides' version",
        Variant::LecturePruned => "the slides' + pruning",
    }
}

/// The label of a task.
pub fn task_label(task: Task) -> &'static str {
    TASKS
        .iter()
        .find(|(t, _)| *t == task)
        .map_or("?", |(_, l)| *l)
}

/// The panel, for the half shown.
pub fn step_through(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.heading("Step through");
    let lab = cx.lab;
    match lab.dimension() {
        Dimension::Two => half_panel(cx, &lab.two().half, ui),
        Dimension::Three => half_panel(cx, &lab.three().half, ui),
    }
}

fn dim_of<P: LabPrimitive>() -> usize {
    if P::DIMENSION == Dimension::Three {
        3
    } else {
        2
    }
}

fn half_panel<P: LabPrimitive>(cx: &mut Cx<'_>, half: &Half<P>, ui: &mut egui::Ui)
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    task_picker(cx, half, ui);
    compare_picker(cx, half, ui);
    ui.separator();
    transport(cx, half, ui);
    super::predict::predict_block(cx, ui);
    ui.separator();
    for (i, lane) in half.lanes().enumerate() {
        if half.lane_count() > 1 {
            ui.label(
                RichText::new(half.lane_name(i))
                    .strong()
                    .color(colors::QUERY),
            );
        }
        recording_state(
            lane.recording.as_ref(),
            lane.snapshot.as_ref(),
            lane.settings.kind,
            i,
            ui,
        );
        ui.separator();
    }
    // Last: a short panel (an embedded lab) shows the step and its counters first.
    super::export::export_buttons(cx, ui);
}

/// Chooses what playback steps through, and the algorithm's variant.
fn task_picker<P: LabPrimitive>(cx: &mut Cx<'_>, half: &Half<P>, ui: &mut egui::Ui) {
    let mut task = half.task;
    egui::ComboBox::from_label("step through")
        .selected_text(task_label(task))
        .show_ui(ui, |ui| {
            for (t, label) in TASKS {
                ui.selectable_value(&mut task, t, label);
            }
        });
    if task != half.task {
        cx.act(HalfAction::SetTask(task));
    }
    // Every variant and the radius have their row whatever the task, greyed out where they
    // do not apply: changing the task moves nothing below (the transport stays put).
    let variants = crate::pseudocode::variants(half.lane.settings.kind, half.task);
    let mut variant = half.variant;
    ui.horizontal_wrapped(|ui| {
        for v in [Variant::Full, Variant::Lecture, Variant::LecturePruned] {
            let enabled = variants.len() > 1 && variants.contains(&v);
            let radio = egui::RadioButton::new(variant == v, variant_label(v));
            if ui
                .add_enabled(enabled, radio)
                .on_disabled_hover_text(
                    "The slides' versions are for a BVH's first hit and nearest point.",
                )
                .clicked()
            {
                variant = v;
            }
        }
    });
    if variant != half.variant {
        cx.act(HalfAction::SetVariant(variant));
    }
    if P::DIMENSION == Dimension::Two {
        let mut radius = half.radius;
        if ui
            .add_enabled(
                half.task == Task::Range,
                egui::Slider::new(&mut radius, 0.0..=50.0)
                    .logarithmic(true)
                    .text("radius"),
            )
            .on_disabled_hover_text("The radius of \"point: within a radius\".")
            .changed()
        {
            cx.act(HalfAction::SetRadius(radius));
        }
    }
}

/// The tree diagram and hover switches, and a second structure (or the same with other
/// build options) to compare with.
fn compare_picker<P: LabPrimitive>(cx: &mut Cx<'_>, half: &Half<P>, ui: &mut egui::Ui) {
    let dim = dim_of::<P>();
    ui.horizontal_wrapped(|ui| {
        let panels = &mut cx.ui.panels;
        let shown = match P::DIMENSION {
            Dimension::Two => &mut panels.tree,
            Dimension::Three => &mut panels.tree3d,
        };
        ui.checkbox(shown, "tree diagram");
        ui.checkbox(&mut cx.ui.link_hover, "hover finds nodes")
            .on_hover_text("hovering the view highlights the node under the pointer, and its place in the tree");
    });
    let mut on = half.compare.is_some();
    let compare = ui
        .checkbox(&mut on, "compare with")
        .on_hover_text("a second structure, or the same one with other build options, side by side on the same question");
    if compare.changed() {
        cx.act(HalfAction::SetCompare(on.then(|| {
            let mut settings = half.lane.settings;
            settings.kind = if settings.kind == StructureKind::SphereTree {
                StructureKind::AabbTree
            } else {
                StructureKind::SphereTree
            };
            settings
        })));
    }
    if let Some(other) = &half.compare {
        let mut settings = other.settings;
        ui.push_id("second structure", |ui| {
            egui::CollapsingHeader::new(format!(
                "second structure: {}",
                settings.kind.label_in(dim)
            ))
            .default_open(true)
            .show(ui, |ui| settings_editor(&mut settings, dim, ui));
        });
        if settings != other.settings {
            cx.act(HalfAction::SetCompare(Some(settings)));
        }
    }
}

fn transport<P: LabPrimitive>(cx: &mut Cx<'_>, half: &Half<P>, ui: &mut egui::Ui) {
    // The sliders' rows do not wrap: in a narrow panel (an embedded lab) the sliders give
    // up width so that their rows, and so the panel, keep inside the window.
    let beside = 165.0;
    ui.spacing_mut().slider_width = (ui.available_width() - beside).clamp(50.0, 100.0);
    let len = half.steps();
    let p = &half.playback;
    ui.horizontal(|ui| {
        use crate::a11y::describe::rename;
        if rename(ui.button("|<"), "first step")
            .on_hover_text("to the start")
            .clicked()
        {
            cx.act(PlaybackAction::GoTo(0));
        }
        if rename(ui.button("<"), "previous step")
            .on_hover_text("one step back")
            .clicked()
        {
            cx.act(PlaybackAction::StepBy(-1));
        }
        let play = if p.playing { "pause" } else { "play" };
        if ui.button(play).clicked() {
            cx.act(PlaybackAction::Toggle);
        }
        if rename(ui.button(">"), "next step")
            .on_hover_text("one step forward")
            .clicked()
        {
            cx.act(PlaybackAction::StepBy(1));
        }
        if rename(ui.button(">|"), "last step")
            .on_hover_text("to the end (live)")
            .clicked()
        {
            cx.act(PlaybackAction::End);
        }
    });
    let mut step = p.shown(len);
    let slider = egui::Slider::new(&mut step, 0..=len).text(format!("step of {len}"));
    if ui.add(slider).changed() {
        cx.act(PlaybackAction::GoTo(step));
    }
    let mut speed = p.speed;
    if ui
        .add(
            egui::Slider::new(&mut speed, 0.5..=200.0)
                .logarithmic(true)
                .text("steps per second"),
        )
        .changed()
    {
        cx.act(PlaybackAction::SetSpeed(speed));
    }
}
