//! What queries answer, what they cost, and the small bookkeeping every structure's queries
//! share (the best hit so far, the k nearest so far), so that it is written once.

use crate::PointQuery;
use crate::primitive::contract;
use crate::volume::{Aabb, BoundingVolume, Sphere};
use crate::{Primitive, Vector};

/// A ray hit: which primitive, where along the ray (`t` in units of the ray's direction), and
/// where on the primitive (`u`, `v`).
///
/// `u` and `v` are what [`Primitive::hit_coordinates`] gives for the hit: for a triangle the
/// barycentric coordinates of Möller and Trumbore, so the hit point is
/// `(1 - u - v) a + u b + v c` and a shading normal or texture coordinate interpolates as
/// `(1 - u - v) n_a + u n_b + v n_c`; for a 2D segment `u` is the parameter along it (the hit
/// is `a + u (b - a)`) and `v` is 0; for a point both are 0. Every structure computes them
/// the same way, from the primitive and the ray, so its hits equal brute force's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The primitive's index in the slice the structure was built from.
    pub prim: usize,
    /// The ray parameter of the hit.
    pub t: f32,
    /// The first coordinate on the primitive (a triangle's barycentric `u`, the weight of
    /// corner `b`; a segment's parameter from `a` to `b`).
    pub u: f32,
    /// The second coordinate on the primitive (a triangle's barycentric `v`, the weight of
    /// corner `c`; 0 for a segment).
    pub v: f32,
}

impl Hit {
    /// A hit on primitive `prim` (its input index) at `t`, with its coordinates on
    /// `primitive` ([`Primitive::hit_coordinates`]).
    pub fn on<P: Primitive>(
        prim: usize,
        t: f32,
        primitive: &P,
        ray: &crate::Ray<P::Point>,
    ) -> Self {
        let [u, v] = primitive.hit_coordinates(ray, t);
        Self { prim, t, u, v }
    }

    /// A hit whose coordinates are not computed yet (the walks keep `(prim, t)` and place
    /// only the answer, with [`placed`]).
    #[inline]
    pub(crate) fn unplaced(prim: usize, t: f32) -> Self {
        Self {
            prim,
            t,
            u: 0.0,
            v: 0.0,
        }
    }
}

/// The hit with its coordinates on its primitive, `prims` in input order.
#[inline]
pub(crate) fn placed<P: Primitive>(
    hit: Option<Hit>,
    prims: &[P],
    ray: &crate::Ray<P::Point>,
) -> Option<Hit> {
    hit.map(|h| Hit::on(h.prim, h.t, &prims[h.prim], ray))
}

/// Every hit with its coordinates on its primitive, `prims` in input order.
pub(crate) fn placed_all<P: Primitive>(
    hits: Vec<Hit>,
    prims: &[P],
    ray: &crate::Ray<P::Point>,
) -> Vec<Hit> {
    hits.into_iter()
        .map(|h| Hit::on(h.prim, h.t, &prims[h.prim], ray))
        .collect()
}

/// [`placed`] for a traced answer.
pub(crate) fn placed_traced<P: Primitive>(
    mut traced: Traced<Option<Hit>>,
    prims: &[P],
    ray: &crate::Ray<P::Point>,
) -> Traced<Option<Hit>> {
    traced.answer = placed(traced.answer, prims, ray);
    traced
}

/// [`placed_all`] for a traced answer.
pub(crate) fn placed_all_traced<P: Primitive>(
    traced: Traced<Vec<Hit>>,
    prims: &[P],
    ray: &crate::Ray<P::Point>,
) -> Traced<Vec<Hit>> {
    Traced {
        answer: placed_all(traced.answer, prims, ray),
        cost: traced.cost,
    }
}

/// A nearest primitive: which one, its point nearest to the query point, and the distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest<V: Vector> {
    /// The primitive's index in the slice the structure was built from.
    pub prim: usize,
    /// The point of the primitive nearest to the query point.
    pub point: V,
    /// The Euclidean distance from the query point to `point`.
    pub distance: f32,
}

/// What a query cost: the counters the lab puts beside brute force.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct QueryCost {
    /// Nodes (or grid cells) visited.
    pub nodes_visited: u64,
    /// Bounding-volume (or cell, or split-plane) tests.
    pub bound_tests: u64,
    /// Primitive tests (a primitive skipped by mailboxing is not counted).
    pub prim_tests: u64,
}

impl std::ops::AddAssign for QueryCost {
    fn add_assign(&mut self, other: Self) {
        self.nodes_visited += other.nodes_visited;
        self.bound_tests += other.bound_tests;
        self.prim_tests += other.prim_tests;
    }
}

/// A query's answer together with its cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Traced<T> {
    /// The answer.
    pub answer: T,
    /// What it cost to find.
    pub cost: QueryCost,
}

/// The region of a range query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RangeShape<V: Vector> {
    /// A closed axis-aligned box.
    Box(Aabb<V>),
    /// A closed ball.
    Ball(Sphere<V>),
}

