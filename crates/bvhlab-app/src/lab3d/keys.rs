//! The 3D view without a mouse: the arrow keys orbit the camera (10° a press, 2° with Shift),
//! `+` and `-` (or Page Up and Page Down) zoom, and Enter does what a click in the middle of
//! the view does: casts a ray from the camera through it, or puts the query point where that
//! ray meets the mesh. To aim, orbit until the spot is in the middle (the view marks it); the
//! exact start, direction and point are numbers in the Ray and point panel.
//!
//! R picks what the arrow keys move, as in 2D: the ray's start e, then the point s its
//! direction passes through (with the ray tool), or the query point q (with the point tool),
//! then the camera again. A picked handle moves 10 screen points a press (1 with Shift) along
//! the camera's right and up axes, in the plane facing the camera, as a drag of the gizmo
//! does. With no ray yet, R makes one across the middle of the view, left to right; with no
//! point, it puts one at the middle of the scene. The handle picked is framed and named in
//! the view, and the status line says which it is.
//!
//! As in 2D ([`crate::lab2d`]), the keys act when the view has the keyboard focus or no
//! widget has it: a focused slider or number keeps its arrow keys.

use bvhlab::Ray3;
use bvhlab::glam::Vec2;
use egui::{Key, Rect};

use super::input::{Handle, click, drag_handle, handles};
use crate::model::lab3d::Lab3d;
use crate::model::tools::Tool3d;
use crate::model::{Action, Action3d};
use crate::ui_state::Cx;

/// One arrow press turns the camera by this much, in radians (10°).
const TURN: f32 = std::f32::consts::PI / 18.0;
/// With Shift held, a fifth of it (2°).
const FINE_TURN: f32 = TURN / 5.0;
/// One zoom press moves the eye this share closer or farther.
const ZOOM: f32 = 1.25;
/// One arrow press moves a picked handle this many screen points (with Shift, 1).
const NUDGE: f32 = 10.0;

/// The handles R picks in turn with the tool in use (after them, the camera again).
fn key_handles(tool: Tool3d) -> &'static [Handle] {
    match tool {
        Tool3d::Ray => &[Handle::RayOrigin, Handle::RayDirection],
        Tool3d::Point => &[Handle::Point],
    }
}

/// What the status line and the view call a handle.
fn handle_name(handle: Handle) -> &'static str {
    match handle {
        Handle::RayOrigin => "the ray's start e",
        Handle::RayDirection => "the ray's point s",
        Handle::Point => "the query point q",
        Handle::Axis(..) => "an axis of the gizmo",
    }
}

/// The handle after `current` (`None`: the camera) in R's turn under `tool`.
fn next_handle(tool: Tool3d, current: Option<Handle>) -> Option<Handle> {
    let list = key_handles(tool);
    match current.and_then(|h| list.iter().position(|&l| l == h)) {
        None => list.first().copied(),
        Some(i) => list.get(i + 1).copied(),
    }
}

/// What makes the thing `handle` moves when there is none yet: a ray across the middle of
/// the view, left to right, from a quarter of its width left of the middle (as in 2D); the
/// query point at the middle of the scene.
fn make_missing(lab: &Lab3d, handle: Handle, rect: Rect) -> Option<Action3d> {
    let camera = lab.camera;
    match handle {
        Handle::RayOrigin | Handle::RayDirection if lab.ray.is_none() => {
            let basis = camera.basis();
            let half_height = camera.distance * (camera.fov_y * 0.5).tan();
            let aspect = if rect.is_positive() {
                rect.aspect_ratio()
            } else {
                1.0
            };
            let quarter_width = half_height * aspect * 0.5;
            let ray = Ray3::new(camera.target - basis.right * quarter_width, basis.right).ok()?;
            Some(Action3d::SetRay(Some(ray)))
        }
        Handle::Point if lab.point.is_none() => Some(Action3d::SetPoint(Some(camera.target))),
        _ => None,
    }
}

