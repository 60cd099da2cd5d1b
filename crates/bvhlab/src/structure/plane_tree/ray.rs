//! Ray queries on a plane tree: front-to-back traversal with the split distance.
//!
//! The classic recursive ray traversal of a BSP or k-d tree (Jansen 1986; Havran's thesis
//! "Heuristic Ray Shooting Algorithms", 2000, §4; pbrt-v3 §4.4.3), on an explicit stack: the
//! ray's `[t_enter, t_exit]` inside the root box is cut at each node's plane crossing
//! `t_split`; the child on the ray's near side (the one holding the origin, when the plane is
//! ahead) gets `[t_enter, t_split]` and is visited first, the far child gets `[t_split, t_exit]`
//! and is visited only when the ray reaches it. A ray parallel to a plane visits the side it
//! runs on; a ray running inside the plane visits both, because a primitive lying in the plane
//! may be stored on either side.
//!
//! Leaves test their primitives through a [`Mailbox`], since a primitive straddling a plane is
//! listed on both sides. The first hit ends the search only when it lies inside the current
//! leaf's interval, i.e. before the next region on the stack begins (the lecture: "stop at the
//! first hit that lies inside the current node"); a hit beyond it stays the best candidate
//! ([`Event::HitBeyondRegion`]) while the regions the ray reaches before it are searched.
//!
//! Events, in order (the grammar is in
//! [`observe`](crate::structure::observe#the-order-of-events)): [`Event::RayBoundTest`] of the
//! root box (then `Prune { RayMissed, at: Test }` on a miss); for each region taken from the
//! stack, `Prune { BeyondBestHit, at: Pop }` when the ray enters it after the best hit (or
//! `t_max`), else [`Event::EnterNode`]; at an inner node [`Event::PlaneCrossed`],
//! [`Event::ChildQueued`] for each child the ray reaches (near child rank 0, keyed by its
//! `t_enter`) and `Prune { RayMissed, at: Test }` for a child it does not; in a leaf
//! [`Event::PrimitiveTest`] per listed primitive (`AlreadyTested` for a mailboxed one),
//! [`Event::NewBest`], and `HitBeyondRegion`. When the search stops, every region left on the
//! stack is reported pruned at `Stop` (`BeyondBestHit`, or `AlreadyHit` for the any-hit
//! query).

use super::{PlaneNode, PlaneTree, PointOfTree, ROOT, node_id, root_interval};
use crate::Ray;
use crate::primitive::contract;
use crate::structure::query::by_t_then_prim;
use crate::structure::{
    Event, Hit, HitTracker, Mailbox, Observer, PrimitiveResult, PruneAt, PruneReason, QueryCost,
    Traced,
};

/// A node waiting on the stack with the part of the ray inside its region.
#[derive(Clone, Copy, Debug)]
struct Span {
    node: u32,
    depth: u32,
    t_enter: f32,
    t_exit: f32,
}

/// The traversal state shared by the three ray queries: the stack of regions still to visit,
/// front to back, and the cost so far.
struct RayWalk<'t, T: PlaneTree> {
    tree: &'t T,
    ray: &'t Ray<PointOfTree<T>>,
    stack: Vec<Span>,
    cost: QueryCost,
}

impl<'t, T: PlaneTree> RayWalk<'t, T> {
    /// Tests the ray against the root box (the slab test) and queues the root.
    fn start<O: Observer<PointOfTree<T>>>(
        tree: &'t T,
        ray: &'t Ray<PointOfTree<T>>,
        t_max: f32,
        observer: &mut O,
    ) -> Self {
        let mut walk = Self {
            tree,
            ray,
            stack: Vec::new(),
            cost: QueryCost::default(),
        };
        // `t <= t_max` has no solution `t >= 0` (or `t_max` is NaN): nothing to search.
        let Some(root) = tree.root_bound().filter(|_| t_max >= 0.0) else {
            return walk;
        };
        walk.cost.bound_tests += 1;
        let interval = root_interval(&root, ray);
        observer.on(Event::RayBoundTest {
            node: node_id(ROOT),
            interval,
        });
        match interval {
            Some((t_enter, t_exit)) => walk.stack.push(Span {
                node: ROOT,
                depth: 0,
                t_enter,
                t_exit,
            }),
            None => observer.on(Event::Prune {
                node: node_id(ROOT),
                reason: PruneReason::RayMissed,
                at: PruneAt::Test,
            }),
        }
        walk
    }

    /// Where the nearest region still on the stack begins (`inf` when none is left). Usually
    /// the top of the stack, but a ray running inside a plane queues both children with the
    /// same interval, so the whole (short) stack is looked at.
    fn next_enter(&self) -> f32 {
        self.stack
            .iter()
            .map(|s| s.t_enter)
            .fold(f32::INFINITY, f32::min)
    }

