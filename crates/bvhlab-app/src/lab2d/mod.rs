//! The 2D half's view: the canvas. Pointer input for the active tool becomes actions
//! (`input.rs`), pan and zoom too; the lab is drawn from its state (`draw.rs`: structure,
//! marks, scene, queries, handles; [`overlay`]: the playback's step; `volumes`: §2's
//! bounding volumes, slab test and separating-axis boxes), with the structure and scene
//! tessellated once per view (`layer.rs`).
//!
//! Mirrors [`crate::lab3d`]: `mod.rs` the widget, `input.rs` the pointer, `draw.rs` what is
//! drawn, `overlay.rs` the playback's state on top.

mod collision;
mod draw;
mod input;
pub mod interaction;
pub mod keys;
mod layer;
pub mod overlay;
mod screen;
mod volumes;

pub use interaction::Interaction;
pub use layer::StaticLayer;
pub use screen::Screen;

use bvhlab::glam::Vec2;
use egui::{PointerButton, Sense};

use crate::model::Action2d;
use crate::model::lab2d::Lab2d;
use crate::model::tools::Tool;
use crate::ui_state::Cx;

/// The canvas's state between frames: a drag in progress, where it is, its cached drawing.
pub struct CanvasState {
    /// A drag or drawing in progress.
    pub interaction: Interaction,
    /// The whole drawing area (both halves when comparing), in points.
    pub rect: egui::Rect,
    /// The bounding volume whose row the pointer is over in the bounding volumes table: the
    /// canvas draws it lit. Set by the panel each frame (drawn before the canvas).
    pub volume_hover: Option<bvhlab::FitKind>,
    /// The structure and scene of each lane, tessellated for the view.
    layers: [Option<StaticLayer>; 2],
    /// The handle the arrow keys move ([`keys`]), once R picked one.
    pub key_handle: Option<keys::KeyHandle>,
}

impl Default for CanvasState {
    fn default() -> Self {
        Self {
            interaction: Interaction::None,
            rect: egui::Rect::NOTHING,
            volume_hover: None,
            layers: [None, None],
            key_handle: None,
        }
    }
}

impl CanvasState {
    /// The first half's screen transform (the canvas's, when not comparing) for `lab`'s
    /// camera.
    pub fn screen(&self, lab: &Lab2d) -> Screen {
        let halves = halves(self.rect, lab.half.compare.is_some());
        Screen {
            camera: lab.camera,
            rect: halves[0],
        }
    }
}

/// Shows the canvas in the rest of `ui` and turns its input into actions: one view, or two
/// side by side (the same scene, camera and question on two structures) when comparing.
pub fn canvas(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    let (response, painter) = ui.allocate_painter(ui.available_size(), Sense::click_and_drag());
    let halves = halves(response.rect, lab.half.compare.is_some());
    cx.ui.canvas.rect = response.rect;
    cx.ui.drawing = Some(response.id);
    if lab.fit_pending && halves[0].is_positive() {
        let size = halves[0].size();
        cx.act(Action2d::FrameScene(Vec2::new(size.x, size.y)));
    }
    // Input goes through the view of the half the pointer is in.
    let pointer = response.interact_pointer_pos().or(response.hover_pos());
    let active = pointer.and_then(|p| halves.iter().position(|r| r.contains(p)));
    let screen = Screen {
        camera: lab.camera,
        rect: halves[active.unwrap_or(0)],
    };
    pan_and_zoom(cx, ui, &response, &screen);
    input::handle_tool(cx, ui, &response, &screen);
    let mut picked = cx.ui.canvas.key_handle;
    keys::handle_keys(cx, ui, &screen, &mut picked, response.id);
    cx.ui.canvas.key_handle = picked;
    if cx.ui.link_hover
        && let (Some(i), Some(p)) = (active, response.hover_pos())
        && !response.dragged()
        && let Some(outline) = lab
            .half
            .lane_at(i)
            .current(lab.scene.revision())
            .and_then(|s| s.outline.as_deref())
    {
        let node = overlay::node_at(outline, screen.to_world(p), lab.display.max_depth);
        cx.ui.hovered = node.map(|n| (i, n));
    }
    // What Predict's question waiting is about, lit in the main lane.
    let asked = cx.lab.predict_about();
    for (i, rect) in halves.iter().enumerate() {
        let screen = Screen {
            camera: lab.camera,
            rect: *rect,
        };
        let clipped = painter.with_clip_rect(*rect);
        let hover = response.hover_pos().filter(|p| rect.contains(*p));
        draw::draw(
            lab,
            &mut cx.ui.canvas,
            cx.ui.hovered,
            &asked,
            i,
            screen,
            &clipped,
            hover,
        );
        if lab.half.compare.is_some() {
            lane_title(&clipped, *rect, &lab.half.lane_name(i));
        }
    }
    keys::draw_picked(
        &painter.with_clip_rect(halves[0]),
        &Screen {
            camera: lab.camera,
            rect: halves[0],
        },
        lab,
        cx.ui.canvas.key_handle,
    );
    if lab.half.compare.is_some() {
        let x = halves[0].right() + 2.0;
        painter.vline(
            x,
            response.rect.y_range(),
            egui::Stroke::new(2.0, egui::Color32::from_gray(70)),
        );
    }
}

