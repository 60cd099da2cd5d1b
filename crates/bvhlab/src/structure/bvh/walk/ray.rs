//! Ray queries: first hit, any hit, all hits.
//!
//! The lecture's recursive `intersect(bvNode, ray, t)`, made iterative with a stack: at an
//! inner node both children's volumes are tested, a missed child is pruned, and the others
//! are visited nearer entry first; a node is skipped when the ray enters it beyond the best
//! hit so far (for any-hit and all-hits queries: beyond `t_max`). The three queries share
//! this walk and differ only in what a leaf does with its primitives ([`RayVisitor`]).
//!
//! The first-hit walk is mirrored in WGSL by `trace` in the app's heat map shader
//! (`crates/bvhlab-app/src/render3d/heatmap/trace.wgsl`), which must visit and test exactly what it
//! does, to count the same nodes and triangles: a change to the order of visits, the
//! pruning or the counting must be made there too. The layout it reads is
//! [`layout::gpu`](crate::structure::bvh::layout::gpu).

use super::stack::{Entry, Stack};
use crate::primitive::contract;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::{GROW, NodeVolume, PreparedRay};
use crate::structure::query::by_t_then_prim;
use crate::structure::{
    Event, Hit, HitTracker, NodeId, Observer, PrimitiveResult, PruneAt, PruneReason, QueryCost,
    Traced,
};
use crate::{Primitive, Ray};

/// What a leaf does with its primitives.
trait RayVisitor<P: Primitive> {
    /// Nodes the ray enters beyond this are skipped.
    fn limit(&self) -> f32;
    /// Tests a leaf's primitives, counting each test in `cost`; returns `true` to end the
    /// query.
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        leaf: Leaf<'_, P>,
        ray: &Ray<P::Point>,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> bool;
}

/// A leaf's primitives in leaf order, with their input indices.
struct Leaf<'a, P> {
    prims: &'a [P],
    ids: &'a [u32],
}

impl<P> Leaf<'_, P> {
    fn iter(&self) -> impl Iterator<Item = (&P, u32)> {
        self.prims.iter().zip(self.ids.iter().copied())
    }
}

/// Tests one primitive, counting and reporting the test; the hit, if within `[0, t_max]`.
#[inline]
fn test<P: Primitive, O: Observer<P::Point>>(
    (prim, id): (&P, u32),
    ray: &Ray<P::Point>,
    t_max: f32,
    observer: &mut O,
    cost: &mut QueryCost,
) -> Option<f32> {
    cost.prim_tests += 1;
    let t = contract::ray_hit(prim, ray).filter(|&t| t <= t_max);
    observer.on(Event::PrimitiveTest {
        prim: id,
        result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
    });
    t
}

struct FirstHit {
    best: HitTracker,
    t_max: f32,
    /// `best.limit()`, kept here so that the hot loop reads a field.
    limit: f32,
}

impl<P: Primitive> RayVisitor<P> for FirstHit {
    #[inline]
    fn limit(&self) -> f32 {
        self.limit
    }
    #[inline]
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        leaf: Leaf<'_, P>,
        ray: &Ray<P::Point>,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> bool {
        for (prim, id) in leaf.iter() {
            if let Some(t) = test((prim, id), ray, self.t_max, observer, cost)
                && self.best.offer(id as usize, t)
            {
                self.limit = t;
                observer.on(Event::NewBest { prim: id, value: t });
            }
        }
        false
    }
}

struct AnyHit {
    found: Option<Hit>,
    t_max: f32,
}

impl<P: Primitive> RayVisitor<P> for AnyHit {
    fn limit(&self) -> f32 {
        self.t_max
    }
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        leaf: Leaf<'_, P>,
        ray: &Ray<P::Point>,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> bool {
        for (prim, id) in leaf.iter() {
            if let Some(t) = test((prim, id), ray, self.t_max, observer, cost) {
                self.found = Some(Hit::unplaced(id as usize, t));
                return true;
            }
        }
        false
    }
}

struct AllHits {
    hits: Vec<Hit>,
    t_max: f32,
}

