//! Drawing world-space geometry on the canvas through the canvas's [`Screen`], and the lab's colours.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, NodeShape, Obb2, Sphere2};
use egui::{Color32, Shape, Stroke};

use crate::lab2d::Screen;

/// The lab's palette, one meaning per colour.
pub mod colors {
    use egui::Color32;

    /// Scene shapes.
    pub const SCENE: Color32 = Color32::from_rgb(200, 200, 210);
    /// Selected shapes.
    pub const SELECTED: Color32 = Color32::from_rgb(255, 210, 80);
    /// Rays and query points.
    pub const QUERY: Color32 = Color32::from_rgb(80, 220, 255);
    /// Hits and closest points.
    pub const ANSWER: Color32 = Color32::from_rgb(255, 70, 200);
    /// Nodes a query went into.
    pub const VISITED: Color32 = Color32::from_rgb(90, 230, 120);
    /// Nodes whose bounding volume the query missed.
    pub const CULLED: Color32 = Color32::from_rgb(240, 90, 70);
    /// Nodes skipped by branch and bound.
    pub const PRUNED: Color32 = Color32::from_rgb(250, 160, 40);
    /// Structure outlines not touched by the query.
    pub const STRUCTURE: Color32 = Color32::from_rgba_premultiplied(110, 130, 190, 150);
    /// The splitting planes (lines in 2D) of a k-d tree, quadtree or BSP tree: a saturated
    /// blue, drawn dashed ([`SPLIT_DASH`](super::SPLIT_DASH)), so that they are told from
    /// the scene's solid grey segments by their pattern as well as their colour.
    pub const SPLIT: Color32 = Color32::from_rgb(64, 128, 255);
    /// Primitives the query tested exactly.
    pub const TESTED: Color32 = Color32::from_rgb(255, 140, 0);
    /// The node the playback is at.
    pub const CURRENT: Color32 = Color32::from_rgb(255, 255, 255);
    /// Nodes waiting on the traversal stack or queue.
    pub const WAITING: Color32 = Color32::from_rgb(150, 120, 255);
    /// A build's current node: primitives going to its first child.
    pub const FIRST_SIDE: Color32 = Color32::from_rgb(90, 200, 255);
    /// ... and to its second child.
    pub const SECOND_SIDE: Color32 = Color32::from_rgb(255, 120, 170);
    /// The x slab.
    pub const SLAB_X: Color32 = Color32::from_rgb(255, 100, 100);
    /// The y slab.
    pub const SLAB_Y: Color32 = Color32::from_rgb(110, 160, 255);
    /// The z slab (3D).
    pub const SLAB_Z: Color32 = Color32::from_rgb(120, 230, 120);
    /// What Predict's question waiting is about: pale yellow, always beside its number and a
    /// question mark ("node 3?"), so that it is not told by colour alone.
    pub const ASKED: Color32 = Color32::from_rgb(255, 250, 130);

    /// Each of §2's bounding volumes: its outline on the canvas, its swatch in the table and
    /// its legend entry. No two volumes share a colour, and none is the tree's boxes' blue
    /// ([`STRUCTURE`]), the selection's yellow ([`SELECTED`]) or the ray's cyan ([`QUERY`]).
    pub fn volume(kind: bvhlab::FitKind) -> Color32 {
        use bvhlab::FitKind;
        match kind {
            // Orange: the lecture's sphere.
            FitKind::SphereCentroid => Color32::from_rgb(255, 130, 30),
            // Pink.
            FitKind::SphereRitter => Color32::from_rgb(255, 120, 210),
            // White: the minimal sphere.
            FitKind::SphereWelzl => Color32::from_rgb(245, 245, 245),
            // Teal.
            FitKind::Aabb => Color32::from_rgb(0, 205, 160),
            // Lime.
            FitKind::Obb => Color32::from_rgb(165, 235, 60),
            // Violet.
            FitKind::ConvexHull => Color32::from_rgb(185, 130, 255),
        }
    }

    /// A volume's short name in the canvas's legend.
    pub fn volume_name(kind: bvhlab::FitKind) -> &'static str {
        use bvhlab::FitKind;
        match kind {
            FitKind::SphereCentroid => "centroid sphere",
            FitKind::SphereRitter => "Ritter sphere",
            FitKind::SphereWelzl => "Welzl sphere",
            FitKind::Aabb => "AABB",
            FitKind::Obb => "OBB (PCA)",
            FitKind::ConvexHull => "convex hull",
        }
    }
}

