//! Shapes as the 3D view draws them: boxes and oriented boxes as their twelve edges, spheres
//! as three great circles, and a splitting plane as the polygon where it cuts its node's box.

use bvhlab::glam::Vec3;
use bvhlab::{Aabb3, NodeShape, SplitPlane};

/// A segment to draw: its ends, colour (gamma-space RGBA, as egui's) and width in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// One end.
    pub a: Vec3,
    /// The other end.
    pub b: Vec3,
    /// Its colour.
    pub color: [f32; 4],
    /// Its width on screen, in points.
    pub width: f32,
}

/// The edges of the box with these eight corners, in binary order (bit `i` set means the
/// upper side along axis `i`, as the core's `corners()`): pairs that differ in one bit.
fn box_edges(corners: &[Vec3; 8], color: [f32; 4], width: f32, out: &mut Vec<Segment>) {
    for i in 0..8usize {
        for bit in 0..3 {
            let j = i | (1 << bit);
            if j != i {
                out.push(Segment {
                    a: corners[i],
                    b: corners[j],
                    color,
                    width,
                });
            }
        }
    }
}

/// How many segments a circle is drawn with.
const CIRCLE_SEGMENTS: usize = 40;

/// A circle of `radius` about `center` in the plane spanned by the unit vectors `u`, `v`.
pub fn circle(
    center: Vec3,
    radius: f32,
    (u, v): (Vec3, Vec3),
    color: [f32; 4],
    width: f32,
    out: &mut Vec<Segment>,
) {
    let at = |k: usize| {
        let angle = k as f32 / CIRCLE_SEGMENTS as f32 * std::f32::consts::TAU;
        center + (u * angle.cos() + v * angle.sin()) * radius
    };
    for k in 0..CIRCLE_SEGMENTS {
        out.push(Segment {
            a: at(k),
            b: at(k + 1),
            color,
            width,
        });
    }
}

/// A node's volume as segments.
pub fn shape(shape: &NodeShape<Vec3>, color: [f32; 4], width: f32, out: &mut Vec<Segment>) {
    match shape {
        NodeShape::Aabb(b) => {
            let corners: Vec<Vec3> = b.corners().collect();
            if let Ok(corners) = <[Vec3; 8]>::try_from(corners) {
                box_edges(&corners, color, width, out);
            }
        }
        NodeShape::Obb(o) => {
            let corners: Vec<Vec3> = o.corners().collect();
            if let Ok(corners) = <[Vec3; 8]>::try_from(corners) {
                box_edges(&corners, color, width, out);
            }
        }
        NodeShape::Sphere(s) => {
            if s.radius.is_finite() && s.radius >= 0.0 {
                for plane in [(Vec3::X, Vec3::Y), (Vec3::Y, Vec3::Z), (Vec3::Z, Vec3::X)] {
                    circle(s.center, s.radius, plane, color, width, out);
                }
            }
        }
    }
}

/// The polygon where the plane cuts `bounds`, corners in order around it (empty when the
/// plane misses the box): the points where it crosses the box's twelve edges, sorted by
/// angle about their centroid.
pub fn plane_in_box(plane: &SplitPlane<Vec3>, bounds: &Aabb3) -> Vec<Vec3> {
    let corners: Vec<Vec3> = bounds.corners().collect();
    if corners.len() != 8 {
        return Vec::new();
    }
    let side = |p: Vec3| plane.normal.dot(p) - plane.offset;
    let mut points: Vec<Vec3> = Vec::new();
    for i in 0..8usize {
        for bit in 0..3 {
            let j = i | (1 << bit);
            if j == i {
                continue;
            }
            let (a, b) = (corners[i], corners[j]);
            let (da, db) = (side(a), side(b));
            if (da <= 0.0 && db >= 0.0) || (da >= 0.0 && db <= 0.0) {
                let t = if (da - db).abs() > 0.0 {
                    da / (da - db)
                } else {
                    0.0
                };
                let p = a + (b - a) * t.clamp(0.0, 1.0);
                if !points.iter().any(|q| (*q - p).length_squared() < 1e-12) {
                    points.push(p);
                }
            }
        }
    }
    if points.len() < 3 {
        return Vec::new();
    }
    let centroid = points.iter().copied().sum::<Vec3>() / points.len() as f32;
    let n = plane.normal.normalize_or_zero();
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    points.sort_by(|p, q| {
        let angle = |x: &Vec3| (*x - centroid).dot(v).atan2((*x - centroid).dot(u));
        angle(p).total_cmp(&angle(q))
    });
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::Aabb3;

    #[test]
    fn a_box_has_twelve_edges_each_along_one_axis() {
        let b = Aabb3::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
        let mut out = Vec::new();
        shape(&NodeShape::Aabb(b), [1.0; 4], 1.0, &mut out);
        assert_eq!(out.len(), 12);
        for s in &out {
            let d = (s.b - s.a).abs();
            assert_eq!(
                [d.x, d.y, d.z].iter().filter(|c| **c > 0.0).count(),
                1,
                "{s:?}"
            );
        }
    }

    #[test]
    fn a_plane_through_a_box_gives_a_convex_polygon_on_the_plane() {
        let b = Aabb3::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let axis = SplitPlane {
            normal: Vec3::Y,
            offset: 0.25,
        };
        let square = plane_in_box(&axis, &b);
        assert_eq!(square.len(), 4);
        assert!(square.iter().all(|p| (p.y - 0.25).abs() < 1e-6));
        let tilted = SplitPlane {
            normal: Vec3::ONE.normalize(),
            offset: 0.0,
        };
        let hexagon = plane_in_box(&tilted, &b);
        assert_eq!(hexagon.len(), 6);
        // In order around: consecutive edges turn the same way.
        let n = tilted.normal;
        for i in 0..6 {
            let (a, b, c) = (hexagon[i], hexagon[(i + 1) % 6], hexagon[(i + 2) % 6]);
            assert!((b - a).cross(c - b).dot(n) > 0.0);
        }
        let miss = SplitPlane {
            normal: Vec3::X,
            offset: 5.0,
        };
        assert!(plane_in_box(&miss, &b).is_empty());
    }
}
