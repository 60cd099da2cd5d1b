//! Lecture §2 on the canvas: the selection's bounding volumes (the one hovered in the
//! bounding volumes table lit), the slab test of the ray against their AABB, and the two
//! boxes of the separating-axis demo.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, FitKind, NodeShape, Ray2};
use egui::{Color32, Stroke};

use super::draw::visible_end;
use crate::model::lab2d::Lab2d;
use crate::model::volumes::{ObbPair, SlabExplain};
use crate::paint::{WorldPainter, colors};

/// The bounding volumes the canvas draws (for its legend): those switched on, while the
/// volumes are shown and there is something to fit them to.
pub(super) fn shown_volumes(lab: &Lab2d) -> Vec<FitKind> {
    if !lab.display.volumes || lab.fits().is_none() {
        return Vec::new();
    }
    FitKind::ALL
        .into_iter()
        .filter(|&k| lab.volumes.has(k))
        .collect()
}

/// The volumes switched on, and the one whose row is hovered in the bounding volumes table
/// (`highlight`, drawn thick and filled whether it is switched on or not).
pub(super) fn draw_volumes(lab: &Lab2d, highlight: Option<FitKind>, wp: &mut WorldPainter<'_>) {
    let Some(fits) = lab.fits() else { return };
    for kind in FitKind::ALL {
        let lit = highlight == Some(kind);
        if !(lit || lab.display.volumes && lab.volumes.has(kind)) {
            continue;
        }
        let color = colors::volume(kind);
        let stroke = Stroke::new(if lit { 4.0 } else { 1.8 }, color);
        let fill = color.gamma_multiply(0.15);
        match kind {
            FitKind::SphereCentroid | FitKind::SphereRitter | FitKind::SphereWelzl => {
                let sphere = match kind {
                    FitKind::SphereCentroid => &fits.centroid,
                    FitKind::SphereRitter => &fits.ritter,
                    _ => &fits.welzl,
                };
                if lit {
                    wp.node_fill(&NodeShape::Sphere(*sphere), fill);
                }
                wp.sphere(sphere, stroke);
                wp.dot(sphere.center, if lit { 4.5 } else { 3.0 }, color);
            }
            FitKind::Aabb => {
                if lit {
                    wp.aabb_fill(&fits.aabb, fill);
                }
                wp.aabb(&fits.aabb, stroke);
            }
            FitKind::Obb => {
                if lit {
                    wp.node_fill(&NodeShape::Obb(fits.obb), fill);
                }
                wp.obb(&fits.obb, stroke);
                // The principal axes, scaled by the standard deviation along each.
                for (axis, var) in fits
                    .pca
                    .axes
                    .iter()
                    .zip([fits.pca.variances.x, fits.pca.variances.y])
                {
                    let len = var.max(0.0).sqrt();
                    wp.line(
                        fits.pca.mean - *axis * len,
                        fits.pca.mean + *axis * len,
                        Stroke::new(1.0, color),
                    );
                }
            }
            FitKind::ConvexHull => {
                if lit && fits.hull.vertices().len() > 2 {
                    wp.convex_fill(fits.hull.vertices(), fill);
                }
                wp.polygon(fits.hull.vertices(), stroke);
            }
        }
    }
    if lab.display.slab_test
        && let Some(ray) = lab.valid_ray()
    {
        draw_slab_test(&fits.aabb, &ray, wp);
    }
}

fn draw_slab_test(aabb: &Aabb2, ray: &Ray2, wp: &mut WorldPainter<'_>) {
    if aabb.is_empty() {
        return;
    }
    let (lo, hi) = wp.screen.visible_world();
    let thin = |c: Color32| Stroke::new(1.0, c.gamma_multiply(0.7));
    for x in [aabb.min.x, aabb.max.x] {
        wp.line(Vec2::new(x, lo.y), Vec2::new(x, hi.y), thin(colors::SLAB_X));
    }
    for y in [aabb.min.y, aabb.max.y] {
        wp.line(Vec2::new(lo.x, y), Vec2::new(hi.x, y), thin(colors::SLAB_Y));
    }
    let explain = SlabExplain::new(aabb, ray);
    let t_far_visible = (visible_end(ray, wp.screen) - ray.origin()).length() / ray.dir().length();
    let clamp = |t: f32| t.clamp(-t_far_visible, t_far_visible);
    let normal = ray.dir().normalize().perp();
    let offset = |px: f32| normal * wp.screen.world_length(px);
    for (axis, color, px) in [(0, colors::SLAB_X, 7.0), (1, colors::SLAB_Y, -7.0)] {
        let a = &explain.axes[axis];
        if a.t_min <= a.t_max {
            wp.line(
                ray.at(clamp(a.t_min)) + offset(px),
                ray.at(clamp(a.t_max)) + offset(px),
                Stroke::new(4.0, color),
            );
        }
    }
    if explain.hits() {
        wp.line(
            ray.at(clamp(explain.t_enter)),
            ray.at(clamp(explain.t_exit)),
            Stroke::new(5.0, colors::ANSWER),
        );
    }
}

pub(super) fn draw_obb_pair(pair: &ObbPair, wp: &mut WorldPainter<'_>) {
    let tests = pair.tests();
    let separating = tests.iter().find(|t| t.separates());
    let color = if separating.is_some() {
        colors::VISITED
    } else {
        colors::CULLED
    };
    for pose in [pair.a, pair.b] {
        let obb = pose.obb();
        wp.convex_fill(&crate::paint::obb_corners(&obb), color.gamma_multiply(0.12));
        wp.obb(&obb, Stroke::new(2.0, color));
        wp.line(pose.center, pose.handle(), Stroke::new(1.0, color));
        wp.dot(pose.handle(), 5.0, color);
    }
    // The projections on the separating axis (or, when they overlap, on every axis).
    let shown: Vec<_> = separating.map_or_else(|| tests.clone(), |t| vec![*t]);
    let mid = (pair.a.center + pair.b.center) * 0.5;
    let reach = pair.a.half.length()
        + pair.b.half.length()
        + (pair.a.center - pair.b.center).length() * 0.5;
    for (k, test) in shown.iter().enumerate() {
        let axis = test.axis.normalize_or_zero();
        let base = mid - axis * axis.dot(mid) + axis.perp() * (reach + 0.6 * k as f32 + 0.5);
        wp.line(
            base + axis * (axis.dot(mid) - reach * 1.5),
            base + axis * (axis.dot(mid) + reach * 1.5),
            Stroke::new(1.0, Color32::GRAY),
        );
        for ((lo, hi), shift, c) in [
            (test.interval_a, 0.12, Color32::from_rgb(255, 200, 120)),
            (test.interval_b, -0.12, Color32::from_rgb(120, 200, 255)),
        ] {
            wp.line(
                base + axis * lo + axis.perp() * shift,
                base + axis * hi + axis.perp() * shift,
                Stroke::new(4.0, c),
            );
        }
    }
}
