//! Axis-aligned boxes as node volumes: the AABB tree, and its hot path, the slab test.

#[cfg(any(target_arch = "wasm32", test))]
use glam::Vec4;

use super::{GROW, NodeVolume, PreparedRange, PreparedRay, SLACK, magnitude};
use crate::PointQuery;
use crate::structure::RangeShape;
use crate::structure::bvh::BvhOptions;
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

impl<V: Vector> NodeVolume for Aabb<V> {
    const NAME: &'static str = "AABB";
    const NEEDS_VERTICES: bool = false;

    /// The union of the primitives' boxes, grown on every side by [`SLACK`] of its largest
    /// coordinate (see the [module documentation](super)). Growing by the box's own
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
    ///
    /// Mirrored in WGSL by `box_entry` in the app's heat map shader
    /// (`crates/bvhlab-app/src/render3d/heatmap/trace.wgsl`), which must give the same entry `t`
    /// bit for bit: a change here must be made there too.
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
    /// square root is [`distance`](crate::PointQuery::distance) (`inf` for an empty box, as
    /// the distance is), so the walks that compare squares prune exactly where rounding
    /// allows.
    ///
    /// The clamp is written as comparisons, as the 4-wide walk's is: the same values (a NaN
    /// coordinate gives a NaN offset either way), and one instruction each where
    /// WebAssembly would call `fmaxf`/`fminf` for `f32::max`/`min`.
    #[inline]
    fn distance_bound_squared(&self, point: V) -> f32 {
        let mut offset = V::ZERO;
        for axis in 0..V::DIM {
            let (p, lo, hi) = (
                point.coord(axis),
                self.min.coord(axis),
                self.max.coord(axis),
            );
            let clamped = if p < lo { lo } else { p };
            let clamped = if clamped > hi { hi } else { clamped };
            offset.set_coord(axis, clamped - p);
        }
        offset.length_squared()
    }

    /// The entry of the slab test above. In WebAssembly it is computed four lanes at a
    /// time (`wide_ray_enter`: SIMD128 there, 1.8 times the scalar test's speed on
    /// incoherent rays in node); natively the scalar test, which the compiler vectorises
    /// well enough that the four-lane one is slower there (SSE2 without a blend).
    #[inline]
    fn ray_enter(&self, ray: &PreparedRay<V>) -> Option<f32> {
        #[cfg(target_arch = "wasm32")]
        {
            wide_ray_enter(self, ray)
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            self.ray_entry(ray).map(|(t_enter, _)| t_enter)
        }
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

/// The slab test of [`ray_entry`](NodeVolume::ray_entry), four lanes at a time: the same
/// operations on the same values (each plane's `t` from the same shifted origin), so the
/// same entry `t`. The scalar loop's `>` and `<`, which skip a NaN plane, become lane
/// selects (not `max` and `min`, whose NaN rules differ between SSE2, NEON and SIMD128);
/// then the largest entry and the smallest exit are taken across lanes, where no NaN is
/// left.
#[cfg(any(target_arch = "wasm32", test))]
#[inline]
fn wide_ray_enter<V: Vector>(b: &Aabb<V>, ray: &PreparedRay<V>) -> Option<f32> {
    let w = &ray.wide;
    let t_min = (lanes(b.min) - w.origin_min) * w.inv_dir;
    let t_max = (lanes(b.max) - w.origin_max) * w.inv_dir;
    let t_near = Vec4::select(w.negative, t_max, t_min);
    let t_far = Vec4::select(w.negative, t_min, t_max);
    let t_near = Vec4::select(t_near.cmpgt(Vec4::ZERO), t_near, Vec4::ZERO);
    let t_far = Vec4::select(t_far.cmplt(Vec4::INFINITY), t_far, Vec4::INFINITY);
    let (t_enter, t_exit) = (t_near.max_element(), t_far.min_element());
    (t_enter <= t_exit * GROW).then_some(t_enter)
}

/// A point's coordinates in four lanes, zeros past its dimension.
#[cfg(any(target_arch = "wasm32", test))]
#[inline]
fn lanes<V: Vector>(v: V) -> Vec4 {
    let mut out = [0.0; 4];
    for (i, lane) in out.iter_mut().enumerate().take(V::DIM) {
        *lane = v.coord(i);
    }
    Vec4::from_array(out)
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::Ray;

    /// A coordinate that often coincides with another: small integers, their negatives
    /// and zeros of both signs, or a random value.
    fn coord(rng: &mut ChaCha8Rng) -> f32 {
        match rng.random_range(0..4) {
            0 => f32::from(rng.random_range(-3i8..=3)),
            1 => -0.0,
            _ => rng.random_range(-4.0f32..4.0),
        }
    }

    /// The wide test gives the scalar test's entry, bit for bit, including rays parallel
    /// to a slab and rays starting on a plane (NaN planes), in 2D and 3D.
    fn check<V: Vector>(seed: u64) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut entered = 0;
        for _ in 0..20_000 {
            let point = |rng: &mut ChaCha8Rng| {
                let mut v = V::ZERO;
                for i in 0..V::DIM {
                    v.set_coord(i, coord(rng));
                }
                v
            };
            let (a, c) = (point(&mut rng), point(&mut rng));
            let fitted = <Aabb<V> as NodeVolume>::fit(
                &Aabb::new(a.min(c), a.max(c)),
                &[],
                &BvhOptions::default(),
            );
            let bare = Aabb::new(a.min(c), a.max(c));
            // Half the rays aim at the box's centre.
            let origin = point(&mut rng);
            let mut dir = if rng.random_bool(0.5) {
                (a + c) * 0.5 - origin
            } else {
                point(&mut rng)
            };
            // A third of them parallel to the first slab.
            if rng.random_bool(0.33) {
                dir.set_coord(0, 0.0);
            }
            let Ok(ray) = Ray::new(origin, dir) else {
                continue;
            };
            let prepared = PreparedRay::new(&ray);
            // A box whose first slab's planes lie exactly where the shifted origins are, so
            // that a parallel ray's plane `t` is `0 × inf = NaN`.
            let mut on_planes = bare;
            on_planes.min.set_coord(0, prepared.origin_near.coord(0));
            on_planes.max.set_coord(0, prepared.origin_far.coord(0));
            if on_planes.min.coord(0) > on_planes.max.coord(0) {
                on_planes = Aabb::new(
                    on_planes.max.min(on_planes.min),
                    on_planes.max.max(on_planes.min),
                );
            }
            for b in [fitted, bare, on_planes] {
                let scalar = b.ray_entry(&prepared).map(|(t, _)| t);
                let wide = wide_ray_enter(&b, &prepared);
                assert_eq!(
                    scalar.map(f32::to_bits),
                    wide.map(f32::to_bits),
                    "{b:?} {ray:?}"
                );
                entered += usize::from(wide.is_some());
            }
        }
        assert!(entered > 10_000, "only {entered} rays entered");
    }

    #[test]
    fn wide_slab_test_equals_the_scalar_one() {
        check::<Vec3>(1);
        check::<Vec2>(2);
    }
}
