//! The canvas transform: world coordinates (y up, as in the lecture's figures) to screen
//! points (y down), from the model's pan and zoom ([`Camera2d`]) and the canvas's rectangle
//! this frame.

use bvhlab::glam::Vec2;
use egui::{Pos2, Rect, pos2};

use crate::model::camera2d::{Camera2d, MAX_SCALE, MIN_SCALE};

/// Where the world is on screen: the camera, and the rectangle it fills.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screen {
    /// The world point at the centre and the zoom.
    pub camera: Camera2d,
    /// The canvas (or one half of it, when comparing) on screen.
    pub rect: Rect,
}

impl Screen {
    /// The screen point of a world point.
    pub fn to_screen(&self, p: Vec2) -> Pos2 {
        let c = self.rect.center();
        let Camera2d { center, scale } = self.camera;
        pos2(
            c.x + (p.x - center.x) * scale,
            c.y - (p.y - center.y) * scale,
        )
    }

    /// The world point under a screen point.
    pub fn to_world(&self, p: Pos2) -> Vec2 {
        let c = self.rect.center();
        let Camera2d { center, scale } = self.camera;
        Vec2::new(
            center.x + (p.x - c.x) / scale,
            center.y - (p.y - c.y) / scale,
        )
    }

    /// A world length on screen.
    pub fn screen_length(&self, world: f32) -> f32 {
        self.camera.screen_length(world)
    }

    /// A screen length in world units.
    pub fn world_length(&self, screen: f32) -> f32 {
        self.camera.world_length(screen)
    }

    /// The camera moved by a screen-space drag.
    pub fn panned(&self, screen_delta: egui::Vec2) -> Camera2d {
        let mut camera = self.camera;
        camera.center -= Vec2::new(screen_delta.x, -screen_delta.y) / camera.scale;
        camera
    }

    /// The camera zoomed by `factor`, keeping the world point under `anchor` fixed.
    pub fn zoomed_at(&self, anchor: Pos2, factor: f32) -> Camera2d {
        let before = self.to_world(anchor);
        let mut zoomed = *self;
        zoomed.camera.scale = (self.camera.scale * factor).clamp(MIN_SCALE, MAX_SCALE);
        let after = zoomed.to_world(anchor);
        zoomed.camera.center += before - after;
        zoomed.camera
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
        let mut screen = Screen {
            camera: Camera2d::default(),
            rect: Rect::from_min_max(pos2(100.0, 50.0), pos2(900.0, 650.0)),
        };
        let p = Vec2::new(3.5, -2.0);
        assert!((screen.to_world(screen.to_screen(p)) - p).length() < 1e-4);
        let anchor = pos2(300.0, 200.0);
        let under = screen.to_world(anchor);
        screen.camera = screen.zoomed_at(anchor, 2.5);
        assert!((screen.to_world(anchor) - under).length() < 1e-4);
        // y is up in the world, down on screen.
        assert!(screen.to_screen(Vec2::new(0.0, 1.0)).y < screen.to_screen(Vec2::ZERO).y);
    }

    #[test]
    fn framing_shows_the_box() {
        let rect = Rect::from_min_size(Pos2::ZERO, egui::vec2(800.0, 600.0));
        let camera = Camera2d::framing(
            Vec2::new(-10.0, 0.0),
            Vec2::new(30.0, 5.0),
            Vec2::new(rect.width(), rect.height()),
        )
        .expect("a box");
        let (lo, hi) = Screen { camera, rect }.visible_world();
        assert!(lo.x <= -10.0 && hi.x >= 30.0 && lo.y <= 0.0 && hi.y >= 5.0);
    }
}
