//! The canvas: pointer input for the active tool (`input.rs`), pan and zoom, and drawing
//! (`draw.rs`: structure, query marks, scene, bounding volumes, queries, handles).

mod draw;
mod input;

pub use draw::{LayerKey, StaticLayer};

use egui::{PointerButton, Sense};

use crate::app::LabApp;
use crate::tool::Tool;

/// Shows the canvas in the rest of `ui` and handles its input.
pub fn canvas(app: &mut LabApp, ui: &mut egui::Ui) {
    let (response, painter) = ui.allocate_painter(ui.available_size(), Sense::click_and_drag());
    app.view.rect = response.rect;
    if app.fit_pending {
        if let Some((lo, hi)) = app.scene.bounds() {
            app.view.fit(lo, hi);
        }
        app.fit_pending = false;
    }
    pan_and_zoom(app, ui, &response);
    input::handle_tool(app, ui, &response);
    app.refresh();
    draw::draw(app, &painter, response.hover_pos());
}

fn pan_and_zoom(app: &mut LabApp, ui: &egui::Ui, response: &egui::Response) {
    let pans = response.dragged_by(PointerButton::Secondary)
        || response.dragged_by(PointerButton::Middle)
        || (app.tool == Tool::Pan && response.dragged_by(PointerButton::Primary));
    if pans {
        app.view.pan(response.drag_delta());
    }
    if let Some(hover) = response.hover_pos() {
        let (scroll, pinch) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
        let factor = (scroll * 0.002).exp() * pinch;
        if factor != 1.0 {
            app.view.zoom_at(hover, factor);
        }
    }
}