impl<V: Vector> RangeShape<V> {
    /// Whether the region and a closed box share a point (used to prune nodes and cells).
    #[inline]
    pub fn overlaps_aabb(&self, aabb: &Aabb<V>) -> bool {
        match self {
            RangeShape::Box(b) => b.overlaps(aabb),
            RangeShape::Ball(s) => !s.is_empty() && aabb.distance(s.center) <= s.radius,
        }
    }

    /// Whether the region and a primitive share a point (exact).
    #[inline]
    pub fn overlaps_primitive<P: Primitive<Point = V>>(&self, prim: &P) -> bool {
        match self {
            RangeShape::Box(b) => prim.intersects_aabb(b),
            RangeShape::Ball(s) => !s.is_empty() && prim.distance(s.center) <= s.radius,
        }
    }

    /// The box around the region.
    #[inline]
    pub fn bounds(&self) -> Aabb<V> {
        match self {
            RangeShape::Box(b) => *b,
            RangeShape::Ball(s) => s.aabb(),
        }
    }
}

/// The nearest hit so far within `[0, t_max]`. Of two hits at the same `t`, the primitive with
/// the lower index wins, so every structure gives the same answer as brute force.
#[derive(Clone, Copy, Debug)]
pub struct HitTracker {
    best: Option<Hit>,
    t_max: f32,
}

impl HitTracker {
    /// No hit yet; hits beyond `t_max` (or any hit, for a NaN `t_max`) are refused.
    #[inline]
    pub fn new(t_max: f32) -> Self {
        Self { best: None, t_max }
    }

    /// The current limit: the best `t` so far, or `t_max`. Nodes the ray enters after this can
    /// be skipped.
    #[inline]
    pub fn limit(&self) -> f32 {
        self.best.map_or(self.t_max, |h| h.t)
    }

    /// Offers a hit; returns whether it became the best. Mirrored in WGSL in `trace` of the
    /// app's heat map shader (`trace.wgsl`): a change here must be made there too.
    #[inline]
    pub fn offer(&mut self, prim: usize, t: f32) -> bool {
        let better = match self.best {
            None => t <= self.t_max,
            Some(best) => t < best.t || (t == best.t && prim < best.prim),
        };
        if better && t >= 0.0 {
            self.best = Some(Hit::unplaced(prim, t));
            return true;
        }
        false
    }

    /// The best hit, if any.
    #[inline]
    pub fn best(&self) -> Option<Hit> {
        self.best
    }

    /// Offers the hit of every primitive of a leaf (`ids` are their input indices), for the
    /// unobserved walks; whether the best changed. A hit beyond `t_max` is refused by
    /// [`offer`](Self::offer) itself: the best is never beyond it.
    #[inline]
    pub(crate) fn offer_leaf<P: Primitive>(
        &mut self,
        prims: &[P],
        ids: &[u32],
        ray: &crate::Ray<P::Point>,
    ) -> bool {
        let mut changed = false;
        for (prim, &id) in prims.iter().zip(ids) {
            if let Some(t) = contract::ray_hit(prim, ray) {
                changed |= self.offer(id as usize, t);
            }
        }
        changed
    }
}

/// The `k` nearest primitives so far, ordered by (distance, index).
#[derive(Clone, Debug)]
pub struct NearestSet<V: Vector> {
    k: usize,
    items: Vec<Nearest<V>>,
}

impl<V: Vector> NearestSet<V> {
    /// An empty set that keeps at most `k` entries.
    #[inline]
    pub fn new(k: usize) -> Self {
        Self {
            k,
            items: Vec::with_capacity(k.min(64)),
        }
    }

    /// The pruning bound: the k-th best distance so far, or `+inf` while fewer than `k` are
    /// known. A node whose bound is farther than this cannot contribute. (With `k = 0`
    /// nothing can, so the bound is `-inf`.)
    #[inline]
    pub fn bound(&self) -> f32 {
        if self.k == 0 {
            f32::NEG_INFINITY
        } else if self.items.len() < self.k {
            f32::INFINITY
        } else {
            self.items[self.k - 1].distance
        }
    }

    /// Offers a primitive's nearest point; returns whether it entered the set. A primitive
    /// already in the set (offered again from another cell) is ignored.
    #[inline]
    pub fn offer(&mut self, prim: usize, point: V, distance: f32) -> bool {
        let key = |n: &Nearest<V>| (n.distance, n.prim);
        if self.k == 0
            || distance.is_nan()
            || self.items.iter().any(|n| n.prim == prim)
            || (self.items.len() == self.k && key(&self.items[self.k - 1]) <= (distance, prim))
        {
            return false;
        }
        let at = self.items.partition_point(|n| key(n) < (distance, prim));
        self.items.insert(
            at,
            Nearest {
                prim,
                point,
                distance,
            },
        );
        self.items.truncate(self.k);
        true
    }

    /// The entries, nearest first.
    #[inline]
    pub fn into_vec(self) -> Vec<Nearest<V>> {
        self.items
    }
}

/// The distance ordering that ties break by index, for sorting all-hits and brute force.
pub(crate) fn by_t_then_prim(a: &Hit, b: &Hit) -> std::cmp::Ordering {
    a.t.total_cmp(&b.t).then(a.prim.cmp(&b.prim))
}