impl<P: Primitive> RayVisitor<P> for AllHits {
    fn limit(&self) -> f32 {
        self.t_max
    }
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        leaf: Leaf<'_, P>,
        ray: &Ray<P::Point>,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> bool {
        for (prim, id) in leaf.iter() {
            if let Some(t) = test((prim, id), ray, self.t_max, observer, cost) {
                self.hits.push(Hit::unplaced(id as usize, t));
            }
        }
        false
    }
}

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The first hit with `0 <= t <= t_max` (none for a NaN `t_max`).
    pub(in crate::structure::bvh) fn first_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let best = HitTracker::new(t_max);
        let mut visitor = FirstHit {
            limit: best.limit(),
            best,
            t_max,
        };
        let cost = self.walk(ray, t_max, &mut visitor, observer);
        Traced {
            answer: visitor.best.best(),
            cost,
        }
    }

    /// Some hit with `0 <= t <= t_max`: the first one met.
    pub(in crate::structure::bvh) fn any_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut visitor = AnyHit { found: None, t_max };
        let cost = self.walk(ray, t_max, &mut visitor, observer);
        Traced {
            answer: visitor.found,
            cost,
        }
    }

    /// Every hit with `0 <= t <= t_max`, sorted by `t`, then index.
    pub(in crate::structure::bvh) fn all_hits<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        let mut visitor = AllHits {
            hits: Vec::new(),
            t_max,
        };
        let cost = self.walk(ray, t_max, &mut visitor, observer);
        let mut hits = visitor.hits;
        hits.sort_by(by_t_then_prim);
        Traced { answer: hits, cost }
    }

    /// The shared walk. Events, in order: for the root and then for both children of each
    /// inner node entered, `RayBoundTest` and, for a child refused, `Prune` (`RayMissed` or
    /// `BeyondBestHit`, at `Test`); `ChildQueued` for the others in visiting order; when a node
    /// is popped, `Prune(BeyondBestHit, at Pop)` if the best hit has meanwhile moved before its
    /// entry, else `EnterNode`, then at a leaf the visitor's `PrimitiveTest`s and `NewBest`s.
    /// When the visitor ends the query, `Prune(AlreadyHit, at Stop)` for every node still
    /// waiting.
    fn walk<Vis: RayVisitor<P>, O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        visitor: &mut Vis,
        observer: &mut O,
    ) -> QueryCost {
        let mut cost = QueryCost::default();
        if self.nodes.is_empty() || t_max.is_nan() {
            return cost;
        }
        let ray = PreparedRay::new(ray);
        let mut stack = Stack::new();
        let root = self.test_child(0, 0, &ray, visitor.limit(), observer, &mut cost);
        stack.push_pair(root, None);
        while let Some(entry) = stack.pop() {
            let limit = visitor.limit();
            if entry.key > limit * GROW {
                observer.on(Event::Prune {
                    node: NodeId(entry.node),
                    reason: PruneReason::BeyondBestHit {
                        t_enter: entry.key,
                        best_t: limit,
                    },
                    at: PruneAt::Pop,
                });
                continue;
            }
            cost.nodes_visited += 1;
            observer.on(Event::EnterNode {
                node: NodeId(entry.node),
                depth: entry.depth,
            });
            let node = &self.nodes[entry.node as usize];
            if node.is_leaf() {
                let range = node.leaf_range();
                let leaf = Leaf {
                    prims: &self.leaf_prims[range.clone()],
                    ids: &self.leaf_ids[range],
                };
                if visitor.leaf(leaf, &ray.ray, observer, &mut cost) {
                    while let Some(rest) = stack.pop() {
                        observer.on(Event::Prune {
                            node: NodeId(rest.node),
                            reason: PruneReason::AlreadyHit,
                            at: PruneAt::Stop,
                        });
                    }
                }
                continue;
            }
            let depth = entry.depth + 1;
            let first = self.test_child(entry.node + 1, depth, &ray, limit, observer, &mut cost);
            let second = self.test_child(node.start, depth, &ray, limit, observer, &mut cost);
            let order = stack.push_pair(first, second);
            for (rank, child) in order.iter().flatten().enumerate() {
                observer.on(Event::ChildQueued {
                    parent: NodeId(entry.node),
                    child: NodeId(child.node),
                    key: child.key,
                    rank: rank as u32,
                });
            }
        }
        cost
    }

    /// Tests a node's volume against the ray; the entry to queue, or `None` when refused.
    #[inline]
    fn test_child<O: Observer<P::Point>>(
        &self,
        node: u32,
        depth: u32,
        ray: &PreparedRay<P::Point>,
        limit: f32,
        observer: &mut O,
        cost: &mut QueryCost,
    ) -> Option<Entry> {
        cost.bound_tests += 1;
        let interval = self.nodes[node as usize].volume.ray_entry(ray);
        observer.on(Event::RayBoundTest {
            node: NodeId(node),
            interval,
        });
        let reason = match interval {
            None => PruneReason::RayMissed,
            Some((t_enter, _)) if t_enter > limit * GROW => PruneReason::BeyondBestHit {
                t_enter,
                best_t: limit,
            },
            Some((t_enter, _)) => {
                return Some(Entry {
                    node,
                    depth,
                    key: t_enter,
                });
            }
        };
        observer.on(Event::Prune {
            node: NodeId(node),
            reason,
            at: PruneAt::Test,
        });
        None
    }
}
