//! What a node volume must answer for the tree to use it, and the query forms it answers
//! (a ray with its precomputed inverse direction, a range with its box as an OBB).
//!
//! Every test here is conservative: it may accept a node that no primitive below it
//! satisfies, never the reverse. The primitives' own tests round differently from the
//! volumes' (a watertight triangle test in a sheared frame, a slab test per axis), so a ray
//! that grazes a triangle exactly on its node's boundary could otherwise be refused by the
//! node and accepted by brute force. Worse, some primitive tests are only as exact as their
//! coordinates: a point primitive is hit when `ray.at(t)` rounds to it, and the watertight
//! triangle test works on `vertex - origin` rounded to `f32`, so their hits may lie up to a
//! few units in the last place of the coordinates off the exact ray. Three measures keep the
//! tree consistent with them: every node volume is grown by [`SLACK`] of its coordinates'
//! magnitude when it is fitted; a query grows it further by [`SLACK`] of its own
//! coordinates' magnitude (the ray origin, the query point, the range); and every comparison
//! of a node's entry `t` or distance against a limit allows [`SLACK`] relative error (as
//! Ize, "Robust BVH Ray Traversal", JCGT 2013, does for the slab test's far end).

mod aabb;
pub(super) mod fit_sliced;
mod obb;
mod sphere;

#[cfg(any(target_arch = "wasm32", test))]
use glam::{BVec4A, Vec4};

use super::BvhOptions;
use crate::structure::RangeShape;
use crate::volume::{Aabb, BoundingVolume, Obb};
use crate::{Primitive, Ray, Vector};

/// Relative slack of the conservative tests: about 8 units in the last place of an `f32`.
pub const SLACK: f32 = 1e-6;

/// Absolute slack of every query's tests, on top of [`SLACK`] of its coordinates: below about
/// 1e-19 the squares in `f32` distances and cross products are subnormal, and the
/// primitives' tests lose precision at that scale. The error of a square root of a sum of
/// a few subnormal squares is below `sqrt(4 × 2^-149) ≈ 1e-22`.
pub const TINY: f32 = 1e-21;

/// Beyond this coordinate magnitude `f32` differences and squares can overflow, so the
/// fitted spheres and OBBs are checked against their vertices (and replaced by an unbounded
/// volume if rounding left one out); below it they contain them by construction.
pub const HUGE: f32 = 1e18;

/// `1 + SLACK`: limits are multiplied by this before a node is refused.
pub const GROW: f32 = 1.0 + SLACK;

