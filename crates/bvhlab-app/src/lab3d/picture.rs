//! The 3D view as a flat picture, for SVG export: the mesh's triangles projected by the
//! camera, shaded by how they face the light and drawn back to front (the painter's
//! algorithm), then the structure's lines, the ray, the gizmo and the markers of
//! [`Draw3d`] on top, as egui shapes in screen space. Drawn from the same state as the view,
//! untessellated, so slides get sharp lines. What reaches behind the eye is cut at the near
//! plane, as the GPU cuts it: a ray cast from an earlier eye, a camera inside the mesh.

use bvhlab::glam::{Vec2, Vec3};
use egui::epaint::{Mesh, Vertex, WHITE_UV};
use egui::{Color32, Pos2, Rect, Shape, Stroke};

use super::draw::{self, Draw3d};
use crate::model::lab3d::Lab3d;
use crate::model::orbit_camera::OrbitCamera;
use crate::paint::colors;

/// The most mesh triangles drawn into a picture (an SVG path each: past this the file would
/// be tens of megabytes); a bigger mesh is left out, and the export says so
/// ([`mesh_left_out`]).
pub const MAX_PICTURE_TRIANGLES: usize = 300_000;

/// Why the picture has no mesh, when it has none for its size.
pub fn mesh_left_out(lab: &Lab3d) -> Option<String> {
    let n = lab.triangles().len();
    (n > MAX_PICTURE_TRIANGLES).then(|| {
        format!(
            "the mesh's {} triangles are left out of the SVG (it draws at most {})",
            crate::model::dimension::thousands(n),
            crate::model::dimension::thousands(MAX_PICTURE_TRIANGLES)
        )
    })
}

/// The picture of the whole view (both halves when comparing) in `rect`, with what
/// Predict's question is `asked` about.
pub fn picture(lab: &Lab3d, asked: &crate::model::predict::About, rect: Rect) -> Vec<Shape> {
    let halves = crate::lab2d::halves(rect, lab.half.compare.is_some());
    let mut shapes = Vec::new();
    for (i, half) in halves.iter().enumerate() {
        shapes.push(Shape::rect_filled(*half, 0.0, super::BACKGROUND));
        let projector = Projector::new(&lab.camera, *half);
        mesh(lab, &projector, &mut shapes);
        overlay(
            &draw::draw(lab, i, *half, i == 0, draw::Lit::default(), asked),
            &projector,
            &mut shapes,
        );
    }
    shapes
}

/// The camera's projection into a rectangle of the screen.
struct Projector {
    camera: OrbitCamera,
    rect: Rect,
    eye: Vec3,
    forward: Vec3,
    /// The near plane's distance: what is nearer is not drawn.
    near: f32,
}

impl Projector {
    fn new(camera: &OrbitCamera, rect: Rect) -> Self {
        Self {
            camera: *camera,
            rect,
            eye: camera.eye(),
            forward: camera.basis().forward,
            near: camera.clip_range().0,
        }
    }

