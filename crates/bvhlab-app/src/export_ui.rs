//! The "Export for slides" buttons: the canvas (both halves when comparing) as SVG, drawn
//! from the same shapes as the screen but untessellated, or as PNG, cut from a screenshot of
//! the window; and the same for the tree diagram.

use std::sync::Arc;

use egui::ColorImage;
use egui::mutex::Mutex;

use crate::app::LabApp;

/// A PNG export waiting for its screenshot.
pub struct PendingPng {
    /// The area to cut out, in points.
    rect: egui::Rect,
    /// The file name to save under.
    name: String,
    /// Filled by the screenshot callback.
    image: Arc<Mutex<Option<Arc<ColorImage>>>>,
}

/// The canvas background, as drawn on screen.
pub const BACKGROUND: egui::Color32 = egui::Color32::from_rgb(24, 26, 32);

/// The export buttons.
pub fn export_buttons(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.label("Canvas:");
        if ui
            .button("SVG")
            .on_hover_text("the canvas as a vector drawing")
            .clicked()
        {
            let shapes = crate::canvas::picture(app, ui.painter());
            let rect = app.canvas_rect;
            let svg = crate::export::svg_document(&shapes, rect, BACKGROUND);
            app.message = Some(saved(crate::export::save_file(
                "bvh-lab-canvas.svg",
                "image/svg+xml",
                svg.as_bytes(),
            )));
        }
        if ui
            .button("PNG")
            .on_hover_text("the canvas as a picture")
            .clicked()
        {
            request_png(app, ui.ctx(), app.canvas_rect, "bvh-lab-canvas.png");
        }
        if let Some(rect) = app.tree_rect {
            ui.label("Tree:");
            if ui
                .button("SVG ")
                .on_hover_text("the tree diagram as a vector drawing")
                .clicked()
            {
                let shapes = crate::tree_panel::tree_picture(app, ui.ctx(), rect);
                let svg = crate::export::svg_document(&shapes, rect, BACKGROUND);
                app.message = Some(saved(crate::export::save_file(
                    "bvh-lab-tree.svg",
                    "image/svg+xml",
                    svg.as_bytes(),
                )));
            }
            if ui
                .button("PNG ")
                .on_hover_text("the tree diagram as a picture")
                .clicked()
            {
                request_png(app, ui.ctx(), rect, "bvh-lab-tree.png");
            }
        }
    });
}

fn saved(result: Result<String, String>) -> String {
    match result {
        Ok(where_) => format!("Exported: {where_}"),
        Err(why) => format!("Export failed: {why}"),
    }
}

fn request_png(app: &mut LabApp, ctx: &egui::Context, rect: egui::Rect, name: &str) {
    let image = Arc::new(Mutex::new(None));
    let slot = image.clone();
    let repaint = ctx.clone();
    ctx.request_screenshot(move |shot| {
        *slot.lock() = Some(shot);
        repaint.request_repaint();
    });
    app.pending_png = Some(PendingPng {
        rect,
        name: name.to_owned(),
        image,
    });
}

/// Saves a PNG whose screenshot has arrived; call once per frame.
pub fn finish_png(app: &mut LabApp, ctx: &egui::Context) {
    let Some(pending) = &app.pending_png else {
        return;
    };
    let Some(shot) = pending.image.lock().take() else {
        return;
    };
    let image = crate::export::crop(&shot, pending.rect, ctx.pixels_per_point());
    let result = crate::export::png_bytes(&image)
        .and_then(|bytes| crate::export::save_file(&pending.name, "image/png", &bytes));
    app.message = Some(saved(result));
    app.pending_png = None;
}