/// A node volume: a [`BoundingVolume`] that can be fitted to a node's primitives and tested
/// conservatively against the queries' prepared forms. Implemented for
/// [`Aabb`] (`aabb.rs`), [`Sphere`](crate::Sphere) (`sphere.rs`) and [`Obb`] (`obb.rs`), in
/// this folder.
pub trait NodeVolume: BoundingVolume + Copy + Send + Sync + 'static {
    /// A short name for labels and messages: "AABB", "sphere", "OBB".
    const NAME: &'static str;

    /// Whether [`fit`](Self::fit) needs the primitives' vertices (the box needs only their
    /// bounds, so its builds skip gathering them).
    const NEEDS_VERTICES: bool;

    /// The volume of a node whose primitives have the union of boxes `bounds` and the
    /// vertices `vertices` (empty unless [`NEEDS_VERTICES`](Self::NEEDS_VERTICES)). It must
    /// contain every one of those primitives.
    fn fit(bounds: &Aabb<Self::Point>, vertices: &[Self::Point], options: &BvhOptions) -> Self;

    /// Where the ray is inside the volume (`t_enter >= 0`), or `None` when it misses;
    /// conservative: a ray that hits a contained primitive never misses.
    fn ray_entry(&self, ray: &PreparedRay<Self::Point>) -> Option<(f32, f32)>;

    /// A lower bound on the distance from `point` to anything inside the volume (0 inside).
    fn distance_bound(&self, point: Self::Point) -> f32 {
        self.distance(point)
    }

    /// The square of [`distance_bound`](Self::distance_bound), for walks that compare
    /// squares and save the square root. Rounding must be monotone with it: whenever
    /// `distance_bound(point) <= r`, this is at most `r * r` (rounded) times
    /// `1 + 4e-6`, plus four of the smallest subnormals. The default squares the bound;
    /// the box computes the sum of squares whose root `distance_bound` takes.
    #[inline]
    fn distance_bound_squared(&self, point: Self::Point) -> f32 {
        let d = self.distance_bound(point);
        d * d
    }

    /// The entry `t` of [`ray_entry`](Self::ray_entry) alone, for the unobserved walk: the
    /// same value and the same `None`, perhaps computed faster (the box does it four lanes
    /// at a time).
    #[inline]
    fn ray_enter(&self, ray: &PreparedRay<Self::Point>) -> Option<f32> {
        self.ray_entry(ray).map(|(t_enter, _)| t_enter)
    }

    /// Whether the volume may share a point with the range (conservative).
    fn overlaps_range(&self, range: &PreparedRange<Self::Point>) -> bool;

    /// Whether two volumes may share a point (conservative): the node test of the
    /// collision query.
    fn overlaps_node(&self, other: &Self) -> bool {
        self.overlaps(other)
    }

    /// The volume of an inner node around its two children's volumes, for a
    /// [`refit`](super::Bvh::refit): it must contain both. The default is
    /// [`merge`](BoundingVolume::merge) (exact for boxes); spheres and OBBs grow it as
    /// [`fit`](Self::fit) grows theirs. Each inner node then costs one call, so a refit is
    /// linear in the nodes, where fitting every node to its primitives' vertices again would
    /// cost their count per level.
    fn enclose(first: &Self, second: &Self, options: &BvhOptions) -> Self {
        let _ = options;
        first.merge(second)
    }

    /// Whether the volume contains the primitive: its box (for a box) or its vertices.
    fn contains_primitive<P: Primitive<Point = Self::Point>>(&self, prim: &P) -> bool {
        prim.vertices().all(|v| self.contains(v))
    }

    /// Whether a child's volume must lie inside its parent's, and does: true for volumes
    /// that need not nest (spheres and OBBs are fitted to the primitives, not to the
    /// children's volumes).
    fn nests_in(&self, _parent: &Self) -> bool {
        true
    }

    /// Whether the volume is one the node tests are conservative for, beyond containing its
    /// primitives: true for boxes and spheres (whose containment test is the queries' own
    /// arithmetic); an OBB's axes must be orthonormal, which its fits make them and a loaded
    /// file might not ([`validate`](crate::SpatialIndex::validate) checks it).
    fn is_well_formed(&self) -> bool {
        true
    }
}

/// A ray with what the node tests precompute once per query: the inverse direction, per
/// axis whether it is negative (which slab plane the ray meets first), and the origin moved
/// by the query's slack so that the slab test sees every box grown by it at no cost.
#[derive(Clone, Copy, Debug)]
pub struct PreparedRay<V: Vector> {
    /// The ray itself.
    pub ray: Ray<V>,
    /// Its origin.
    pub origin: V,
    /// `1 / dir`, `±inf` where a component is `±0`.
    pub inv_dir: V,
    /// Per axis, whether `inv_dir` is negative (`-0` counts): the ray then enters a slab
    /// through its `max` plane.
    pub negative: [bool; 3],
    /// How much the ray's own rounding can move a hit: [`SLACK`] of its origin's magnitude,
    /// plus [`TINY`].
    pub slack: f32,
    /// The origin moved by `slack` away from each slab's entry plane, so that
    /// `(plane - origin_near) * inv_dir` is the entry `t` of the slab grown by `slack`.
    pub origin_near: V,
    /// The origin moved by `slack` away from each slab's exit plane.
    pub origin_far: V,
    /// The same, four lanes wide, for the box's four-lane test (WebAssembly only, and
    /// the unit test that holds it to the scalar one).
    #[cfg(any(target_arch = "wasm32", test))]
    pub(super) wide: WideRay,
}

/// A [`PreparedRay`] in 128-bit vectors (SSE2 natively, SIMD128 in WebAssembly), for the
/// box's four-lane slab test ([`NodeVolume::ray_enter`] of [`Aabb`]): per axis the origin as
/// seen from the slab's `min` plane and from its `max` plane (`origin_near` or `origin_far`,
/// by the direction's sign), the inverse direction, and the sign. Lanes past the dimension
/// hold origin 0 and inverse direction `+inf`, so that with a box coordinate of 0 they give
/// NaN, which the test ignores as it ignores a ray lying in a slab's plane.
#[cfg(any(target_arch = "wasm32", test))]
#[derive(Clone, Copy, Debug)]
pub(super) struct WideRay {
    pub origin_min: Vec4,
    pub origin_max: Vec4,
    pub inv_dir: Vec4,
    pub negative: BVec4A,
}

