//! The canvas: pointer input for the active tool (`input.rs`), pan and zoom, and drawing
//! (`draw.rs`: structure, query marks, scene, bounding volumes, queries, handles).

mod draw;
mod input;
pub mod steps;

pub use draw::{LayerKey, StaticLayer};

use egui::{PointerButton, Sense};

use crate::app::LabApp;
use crate::tool::Tool;

/// Shows the canvas in the rest of `ui` and handles its input: one view, or two side by
/// side (the same scene, view and question on two structures) when comparing.
pub fn canvas(app: &mut LabApp, ui: &mut egui::Ui) {
    let (response, painter) = ui.allocate_painter(ui.available_size(), Sense::click_and_drag());
    let halves = halves(response.rect, app.compare.is_some());
    app.canvas_rect = response.rect;
    app.view.rect = halves[0];
    if app.fit_pending {
        if let Some((lo, hi)) = app.scene.bounds() {
            app.view.fit(lo, hi);
        }
        app.fit_pending = false;
    }
    // Input goes through the view of the half the pointer is in.
    let pointer = response.interact_pointer_pos().or(response.hover_pos());
    let active = pointer.and_then(|p| halves.iter().position(|r| r.contains(p)));
    app.view.rect = halves[active.unwrap_or(0)];
    pan_and_zoom(app, ui, &response);
    input::handle_tool(app, ui, &response);
    app.refresh();
    if app.link_hover
        && let (Some(i), Some(p)) = (active, response.hover_pos())
        && !response.dragged()
    {
        let world = app.view.to_world(p);
        let lane = app.lane_at(i);
        if let Some(built) = &lane.built {
            let node = steps::node_at(&built.outline, world, app.display.max_depth);
            app.hovered = node.map(|n| (i, n));
        }
    }
    for (i, rect) in halves.iter().enumerate() {
        let mut view = app.view;
        view.rect = *rect;
        let clipped = painter.with_clip_rect(*rect);
        let hover = response.hover_pos().filter(|p| rect.contains(*p));
        draw::draw(app, i, view, &clipped, hover);
        if app.compare.is_some() {
            let name = app.lane_at(i).settings.kind.label();
            clipped.text(
                rect.left_top() + egui::vec2(8.0, 6.0),
                egui::Align2::LEFT_TOP,
                name,
                egui::FontId::proportional(15.0),
                crate::paint::colors::QUERY,
            );
        }
    }
    if app.compare.is_some() {
        let x = halves[0].right() + 2.0;
        painter.vline(
            x,
            response.rect.y_range(),
            egui::Stroke::new(2.0, egui::Color32::from_gray(70)),
        );
    }
    app.view.rect = halves[0];
}

/// The canvas rect, or its two halves with a small gap.
fn halves(rect: egui::Rect, split: bool) -> Vec<egui::Rect> {
    if !split {
        return vec![rect];
    }
    let mid = rect.center().x;
    vec![
        egui::Rect::from_min_max(rect.min, egui::pos2(mid - 2.0, rect.max.y)),
        egui::Rect::from_min_max(egui::pos2(mid + 2.0, rect.min.y), rect.max),
    ]
}

/// The shapes of the whole canvas (both halves when comparing), for SVG export.
pub fn picture(app: &mut LabApp, painter: &egui::Painter) -> Vec<egui::Shape> {
    let rect = app.view.rect;
    let count = if app.compare.is_some() { 2 } else { 1 };
    let mut shapes = Vec::new();
    for i in 0..count {
        let mut view = app.view;
        view.rect = rect.translate(egui::vec2(rect.width() * i as f32 + 4.0 * i as f32, 0.0));
        shapes.push(egui::Shape::Vec(draw::picture(app, i, view, painter)));
    }
    shapes
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
