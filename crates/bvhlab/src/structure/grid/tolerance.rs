//! Rounding tolerances and `f64` box arithmetic for the two space partitions, the uniform
//! grid and the 2^D tree.
//!
//! Both list a primitive in every cell it touches, so a query must visit every cell that the
//! exact ray (or region) meets, and decide so in floating point. The helpers here make that
//! decision generous by a small rounding tolerance: a cell is visited when the ray passes
//! within [`RayTolerance::len`] of it, and a search stops only when a cell lies beyond the best
//! answer by more than the rounding error of the primitive tests. Visiting one cell too many
//! costs a little time; skipping one would give a wrong answer. Box arithmetic is done in
//! `f64`, where `f32` coordinates up to `3.4e38` neither overflow nor underflow.

use std::cmp::Ordering;

use crate::structure::RangeShape;
use crate::volume::Aabb;
use crate::{BoundingVolume, Ray, Vector};

/// The largest absolute coordinate, in `f64`.
pub(crate) fn max_abs<V: Vector>(v: V) -> f64 {
    (0..V::DIM).fold(0.0, |m, i| m.max(f64::from(v.coord(i)).abs()))
}

/// The largest absolute coordinate of a box (0 for the empty box).
pub(crate) fn box_max_abs<V: Vector>(b: &Aabb<V>) -> f64 {
    if b.is_empty() {
        0.0
    } else {
        max_abs(b.min).max(max_abs(b.max))
    }
}

/// The rounding tolerances of one ray query against a structure.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayTolerance {
    /// A length: cells within this distance of the ray are visited. About 8 `f32` ulps of the
    /// largest coordinate in play, which bounds the error of the primitives' `f32` ray tests
    /// (and an absolute floor for scenes scaled down to 1e-20, where products are subnormal).
    pub len: f64,
    /// The same tolerance in units of `t` (`len / |d|`).
    pub t: f64,
}

impl RayTolerance {
    /// The tolerances for `ray` against a structure whose cells lie in `scene`.
    pub(crate) fn new<V: Vector>(ray: &Ray<V>, scene: &Aabb<V>) -> Self {
        let len = 1e-6 * (box_max_abs(scene) + max_abs(ray.origin())) + 1e-23;
        let d = ray.dir();
        let d_len = (0..V::DIM)
            .map(|i| f64::from(d.coord(i)).powi(2))
            .sum::<f64>()
            .sqrt();
        Self {
            len,
            t: len / d_len,
        }
    }

    /// How far beyond a hit at `t` a cell may begin and still hold a hit that rounds to an
    /// earlier `t`: cells are pruned only beyond `t + hit_slack(t)`.
    pub(crate) fn hit_slack(&self, t: f64) -> f64 {
        1e-5 * t.abs() + 10.0 * self.t
    }
}

/// Where the ray is inside the box grown by `grow` on every side: `[t_enter, t_exit]` with
/// `t >= 0`, or `None`. The slab test (Kay and Kajiya, 1986) in `f64`; a ray parallel to a
/// slab is inside it when its origin is (no `0 · inf`).
pub(crate) fn ray_box_interval<V: Vector>(
    ray: &Ray<V>,
    b: &Aabb<V>,
    grow: f64,
) -> Option<(f64, f64)> {
    let (o, d) = (ray.origin(), ray.dir());
    let mut enter = 0.0f64;
    let mut exit = f64::INFINITY;
    for i in 0..V::DIM {
        let lo = f64::from(b.min.coord(i)) - grow;
        let hi = f64::from(b.max.coord(i)) + grow;
        let (oi, di) = (f64::from(o.coord(i)), f64::from(d.coord(i)));
        if di == 0.0 {
            if !(lo <= oi && oi <= hi) {
                return None;
            }
        } else {
            let (t0, t1) = ((lo - oi) / di, (hi - oi) / di);
            let (near, far) = if di > 0.0 { (t0, t1) } else { (t1, t0) };
            enter = enter.max(near);
            exit = exit.min(far);
        }
    }
    (enter <= exit).then_some((enter, exit))
}

