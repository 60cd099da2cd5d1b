//! The "Export for slides" buttons: the view (the 2D canvas or the 3D view, both halves when
//! comparing) as SVG, drawn from the same state as the screen but untessellated, or as PNG,
//! cut from a screenshot of the window; and the same for the tree diagram.

use std::sync::Arc;

use egui::ColorImage;
use egui::mutex::Mutex;

use crate::model::{Action, Dimension};
use crate::ui_state::{Cx, UiState};

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

/// The export buttons: the view (the 2D canvas or the 3D view) and the tree diagram.
pub fn export_buttons(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab;
    let three = lab.dimension() == Dimension::Three;
    let (view_rect, name) = if three {
        (cx.ui.view3d.rect, "bvh-lab-view")
    } else {
        (cx.ui.canvas.rect, "bvh-lab-canvas")
    };
    ui.horizontal_wrapped(|ui| {
        ui.label(if three { "View:" } else { "Canvas:" });
        if ui
            .button("SVG")
            .on_hover_text("the view as a vector drawing")
            .clicked()
        {
            let shapes = if three {
                crate::lab3d::picture::picture(lab.three(), &lab.predict_about(), view_rect)
            } else {
                crate::lab2d::picture(lab.two(), &lab.predict_about(), view_rect, ui.painter())
            };
            let svg = crate::export::svg_document(&shapes, view_rect, BACKGROUND);
            let saved =
                crate::export::save_file(&format!("{name}.svg"), "image/svg+xml", svg.as_bytes());
            let left_out = three
                .then(|| crate::lab3d::picture::mesh_left_out(lab.three()))
                .flatten();
            cx.act(said(saved.map(|at| match left_out {
                Some(why) => format!("{at} ({why})"),
                None => at,
            })));
        }
        if ui
            .button("PNG")
            .on_hover_text("the view as a picture")
            .clicked()
        {
            request_png(cx, ui.ctx(), view_rect, &format!("{name}.png"));
        }
        if let Some(rect) = cx.ui.tree_rect {
            ui.label("Tree:");
            if crate::a11y::describe::rename(ui.button("SVG "), "SVG of the tree diagram")
                .on_hover_text("the tree diagram as a vector drawing")
                .clicked()
            {
                let shapes = super::tree::tree_picture(cx, ui.ctx(), rect);
                let svg = crate::export::svg_document(&shapes, rect, BACKGROUND);
                cx.act(said(crate::export::save_file(
                    "bvh-lab-tree.svg",
                    "image/svg+xml",
                    svg.as_bytes(),
                )));
            }
            if crate::a11y::describe::rename(ui.button("PNG "), "PNG of the tree diagram")
                .on_hover_text("the tree diagram as a picture")
                .clicked()
            {
                request_png(cx, ui.ctx(), rect, "bvh-lab-tree.png");
            }
        }
    });
}

/// What the status line says about an export.
fn said(result: Result<String, String>) -> Action {
    Action::SetMessage(Some(saved(result)))
}

fn saved(result: Result<String, String>) -> String {
    match result {
        Ok(where_) => format!("Exported: {where_}"),
        Err(why) => format!("Export failed: {why}"),
    }
}

fn request_png(cx: &mut Cx<'_>, ctx: &egui::Context, rect: egui::Rect, name: &str) {
    let image = Arc::new(Mutex::new(None));
    let slot = image.clone();
    let repaint = ctx.clone();
    ctx.request_screenshot(move |shot| {
        *slot.lock() = Some(shot);
        repaint.request_repaint();
    });
    cx.ui.pending_png = Some(PendingPng {
        rect,
        name: name.to_owned(),
        image,
    });
}

/// Saves a PNG whose screenshot has arrived; call once per frame. What the status line
/// says, once it is saved (or failed).
pub fn finish_png(ui: &mut UiState, ctx: &egui::Context) -> Option<Action> {
    let pending = ui.pending_png.as_ref()?;
    let shot = pending.image.lock().take()?;
    let image = crate::export::crop(&shot, pending.rect, ctx.pixels_per_point());
    let result = crate::export::png_bytes(&image)
        .and_then(|bytes| crate::export::save_file(&pending.name, "image/png", &bytes));
    ui.pending_png = None;
    Some(said(result))
}
