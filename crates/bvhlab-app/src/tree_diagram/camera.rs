//! The diagram's pan and zoom: layout units to screen points (`Camera`), and when the
//! picture moves without the student moving it (`Viewport`).
//!
//! A tree with thousands of leaves is far wider than deep, so x and y have their own scales:
//! "fit" shows every leaf across the width and every level down the height, and zooming in
//! widens the levels only up to a comfortable spacing, after which it spreads the leaves
//! alone. A grid keeps one scale, so its cells stay square.

use bvhlab::NodeId;
use egui::{Pos2, Rect, Vec2, pos2, vec2};

use super::TreeHighlight;
use super::layout::{Arrangement, Layout};

/// Room left around the fitted diagram, in points.
const PAD: f32 = 16.0;
/// The largest radius of a node's dot (half the side of a leaf's square), in points.
const MAX_RADIUS: f32 = 9.0;
/// Room left under the deepest row of a fitted tree: its leaves' squares and, below them, the
/// primitive counts (a line of 11-point text: see `draw.rs`).
const BELOW_DEEPEST: f32 = MAX_RADIUS + 1.0 + 16.0;
/// The widest spacing "fit" gives neighbouring nodes, in points.
const FIT_X: f32 = 40.0;
/// The widest spacing "fit" gives levels, in points.
const FIT_Y: f32 = 56.0;
/// Zooming in stops widening levels here (unless "fit" made them wider).
const MAX_LEVEL: f32 = 80.0;
/// Zooming out stops narrowing levels here (unless "fit" made them narrower).
const MIN_LEVEL: f32 = 6.0;
/// The largest cell of a grid, in points, when fitted.
const FIT_CELL: f32 = 44.0;

/// Layout units to screen points: `screen = origin + (x * x_scale, row * y_scale)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Camera {
    origin: Pos2,
    x_scale: f32,
    y_scale: f32,
    /// Both scales move together (grids).
    uniform: bool,
}

impl Camera {
    /// The whole layout inside `rect`, centred across, root at the top.
    pub(super) fn fit(layout: &Layout, rect: Rect) -> Self {
        let inner = rect.shrink(PAD);
        let (w, h) = (inner.width().max(1.0), inner.height().max(1.0));
        match layout.arrangement {
            Arrangement::Tree { levels } => {
                let h = (h - (BELOW_DEEPEST - PAD)).max(1.0);
                let x_scale = if layout.x_max > 0.0 {
                    (w / layout.x_max).min(FIT_X)
                } else {
                    FIT_X
                };
                let y_scale = if levels > 1 {
                    (h / (levels - 1) as f32).min(FIT_Y)
                } else {
                    FIT_Y
                };
                Self {
                    origin: pos2(inner.center().x - 0.5 * layout.x_max * x_scale, inner.top()),
                    x_scale,
                    y_scale,
                    uniform: false,
                }
            }
            Arrangement::Grid { cols, rows } => {
                let scale = (w / cols as f32).min(h / rows as f32).min(FIT_CELL);
                let half = vec2(cols as f32 - 1.0, rows as f32 - 1.0) * 0.5 * scale;
                Self {
                    origin: inner.center() - half,
                    x_scale: scale,
                    y_scale: scale,
                    uniform: true,
                }
            }
        }
    }

    /// The screen point of a layout point.
    pub(super) fn to_screen(self, p: [f32; 2]) -> Pos2 {
        self.origin + vec2(p[0] * self.x_scale, p[1] * self.y_scale)
    }

    /// The layout point under a screen point.
    pub(super) fn to_layout(self, p: Pos2) -> [f32; 2] {
        let d = p - self.origin;
        [d.x / self.x_scale, d.y / self.y_scale]
    }

    /// Points between neighbouring columns and rows.
    pub(super) fn scales(&self) -> Vec2 {
        vec2(self.x_scale, self.y_scale)
    }

    /// Moves the diagram with a drag.
    pub(super) fn pan(&mut self, delta: Vec2) {
        self.origin += delta;
    }

    /// Zooms by `factor` keeping the layout point under `anchor` where it is.
    pub(super) fn zoom_at(&mut self, anchor: Pos2, factor: f32) {
        let under = self.to_layout(anchor);
        self.x_scale = (self.x_scale * factor).clamp(1e-4, 1e4);
        self.y_scale = if self.uniform {
            self.x_scale
        } else {
            let y = self.y_scale;
            (y * factor).clamp(y.min(MIN_LEVEL), y.max(MAX_LEVEL))
        };
        self.origin = anchor - vec2(under[0] * self.x_scale, under[1] * self.y_scale);
    }