/// The split planes' dashes and gaps, in screen points.
pub const SPLIT_DASH: (f32, f32) = (6.0, 4.0);

/// What the legend names a space partition's splitting planes (lines in 2D).
pub const SPLIT_NAME: &str = "split plane (dashed)";

/// Turns world geometry into egui shapes in screen space, collected so that the caller can
/// paint them now or tessellate them once and reuse the mesh (see `lab2d::layer`).
pub struct WorldPainter<'a> {
    /// The transform.
    pub screen: &'a Screen,
    /// The shapes so far, in painting order.
    pub shapes: Vec<Shape>,
}

impl<'a> WorldPainter<'a> {
    /// A painter with no shapes yet.
    pub fn new(screen: &'a Screen) -> Self {
        Self {
            screen,
            shapes: Vec::new(),
        }
    }

    /// Adds a screen-space shape.
    pub fn add(&mut self, shape: impl Into<Shape>) {
        self.shapes.push(shape.into());
    }

    /// A segment.
    pub fn line(&mut self, a: Vec2, b: Vec2, stroke: Stroke) {
        let seg = Shape::line_segment([self.screen.to_screen(a), self.screen.to_screen(b)], stroke);
        self.add(seg);
    }

    /// A dashed segment: dashes and gaps of [`SPLIT_DASH`] screen points.
    pub fn dashed_line(&mut self, a: Vec2, b: Vec2, stroke: Stroke) {
        let ends = [self.screen.to_screen(a), self.screen.to_screen(b)];
        let (dash, gap) = SPLIT_DASH;
        self.add(Shape::Vec(Shape::dashed_line(&ends, stroke, dash, gap)));
    }

    /// A dot of `radius` screen points.
    pub fn dot(&mut self, p: Vec2, radius: f32, color: Color32) {
        let dot = Shape::circle_filled(self.screen.to_screen(p), radius, color);
        self.add(dot);
    }

    /// A closed polygon's outline.
    pub fn polygon(&mut self, points: &[Vec2], stroke: Stroke) {
        let pts = points.iter().map(|&p| self.screen.to_screen(p)).collect();
        self.add(Shape::closed_line(pts, stroke));
    }

    /// A filled convex polygon.
    pub fn convex_fill(&mut self, points: &[Vec2], fill: Color32) {
        let pts = points.iter().map(|&p| self.screen.to_screen(p)).collect();
        self.add(Shape::convex_polygon(pts, fill, Stroke::NONE));
    }

    /// An axis-aligned box.
    pub fn aabb(&mut self, b: &Aabb2, stroke: Stroke) {
        if !(b.min.is_finite() && b.max.is_finite()) {
            return;
        }
        let rect =
            egui::Rect::from_two_pos(self.screen.to_screen(b.min), self.screen.to_screen(b.max));
        self.add(Shape::rect_stroke(
            rect,
            0.0,
            stroke,
            egui::StrokeKind::Middle,
        ));
    }

    /// An axis-aligned box, filled.
    pub fn aabb_fill(&mut self, b: &Aabb2, fill: Color32) {
        if !(b.min.is_finite() && b.max.is_finite()) {
            return;
        }
        let rect =
            egui::Rect::from_two_pos(self.screen.to_screen(b.min), self.screen.to_screen(b.max));
        self.add(Shape::rect_filled(rect, 0.0, fill));
    }

    /// A circle.
    pub fn sphere(&mut self, s: &Sphere2, stroke: Stroke) {
        if s.center.is_finite() && s.radius.is_finite() && s.radius >= 0.0 {
            let circle = Shape::circle_stroke(
                self.screen.to_screen(s.center),
                self.screen.screen_length(s.radius),
                stroke,
            );
            self.add(circle);
        }
    }

    /// An oriented box.
    pub fn obb(&mut self, o: &Obb2, stroke: Stroke) {
        let corners = obb_corners(o);
        if corners.iter().all(|c| c.is_finite()) {
            self.polygon(&corners, stroke);
        }
    }

    /// A node's shape.
    pub fn node_shape(&mut self, shape: &NodeShape<Vec2>, stroke: Stroke) {
        match shape {
            NodeShape::Aabb(b) => self.aabb(b, stroke),
            NodeShape::Sphere(s) => self.sphere(s, stroke),
            NodeShape::Obb(o) => self.obb(o, stroke),
        }
    }

