//! Lecture §2 in the 3D view: the bounding volumes of the mesh or of the brush's part (the
//! one pointed at in the §2 table lit), the part's triangles, and the slab test of the ray
//! against the part's AABB, one colour per axis.

use std::collections::HashSet;

use bvhlab::glam::Vec3;
use bvhlab::{Aabb3, BoundingVolume, FitKind, NodeShape, Ray3};

use super::draw::{Dot, Draw3d, Polygon, rgba};
use super::wire::{self, Segment};
use crate::model::lab3d::Lab3d;
use crate::model::volumes::{Fits, SlabExplain};
use crate::model::volumes3d::Part3d;
use crate::paint::colors;

/// The most triangles of the brush's part lit.
const PART_TRIANGLE_CAP: usize = 200_000;

/// The slab colours, x, y and z.
pub const SLAB_COLORS: [egui::Color32; 3] = [colors::SLAB_X, colors::SLAB_Y, colors::SLAB_Z];

/// The legend's entries for what `draw_volumes` draws: the brush's part, the volumes
/// switched on, and the three slabs.
pub fn legend(lab: &Lab3d) -> Vec<(egui::Color32, &'static str)> {
    let Some(part) = lab.part_fits() else {
        return Vec::new();
    };
    let mut all = Vec::new();
    if lab.volumes.part == Part3d::Brush {
        all.push((colors::SELECTED, "brushed triangles"));
    }
    if part.fits.is_some() {
        all.extend(
            FitKind::ALL
                .into_iter()
                .filter(|&k| lab.volumes.toggles.has(k))
                .map(|k| (colors::volume(k), colors::volume_name(k))),
        );
        if lab.volumes.slab_test && lab.ray.is_some() {
            all.extend(SLAB_COLORS.into_iter().zip(["x slab", "y slab", "z slab"]));
        }
    }
    all
}

/// Adds the volumes switched on (and the one `highlight`ed, whether on or not), the brush's
/// triangles and the slab test to `d`, while the volumes are shown.
pub(super) fn draw_volumes(lab: &Lab3d, highlight: Option<FitKind>, d: &mut Draw3d) {
    let Some(part) = lab.part_fits() else { return };
    if lab.volumes.part == Part3d::Brush {
        let lit = rgba(colors::SELECTED, 0.85);
        d.highlights.extend(
            part.triangles
                .iter()
                .take(PART_TRIANGLE_CAP)
                .map(|&t| (t, lit)),
        );
    }
    let Some(fits) = &part.fits else { return };
    let facing = {
        let basis = lab.camera.basis();
        (basis.right, basis.up)
    };
    for kind in FitKind::ALL {
        let lit = highlight == Some(kind);
        if !(lit || lab.volumes.toggles.has(kind)) {
            continue;
        }
        let (color, width) = (
            rgba(colors::volume(kind), 0.95),
            if lit { 4.0 } else { 1.6 },
        );
        match kind {
            FitKind::SphereCentroid | FitKind::SphereRitter | FitKind::SphereWelzl => {
                if let Some(s) = fits.sphere(kind).filter(|s| s.radius.is_finite()) {
                    // The outline as the camera sees it, and the equator for depth.
                    wire::circle(s.center, s.radius, facing, color, width, &mut d.overlay);
                    let faint = rgba(colors::volume(kind), 0.45);
                    wire::circle(
                        s.center,
                        s.radius,
                        (Vec3::X, Vec3::Z),
                        faint,
                        1.0,
                        &mut d.lines,
                    );
                    d.dots.push(Dot {
                        at: s.center,
                        radius: 3.5,
                        color,
                    });
                }
            }
            FitKind::Aabb => wire::shape(&NodeShape::Aabb(fits.aabb), color, width, &mut d.overlay),
            FitKind::Obb => obb(fits, color, width, d),
            // Faint: a mesh's hull has hundreds of edges.
            FitKind::ConvexHull => hull(
                fits,
                rgba(colors::volume(kind), if lit { 0.95 } else { 0.4 }),
                if lit { 2.5 } else { 1.0 },
                d,
            ),
        }
    }
    if lab.volumes.slab_test
        && let Some(ray) = &lab.ray
    {
        slab_test(&fits.aabb, ray, d);
    }
}

