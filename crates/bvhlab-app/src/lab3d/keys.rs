//! The 3D view without a mouse: the arrow keys orbit the camera (10° a press, 2° with Shift),
//! `+` and `-` (or Page Up and Page Down) zoom, and Enter does what a click in the middle of
//! the view does: casts a ray from the camera through it, or puts the query point where that
//! ray meets the mesh. To aim, orbit until the spot is in the middle (the view marks it); the
//! exact start, direction and point are numbers in the Ray and point panel.
//!
//! As in 2D ([`crate::lab2d`]), the keys act when the view has the keyboard focus or no
//! widget has it: a focused slider or number keeps its arrow keys.

use bvhlab::glam::Vec2;
use egui::{Key, Rect};

use super::input::click;
use crate::model::Action3d;
use crate::ui_state::Cx;

/// One arrow press turns the camera by this much, in radians (10°).
const TURN: f32 = std::f32::consts::PI / 18.0;
/// With Shift held, a fifth of it (2°).
const FINE_TURN: f32 = TURN / 5.0;
/// One zoom press moves the eye this share closer or farther.
const ZOOM: f32 = 1.25;

/// Reads the view's keys in `rect` (the first half); `view` is the view's widget id.
pub(super) fn handle_keys(cx: &mut Cx<'_>, ui: &egui::Ui, rect: Rect, view: egui::Id) {
    let ctx = ui.ctx();
    crate::lab2d::keys::keep_arrow_keys(ctx, view);
    if ctx.text_edit_focused() || ctx.memory(|m| m.focused().is_some_and(|f| f != view)) {
        return;
    }
    let (turn, zoom, enter) = ui.input(|i| {
        let step = if i.modifiers.shift { FINE_TURN } else { TURN };
        // Every press counts: a slow frame (software rendering) may get several.
        let press = |key, v: Vec2| v * i.num_presses(key) as f32;
        let turn = press(Key::ArrowLeft, Vec2::NEG_X)
            + press(Key::ArrowRight, Vec2::X)
            + press(Key::ArrowUp, Vec2::NEG_Y)
            + press(Key::ArrowDown, Vec2::Y);
        let closer =
            i.num_presses(Key::Plus) + i.num_presses(Key::Equals) + i.num_presses(Key::PageUp);
        let farther = i.num_presses(Key::Minus) + i.num_presses(Key::PageDown);
        let zoom = ZOOM.powi(farther as i32 - closer as i32);
        (turn * step, zoom, i.key_pressed(Key::Enter))
    });
    let lab = cx.lab.three();
    let mut camera = lab.camera;
    // An arrow turns the camera as a drag that way does.
    camera.turn(-turn.x, turn.y);
    camera.zoom(zoom);
    if camera != lab.camera {
        cx.act(Action3d::SetCamera(camera));
    }
    // Through the camera as turned this frame (a fast Enter after an arrow comes in the same
    // frame as it).
    if enter && rect.is_positive() {
        let size = Vec2::new(rect.width(), rect.height());
        if let Some(action) = click(lab, &camera, size * 0.5, size) {
            cx.act(action);
        }
    }
}

/// Marks the middle of the view at `rect` while the view has the keyboard focus: where Enter
/// casts the ray through. A cross in the view's outline and a word, not a colour alone.
pub(super) fn draw_aim(ui: &egui::Ui, painter: &egui::Painter, rect: Rect, view: egui::Id) {
    if !ui.ctx().memory(|m| m.has_focus(view)) || !rect.is_positive() {
        return;
    }
    let c = rect.center();
    let stroke = ui.visuals().selection.stroke;
    let halo = egui::Stroke::new(stroke.width + 2.0, egui::Color32::BLACK);
    for s in [halo, stroke] {
        painter.line_segment([c - egui::vec2(10.0, 0.0), c + egui::vec2(10.0, 0.0)], s);
        painter.line_segment([c - egui::vec2(0.0, 10.0), c + egui::vec2(0.0, 10.0)], s);
    }
    painter.text(
        c + egui::vec2(14.0, 14.0),
        egui::Align2::LEFT_TOP,
        "Enter aims here",
        egui::FontId::proportional(12.0),
        stroke.color,
    );
}