#[cfg(any(target_arch = "wasm32", test))]
impl WideRay {
    fn new<V: Vector>(origin_near: V, origin_far: V, inv_dir: V, negative: [bool; 3]) -> Self {
        // Per lane: the origin as the slab's `min` and `max` planes see it, `1 / dir`.
        let (mut at_min, mut at_max, mut inv) = ([0.0; 4], [0.0; 4], [f32::INFINITY; 4]);
        for i in 0..V::DIM {
            let (near, far) = (origin_near.coord(i), origin_far.coord(i));
            // The ray enters a slab through `min` unless its direction is negative there.
            (at_min[i], at_max[i]) = if negative[i] {
                (far, near)
            } else {
                (near, far)
            };
            inv[i] = inv_dir.coord(i);
        }
        Self {
            origin_min: Vec4::from_array(at_min),
            origin_max: Vec4::from_array(at_max),
            inv_dir: Vec4::from_array(inv),
            negative: BVec4A::new(negative[0], negative[1], negative[2], false),
        }
    }
}

impl<V: Vector> PreparedRay<V> {
    /// Precomputes what the node tests need.
    ///
    /// Mirrored in WGSL by `prepare_ray` in the app's heat map shader
    /// (`crates/bvhlab-app/src/render3d/heatmap/trace.wgsl`; the shifted origins come from its
    /// `Params`, filled in `heatmap/gpu.rs`): a change here must be made there too.
    pub fn new(ray: &Ray<V>) -> Self {
        let (origin, inv_dir) = (ray.origin(), ray.inv_dir());
        let slack = SLACK * magnitude(origin) + TINY;
        let (mut origin_near, mut origin_far) = (origin, origin);
        let mut negative = [false; 3];
        for (i, neg) in negative.iter_mut().enumerate().take(V::DIM) {
            *neg = inv_dir.coord(i).is_sign_negative();
            // Entering through `min - slack` (or leaving through `max + slack`) is entering
            // through `min` from an origin moved up by `slack`; mirrored when negative.
            let s = if *neg { -slack } else { slack };
            origin_near.set_coord(i, origin.coord(i) + s);
            origin_far.set_coord(i, origin.coord(i) - s);
        }
        Self {
            ray: *ray,
            origin,
            inv_dir,
            negative,
            slack,
            origin_near,
            origin_far,
            #[cfg(any(target_arch = "wasm32", test))]
            wide: WideRay::new(origin_near, origin_far, inv_dir, negative),
        }
    }
}

/// A range query's region with the forms the node tests need.
#[derive(Clone, Copy, Debug)]
pub struct PreparedRange<V: Vector> {
    /// The region.
    pub shape: RangeShape<V>,
    /// [`SLACK`] of the region's coordinates' magnitude, plus [`TINY`]: how far the
    /// primitives' rounded tests may reach beyond it.
    pub slack: f32,
    /// The region's bounding box, grown by `slack`, as an [`Obb`] (for the OBB tree's
    /// separating-axis test).
    pub as_obb: Obb<V>,
}

impl<V: Vector> PreparedRange<V> {
    /// Precomputes what the node tests need.
    pub fn new(shape: &RangeShape<V>) -> Self {
        let bounds = shape.bounds();
        let slack = SLACK * magnitude(bounds.min).max(magnitude(bounds.max));
        // An empty region (min = +inf) has no slack.
        let slack = if slack.is_finite() {
            slack + TINY
        } else {
            TINY
        };
        let mut as_obb = Obb::from_aabb(&bounds);
        if !as_obb.is_empty() {
            as_obb.half_extents = as_obb.half_extents + V::splat(slack);
        }
        Self {
            shape: *shape,
            slack,
            as_obb,
        }
    }

    /// The ball's radius with the slack of [`GROW`] and [`slack`](Self::slack), or `None`
    /// for a box.
    pub fn grown_radius(&self) -> Option<f32> {
        match &self.shape {
            RangeShape::Ball(s) => Some(s.radius * GROW + self.slack),
            RangeShape::Box(_) => None,
        }
    }
}

/// The slack of a query at `point`: [`SLACK`] of its magnitude, plus [`TINY`].
pub(super) fn query_slack<V: Vector>(point: V) -> f32 {
    SLACK * magnitude(point) + TINY
}

/// `max_i |v_i|`: the scale of a coordinate, for slack that grows with it.
pub(super) fn magnitude<V: Vector>(v: V) -> f32 {
    v.abs().max_element()
}

/// How much to grow a fitted volume of size `size` at `center` so that the traversal's
/// tests, rounded their own way, never refuse what it contains.
pub(super) fn growth<V: Vector>(center: V, size: f32) -> f32 {
    SLACK * (magnitude(center) + size) + f32::MIN_POSITIVE
}
