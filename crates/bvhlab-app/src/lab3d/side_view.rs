//! The side view: a small inset in a corner of the 3D view that shows the ray from the side.
//! A clicked ray leaves the eye through the clicked pixel, so the main view sees it end on,
//! as a dot; the inset looks from a camera turned 90° about the up axis (orthographic), where
//! the ray runs across: the mesh's bounding box and a sprinkle of its vertices, the ray from
//! its origin e (or from near the mesh, when the eye is far) to its hit (or to where it
//! leaves the box), and the hit.

use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use egui::{Align2, Color32, FontId, Pos2, Rect, Stroke, vec2};

use crate::model::lab3d::Lab3d;
use crate::model::lane::Lane;
use crate::paint::colors;
use crate::pseudocode::Task;

/// The most mesh vertices sprinkled in the inset.
const VERTEX_CAP: usize = 2_500;

/// Where the inset drew the ray, for tests and the page's report.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideView {
    /// The inset's area on screen.
    pub rect: Rect,
    /// Where the drawn ray starts: its origin, or where it comes within a box's diagonal
    /// of the mesh (marked "from e") when the eye is farther.
    pub origin: Pos2,
    /// Where the drawn ray ends: the hit, or where the ray leaves the mesh's box.
    pub end: Pos2,
    /// The hit, once playback has found it.
    pub hit: Option<Pos2>,
}

/// The side camera's two screen axes in the world: the main camera's forward, levelled
/// (to the right), and the world's up.
fn axes(lab: &Lab3d) -> (Vec3, Vec3) {
    let (sy, cy) = lab.camera.yaw.sin_cos();
    (Vec3::new(-sy, 0.0, -cy), Vec3::Y)
}

/// The inset's area in a view of `rect`: the bottom-right corner, or none when the view is
/// too small to spare one.
pub fn inset_rect(rect: Rect) -> Option<Rect> {
    let width = (rect.width() * 0.34).clamp(120.0, 260.0);
    let height = (width * 0.7).min(rect.height() * 0.4);
    if rect.width() < width * 1.6 || height < 70.0 {
        return None;
    }
    let max = rect.right_bottom() - vec2(10.0, 10.0);
    Some(Rect::from_min_max(max - vec2(width, height), max))
}

/// The part of the ray the inset draws, in the world.
struct Span {
    /// Where the drawn ray starts.
    start: Vec3,
    /// Whether that is the ray's origin (else the eye is far and the ray is cut).
    from_eye: bool,
    /// Where it ends.
    end: Vec3,
    /// The hit, once playback has found it.
    hit: Option<Vec3>,
}

/// The ray from its origin, or from a box's diagonal before the box's centre when the eye is
/// farther (a far eye would shrink the mesh to a speck), to its hit as playback stands, or
/// to where it leaves the box.
fn span(ray: &bvhlab::Ray3, bounds: &bvhlab::Aabb3, best_t: Option<f32>) -> Span {
    let centre = (bounds.min + bounds.max) * 0.5;
    let reach = (bounds.max - bounds.min).length().max(1e-6);
    let unit = ray.dir().normalize_or_zero();
    let to_centre = centre - ray.origin();
    let (start, from_eye) = if to_centre.length() <= reach {
        (ray.origin(), true)
    } else {
        // Where the ray first comes within `reach` of the centre (or passes nearest).
        let along = unit.dot(to_centre);
        let miss = (to_centre.length_squared() - along * along).max(0.0);
        let back = (reach * reach - miss).max(0.0).sqrt();
        (ray.origin() + unit * (along - back).max(0.0), false)
    };
    let hit = best_t.map(|t| ray.at(t));
    let end = hit.unwrap_or_else(|| {
        let exit = bounds.slab_test(ray).interval().map(|(_, exit)| exit);
        let far = to_centre.length() * 1.3 / ray.dir().length().max(1e-12);
        ray.at(exit.unwrap_or(far))
    });
    Span {
        start,
        from_eye,
        end,
        hit,
    }
}

/// The side camera's orthographic projection, fitted to some points inside a rect.
struct Projection {
    right: Vec3,
    up: Vec3,
    mid: (f32, f32),
    scale: f32,
    centre: Pos2,
}

impl Projection {
    /// The projection that fits `points` into `inner` (none if they are degenerate).
    fn fit(lab: &Lab3d, points: &[Vec3], inner: Rect) -> Option<Self> {
        let (right, up) = axes(lab);
        let (mut lo, mut hi) = (
            (f32::INFINITY, f32::INFINITY),
            (f32::NEG_INFINITY, f32::NEG_INFINITY),
        );
        for p in points {
            let (u, v) = (p.dot(right), p.dot(up));
            lo = (lo.0.min(u), lo.1.min(v));
            hi = (hi.0.max(u), hi.1.max(v));
        }
        let span = ((hi.0 - lo.0).max(1e-6), (hi.1 - lo.1).max(1e-6));
        let scale = (inner.width() / span.0).min(inner.height() / span.1);
        scale.is_finite().then_some(Self {
            right,
            up,
            mid: ((lo.0 + hi.0) * 0.5, (lo.1 + hi.1) * 0.5),
            scale,
            centre: inner.center(),
        })
    }

