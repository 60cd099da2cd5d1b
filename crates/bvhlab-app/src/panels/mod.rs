//! The panels beside the view. Each reads the lab and asks for changes with actions (it
//! writes nothing of the lab's), as egui's demo app keeps its demos: a small trait
//! ([`Panel`]), one file per panel, and one list per half ([`PANELS_2D`], [`PANELS_3D`]) in
//! the lecture's order.
//!
//! - The controls (left): [`lesson`] first, then [`scene`], [`volumes`], [`structure`], [`queries`], [`save_share`]
//!   in 2D; [`mesh`] (with [`motion`] for a mesh that moves), [`volumes3d`], [`structure`], [`ray_point`], [`heat`], [`save_share`] in 3D.
//! - "Step through" (right): [`step_through`] (task, comparison, transport, export, and each
//!   lane's recording at the step: [`recording`], with a build's split in [`split`]).
//! - Below the view: the tree diagrams ([`tree`]); at the bottom, the status line
//!   ([`status`]). [`export`]: the canvas, the 3D view and the tree as SVG or PNG.

pub mod collision;
pub mod collision2d;
pub mod collision3d;
pub mod export;
pub mod formula;
pub mod heat;
pub mod lesson;
pub mod lesson_writer;
pub mod mesh;
pub mod motion;
pub mod predict;
pub mod queries;
pub mod ray_point;
pub mod recording;
pub mod refit;
pub mod sat3d;
pub mod save_share;
pub mod scene;
pub mod split;
pub mod status;
pub mod step_through;
pub mod structure;
pub mod tree;
pub mod volumes;
pub mod volumes3d;

use egui::{CollapsingHeader, Color32, RichText};

use crate::model::{Action, Dimension};
use crate::ui_state::Cx;

/// One section of the controls.
pub trait Panel {
    /// Its heading.
    fn title(&self) -> &'static str;
    /// Draws it from the lab, asking for changes through `cx`.
    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui);
}

/// The 2D controls, in the lecture's order.
pub const PANELS_2D: [&dyn Panel; 5] = [
    &scene::Scene,
    &volumes::Volumes,
    &structure::Structure2d,
    &queries::Queries,
    &save_share::SaveShare,
];

/// The 3D controls.
pub const PANELS_3D: [&dyn Panel; 6] = [
    &mesh::Mesh,
    &volumes3d::Volumes3dPanel,
    &structure::Structure3d,
    &ray_point::RayPoint,
    &heat::Heat,
    &save_share::SaveShare,
];

/// The controls column: the lessons' pane (kept in view), then, scrolling below it, the 2D /
/// 3D switch and the half's panels. `with_question`: "Step through" is not on screen, so
/// the lesson's pane shows Predict's question ([`lesson::pane`]).
pub fn controls(cx: &mut Cx<'_>, ui: &mut egui::Ui, with_question: bool) {
    CollapsingHeader::new("Lessons")
        .default_open(true)
        .show(ui, |ui| lesson::pane(cx, ui, with_question));
    ui.separator();
    egui::ScrollArea::vertical()
        .id_salt("controls")
        .show(ui, |ui| {
            dimension_switch(cx, ui);
            let panels: &[&dyn Panel] = match cx.lab.dimension() {
                Dimension::Two => &PANELS_2D,
                Dimension::Three => &PANELS_3D,
            };
            for panel in panels {
                CollapsingHeader::new(panel.title())
                    .default_open(true)
                    .show(ui, |ui| panel.show(cx, ui));
            }
        });
}

/// The 2D / 3D switch.
fn dimension_switch(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        let mut shown = cx.lab.dimension();
        ui.selectable_value(&mut shown, Dimension::Two, "2D: segments");
        ui.selectable_value(&mut shown, Dimension::Three, "3D: meshes");
        if shown != cx.lab.dimension() {
            cx.act(Action::Show(shown));
        }
    });
    ui.separator();
}

/// A coloured dot and its meaning.
pub fn legend(ui: &mut egui::Ui, color: Color32, text: String) {
    ui.label(RichText::new("•").color(color));
    ui.label(text);
}

/// A checkbox over a copy of a value: asks for `action(value)` when it is ticked or
/// unticked.
pub fn toggle<T: Copy>(
    ui: &mut egui::Ui,
    value: T,
    field: impl FnOnce(&mut T) -> &mut bool,
    text: &str,
) -> Option<T> {
    let mut copy = value;
    ui.checkbox(field(&mut copy), text)
        .changed()
        .then_some(copy)
}

/// A row of three number fields (x, y, z) after the words `row`, each field named for screen
/// readers by `row` and its axis ("B turn about x, y, z: y"), as its prefix shows it.
pub fn xyz_fields(
    ui: &mut egui::Ui,
    row: &str,
    values: &mut [f32; 3],
    field: impl Fn(egui::DragValue<'_>) -> egui::DragValue<'_>,
) {
    ui.horizontal(|ui| {
        ui.label(row);
        for (axis, value) in ["x", "y", "z"].into_iter().zip(values.iter_mut()) {
            let response = ui.add(field(
                egui::DragValue::new(value).prefix(format!("{axis} ")),
            ));
            let (enabled, now) = (ui.is_enabled(), f64::from(*value));
            response.widget_info(|| {
                let mut info = egui::WidgetInfo::drag_value(enabled, now);
                info.label = Some(format!("{row}: {axis}"));
                info
            });
        }
    });
}

/// A row of number fields for a point's coordinates (x, y and, in 3D, z), each named for
/// screen readers ("origin x", ...); whether one changed.
pub fn coords_editor(ui: &mut egui::Ui, label: &str, coords: &mut [f32]) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        for (axis, c) in ["x", "y", "z"].into_iter().zip(coords.iter_mut()) {
            let name = ui.label(RichText::new(axis).weak()).id;
            changed |= ui
                .add(egui::DragValue::new(c).speed(0.01).max_decimals(4))
                .labelled_by(name)
                .changed();
        }
        changed
    })
    .inner
}
