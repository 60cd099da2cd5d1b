//! Which part of the 2D world the canvas shows: the world point at its centre and the zoom.
//! The canvas turns this into screen coordinates with its rectangle
//! ([`crate::lab2d::Screen`]); the model keeps only what is saved and shared.

use bvhlab::glam::Vec2;

/// The canvas's pan and zoom (world coordinates have y up, as in the lecture's figures).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera2d {
    /// The world point at the canvas centre.
    pub center: Vec2,
    /// Screen points per world unit.
    pub scale: f32,
}

/// The zoom range, in screen points per world unit.
pub const MIN_SCALE: f32 = 1e-3;
/// See [`MIN_SCALE`].
pub const MAX_SCALE: f32 = 1e6;

impl Default for Camera2d {
    fn default() -> Self {
        Self {
            center: Vec2::ZERO,
            scale: 30.0,
        }
    }
}

impl Camera2d {
    /// The camera that frames the world box `[min, max]` in a canvas of `size` points, with
    /// a margin; `None` for an empty or non-finite box or canvas.
    pub fn framing(min: Vec2, max: Vec2, size: Vec2) -> Option<Self> {
        if !(min.is_finite() && max.is_finite() && size.is_finite())
            || min.cmpgt(max).any()
            || size.min_element() <= 0.0
        {
            return None;
        }
        let extent = (max - min).max(Vec2::splat(1e-3));
        let margin = 0.85;
        Some(Self {
            center: (min + max) * 0.5,
            scale: ((size.x / extent.x).min(size.y / extent.y) * margin)
                .clamp(MIN_SCALE, MAX_SCALE),
        })
    }

    /// A world length as screen points.
    pub fn screen_length(&self, world: f32) -> f32 {
        world * self.scale
    }

    /// A screen length in world units.
    pub fn world_length(&self, screen: f32) -> f32 {
        screen / self.scale
    }

    /// Whether the camera can be shown: a finite centre and a zoom in range.
    pub fn is_valid(&self) -> bool {
        self.center.is_finite() && (MIN_SCALE..=MAX_SCALE).contains(&self.scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_shows_the_box() {
        let c = Camera2d::framing(
            Vec2::new(-10.0, 0.0),
            Vec2::new(30.0, 5.0),
            Vec2::new(800.0, 600.0),
        )
        .expect("a box");
        let half = Vec2::new(400.0, 300.0) / c.scale;
        assert!(c.center.x - half.x <= -10.0 && c.center.x + half.x >= 30.0);
        assert!(c.center.y - half.y <= 0.0 && c.center.y + half.y >= 5.0);
        assert_eq!(
            Camera2d::framing(Vec2::ONE, Vec2::ZERO, Vec2::splat(100.0)),
            None
        );
    }
}
