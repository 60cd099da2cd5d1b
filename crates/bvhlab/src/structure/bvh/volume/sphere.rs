//! Spheres as node volumes: the sphere tree (lecture §3, "Sphere trees and AABB trees").

use super::{GROW, HUGE, NodeVolume, PreparedRange, PreparedRay, growth, magnitude};
use crate::PointQuery;
use crate::Vector;
use crate::structure::RangeShape;
use crate::structure::bvh::{BvhOptions, SphereFit};
use crate::volume::{Aabb, BoundingVolume, Sphere};

impl<V: Vector> NodeVolume for Sphere<V> {
    const NAME: &'static str = "sphere";
    const NEEDS_VERTICES: bool = true;

    /// Ritter's or Welzl's sphere of the node's vertices ([`SphereFit`]), grown by
    /// [`SLACK`](super::SLACK) of its scale. A sphere that holds a primitive's vertices holds
    /// the primitive (a segment or triangle is their convex hull), so each node holds its
    /// primitives. The spheres need not nest: a node's sphere is fitted to its vertices, not
    /// to its children's spheres, which is tighter.
    ///
    /// With coordinates beyond [`HUGE`] the fits' `f32` steps can overflow; a sphere that
    /// then fails to hold a vertex is replaced by the unbounded sphere (centre 0, radius
    /// `+inf`), which every test accepts.
    fn fit(bounds: &Aabb<V>, vertices: &[V], options: &BvhOptions) -> Self {
        let sphere = match options.sphere_fit {
            SphereFit::Ritter => Sphere::ritter_fit(vertices),
            SphereFit::Welzl => Sphere::welzl_fit(vertices),
        };
        if sphere.is_empty() {
            return sphere;
        }
        let grown = Sphere::new(
            sphere.center,
            sphere.radius + growth(sphere.center, sphere.radius),
        );
        let huge = magnitude(bounds.min).max(magnitude(bounds.max)) > HUGE;
        if !grown.center.is_finite()
            || grown.radius.is_nan()
            || (huge && !vertices.iter().all(|&v| grown.contains(v)))
        {
            return Sphere::new(V::ZERO, f32::INFINITY);
        }
        grown
    }

    /// The smallest sphere around both ([`merge`](BoundingVolume::merge), which rounds its
    /// radius up), grown by [`SLACK`](super::SLACK) of its scale as [`fit`](Self::fit)
    /// grows a fitted one. Looser than a sphere fitted to the node's vertices, which is the
    /// price of a refit linear in the nodes.
    fn enclose(first: &Self, second: &Self, _options: &BvhOptions) -> Self {
        let merged = first.merge(second);
        if merged.is_empty() || merged.radius == f32::INFINITY {
            return merged;
        }
        Sphere::new(
            merged.center,
            merged.radius + growth(merged.center, merged.radius),
        )
    }

    /// The ray-sphere quadratic `|e + t d|² = r²` (e: origin relative to the centre, `r`
    /// grown by the ray's slack), in `f64` with `e` formed in `f64` (exact for `f32`
    /// inputs), solved without cancellation (Press et al., "Numerical Recipes", §5.6).
    fn ray_entry(&self, ray: &PreparedRay<V>) -> Option<(f32, f32)> {
        if self.radius == f32::INFINITY {
            return Some((0.0, f32::INFINITY));
        }
        let e = ray.origin.to_dvec3() - self.center.to_dvec3();
        let d = ray.ray.dir().to_dvec3();
        let r = f64::from(self.radius) + f64::from(ray.slack);
        let (a, half_b, c) = (d.dot(d), e.dot(d), e.dot(e) - r * r);
        let disc = half_b * half_b - a * c;
        if disc < 0.0 || r < 0.0 {
            return None;
        }
        let q = -(half_b + half_b.signum() * disc.sqrt());
        let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
        let (t0, t1) = (r0.min(r1), r0.max(r1));
        (t1 >= 0.0).then(|| (t0.max(0.0) as f32, t1 as f32))
    }

    fn overlaps_range(&self, range: &PreparedRange<V>) -> bool {
        match &range.shape {
            RangeShape::Box(b) => b.distance(self.center) <= self.radius * GROW + range.slack,
            RangeShape::Ball(s) => {
                !s.is_empty()
                    && self.center_distance(s.center)
                        <= (f64::from(self.radius) + f64::from(s.radius)) * f64::from(GROW)
                            + f64::from(range.slack)
            }
        }
    }
}
