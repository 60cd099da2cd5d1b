//! The canvas transform: world coordinates (y up, as in the lecture's figures) to screen
//! points (y down), with pan and zoom.

use bvhlab::glam::Vec2;
use egui::{Pos2, Rect, pos2};

/// Which part of the world the canvas shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The world point at the canvas centre.
    pub center: Vec2,
    /// Screen points per world unit.
    pub scale: f32,
    /// The canvas rectangle on screen, set each frame.
    pub rect: Rect,
}

impl Default for View {
    fn default() -> Self {
        Self {
            center: Vec2::ZERO,
            scale: 30.0,
            rect: Rect::from_min_size(Pos2::ZERO, egui::vec2(800.0, 600.0)),
        }
    }
}

impl View {
    /// The screen point of a world point.
    pub fn to_screen(&self, p: Vec2) -> Pos2 {
        let c = self.rect.center();
        pos2(
            c.x + (p.x - self.center.x) * self.scale,
            c.y - (p.y - self.center.y) * self.scale,
        )
    }

    /// The world point under a screen point.
    pub fn to_world(&self, p: Pos2) -> Vec2 {
        let c = self.rect.center();
        Vec2::new(
            self.center.x + (p.x - c.x) / self.scale,
            self.center.y - (p.y - c.y) / self.scale,
        )
    }

    /// A world length on screen.
    pub fn screen_length(&self, world: f32) -> f32 {
        world * self.scale
    }

    /// A screen length in world units.
    pub fn world_length(&self, screen: f32) -> f32 {
        screen / self.scale
    }

    /// Moves the view by a screen-space drag.
    pub fn pan(&mut self, screen_delta: egui::Vec2) {
        self.center -= Vec2::new(screen_delta.x, -screen_delta.y) / self.scale;
    }

    /// Zooms by `factor` keeping the world point under `anchor` fixed.
    pub fn zoom_at(&mut self, anchor: Pos2, factor: f32) {
        let before = self.to_world(anchor);
        self.scale = (self.scale * factor).clamp(1e-3, 1e6);
        let after = self.to_world(anchor);
        self.center += before - after;
    }

    /// Frames the world box `[min, max]` in the canvas with a margin.
    pub fn fit(&mut self, min: Vec2, max: Vec2) {
        if !(min.is_finite() && max.is_finite()) || min.cmpgt(max).any() {
            return;
        }
        let size = (max - min).max(Vec2::splat(1e-3));
        let margin = 0.85;
        self.center = (min + max) * 0.5;
        self.scale = (self.rect.width() / size.x)
            .min(self.rect.height() / size.y)
            .max(1e-3)
            * margin;
    }

    /// The world box the canvas shows.
    pub fn visible_world(&self) -> (Vec2, Vec2) {
        let a = self.to_world(self.rect.left_bottom());
        let b = self.to_world(self.rect.right_top());
        (a.min(b), a.max(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_zoom_anchor() {
        let mut view = View {
            rect: Rect::from_min_max(pos2(100.0, 50.0), pos2(900.0, 650.0)),
            ..View::default()
        };
        let p = Vec2::new(3.5, -2.0);
        assert!((view.to_world(view.to_screen(p)) - p).length() < 1e-4);
        let anchor = pos2(300.0, 200.0);
        let under = view.to_world(anchor);
        view.zoom_at(anchor, 2.5);
        assert!((view.to_world(anchor) - under).length() < 1e-4);
        // y is up in the world, down on screen.
        assert!(view.to_screen(Vec2::new(0.0, 1.0)).y < view.to_screen(Vec2::ZERO).y);
    }

    #[test]
    fn fit_shows_the_box() {
        let mut view = View::default();
        view.fit(Vec2::new(-10.0, 0.0), Vec2::new(30.0, 5.0));
        let (lo, hi) = view.visible_world();
        assert!(lo.x <= -10.0 && hi.x >= 30.0 && lo.y <= 0.0 && hi.y >= 5.0);
    }
}
