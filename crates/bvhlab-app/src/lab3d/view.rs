//! The 3D view in the middle of the lab: the pointer, then the mesh and everything in
//! [`Draw3d`] drawn by the wgpu renderer through an `egui_wgpu` paint
//! callback, with the heat map, the progress of a build and a legend on top.

use egui::{Align2, Color32, FontId, Sense};

use super::Lab3d;
use super::draw::{self, Draw3d, rgba};
use super::input::{self, Asked};
use crate::app::LabApp;
use crate::paint::colors;
use crate::view3d::gpu::{self, Frame3d, Line3d, Marker};

/// The view's background.
const BACKGROUND: Color32 = Color32::from_rgb(24, 26, 32);

/// Shows the 3D view in `ui`'s remaining space.
pub fn view(app: &mut LabApp, ui: &mut egui::Ui) {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    app.lab3d.view_rect = rect;
    if rect.is_positive() {
        app.lab3d.place_defaults(rect.aspect_ratio());
    }
    if let Some(asked) = input::handle_input(&mut app.lab3d, &response, rect) {
        match asked {
            Asked::Ray => app.ask_about_ray(),
            Asked::Point => app.ask_about_point(),
        }
        app.refresh();
    }
    let painter = ui.painter_at(rect);
    let lab = &app.lab3d;
    let drawn = draw::draw(lab, app.task);
    if app.render_state.is_some() {
        let id = ui.make_persistent_id("3d view");
        gpu::paint_3d(ui, rect, id, frame(lab, &drawn));
    } else {
        painter.rect_filled(rect, 0.0, BACKGROUND);
        painter.text(
            rect.center(),
            Align2::CENTER_CENTER,
            "The 3D view draws with wgpu (WebGPU or WebGL2), which is not available here.",
            FontId::proportional(14.0),
            Color32::LIGHT_GRAY,
        );
    }
    super::heat::overlay(app, ui, rect);
    let lab = &app.lab3d;
    if let Some(job) = &lab.job {
        painter.text(
            rect.center_top() + egui::vec2(0.0, 24.0),
            Align2::CENTER_CENTER,
            format!(
                "building the {}: {:.0}%",
                job.settings.kind.label_in(3),
                job.fraction() * 100.0
            ),
            FontId::proportional(16.0),
            Color32::WHITE,
        );
    }
    if drawn.level_cut {
        painter.text(
            rect.left_bottom() + egui::vec2(8.0, -8.0),
            Align2::LEFT_BOTTOM,
            format!(
                "this level has more than {} nodes: only the first are drawn",
                draw::LEVEL_CAP
            ),
            FontId::proportional(12.0),
            colors::PRUNED,
        );
    }
    legend(&painter, rect);
}

/// The mesh and the draw list as the renderer's frame.
fn frame(lab: &Lab3d, drawn: &Draw3d) -> Frame3d {
    let line = |s: &super::wire::Segment| Line3d {
        a: s.a.to_array(),
        b: s.b.to_array(),
        color: s.color,
        width_px: s.width,
    };
    let mut triangles = Vec::new();
    for polygon in &drawn.polygons {
        let c = &polygon.corners;
        for i in 1..c.len().saturating_sub(1) {
            triangles.push(gpu::ColorTriangle {
                a: c[0].to_array(),
                b: c[i].to_array(),
                c: c[i + 1].to_array(),
                color: polygon.color,
            });
        }
    }
    let mesh_alpha = if lab.display.xray { 0.35 } else { 1.0 };
    Frame3d {
        camera: lab.camera,
        background: rgba(BACKGROUND, 1.0),
        mesh: lab.mesh.as_ref().map(|m| m.gpu.clone()),
        mesh_color: rgba(colors::SCENE, mesh_alpha),
        highlights: drawn.highlights.clone(),
        lines: drawn.lines.iter().map(line).collect(),
        overlay_lines: drawn.overlay.iter().map(line).collect(),
        triangles,
        markers: drawn
            .dots
            .iter()
            .map(|d| Marker {
                pos: d.at.to_array(),
                radius_px: d.radius,
                color: d.color,
            })
            .collect(),
    }
}

/// What the colours mean.
fn legend(painter: &egui::Painter, rect: egui::Rect) {
    let entries = [
        (colors::VISITED, "visited"),
        (colors::CULLED, "culled"),
        (colors::PRUNED, "pruned"),
        (colors::WAITING, "waiting"),
        (colors::CURRENT, "current"),
        (colors::TESTED, "tested triangle"),
        (colors::ANSWER, "answer"),
    ];
    let mut at = rect.right_top() + egui::vec2(-120.0, 10.0);
    for (color, label) in entries {
        painter.rect_filled(
            egui::Rect::from_min_size(at, egui::vec2(10.0, 10.0)),
            2.0,
            color,
        );
        painter.text(
            at + egui::vec2(16.0, 5.0),
            Align2::LEFT_CENTER,
            label,
            FontId::proportional(12.0),
            Color32::LIGHT_GRAY,
        );
        at.y += 16.0;
    }
}