    /// A node's shape, filled (boxes and oriented boxes; circles as a disc).
    pub fn node_fill(&mut self, shape: &NodeShape<Vec2>, fill: Color32) {
        match shape {
            NodeShape::Aabb(b) => self.aabb_fill(b, fill),
            NodeShape::Sphere(s) => {
                if s.center.is_finite() && s.radius.is_finite() {
                    let disc = Shape::circle_filled(
                        self.screen.to_screen(s.center),
                        self.screen.screen_length(s.radius),
                        fill,
                    );
                    self.add(disc);
                }
            }
            NodeShape::Obb(o) => self.convex_fill(&obb_corners(o), fill),
        }
    }

    /// A circle of `radius` screen points around a world point.
    pub fn ring(&mut self, center: Vec2, radius: f32, stroke: Stroke) {
        let ring = Shape::circle_stroke(self.screen.to_screen(center), radius, stroke);
        self.add(ring);
    }

    /// Text at a world point (needs the fonts, so only for shapes painted directly).
    pub fn text(&mut self, fonts: &egui::Painter, at: Vec2, text: &str, color: Color32) {
        let galley = fonts.layout_no_wrap(text.to_owned(), egui::FontId::proportional(13.0), color);
        let pos = self.screen.to_screen(at) - egui::vec2(0.0, galley.size().y);
        self.add(Shape::galley(pos, galley, color));
    }
}

/// An oriented box's corners in order around it.
pub fn obb_corners(o: &Obb2) -> [Vec2; 4] {
    let [u, v] = o.axes;
    let (hu, hv) = (u * o.half_extents.x, v * o.half_extents.y);
    [
        o.center - hu - hv,
        o.center + hu - hv,
        o.center + hu + hv,
        o.center - hu + hv,
    ]
}

/// The part of the line `normal · x = offset` inside `bounds`, clipped further to the
/// half-planes `clip` (each `(normal, offset, keep_above)`): a BSP split drawn only across
/// its own region.
pub fn clipped_plane(
    normal: Vec2,
    offset: f32,
    bounds: &Aabb2,
    clip: &[(Vec2, f32, bool)],
) -> Option<(Vec2, Vec2)> {
    if normal.length_squared() == 0.0 || !bounds.min.is_finite() || !bounds.max.is_finite() {
        return None;
    }
    let n = normal.normalize();
    let base = n * (offset / normal.length());
    let dir = n.perp();
    let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
    // Clip against the box's four sides, then the ancestors' half-planes.
    let mut planes: Vec<(Vec2, f32, bool)> = vec![
        (Vec2::X, bounds.min.x, true),
        (Vec2::X, bounds.max.x, false),
        (Vec2::Y, bounds.min.y, true),
        (Vec2::Y, bounds.max.y, false),
    ];
    planes.extend_from_slice(clip);
    for (m, d, above) in planes {
        // Points base + s dir with m·x >= d (above) or <= d (below).
        let (rate, value) = (m.dot(dir), m.dot(base) - d);
        let sign = if above { 1.0 } else { -1.0 };
        let (rate, value) = (rate * sign, value * sign);
        if rate.abs() < 1e-12 {
            if value < -1e-6 * (1.0 + d.abs()) {
                return None;
            }
            continue;
        }
        let s = -value / rate;
        if rate > 0.0 {
            lo = lo.max(s);
        } else {
            hi = hi.min(s);
        }
    }
    (lo < hi && lo.is_finite() && hi.is_finite()).then(|| (base + dir * lo, base + dir * hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_clip_to_their_region() {
        let bounds = Aabb2::new(Vec2::ZERO, Vec2::splat(10.0));
        let (a, b) = clipped_plane(Vec2::X, 4.0, &bounds, &[]).expect("crosses the box");
        assert!((a.x - 4.0).abs() < 1e-5 && (b.x - 4.0).abs() < 1e-5);
        assert!((a.y - b.y).abs() > 9.99);
        // Keep only y >= 6: the line x = 4 is cut to y in [6, 10].
        let (a, b) =
            clipped_plane(Vec2::X, 4.0, &bounds, &[(Vec2::Y, 6.0, true)]).expect("still crosses");
        assert!((a.y.min(b.y) - 6.0).abs() < 1e-4, "{a} {b}");
        assert!(clipped_plane(Vec2::X, 40.0, &bounds, &[]).is_none());
    }
}