/// Reads the view's keys in `rect` (the first half); `view` is the view's widget id.
pub(super) fn handle_keys(cx: &mut Cx<'_>, ui: &egui::Ui, rect: Rect, view: egui::Id) {
    let ctx = ui.ctx();
    crate::lab2d::keys::keep_arrow_keys(ctx, view);
    if ctx.text_edit_focused() || ctx.memory(|m| m.focused().is_some_and(|f| f != view)) {
        return;
    }
    let (arrows, fine, zoom, enter, cycle) = ui.input(|i| {
        // Every press counts: a slow frame (software rendering) may get several.
        let press = |key, v: Vec2| v * i.num_presses(key) as f32;
        let arrows = press(Key::ArrowLeft, Vec2::NEG_X)
            + press(Key::ArrowRight, Vec2::X)
            + press(Key::ArrowUp, Vec2::NEG_Y)
            + press(Key::ArrowDown, Vec2::Y);
        let closer =
            i.num_presses(Key::Plus) + i.num_presses(Key::Equals) + i.num_presses(Key::PageUp);
        let farther = i.num_presses(Key::Minus) + i.num_presses(Key::PageDown);
        let zoom = ZOOM.powi(farther as i32 - closer as i32);
        (
            arrows,
            i.modifiers.shift,
            zoom,
            i.key_pressed(Key::Enter),
            i.num_presses(Key::R),
        )
    });
    let tool = cx.lab.three().tool;
    // A handle of another tool (the tool changed since) moves nothing: back to the camera.
    if cx
        .ui
        .view3d
        .key_handle
        .is_some_and(|h| !key_handles(tool).contains(&h))
    {
        cx.ui.view3d.key_handle = None;
    }
    for _ in 0..cycle {
        pick_next(cx, rect);
    }
    let lab = cx.lab.three();
    let mut camera = lab.camera;
    match cx.ui.view3d.key_handle {
        Some(handle) if arrows != Vec2::ZERO && rect.is_positive() => {
            let size = Vec2::new(rect.width(), rect.height());
            let delta = arrows * if fine { 1.0 } else { NUDGE };
            if let Some(action) = drag_handle(lab, rect, handle, delta, size) {
                cx.act(action);
            }
        }
        Some(_) => {}
        // An arrow turns the camera as a drag that way does.
        None => {
            let turn = arrows * if fine { FINE_TURN } else { TURN };
            camera.turn(-turn.x, turn.y);
        }
    }
    camera.zoom(zoom);
    let lab = cx.lab.three();
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

/// R: picks the next handle (making the ray or point when there is none), or the camera
/// after the last, and says so on the status line.
fn pick_next(cx: &mut Cx<'_>, rect: Rect) {
    let lab = cx.lab.three();
    let next = next_handle(lab.tool, cx.ui.view3d.key_handle);
    if let Some(action) = next.and_then(|h| make_missing(lab, h, rect)) {
        cx.act(action);
    }
    cx.ui.view3d.key_handle = next;
    let message = match next {
        Some(h) => format!(
            "The arrow keys move {} along the camera's axes (Shift: finer); R picks the next.",
            handle_name(h)
        ),
        None => "The arrow keys turn the camera; R picks a handle to move.".to_owned(),
    };
    cx.act(Action::SetMessage(Some(message)));
}

/// Frames the handle the arrow keys move and names it beside the frame, so that a keyboard
/// user sees which it is (a shape and a word, not a colour alone).
pub(super) fn draw_picked(
    painter: &egui::Painter,
    lab: &Lab3d,
    rect: Rect,
    picked: Option<Handle>,
) {
    let Some(picked) = picked else {
        return;
    };
    let size = Vec2::new(rect.width(), rect.height());
    let on_screen = handles(lab, rect)
        .into_iter()
        .find(|(h, _)| *h == picked)
        .and_then(|(_, at)| lab.camera.project(at, size))
        .map(|at| rect.min + egui::vec2(at.x, at.y))
        .filter(|&at| rect.shrink(4.0).contains(at));
    let Some(centre) = on_screen else {
        // A clicked ray starts at the eye: its start is behind or beside the view until it
        // moves or the camera turns. Say so where the frame would be missing.
        let words = format!(
            "The arrows move {}, outside the view: turn or zoom out (-) to see it.",
            handle_name(picked)
        );
        label(
            painter,
            rect.left_bottom() + egui::vec2(8.0, -8.0),
            egui::Align2::LEFT_BOTTOM,
            words,
        );
        return;
    };
    let stroke = egui::Stroke::new(2.0, crate::paint::colors::SELECTED);
    let halo = egui::Stroke::new(4.0, egui::Color32::BLACK);
    let square = Rect::from_center_size(centre, egui::vec2(18.0, 18.0));
    for s in [halo, stroke] {
        painter.rect_stroke(square, 2.0, s, egui::StrokeKind::Outside);
    }
    let words = format!("arrows move {}", handle_name(picked));
    label(
        painter,
        centre + egui::vec2(14.0, -14.0),
        egui::Align2::LEFT_BOTTOM,
        words,
    );
}

/// Words in the selection's yellow on a dark backing, readable over the mesh and the lines.
fn label(painter: &egui::Painter, at: egui::Pos2, align: egui::Align2, words: String) {
    let galley = painter.layout_no_wrap(
        words,
        egui::FontId::proportional(13.0),
        crate::paint::colors::SELECTED,
    );
    let rect = align.anchor_size(at, galley.size());
    painter.rect_filled(rect.expand(3.0), 3.0, egui::Color32::from_black_alpha(200));
    painter.galley(rect.min, galley, crate::paint::colors::SELECTED);
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