    /// Descends to the next leaf the ray reaches, front to back, skipping regions the ray
    /// enters only after `limit` (the best hit so far, or `t_max`).
    fn next_leaf<O: Observer<PointOfTree<T>>>(
        &mut self,
        limit: f32,
        observer: &mut O,
    ) -> Option<(Span, &'t [u32])> {
        while let Some(span) = self.stack.pop() {
            if span.t_enter > limit {
                observer.on(Event::Prune {
                    node: node_id(span.node),
                    reason: PruneReason::BeyondBestHit {
                        t_enter: span.t_enter,
                        best_t: limit,
                    },
                    at: PruneAt::Pop,
                });
                continue;
            }
            observer.on(Event::EnterNode {
                node: node_id(span.node),
                depth: span.depth,
            });
            self.cost.nodes_visited += 1;
            let children = match self.tree.node(span.node) {
                PlaneNode::Leaf(prims) => return Some((span, prims)),
                PlaneNode::Inner(children) => children,
            };
            self.cost.bound_tests += 1;
            let crossing = self.tree.crossing(span.node, self.ray);
            observer.on(Event::PlaneCrossed {
                node: node_id(span.node),
                t: crossing.t(),
            });
            let order = crossing.split(span.t_enter, span.t_exit);
            for (rank, (side, t_enter, _)) in order.iter().flatten().enumerate() {
                observer.on(Event::ChildQueued {
                    parent: node_id(span.node),
                    child: node_id(children[*side]),
                    key: *t_enter,
                    rank: rank as u32,
                });
            }
            for (side, t_enter, t_exit) in order.iter().rev().flatten() {
                self.stack.push(Span {
                    node: children[*side],
                    depth: span.depth + 1,
                    t_enter: *t_enter,
                    t_exit: *t_exit,
                });
            }
            // A child the ray does not reach is skipped: it misses that region.
            for (side, child) in children.into_iter().enumerate() {
                if order.iter().flatten().all(|(s, _, _)| *s != side) {
                    observer.on(Event::Prune {
                        node: node_id(child),
                        reason: PruneReason::RayMissed,
                        at: PruneAt::Test,
                    });
                }
            }
        }
        None
    }

    /// Skips every region still on the stack, nearest first.
    fn prune_rest<O: Observer<PointOfTree<T>>>(
        &mut self,
        reason: impl Fn(&Span) -> PruneReason,
        observer: &mut O,
    ) {
        while let Some(span) = self.stack.pop() {
            observer.on(Event::Prune {
                node: node_id(span.node),
                reason: reason(&span),
                at: PruneAt::Stop,
            });
        }
    }

    /// Tests primitive `prim` once per query: its hit within `[0, t_max]`, or `None` for a
    /// miss or when the mailbox says it was tested already.
    fn test<O: Observer<PointOfTree<T>>>(
        &mut self,
        prim: u32,
        t_max: f32,
        mailbox: &mut Mailbox,
        observer: &mut O,
    ) -> Option<f32> {
        if !mailbox.admit(prim, observer) {
            return None;
        }
        self.cost.prim_tests += 1;
        let t =
            contract::ray_hit(&self.tree.prims()[prim as usize], self.ray).filter(|&t| t <= t_max);
        observer.on(Event::PrimitiveTest {
            prim,
            result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
        });
        t
    }
}

/// The first hit with `0 <= t <= t_max`, ties to the lower index.
pub(crate) fn first_hit<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    tree: &T,
    ray: &Ray<PointOfTree<T>>,
    t_max: f32,
    observer: &mut O,
) -> Traced<Option<Hit>> {
    let mut walk = RayWalk::start(tree, ray, t_max, observer);
    let mut best = HitTracker::new(t_max);
    let mut mailbox = Mailbox::new();
    while let Some((span, prims)) = walk.next_leaf(best.limit(), observer) {
        let mut improved = false;
        for &prim in prims {
            if let Some(t) = walk.test(prim, t_max, &mut mailbox, observer)
                && best.offer(prim as usize, t)
            {
                improved = true;
                observer.on(Event::NewBest { prim, value: t });
            }
        }
        let Some(hit) = best.best() else { continue };
        // Before every region still to visit: none can hold a nearer (or equally near,
        // lower-index) hit. At exactly a region's entry a tie is still possible there.
        if hit.t < walk.next_enter() {
            walk.prune_rest(
                |s| PruneReason::BeyondBestHit {
                    t_enter: s.t_enter,
                    best_t: hit.t,
                },
                observer,
            );
            break;
        }
        if improved && hit.t > span.t_exit {
            observer.on(Event::HitBeyondRegion {
                prim: hit.prim as u32,
                t: hit.t,
                t_exit: span.t_exit,
            });
        }
    }
    Traced {
        answer: best.best(),
        cost: walk.cost,
    }
}

/// Some hit with `0 <= t <= t_max`: the first one found, front to back.
pub(crate) fn any_hit<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    tree: &T,
    ray: &Ray<PointOfTree<T>>,
    t_max: f32,
    observer: &mut O,
) -> Traced<Option<Hit>> {
    let mut walk = RayWalk::start(tree, ray, t_max, observer);
    let mut mailbox = Mailbox::new();
    while let Some((_, prims)) = walk.next_leaf(t_max, observer) {
        for &prim in prims {
            if let Some(t) = walk.test(prim, t_max, &mut mailbox, observer) {
                walk.prune_rest(|_| PruneReason::AlreadyHit, observer);
                return Traced {
                    answer: Some(Hit::unplaced(prim as usize, t)),
                    cost: walk.cost,
                };
            }
        }
    }
    Traced {
        answer: None,
        cost: walk.cost,
    }
}

/// Every primitive hit with `0 <= t <= t_max`, once each, sorted by `(t, index)`.
pub(crate) fn all_hits<T: PlaneTree, O: Observer<PointOfTree<T>>>(
    tree: &T,
    ray: &Ray<PointOfTree<T>>,
    t_max: f32,
    observer: &mut O,
) -> Traced<Vec<Hit>> {
    let mut walk = RayWalk::start(tree, ray, t_max, observer);
    let mut mailbox = Mailbox::new();
    let mut hits = Vec::new();
    while let Some((_, prims)) = walk.next_leaf(t_max, observer) {
        for &prim in prims {
            if let Some(t) = walk.test(prim, t_max, &mut mailbox, observer) {
                hits.push(Hit::unplaced(prim as usize, t));
            }
        }
    }
    hits.sort_by(by_t_then_prim);
    Traced {
        answer: hits,
        cost: walk.cost,
    }
}