/// A compared view's title at the top left of its `half`, wrapped to the half's width (a
/// long name, "AABB tree (split at the middle of the longest axis)", was cut at its edge).
pub fn lane_title(painter: &egui::Painter, half: egui::Rect, name: &str) {
    let galley = painter.layout(
        name.to_owned(),
        egui::FontId::proportional(15.0),
        crate::paint::colors::QUERY,
        (half.width() - 16.0).max(40.0),
    );
    painter.galley(
        half.left_top() + egui::vec2(8.0, 6.0),
        galley,
        crate::paint::colors::QUERY,
    );
}

/// The view's legend entries after the marks ([`crate::legend`]): the split planes when
/// drawn, then the bounding volumes drawn, each one's colour and name.
pub fn legend_volumes(lab: &Lab2d) -> Vec<(egui::Color32, &'static str)> {
    let lanes = if lab.half.compare.is_some() { 2 } else { 1 };
    let splits = (0..lanes).any(|i| draw::draws_splits(lab, i));
    splits
        .then_some((crate::paint::colors::SPLIT, crate::paint::SPLIT_NAME))
        .into_iter()
        .chain(volumes::shown_volumes(lab).into_iter().map(|k| {
            (
                crate::paint::colors::volume(k),
                crate::paint::colors::volume_name(k),
            )
        }))
        .collect()
}

/// The canvas rect, or its two halves with a small gap.
pub fn halves(rect: egui::Rect, split: bool) -> Vec<egui::Rect> {
    if !split {
        return vec![rect];
    }
    let mid = rect.center().x;
    vec![
        egui::Rect::from_min_max(rect.min, egui::pos2(mid - 2.0, rect.max.y)),
        egui::Rect::from_min_max(egui::pos2(mid + 2.0, rect.min.y), rect.max),
    ]
}

/// The shapes of the whole canvas (both halves when comparing), for SVG export, with what
/// Predict's question is `asked` about.
pub fn picture(
    lab: &Lab2d,
    asked: &crate::model::predict::About,
    rect: egui::Rect,
    painter: &egui::Painter,
) -> Vec<egui::Shape> {
    halves(rect, lab.half.compare.is_some())
        .into_iter()
        .enumerate()
        .map(|(i, rect)| {
            let screen = Screen {
                camera: lab.camera,
                rect,
            };
            egui::Shape::Vec(draw::picture(lab, i, asked, screen, painter))
        })
        .collect()
}

fn pan_and_zoom(cx: &mut Cx<'_>, ui: &egui::Ui, response: &egui::Response, screen: &Screen) {
    let tool = cx.lab.two().tool;
    let pans = response.dragged_by(PointerButton::Secondary)
        || response.dragged_by(PointerButton::Middle)
        || (tool == Tool::Pan && response.dragged_by(PointerButton::Primary));
    let mut camera = screen.camera;
    if pans {
        camera = Screen { camera, ..*screen }.panned(response.drag_delta());
    }
    if let Some(hover) = response.hover_pos() {
        let (scroll, pinch) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
        let factor = (scroll * 0.002).exp() * pinch;
        if factor != 1.0 {
            camera = Screen { camera, ..*screen }.zoomed_at(hover, factor);
        }
    }
    if camera != screen.camera {
        cx.act(Action2d::SetCamera(camera));
    }
}