/// Euclidean distance from `p` to the closed box, in `f64` (0 inside).
pub(crate) fn box_distance<V: Vector>(b: &Aabb<V>, p: V) -> f64 {
    let mut sum = 0.0;
    for i in 0..V::DIM {
        let (lo, hi, x) = (
            f64::from(b.min.coord(i)),
            f64::from(b.max.coord(i)),
            f64::from(p.coord(i)),
        );
        let gap = if x < lo {
            lo - x
        } else if x > hi {
            x - hi
        } else {
            0.0
        };
        sum += gap * gap;
    }
    sum.sqrt()
}

/// Whether a cell at box distance `distance` may still hold a primitive nearer than `bound`
/// (the k-th best so far). Generous by the rounding error of the primitives' `f32` closest
/// points: relative to the distance and to the coordinates (`scale`), with an absolute floor
/// for subnormal squares. Ties must be visited: at equal distance the lower index wins.
pub(crate) fn may_be_nearer(distance: f64, bound: f32, scale: f64) -> bool {
    let bound = f64::from(bound);
    let limit = bound + 1e-5 * bound.abs() + 1e-6 * scale + 1e-22;
    distance.partial_cmp(&limit) != Some(Ordering::Greater)
}

/// Whether a range query's region is one the structures can prune with: a box with finite,
/// ordered corners, or a ball with a finite centre and a finite radius `>= 0`. Other regions
/// are answered by testing every primitive, exactly as brute force does.
pub(crate) fn is_prunable_range<V: Vector>(shape: &RangeShape<V>) -> bool {
    match shape {
        RangeShape::Box(b) => {
            b.min.is_finite()
                && b.max.is_finite()
                && (0..V::DIM).all(|i| b.min.coord(i) <= b.max.coord(i))
        }
        RangeShape::Ball(s) => s.center.is_finite() && s.radius.is_finite() && s.radius >= 0.0,
    }
}

/// The box whose cells a range query visits: the region's box, grown for a ball by the same
/// tolerance as [`range_may_touch`] (the ball's `f32` box may round inward). `scene` is the
/// structure's largest coordinate ([`box_max_abs`] of its bounds).
pub(crate) fn range_box<V: Vector>(shape: &RangeShape<V>, scene: f64) -> Aabb<V> {
    match shape {
        RangeShape::Box(b) => *b,
        RangeShape::Ball(s) => {
            let r = f64::from(s.radius);
            let grow = r + 1e-5 * r + 1e-6 * max_abs(s.center).max(scene) + 1e-22;
            let (mut lo, mut hi) = (s.center, s.center);
            for i in 0..V::DIM {
                let c = f64::from(s.center.coord(i));
                lo.set_coord(i, ((c - grow) as f32).max(f32::MIN));
                hi.set_coord(i, ((c + grow) as f32).min(f32::MAX));
            }
            Aabb::new(lo, hi)
        }
    }
}

/// Whether a cell may hold a primitive that overlaps the region: exact for a box (closed
/// boxes that share a point), generous by the rounding tolerance for a ball. The tolerance
/// counts the structure's largest coordinate `scene` too: a primitive's distance is only as
/// exact as its own coordinates, and a primitive reaching from a cell of tiny coordinates to
/// 1e6 may round into a ball that its cell lies outside of.
pub(crate) fn range_may_touch<V: Vector>(
    shape: &RangeShape<V>,
    cell: &Aabb<V>,
    scene: f64,
) -> bool {
    match shape {
        RangeShape::Box(b) => b.overlaps(cell),
        RangeShape::Ball(s) => {
            let scale = max_abs(s.center).max(box_max_abs(cell)).max(scene);
            may_be_nearer(box_distance(cell, s.center), s.radius, scale)
        }
    }
}