    /// Pans so that the layout point `p` is at the centre of `rect`.
    pub(super) fn center_on(&mut self, p: [f32; 2], rect: Rect) {
        self.origin += rect.center() - self.to_screen(p);
    }

    /// The radius of a node's dot (half the side of a leaf's square), in points.
    pub(super) fn node_radius(&self) -> f32 {
        if self.uniform {
            (0.42 * self.x_scale).max(0.5)
        } else {
            (0.36 * self.x_scale.min(self.y_scale)).clamp(1.5, MAX_RADIUS)
        }
    }
}

/// The camera and what decides when it moves on its own: a fit when the layout is new, when
/// "Fit" is pressed, or when the widget is resized before the student moved anything; a pan
/// to the linked or current node when it changes and is off screen.
#[derive(Default)]
pub(super) struct Viewport {
    /// `None` until the first frame, and after a new layout: fit then.
    pub(super) camera: Option<Camera>,
    /// "Fit" was pressed.
    pub(super) fit_requested: bool,
    /// The rectangle the camera was last used in.
    rect: Option<Rect>,
    /// The student panned or zoomed since the last fit (so a resize does not refit).
    moved: bool,
    last_linked: Option<NodeId>,
    last_current: Option<NodeId>,
}

impl Viewport {
    /// This frame's camera for the diagram in `response.rect`, after the student's drag,
    /// scroll or pinch, and after bringing a newly linked or current node into view.
    pub(super) fn update(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        layout: &Layout,
        highlight: &TreeHighlight<'_>,
    ) -> Camera {
        let rect = response.rect;
        let mut camera = match (self.camera, self.rect) {
            (Some(mut camera), Some(before))
                if !self.fit_requested && (self.moved || before.size() == rect.size()) =>
            {
                // The diagram moved on screen (the panel above it grew): the picture moves
                // with it.
                camera.pan(rect.min - before.min);
                camera
            }
            _ => {
                self.moved = false;
                self.fit_requested = false;
                Camera::fit(layout, rect)
            }
        };
        if response.dragged() {
            camera.pan(response.drag_delta());
            self.moved = true;
        }
        if let Some(pointer) = response.hover_pos() {
            let (scroll, pinch) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            let factor = (scroll * 0.002).exp() * pinch;
            if factor != 1.0 {
                camera.zoom_at(pointer, factor);
                self.moved = true;
                // The diagram took the scroll: a scroll area around it must not scroll too.
                ui.input_mut(|i| i.smooth_scroll_delta.y = 0.0);
            }
        }
        for (target, last) in [
            (highlight.linked, &mut self.last_linked),
            (highlight.current, &mut self.last_current),
        ] {
            if std::mem::replace(last, target) != target
                && let Some(p) = target.and_then(|id| layout.pos.get(id.index()))
                && !rect.shrink(12.0).contains(camera.to_screen(*p))
            {
                camera.center_on(*p, rect);
            }
        }
        self.camera = Some(camera);
        self.rect = Some(rect);
        camera
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zoom_keeps_the_anchor_and_round_trips() {
        let mut cam = Camera {
            origin: pos2(10.0, 20.0),
            x_scale: 2.0,
            y_scale: 30.0,
            uniform: false,
        };
        let p = [7.5, 3.0];
        let back = cam.to_layout(cam.to_screen(p));
        assert!((back[0] - p[0]).abs() < 1e-4 && (back[1] - p[1]).abs() < 1e-4);
        let anchor = pos2(123.0, 77.0);
        let under = cam.to_layout(anchor);
        cam.zoom_at(anchor, 4.0);
        let after = cam.to_layout(anchor);
        assert!((after[0] - under[0]).abs() < 1e-3 && (after[1] - under[1]).abs() < 1e-3);
        assert_eq!(cam.x_scale, 8.0);
        // Levels stop widening at MAX_LEVEL while the leaves keep spreading.
        assert_eq!(cam.y_scale, MAX_LEVEL);
        let rect = Rect::from_min_size(pos2(0.0, 0.0), vec2(300.0, 200.0));
        cam.center_on(p, rect);
        assert!((cam.to_screen(p) - rect.center()).length() < 1e-3);
    }
}
