//! The 2D scene: the canvas's tool, the presets, and clearing, undoing, deleting and counting
//! shapes.

use super::Panel;
use crate::model::Action2d;
use crate::model::presets::Preset;
use crate::model::tools::Tool;
use crate::ui_state::Cx;

/// The scene panel.
pub struct Scene;

impl Panel for Scene {
    fn title(&self) -> &'static str {
        "Scene"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        let lab = cx.lab.two();
        ui.label("Tool");
        let mut tool = lab.tool;
        ui.horizontal_wrapped(|ui| {
            for t in Tool::ALL {
                ui.selectable_value(&mut tool, t, t.label());
            }
        });
        if tool != lab.tool {
            // A drawing in progress belongs to the tool it was started with.
            cx.ui.canvas.interaction = crate::lab2d::Interaction::None;
            cx.act(Action2d::SetTool(tool));
        }
        // A preset chosen loads, even the one named already: after a lesson put another
        // structure on its scene ("k-d tree on a handful of shapes" under an AABB tree),
        // choosing it again must give what its name says.
        let mut chosen = None;
        egui::ComboBox::from_label("Preset")
            .selected_text(lab.preset.label())
            .show_ui(ui, |ui| {
                for p in Preset::ALL {
                    if ui.selectable_label(p == lab.preset, p.label()).clicked() {
                        chosen = Some(p);
                    }
                }
            });
        if let Some(preset) = chosen {
            cx.act(Action2d::LoadPreset(preset));
        }
        ui.horizontal(|ui| {
            if ui.button("Reload preset").clicked() {
                cx.act(Action2d::LoadPreset(lab.preset));
            }
            if ui.button("Fit view").clicked() {
                let size = cx.ui.canvas.screen(lab).rect.size();
                cx.act(Action2d::FrameScene(bvhlab::glam::Vec2::new(
                    size.x, size.y,
                )));
            }
            if ui.button("Clear").clicked() {
                cx.act(Action2d::Clear);
            }
        });
        if let Some(animation) = lab.animation {
            let mut on = animation.on;
            ui.horizontal(|ui| {
                ui.checkbox(&mut on, "Animate")
                    .on_hover_text("The shapes drift and turn; editing the scene stops them");
                ui.label(format!("{:.1} s", animation.time));
            });
            if on != animation.on {
                cx.act(Action2d::SetAnimate(on));
            }
        }
        ui.horizontal(|ui| {
            let history = lab.history();
            let undo = ui
                .add_enabled(history.next_undo().is_some(), egui::Button::new("Undo"))
                .on_hover_text(history.next_undo().map_or_else(
                    || "No scene edit to undo".to_owned(),
                    |what| format!("Undo {what} (Ctrl+Z)"),
                ))
                .on_disabled_hover_text("No scene edit to undo");
            if undo.clicked() {
                cx.act(Action2d::Undo);
            }
            let redo = ui
                .add_enabled(history.next_redo().is_some(), egui::Button::new("Redo"))
                .on_hover_text(history.next_redo().map_or_else(
                    || "Nothing undone to redo".to_owned(),
                    |what| format!("Redo {what} (Ctrl+Shift+Z or Ctrl+Y)"),
                ))
                .on_disabled_hover_text("Nothing undone to redo");
            if redo.clicked() {
                cx.act(Action2d::Redo);
            }
        });
        let n_sel = lab.selection.len();
        if ui
            .add_enabled(
                n_sel > 0,
                egui::Button::new(format!("Delete selected ({n_sel})")),
            )
            .clicked()
        {
            cx.act(Action2d::DeleteSelection);
        }
        ui.label(format!(
            "{} shapes, {} primitives (segments; a point is a segment of length 0).",
            lab.scene.shapes().len(),
            lab.prims().segments.len()
        ));
    }
}