    /// The part of the closed polygon `corners` in front of the near plane (Sutherland and
    /// Hodgman's clipping against one plane); empty when none of it is.
    fn in_front(&self, corners: &[Vec3]) -> Vec<Vec3> {
        let depths: Vec<f32> = corners.iter().map(|&p| self.depth(p) - self.near).collect();
        if depths.iter().all(|&d| d >= 0.0) {
            return corners.to_vec();
        }
        let mut out = Vec::with_capacity(corners.len() + 1);
        for i in 0..corners.len() {
            let j = (i + 1) % corners.len();
            let (p, q, dp, dq) = (corners[i], corners[j], depths[i], depths[j]);
            if dp >= 0.0 {
                out.push(p);
            }
            if (dp >= 0.0) != (dq >= 0.0) {
                out.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
        out
    }

    /// The part of the segment `a`–`b` in front of the near plane, if any.
    fn segment_in_front(&self, a: Vec3, b: Vec3) -> Option<(Vec3, Vec3)> {
        let (da, db) = (self.depth(a) - self.near, self.depth(b) - self.near);
        let cut = |p: Vec3, q: Vec3, dp: f32, dq: f32| p + (q - p) * (dp / (dp - dq));
        match (da >= 0.0, db >= 0.0) {
            (true, true) => Some((a, b)),
            (false, false) => None,
            (true, false) => Some((a, cut(a, b, da, db))),
            (false, true) => Some((cut(a, b, da, db), b)),
        }
    }

    /// A point's screen position, or `None` behind the camera.
    fn at(&self, p: Vec3) -> Option<Pos2> {
        let size = Vec2::new(self.rect.width(), self.rect.height());
        let q = self.camera.project(p, size)?;
        Some(self.rect.min + egui::vec2(q.x, q.y))
    }

    /// How far in front of the camera a point is.
    fn depth(&self, p: Vec3) -> f32 {
        (p - self.eye).dot(self.forward)
    }
}

/// The mesh's triangles, back to front, shaded.
fn mesh(lab: &Lab3d, projector: &Projector, shapes: &mut Vec<Shape>) {
    let Some(mesh) = &lab.mesh else { return };
    let triangles = mesh.mesh.triangles();
    if triangles.len() > MAX_PICTURE_TRIANGLES {
        return;
    }
    let light = (projector.forward * -1.0 + Vec3::Y * 0.5).normalize_or_zero();
    let alpha = if lab.display.xray { 0.35 } else { 1.0 };
    let mut placed: Vec<(f32, [Pos2; 3], f32)> = Vec::with_capacity(triangles.len());
    for t in triangles {
        // A triangle reaching behind the eye is cut to a polygon, drawn as a fan.
        let corners = projector.in_front(&[t.a, t.b, t.c]);
        let Some(corners) = corners
            .iter()
            .map(|&p| projector.at(p))
            .collect::<Option<Vec<Pos2>>>()
        else {
            continue;
        };
        let centre = (t.a + t.b + t.c) / 3.0;
        let normal = (t.b - t.a).cross(t.c - t.a).normalize_or_zero();
        let facing = normal.dot(light).abs();
        for i in 1..corners.len().saturating_sub(1) {
            placed.push((
                projector.depth(centre),
                [corners[0], corners[i], corners[i + 1]],
                facing,
            ));
        }
    }
    placed.sort_by(|a, b| b.0.total_cmp(&a.0));
    let base = colors::SCENE;
    let mut out = Mesh::default();
    for (_, corners, facing) in placed {
        let shade = 0.35 + 0.65 * facing;
        let color = Color32::from_rgba_unmultiplied(
            (f32::from(base.r()) * shade) as u8,
            (f32::from(base.g()) * shade) as u8,
            (f32::from(base.b()) * shade) as u8,
            (255.0 * alpha) as u8,
        );
        let first = out.vertices.len() as u32;
        for pos in corners {
            out.vertices.push(Vertex {
                pos,
                uv: WHITE_UV,
                color,
            });
        }
        out.indices.extend([first, first + 1, first + 2]);
    }
    shapes.push(Shape::mesh(out));
}

/// The draw list's lines, polygons and markers.
fn overlay(drawn: &Draw3d, projector: &Projector, shapes: &mut Vec<Shape>) {
    let color = |c: [f32; 4]| {
        Color32::from_rgba_unmultiplied(
            (c[0] * 255.0) as u8,
            (c[1] * 255.0) as u8,
            (c[2] * 255.0) as u8,
            (c[3] * 255.0) as u8,
        )
    };
    for polygon in &drawn.polygons {
        let points: Option<Vec<Pos2>> = projector
            .in_front(&polygon.corners)
            .iter()
            .map(|&p| projector.at(p))
            .collect();
        if let Some(points) = points.filter(|p| p.len() >= 3) {
            shapes.push(Shape::convex_polygon(
                points,
                color(polygon.color),
                Stroke::NONE,
            ));
        }
    }
    for segment in drawn.lines.iter().chain(&drawn.overlay) {
        let Some((a, b)) = projector.segment_in_front(segment.a, segment.b) else {
            continue;
        };
        if let (Some(a), Some(b)) = (projector.at(a), projector.at(b)) {
            shapes.push(Shape::line_segment(
                [a, b],
                Stroke::new(segment.width, color(segment.color)),
            ));
        }
    }
    for dot in &drawn.dots {
        if let Some(at) = projector.at(dot.at) {
            shapes.push(Shape::circle_filled(at, dot.radius, color(dot.color)));
        }
    }
}
