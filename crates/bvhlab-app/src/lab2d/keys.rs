//! The ray and the query point without a mouse: R picks the handle the arrow keys move (the
//! ray's start e, its second point s, the query point q, in turn; with no ray it makes one
//! across the middle of the view), and the arrow keys move it 10 screen points (1 with Shift).
//! The handle picked is framed on the canvas, and the status line says which it is.
//!
//! The keys act when the canvas has the keyboard focus (a keyboard user tabs to it) or no
//! widget has it: a focused slider or number keeps its arrow keys, and Tab still walks the
//! panels' widgets.

use bvhlab::glam::Vec2;

use super::Screen;
use crate::model::lab2d::{Lab2d, RayHandles};
use crate::model::{Action, Action2d};
use crate::ui_state::Cx;

/// A handle the arrow keys move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyHandle {
    /// The ray's start, e.
    RayStart,
    /// The point the ray passes through, s.
    RayTarget,
    /// The query point, q.
    Point,
}

impl KeyHandle {
    /// Where it is in `lab`, if it exists.
    fn at(self, lab: &Lab2d) -> Option<Vec2> {
        match self {
            Self::RayStart => lab.ray.map(|r| r.origin),
            Self::RayTarget => lab.ray.map(|r| r.target),
            Self::Point => lab.point,
        }
    }

    /// What the status line calls it.
    fn name(self) -> &'static str {
        match self {
            Self::RayStart => "the ray's start e",
            Self::RayTarget => "the ray's point s",
            Self::Point => "the query point q",
        }
    }

    /// The handle after it, in turn.
    fn next(self) -> Self {
        match self {
            Self::RayStart => Self::RayTarget,
            Self::RayTarget => Self::Point,
            Self::Point => Self::RayStart,
        }
    }
}

/// Keeps the arrow keys for the drawing `view` while it has the focus: egui would otherwise
/// take them to move the focus to the widget beside it (Tab and Escape still leave).
pub(crate) fn keep_arrow_keys(ctx: &egui::Context, view: egui::Id) {
    ctx.memory_mut(|m| {
        m.set_focus_lock_filter(
            view,
            egui::EventFilter {
                horizontal_arrows: true,
                vertical_arrows: true,
                tab: false,
                escape: false,
            },
        );
    });
}

/// Reads R and the arrow keys; `picked` is the handle the arrows move, kept between frames.
pub(super) fn handle_keys(
    cx: &mut Cx<'_>,
    ui: &egui::Ui,
    screen: &Screen,
    picked: &mut Option<KeyHandle>,
    canvas: egui::Id,
) {
    let ctx = ui.ctx();
    keep_arrow_keys(ctx, canvas);
    if ctx.text_edit_focused() || ctx.memory(|m| m.focused().is_some_and(|f| f != canvas)) {
        return;
    }
    let (cycles, arrows, fine) = ui.input(|i| {
        // Every press counts: a slow frame (software rendering) may get several.
        let arrow = |key, v: Vec2| v * i.num_presses(key) as f32;
        let arrows = arrow(egui::Key::ArrowLeft, Vec2::NEG_X)
            + arrow(egui::Key::ArrowRight, Vec2::X)
            + arrow(egui::Key::ArrowUp, Vec2::Y)
            + arrow(egui::Key::ArrowDown, Vec2::NEG_Y);
        (i.num_presses(egui::Key::R), arrows, i.modifiers.shift)
    });
    // Every press picks once, as for the arrows: two presses in one slow frame go two handles on.
    for _ in 0..cycles {
        pick_next(cx, screen, picked);
    }
    let lab = cx.lab.two();
    let Some(handle) = *picked else {
        return;
    };
    if arrows == Vec2::ZERO {
        return;
    }
    let Some(at) = handle.at(lab) else {
        *picked = None;
        return;
    };
    let moved = at + arrows * screen.world_length(if fine { 1.0 } else { 10.0 });
    let action = match (handle, lab.ray) {
        (KeyHandle::RayStart, Some(r)) => Action2d::SetRay(Some(RayHandles { origin: moved, ..r })),
        (KeyHandle::RayTarget, Some(r)) => {
            Action2d::SetRay(Some(RayHandles { target: moved, ..r }))
        }
        (KeyHandle::Point, _) => Action2d::SetPoint(Some(moved)),
        _ => return,
    };
    cx.act(action);
}

/// R: the arrows' next handle that is there (ray start, ray target, query point), said in
/// the status line; with nothing to move yet, a ray across the middle of the view.
fn pick_next(cx: &mut Cx<'_>, screen: &Screen, picked: &mut Option<KeyHandle>) {
    let start = picked.map_or(KeyHandle::RayStart, KeyHandle::next);
    let lab = cx.lab.two();
    let found = [start, start.next(), start.next().next()]
        .into_iter()
        .find(|h| h.at(lab).is_some());
    let handle = found.unwrap_or_else(|| {
        let middle = screen.to_world(screen.rect.center());
        let half_width = screen.world_length(screen.rect.width() / 4.0);
        cx.act(Action2d::SetRay(Some(RayHandles {
            origin: middle - Vec2::new(half_width, 0.0),
            target: middle,
        })));
        KeyHandle::RayStart
    });
    *picked = Some(handle);
    cx.act(Action::SetMessage(Some(format!(
        "The arrow keys move {} (Shift: finer); R picks the next handle.",
        handle.name()
    ))));
}

/// Frames the handle the arrow keys move, so that a keyboard user sees which it is.
pub(super) fn draw_picked(
    painter: &egui::Painter,
    screen: &Screen,
    lab: &Lab2d,
    picked: Option<KeyHandle>,
) {
    let Some(at) = picked.and_then(|h| h.at(lab)) else {
        return;
    };
    let centre = screen.to_screen(at);
    let square = egui::Rect::from_center_size(centre, egui::vec2(18.0, 18.0));
    painter.rect_stroke(
        square,
        2.0,
        egui::Stroke::new(2.0, crate::paint::colors::SELECTED),
        egui::StrokeKind::Outside,
    );
}
