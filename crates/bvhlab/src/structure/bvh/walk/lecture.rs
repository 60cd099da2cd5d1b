//! The slides' own BVH queries, literally (lecture §3, "BVH intersection query" and "BVH
//! distance query"), so that the lab can run them beside the real traversals and a student can
//! count what the slides leave out.
//!
//! The slides give two recursive pseudocodes and note what they omit: `intersect(bvNode, ray,
//! t)` recurses into the left child, then the right, whatever the hits found so far, and
//! `minDistance(bvNode, point, currentMin)` recurses into both children of every node without
//! testing a single bounding volume. The real traversals (`ray.rs`,
//! `nearest.rs`) visit the nearer child first and skip what cannot beat the best so
//! far. The versions here are the slides' recursions as written, plus a third, the distance
//! query with the pruning the slide mentions but still in the slide's left-then-right order,
//! so that the lab can show each omission's cost on its own.
//!
//! They answer exactly what the real traversals answer (the same hit, the same nearest
//! primitive, ties to the lower index): each call returns its subtree's best, as the slides'
//! return values do, and a query-wide tracker of the best so far reports `NewBest` (and, for
//! the pruned distance query, bounds the pruning). Recursion depth is bounded by the tree's
//! depth, at most [`MAX_DEPTH`](crate::structure::bvh::MAX_DEPTH).

use crate::primitive::contract;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::{GROW, NodeVolume, PreparedRay, query_slack};
use crate::structure::query::placed;
use crate::structure::{
    Event, Hit, HitTracker, Nearest, NearestSet, NodeId, Observer, PrimitiveResult, PruneAt,
    PruneReason, QueryCost, Traced,
};
use crate::{Primitive, Ray, Vector};

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The slides' `intersect(bvNode, ray, t)`, literally: recursive, left child then right
    /// child, no near-first order, no pruning by the best hit so far. Answers the first hit
    /// with `0 <= t <= t_max`, exactly as
    /// [`ray_first_hit`](crate::RayCast::ray_first_hit) does, at a higher
    /// cost.
    ///
    /// Events, per call, in the recursion's order: `EnterNode`, then `RayBoundTest` (the
    /// slide's `bvNode.intersect(ray, t)`); on a miss `Prune(RayMissed, at Test)` and the
    /// call returns. A leaf then reports a `PrimitiveTest` per primitive (hits beyond `t_max`
    /// count as misses) and `NewBest` whenever the query's best hit improves; an inner node
    /// reports `ChildQueued` (key 0, rank 0) for its left child just before recursing into
    /// it, then `ChildQueued` (key 0, rank 1) for its right child just before that call. An
    /// empty tree, or a NaN `t_max`, answers `None` with no events.
    pub fn lecture_intersect_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut query = Intersect {
            bvh: self,
            ray: PreparedRay::new(ray),
            t_max,
            best_so_far: HitTracker::new(t_max),
            cost: QueryCost::default(),
            observer,
        };
        let answer = if self.nodes.is_empty() || t_max.is_nan() {
            None
        } else {
            query.intersect(0, 0)
        };
        Traced {
            answer: placed(answer, &self.prims, ray),
            cost: query.cost,
        }
    }

    /// [`lecture_intersect_observed`](Self::lecture_intersect_observed), unobserved.
    pub fn lecture_intersect(&self, ray: &Ray<P::Point>, t_max: f32) -> Option<Hit> {
        self.lecture_intersect_observed(ray, t_max, &mut ()).answer
    }

    /// The slides' `minDistance(bvNode, point, currentMin)`, literally: visits both children
    /// of every node (the slide tests no bounding volume), and leaves compute their
    /// primitives' distances. Answers the nearest primitive exactly as
    /// [`closest_point`](crate::PointQuery::closest_point) does, after
    /// visiting every node and testing every primitive.
    ///
    /// Events, per call, in the recursion's order: `EnterNode`; a leaf then reports a
    /// `PrimitiveTest` with each primitive's distance and `NewBest` whenever the query's
    /// nearest improves; an inner node reports `ChildQueued` (key 0, rank 0) for its left
    /// child just before recursing into it, then `ChildQueued` (key 0, rank 1) for its right
    /// child. An empty tree, or a point with a NaN or infinite coordinate, answers `None`
    /// with no events.
    pub fn lecture_min_distance_observed<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        observer: &mut O,
    ) -> Traced<Option<Nearest<P::Point>>> {
        self.min_distance_query(point, false, observer)
    }

    /// [`lecture_min_distance_observed`](Self::lecture_min_distance_observed), unobserved.
    pub fn lecture_min_distance(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        self.lecture_min_distance_observed(point, &mut ()).answer
    }

    /// The slides' `minDistance` with the pruning the slide leaves out, still in the slide's
    /// left-then-right order: a node whose volume is farther from the point than the nearest
    /// primitive so far (`currentMin`) is skipped. Answers exactly as
    /// [`lecture_min_distance_observed`](Self::lecture_min_distance_observed) does.
    ///
    /// A node at exactly `currentMin` is still entered, as in the real traversal: a primitive
    /// there may tie, and ties go to the lower index. Like the real traversal, the comparison
    /// allows the volumes' rounding slack ([`SLACK`] of the distances and of
    /// the point's coordinates).
    ///
    /// Events: those of the unpruned query, with, at the start of each call (before its
    /// `EnterNode`), `DistanceBoundTest` with the distance from the point to the node's
    /// volume, then `Prune(NoNearer, at Test)` with that distance and `currentMin` when the
    /// node is skipped (and the call returns).
    ///
    /// [`SLACK`]: crate::structure::bvh::SLACK
    pub fn lecture_min_distance_pruned_observed<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        observer: &mut O,
    ) -> Traced<Option<Nearest<P::Point>>> {
        self.min_distance_query(point, true, observer)
    }

    /// [`lecture_min_distance_pruned_observed`](Self::lecture_min_distance_pruned_observed),
    /// unobserved.
    pub fn lecture_min_distance_pruned(&self, point: P::Point) -> Option<Nearest<P::Point>> {
        self.lecture_min_distance_pruned_observed(point, &mut ())
            .answer
    }

    /// Both distance queries: `prune` says whether nodes are tested against `currentMin`.
    fn min_distance_query<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        prune: bool,
        observer: &mut O,
    ) -> Traced<Option<Nearest<P::Point>>> {
        let mut query = MinDistance {
            bvh: self,
            point,
            slack: query_slack(point),
            prune,
            current_min: NearestSet::new(1),
            cost: QueryCost::default(),
            observer,
        };
        let answer = if self.nodes.is_empty() || !point.is_finite() {
            None
        } else {
            query.min_distance(0, 0)
        };
        Traced {
            answer,
            cost: query.cost,
        }
    }
}