    /// Where `p` is in the inset.
    fn at(&self, p: Vec3) -> Pos2 {
        let (u, v) = (p.dot(self.right), p.dot(self.up));
        self.centre
            + vec2(
                (u - self.mid.0) * self.scale,
                -(v - self.mid.1) * self.scale,
            )
    }
}

/// The eight corners of `b`.
fn corners(b: &bvhlab::Aabb3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        Vec3::new(
            pick(1, b.min.x, b.max.x),
            pick(2, b.min.y, b.max.y),
            pick(4, b.min.z, b.max.z),
        )
    })
}

/// The inset for lane `lane`'s ray in a view of `view`, painted; or none when there is no
/// ray question, no mesh, or no room.
pub fn side_view(
    lab: &Lab3d,
    lane: &Lane<Triangle3>,
    view: Rect,
    painter: &egui::Painter,
) -> Option<SideView> {
    let task = lab.half.task;
    if !matches!(task, Task::FirstHit | Task::AnyHit | Task::AllHits) {
        return None;
    }
    let (ray, mesh) = (lab.ray?, lab.mesh.as_ref()?);
    let rect = inset_rect(view)?;
    let bounds = mesh.bounds();
    let best_t = lane
        .snapshot
        .as_ref()
        .and_then(|s| s.best.first().map(|b| b.1));
    let span = span(&ray, &bounds, best_t);
    let corners = corners(&bounds);
    let mut fitted = corners.to_vec();
    fitted.extend([span.start, span.end]);
    // Room for the title above, and for the label of the ray's start under it.
    let inner = Rect::from_min_max(rect.min + vec2(12.0, 40.0), rect.max - vec2(12.0, 10.0));
    let proj = Projection::fit(lab, &fitted, inner)?;

    painter.rect_filled(rect, 4.0, Color32::from_rgba_unmultiplied(40, 44, 54, 235));
    painter.rect_stroke(
        rect,
        4.0,
        Stroke::new(1.0, Color32::from_gray(110)),
        egui::StrokeKind::Inside,
    );
    let clipped = painter.with_clip_rect(rect);
    let positions = mesh.mesh.positions();
    let stride = positions.len().div_ceil(VERTEX_CAP).max(1);
    let speck = Color32::from_rgba_unmultiplied(200, 200, 210, 110);
    for &p in positions.iter().step_by(stride) {
        clipped.rect_filled(
            Rect::from_center_size(proj.at(p), vec2(1.5, 1.5)),
            0.0,
            speck,
        );
    }
    let edge = Stroke::new(1.0, colors::STRUCTURE);
    for a in 0..8_usize {
        for bit in [1, 2, 4] {
            if a & bit == 0 {
                clipped.line_segment([proj.at(corners[a]), proj.at(corners[a | bit])], edge);
            }
        }
    }
    let (origin, end) = (proj.at(span.start), proj.at(span.end));
    clipped.line_segment([origin, end], Stroke::new(2.0, colors::QUERY));
    if span.from_eye {
        clipped.circle_filled(origin, 3.5, colors::QUERY);
    }
    // Beside the ray's start, on the side the ray leaves free.
    let (offset, align) = if end.y > origin.y {
        (vec2(-2.0, -5.0), Align2::LEFT_BOTTOM)
    } else {
        (vec2(-2.0, 5.0), Align2::LEFT_TOP)
    };
    clipped.text(
        origin + offset,
        align,
        if span.from_eye { "e" } else { "from e" },
        FontId::proportional(crate::theme::SMALLEST_TEXT),
        colors::QUERY,
    );
    let hit = span.hit.map(|h| proj.at(h));
    if let Some(h) = hit {
        clipped.circle_filled(h, 4.5, colors::ANSWER);
    }
    painter.text(
        rect.left_top() + vec2(6.0, 4.0),
        Align2::LEFT_TOP,
        "the ray from the side",
        FontId::proportional(crate::theme::SMALLEST_TEXT),
        Color32::from_gray(220),
    );
    Some(SideView {
        rect,
        origin,
        end,
        hit,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::pos2;

    #[test]
    fn the_inset_fits_in_a_big_view_and_not_in_a_tiny_one() {
        let view = Rect::from_min_size(pos2(100.0, 50.0), vec2(800.0, 600.0));
        let inset = inset_rect(view).expect("room");
        assert!(view.contains_rect(inset));
        assert!(inset.width() >= 120.0);
        assert!(inset_rect(Rect::from_min_size(Pos2::ZERO, vec2(150.0, 90.0))).is_none());
    }
}