/// The PCA box, and its three principal axes from the mean, each as long as the standard
/// deviation along it (as in 2D).
fn obb(fits: &Fits<Vec3>, color: [f32; 4], width: f32, d: &mut Draw3d) {
    wire::shape(&NodeShape::Obb(fits.obb), color, width, &mut d.overlay);
    let pca = &fits.pca;
    for (axis, var) in pca.axes.iter().zip(pca.variances.to_array()) {
        let len = var.max(0.0).sqrt();
        d.overlay.push(Segment {
            a: pca.mean - *axis * len,
            b: pca.mean + *axis * len,
            color,
            width: width.max(2.0),
        });
    }
}

/// The hull's edges, each once (two facets share each).
fn hull(fits: &Fits<Vec3>, color: [f32; 4], width: f32, d: &mut Draw3d) {
    let mut seen = HashSet::new();
    for facet in fits.hull.facets() {
        let (a, b, c) = (facet.a, facet.b, facet.c);
        for (p, q) in [(a, b), (b, c), (c, a)] {
            let key = {
                let (p, q) = (
                    p.to_array().map(f32::to_bits),
                    q.to_array().map(f32::to_bits),
                );
                if p <= q { (p, q) } else { (q, p) }
            };
            if seen.insert(key) {
                d.lines.push(Segment {
                    a: p,
                    b: q,
                    color,
                    width,
                });
            }
        }
    }
}

/// The slab test in the view: each axis's two planes as the box's faces, tinted in the
/// axis's colour; where the ray enters and leaves each slab, as dots of that colour; and
/// the part of the ray inside every slab at once (the box), in the answer's colour.
fn slab_test(aabb: &Aabb3, ray: &Ray3, d: &mut Draw3d) {
    if aabb.is_empty() {
        return;
    }
    let explain = SlabExplain::new(aabb, ray);
    for (axis, a) in explain.axes.iter().enumerate() {
        let color = SLAB_COLORS[axis];
        for plane in [a.lo, a.hi] {
            d.polygons.push(Polygon {
                corners: face(aabb, axis, plane),
                color: rgba(color, 0.08),
            });
        }
        for t in [a.t_min, a.t_max] {
            if t.is_finite() && t >= 0.0 {
                d.dots.push(Dot {
                    at: ray.at(t),
                    radius: 5.0,
                    color: rgba(color, 1.0),
                });
            }
        }
    }
    if explain.hits() && explain.t_exit.is_finite() {
        d.overlay.push(Segment {
            a: ray.at(explain.t_enter),
            b: ray.at(explain.t_exit),
            color: rgba(colors::ANSWER, 1.0),
            width: 5.0,
        });
    }
}

/// The box's face on the plane `coordinate[axis] = plane`, corners in order around it.
fn face(aabb: &Aabb3, axis: usize, plane: f32) -> Vec<Vec3> {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    [(0, 0), (1, 0), (1, 1), (0, 1)]
        .into_iter()
        .map(|(i, j)| {
            let mut p = Vec3::ZERO;
            p[axis] = plane;
            p[u] = if i == 0 { aabb.min[u] } else { aabb.max[u] };
            p[v] = if j == 0 { aabb.min[v] } else { aabb.max[v] };
            p
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_face_lies_on_its_plane_and_spans_the_box() {
        let aabb = Aabb3::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
        for axis in 0..3 {
            let corners = face(&aabb, axis, aabb.max[axis]);
            assert_eq!(corners.len(), 4);
            assert!(corners.iter().all(|c| c[axis] == aabb.max[axis]));
            let spanned = Aabb3::from_points(&corners);
            for other in (0..3).filter(|&o| o != axis) {
                assert_eq!(
                    (spanned.min[other], spanned.max[other]),
                    (aabb.min[other], aabb.max[other])
                );
            }
        }
    }
}