/// One `intersect` query: the ray, the query-wide best hit, the counters.
struct Intersect<'a, B, P: Primitive, O> {
    bvh: &'a Bvh<B, P>,
    ray: PreparedRay<P::Point>,
    t_max: f32,
    /// The best hit of the whole query so far: only for `NewBest` (nothing is pruned by it).
    best_so_far: HitTracker,
    cost: QueryCost,
    observer: &'a mut O,
}

impl<B, P, O> Intersect<'_, B, P, O>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    O: Observer<P::Point>,
{
    /// `intersect(bvNode, ray, t)`: the nearest hit below `node`, the slide's `t`.
    fn intersect(&mut self, node: u32, depth: u32) -> Option<Hit> {
        let bvh = self.bvh;
        let bv_node = &bvh.nodes[node as usize];
        self.cost.nodes_visited += 1;
        self.observer.on(Event::EnterNode {
            node: NodeId(node),
            depth,
        });
        // if (bvNode == null || !bvNode.intersect(ray, t)) return false;
        self.cost.bound_tests += 1;
        let interval = bv_node.volume.ray_entry(&self.ray);
        self.observer.on(Event::RayBoundTest {
            node: NodeId(node),
            interval,
        });
        if interval.is_none() {
            self.observer.on(Event::Prune {
                node: NodeId(node),
                reason: PruneReason::RayMissed,
                at: PruneAt::Test,
            });
            return None;
        }
        if bv_node.is_leaf() {
            return self.leaf(bv_node.leaf_range());
        }
        // i1 = intersect(bvNode.left, ray, t1); i2 = intersect(bvNode.right, ray, t2);
        let (left, right) = (node + 1, bv_node.start);
        queue_child(self.observer, node, left, 0);
        let t1 = self.intersect(left, depth + 1);
        queue_child(self.observer, node, right, 1);
        let t2 = self.intersect(right, depth + 1);
        // if (i1 && i2) t = min(t1, t2); else t = whichever hit.
        self.nearer(t1, t2)
    }

    /// A leaf's primitives, each tested against the ray: the nearest hit among them.
    fn leaf(&mut self, range: std::ops::Range<usize>) -> Option<Hit> {
        let bvh = self.bvh;
        let mut nearest = HitTracker::new(self.t_max);
        for (prim, &id) in bvh.leaf_prims[range.clone()]
            .iter()
            .zip(&bvh.leaf_ids[range])
        {
            self.cost.prim_tests += 1;
            let t = contract::ray_hit(prim, &self.ray.ray).filter(|&t| t <= self.t_max);
            self.observer.on(Event::PrimitiveTest {
                prim: id,
                result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
            });
            if let Some(t) = t {
                nearest.offer(id as usize, t);
                if self.best_so_far.offer(id as usize, t) {
                    self.observer.on(Event::NewBest { prim: id, value: t });
                }
            }
        }
        nearest.best()
    }

