//! Axis-aligned boxes as node volumes: the AABB tree, and its hot path, the slab test.

use super::BvhOptions;
use super::volume::{GROW, NodeVolume, PreparedRange, PreparedRay, SLACK, magnitude};
use crate::structure::RangeShape;
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

impl<V: Vector> NodeVolume for Aabb<V> {
    const NAME: &'static str = "AABB";
    const NEEDS_VERTICES: bool = false;

    /// The union of the primitives' boxes, grown on every side by [`SLACK`] of its largest
    /// coordinate (see the [module documentation](super::volume)). Growing by the box's own
    /// magnitude keeps children inside their parents: a parent's coordinates are at least
    /// as large.
    fn fit(bounds: &Aabb<V>, _vertices: &[V], _options: &BvhOptions) -> Self {
        let grow =
            V::splat(SLACK * magnitude(bounds.min).max(magnitude(bounds.max)) + f32::MIN_POSITIVE);
        Aabb::new(bounds.min - grow, bounds.max + grow)
    }

    /// The slab test (Kay and Kajiya, SIGGRAPH 1986) with the sign of each direction
    /// component precomputed (Williams, Barrus, Morley and Shirley, "An Efficient and Robust
    /// Ray-Box Intersection Algorithm", JGT 2005), so no branch depends on the box.
    ///
    /// A ray parallel to a slab has `inv_dir = ±inf`. If its origin lies strictly inside
    /// the slab both ends give `∓inf` and `±inf`; if it lies on one of the slab's planes
    /// that end gives `0 × inf = NaN`, and the comparisons below, false for NaN, ignore it,
    /// so the ray counts as inside the closed slab. The planes are moved out by the ray's
    /// slack through the precomputed shifted origins, and the far end is grown by [`GROW`]
    /// (Ize, "Robust BVH Ray Traversal", JCGT 2013), so that a ray grazing a primitive on
    /// the box's boundary is not refused by the box's rounding.
    #[inline]
    fn ray_entry(&self, ray: &PreparedRay<V>) -> Option<(f32, f32)> {
        let mut t_enter = 0.0f32;
        let mut t_exit = f32::INFINITY;
        for i in 0..V::DIM {
            let (near, far) = if ray.negative[i] {
                (self.max.coord(i), self.min.coord(i))
            } else {
                (self.min.coord(i), self.max.coord(i))
            };
            let inv = ray.inv_dir.coord(i);
            let t_near = (near - ray.origin_near.coord(i)) * inv;
            let t_far = (far - ray.origin_far.coord(i)) * inv;
            t_enter = if t_near > t_enter { t_near } else { t_enter };
            t_exit = if t_far < t_exit { t_far } else { t_exit };
        }
        (t_enter <= t_exit * GROW).then_some((t_enter, t_exit))
    }

    /// The squared distance from `point` to the nearest point of the box: the value whose
    /// square root is [`distance`](BoundingVolume::distance) (`inf` for an empty box, as
    /// the distance is), so the walks that compare squares prune exactly where rounding
    /// allows.
    #[inline]
    fn distance_bound_squared(&self, point: V) -> f32 {
        (point.max(self.min).min(self.max) - point).length_squared()
    }

    fn overlaps_range(&self, range: &PreparedRange<V>) -> bool {
        match &range.shape {
            RangeShape::Box(b) => self.overlaps(b),
            RangeShape::Ball(s) => range
                .grown_radius()
                .is_some_and(|r| !s.is_empty() && self.distance(s.center) <= r),
        }
    }

    fn contains_primitive<P: Primitive<Point = V>>(&self, prim: &P) -> bool {
        let b = prim.bounds();
        self.contains(b.min) && self.contains(b.max)
    }

    /// A box node is the union of its children's boxes, so each child lies inside it.
    fn nests_in(&self, parent: &Self) -> bool {
        parent.contains(self.min) && parent.contains(self.max)
    }
}
