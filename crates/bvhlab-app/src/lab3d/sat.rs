//! The separating-axis test in the 3D view: both boxes (green when an axis separates them,
//! red when they overlap, as in 2D), the candidate axis looked at as a long line beside
//! them, and each box's shadow on it, A's in orange and B's in blue, with dashes from the
//! corners that cast each shadow's ends.

use bvhlab::glam::Vec3;
use bvhlab::{NodeShape, Obb3};
use egui::Color32;

use super::draw::{Dot, Draw3d, rgba};
use super::wire::{self, Segment};
use crate::model::lab3d::Lab3d;
use crate::paint::colors;

/// Box A's shadow.
pub const SHADOW_A: Color32 = Color32::from_rgb(255, 200, 120);
/// Box B's shadow.
pub const SHADOW_B: Color32 = Color32::from_rgb(120, 200, 255);

/// The legend's entries while the test is on.
pub fn legend(lab: &Lab3d) -> Vec<(Color32, &'static str)> {
    let Some(pair) = &lab.obb_pair else {
        return Vec::new();
    };
    let boxes = if pair.separating().is_some() {
        (colors::VISITED, "boxes apart")
    } else {
        (colors::CULLED, "boxes overlap")
    };
    vec![boxes, (SHADOW_A, "A's shadow"), (SHADOW_B, "B's shadow")]
}

/// Adds the boxes, the axis looked at and the shadows to `d`.
pub(super) fn draw_sat(lab: &Lab3d, d: &mut Draw3d) {
    let Some(pair) = &lab.obb_pair else { return };
    let color = if pair.separating().is_some() {
        colors::VISITED
    } else {
        colors::CULLED
    };
    let (a, b) = (pair.a.obb(), pair.b.obb());
    for obb in [&a, &b] {
        wire::shape(&NodeShape::Obb(*obb), rgba(color, 1.0), 2.0, &mut d.overlay);
    }
    let Some(test) = pair.tests()[pair.step] else {
        return;
    };
    let axis = test.axis;
    // The line runs just below both boxes (below as the camera sees it), so the shadows do
    // not fall on the boxes: its point at parameter s projects to s on the axis.
    let mid = (a.center + b.center) * 0.5;
    let up = lab.camera.basis().up;
    let across = (up - axis * up.dot(axis))
        .try_normalize()
        .unwrap_or_else(|| axis.any_orthonormal_vector());
    let below = [&a, &b]
        .iter()
        .map(|o| (o.center - mid).dot(across).abs() + radius_along(o, across))
        .fold(0.0_f32, f32::max);
    let base = mid - axis * axis.dot(mid) - across * below * 1.15;
    let at = |s: f32| base + axis * s;
    let (lo, hi) = (
        test.interval_a.0.min(test.interval_b.0),
        test.interval_a.1.max(test.interval_b.1),
    );
    let margin = (hi - lo) * 0.15;
    d.overlay.push(Segment {
        a: at(lo - margin),
        b: at(hi + margin),
        color: rgba(Color32::GRAY, 1.0),
        width: 1.5,
    });
    for (obb, (lo, hi), shade, shift) in [
        (&a, test.interval_a, SHADOW_A, 0.03),
        (&b, test.interval_b, SHADOW_B, -0.03),
    ] {
        let offset = across * below * shift;
        d.overlay.push(Segment {
            a: at(lo) + offset,
            b: at(hi) + offset,
            color: rgba(shade, 1.0),
            width: 5.0,
        });
        for end in [lo, hi] {
            if let Some(corner) = casting_corner(obb, axis, end) {
                dashed(corner, at(end) + offset, rgba(shade, 0.8), d);
            }
        }
    }
    if test.separates() {
        let (gap_from, gap_to) = if test.interval_a.1 < test.interval_b.0 {
            (test.interval_a.1, test.interval_b.0)
        } else {
            (test.interval_b.1, test.interval_a.0)
        };
        for s in [gap_from, gap_to] {
            d.dots.push(Dot {
                at: at(s),
                radius: 4.0,
                color: rgba(colors::VISITED, 1.0),
            });
        }
    }
}

/// Half the box's shadow on the unit vector `dir`.
fn radius_along(obb: &Obb3, dir: Vec3) -> f32 {
    obb.axes
        .iter()
        .zip(obb.half_extents.to_array())
        .map(|(axis, half)| axis.dot(dir).abs() * half)
        .sum()
}

/// The box's corner whose projection on `axis` is `end` (the nearest, for rounding).
fn casting_corner(obb: &Obb3, axis: Vec3, end: f32) -> Option<Vec3> {
    obb.corners().min_by(|p, q| {
        (p.dot(axis) - end)
            .abs()
            .total_cmp(&(q.dot(axis) - end).abs())
    })
}

/// A dashed line from `a` to `b`: 12 dashes.
fn dashed(a: Vec3, b: Vec3, color: [f32; 4], d: &mut Draw3d) {
    const DASHES: usize = 12;
    for k in 0..DASHES {
        let (s, t) = (k as f32 / DASHES as f32, (k as f32 + 0.5) / DASHES as f32);
        d.overlay.push(Segment {
            a: a.lerp(b, s),
            b: a.lerp(b, t),
            color,
            width: 1.0,
        });
    }
}