    /// The nearer of two subtrees' hits, by the real traversal's rule (`HitTracker`: the
    /// smaller `t`, then the lower index).
    fn nearer(&self, a: Option<Hit>, b: Option<Hit>) -> Option<Hit> {
        let mut nearest = HitTracker::new(self.t_max);
        for hit in [a, b].into_iter().flatten() {
            nearest.offer(hit.prim, hit.t);
        }
        nearest.best()
    }
}

/// One `minDistance` query: the point, the query-wide nearest (`currentMin`), the counters.
struct MinDistance<'a, B, P: Primitive, O> {
    bvh: &'a Bvh<B, P>,
    point: P::Point,
    /// How far the primitives' rounded distances may fall below the volumes' (see `volume`).
    slack: f32,
    /// Whether a node farther than `current_min` is skipped (the slide's version does not).
    prune: bool,
    /// The nearest primitive of the whole query so far: `NewBest`, and the pruning bound.
    current_min: NearestSet<P::Point>,
    cost: QueryCost,
    observer: &'a mut O,
}

impl<B, P, O> MinDistance<'_, B, P, O>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    O: Observer<P::Point>,
{
    /// `minDistance(bvNode, point, currentMin)`: the nearest primitive below `node`
    /// (`None` when the node is skipped).
    fn min_distance(&mut self, node: u32, depth: u32) -> Option<Nearest<P::Point>> {
        let bvh = self.bvh;
        let bv_node = &bvh.nodes[node as usize];
        if self.prune && self.no_nearer(node, &bv_node.volume) {
            return None;
        }
        self.cost.nodes_visited += 1;
        self.observer.on(Event::EnterNode {
            node: NodeId(node),
            depth,
        });
        if bv_node.is_leaf() {
            return self.leaf(bv_node.leaf_range());
        }
        // d1 = minDistance(bvNode.left, point, currentMin);
        // d2 = minDistance(bvNode.right, point, currentMin);
        let (left, right) = (node + 1, bv_node.start);
        queue_child(self.observer, node, left, 0);
        let d1 = self.min_distance(left, depth + 1);
        queue_child(self.observer, node, right, 1);
        let d2 = self.min_distance(right, depth + 1);
        // return min(d1, d2)
        nearer(d1, d2)
    }

    /// The pruning the slide leaves out: whether the node's volume is farther from the point
    /// than `currentMin` (reported as a `DistanceBoundTest`, then a `Prune` when it is).
    fn no_nearer(&mut self, node: u32, volume: &B) -> bool {
        self.cost.bound_tests += 1;
        let distance = volume.distance_bound(self.point);
        self.observer.on(Event::DistanceBoundTest {
            node: NodeId(node),
            distance,
        });
        let best = self.current_min.bound();
        // The same test as the real traversal's: a node at the bound may hold a tie.
        if distance > best * GROW + self.slack {
            self.observer.on(Event::Prune {
                node: NodeId(node),
                reason: PruneReason::NoNearer { distance, best },
                at: PruneAt::Test,
            });
            return true;
        }
        false
    }

    /// A leaf's primitives, each measured: the nearest among them.
    fn leaf(&mut self, range: std::ops::Range<usize>) -> Option<Nearest<P::Point>> {
        let bvh = self.bvh;
        let mut nearest = None;
        for (prim, &id) in bvh.leaf_prims[range.clone()]
            .iter()
            .zip(&bvh.leaf_ids[range])
        {
            self.cost.prim_tests += 1;
            let point = contract::project_point(prim, self.point);
            let distance = (point - self.point).length();
            self.observer.on(Event::PrimitiveTest {
                prim: id,
                result: PrimitiveResult::Distance(distance),
            });
            if self.current_min.offer(id as usize, point, distance) {
                self.observer.on(Event::NewBest {
                    prim: id,
                    value: distance,
                });
            }
            if !distance.is_nan() {
                let this = Nearest {
                    prim: id as usize,
                    point,
                    distance,
                };
                nearest = nearer(nearest, Some(this));
            }
        }
        nearest
    }
}

/// The nearer of two candidates by `NearestSet`'s rule: the smaller distance, then the lower
/// index.
fn nearer<V: Vector>(a: Option<Nearest<V>>, b: Option<Nearest<V>>) -> Option<Nearest<V>> {
    match (a, b) {
        (Some(x), Some(y)) if (y.distance, y.prim) < (x.distance, x.prim) => Some(y),
        (Some(x), _) => Some(x),
        (None, y) => y,
    }
}

/// Reports the recursive call about to be made: `rank` 0 for the left child, 1 for the right,
/// with no ordering key (the slides visit children in their stored order).
fn queue_child<V: Vector, O: Observer<V>>(observer: &mut O, parent: u32, child: u32, rank: u32) {
    observer.on(Event::ChildQueued {
        parent: NodeId(parent),
        child: NodeId(child),
        key: 0.0,
        rank,
    });
}
