//! Save and share: export and import scene files, and a link that opens this state.

use super::Panel;
use crate::ui_state::Cx;

/// The save-and-share panel.
pub struct SaveShare;

impl Panel for SaveShare {
    fn title(&self) -> &'static str {
        "Save and share"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        use crate::persist;
        {
            ui.horizontal_wrapped(|ui| {
                if ui
                    .button("Export scene")
                    .on_hover_text("Save the scene, structures, queries and view as a .json file.")
                    .clicked()
                {
                    cx.act(persist::export_scene(cx.lab));
                }
                if ui
                    .button("Import scene…")
                    .on_hover_text("Open a .json scene file (or drop it on the window).")
                    .clicked()
                    && let Some(a) = persist::import_scene(ui.ctx())
                {
                    cx.act(a);
                }
                if ui
                    .button("Copy share link")
                    .on_hover_text("A link that opens the lab in this state.")
                    .clicked()
                    && let Some(a) = persist::copy_share_link(cx.lab, ui.ctx())
                {
                    cx.act(a);
                }
            });
            if let Some(link) = persist::share_link_text(ui.ctx()) {
                ui.add(
                    egui::TextEdit::singleline(&mut &*link)
                        .desired_width(f32::INFINITY)
                        .id_salt("share link"),
                );
            }
            ui.label("Drop a .json scene file on the window to open it.");
        }
    }
}
