//! Ray queries on the 2^D tree: depth first, front to back.
//!
//! The lecture's traversal of a space partition: a ray interacts with a child when the child
//! holds the ray origin or the ray crosses into it; visit those children nearest first, and a
//! hit found in a leaf ends the search only if it lies inside that leaf. Children are ordered
//! by where the ray enters them, sorting the at most 2^D entry `t`s (Revelles, Ureña and
//! Lastra, "An efficient parametric algorithm for octree traversal", 2000, derive the same
//! order from the mid-plane crossings; a sort of eight numbers serves every dimension). A cell
//! is entered when the ray passes within the rounding tolerance of it (`RayTolerance`, shared
//! with the grid), and skipped once it begins beyond the best hit so far.

use std::ops::ControlFlow;

use super::layout::{Orthtree, child_box_at, child_count, split_point};
use crate::structure::grid::probe::RayProbe;
use crate::structure::grid::tolerance::{RayTolerance, ray_box_interval};
use crate::structure::query::by_t_then_prim;
use crate::structure::{Event, Hit, HitTracker, NodeId, Observer, PruneAt, PruneReason, Traced};
use crate::volume::Aabb;
use crate::{Primitive, Ray, Vector};

/// What a ray query does with the leaves the walk reaches.
trait LeafVisitor<'a, P: Primitive> {
    /// Cells that begin beyond this `t` (the best hit, or `t_max`) are skipped.
    fn limit(&self) -> f32;
    /// Tests a leaf's primitives; the ray leaves the leaf at `t_exit`. `Break` ends the walk.
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        prims: &[u32],
        t_exit: f64,
        observer: &mut O,
    ) -> ControlFlow<()>;
    /// The probe that tests primitives and counts the cost.
    fn probe(&mut self) -> &mut RayProbe<'a, P>;
}

/// A cell on the walk's stack.
#[derive(Clone, Copy)]
struct Pending<V: Vector> {
    node: u32,
    bounds: Aabb<V>,
    depth: u32,
    t_enter: f64,
    t_exit: f64,
}

struct FirstHit<'a, P: Primitive> {
    probe: RayProbe<'a, P>,
    best: HitTracker,
}

impl<'a, P: Primitive> LeafVisitor<'a, P> for FirstHit<'a, P> {
    fn limit(&self) -> f32 {
        self.best.limit()
    }
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        prims: &[u32],
        t_exit: f64,
        observer: &mut O,
    ) -> ControlFlow<()> {
        for &i in prims {
            if let Some(t) = self.probe.test(i, observer) {
                if f64::from(t) > t_exit {
                    observer.on(Event::HitBeyondRegion {
                        prim: i,
                        t,
                        t_exit: t_exit as f32,
                    });
                }
                if self.best.offer(i as usize, t) {
                    observer.on(Event::NewBest { prim: i, value: t });
                }
            }
        }
        ControlFlow::Continue(())
    }
    fn probe(&mut self) -> &mut RayProbe<'a, P> {
        &mut self.probe
    }
}

struct AnyHit<'a, P: Primitive> {
    probe: RayProbe<'a, P>,
    t_max: f32,
    found: Option<Hit>,
}

impl<'a, P: Primitive> LeafVisitor<'a, P> for AnyHit<'a, P> {
    fn limit(&self) -> f32 {
        self.t_max
    }
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        prims: &[u32],
        _: f64,
        observer: &mut O,
    ) -> ControlFlow<()> {
        for &i in prims {
            if let Some(t) = self.probe.test(i, observer) {
                self.found = Some(Hit::unplaced(i as usize, t));
                return ControlFlow::Break(());
            }
        }
        ControlFlow::Continue(())
    }
    fn probe(&mut self) -> &mut RayProbe<'a, P> {
        &mut self.probe
    }
}

struct AllHits<'a, P: Primitive> {
    probe: RayProbe<'a, P>,
    t_max: f32,
    hits: Vec<Hit>,
}

impl<'a, P: Primitive> LeafVisitor<'a, P> for AllHits<'a, P> {
    fn limit(&self) -> f32 {
        self.t_max
    }
    fn leaf<O: Observer<P::Point>>(
        &mut self,
        prims: &[u32],
        _: f64,
        observer: &mut O,
    ) -> ControlFlow<()> {
        for &i in prims {
            if let Some(t) = self.probe.test(i, observer) {
                self.hits.push(Hit::unplaced(i as usize, t));
            }
        }
        ControlFlow::Continue(())
    }
    fn probe(&mut self) -> &mut RayProbe<'a, P> {
        &mut self.probe
    }
}

impl<P: Primitive> Orthtree<P> {
    /// Walks the cells along the ray front to back, handing each leaf to `visitor`.
    fn walk<'a, L: LeafVisitor<'a, P>, O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        visitor: &mut L,
        observer: &mut O,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let tol = RayTolerance::new(ray, &self.root);
        let root = ray_box_interval(ray, &self.root, tol.len);
        bound_test(visitor.probe(), NodeId(0), root, observer);
        let Some((t_enter, t_exit)) = root else {
            return;
        };
        let mut stack = vec![Pending {
            node: 0,
            bounds: self.root,
            depth: 0,
            t_enter,
            t_exit,
        }];
        while let Some(cell) = stack.pop() {
            let limit = visitor.limit();
            let limit64 = f64::from(limit);
            if cell.t_enter > limit64 + tol.hit_slack(limit64) {
                observer.on(Event::Prune {
                    node: NodeId(cell.node),
                    reason: PruneReason::BeyondBestHit {
                        t_enter: cell.t_enter as f32,
                        best_t: limit,
                    },
                    at: PruneAt::Pop,
                });
                continue;
            }
            visitor.probe().cost.nodes_visited += 1;
            observer.on(Event::EnterNode {
                node: NodeId(cell.node),
                depth: cell.depth,
            });
            let node = self.nodes[cell.node as usize];
            if node.is_leaf() {
                let prims = self.leaf_primitives(NodeId(cell.node));
                if visitor.leaf(prims, cell.t_exit, observer).is_break() {
                    return;
                }
                continue;
            }
            // The non-empty children the ray meets, ordered by entry t (ties by child index).
            let mid = split_point(&cell.bounds);
            let halves = HalfSlabs::new(ray, &cell.bounds, mid, tol.len);
            let mut order = [(0.0f64, 0usize, 0.0f64); 8];
            let mut len = 0;
            for k in 0..child_count::<P::Point>() {
                let interval = halves.child_interval::<P::Point>(k);
                let child = node.first + k as u32;
                bound_test(visitor.probe(), NodeId(child), interval, observer);
                // An empty leaf can hold no hit: it is not queued.
                if let Some((t0, t1)) = interval.filter(|_| !self.is_empty_leaf(child)) {
                    order[len] = (t0, k, t1);
                    len += 1;
                }
            }
            let order = &mut order[..len];
            order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for (rank, &(t0, k, _)) in order.iter().enumerate() {
                observer.on(Event::ChildQueued {
                    parent: NodeId(cell.node),
                    child: NodeId(node.first + k as u32),
                    key: t0 as f32,
                    rank: rank as u32,
                });
            }
            for &(t0, k, t1) in order.iter().rev() {
                stack.push(Pending {
                    node: node.first + k as u32,
                    bounds: child_box_at(&cell.bounds, mid, k),
                    depth: cell.depth + 1,
                    t_enter: t0,
                    t_exit: t1,
                });
            }
        }
    }

    pub(super) fn walk_first_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut visitor = FirstHit {
            probe: RayProbe::new(&self.prims, ray, t_max),
            best: HitTracker::new(t_max),
        };
        self.walk(ray, &mut visitor, observer);
        Traced {
            answer: visitor.best.best(),
            cost: visitor.probe.cost,
        }
    }

    pub(super) fn walk_any_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut visitor = AnyHit {
            probe: RayProbe::new(&self.prims, ray, t_max),
            t_max,
            found: None,
        };
        self.walk(ray, &mut visitor, observer);
        Traced {
            answer: visitor.found,
            cost: visitor.probe.cost,
        }
    }

    pub(super) fn walk_all_hits<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        let mut visitor = AllHits {
            probe: RayProbe::new(&self.prims, ray, t_max),
            t_max,
            hits: Vec::new(),
        };
        self.walk(ray, &mut visitor, observer);
        visitor.hits.sort_by(by_t_then_prim);
        Traced {
            answer: visitor.hits,
            cost: visitor.probe.cost,
        }
    }
}

/// Where the ray is between the planes of each half of a cell, per axis: the parametric
/// form of the slab test for all 2^D children at once (Revelles et al. 2000), from the
/// crossings of the cell's three planes per axis. Each half-slab is grown by the tolerance
/// `grow`, so a child's interval is exactly that of [`ray_box_interval`] on its box grown
/// by `grow`: only cheaper.
pub(super) struct HalfSlabs {
    /// `[axis][half]`: where the ray enters and leaves that half's slab.
    near: [[f64; 2]; 3],
    far: [[f64; 2]; 3],
}

impl HalfSlabs {
    pub(super) fn new<V: Vector>(ray: &Ray<V>, cell: &Aabb<V>, mid: V, grow: f64) -> Self {
        let mut slabs = Self {
            near: [[f64::NEG_INFINITY; 2]; 3],
            far: [[f64::INFINITY; 2]; 3],
        };
        let (o, d) = (ray.origin(), ray.dir());
        for i in 0..V::DIM {
            let (oi, di) = (f64::from(o.coord(i)), f64::from(d.coord(i)));
            let m = f64::from(mid.coord(i));
            let spans = [
                (f64::from(cell.min.coord(i)) - grow, m + grow),
                (m - grow, f64::from(cell.max.coord(i)) + grow),
            ];
            for (half, (lo, hi)) in spans.into_iter().enumerate() {
                let (near, far) = if di == 0.0 {
                    if lo <= oi && oi <= hi {
                        (f64::NEG_INFINITY, f64::INFINITY)
                    } else {
                        (f64::INFINITY, f64::NEG_INFINITY)
                    }
                } else {
                    let (t0, t1) = ((lo - oi) / di, (hi - oi) / di);
                    if di > 0.0 { (t0, t1) } else { (t1, t0) }
                };
                slabs.near[i][half] = near;
                slabs.far[i][half] = far;
            }
        }
        slabs
    }

    /// Child `k`'s interval with `t >= 0`, or `None`.
    pub(super) fn child_interval<V: Vector>(&self, k: usize) -> Option<(f64, f64)> {
        let (mut enter, mut exit) = (0.0f64, f64::INFINITY);
        for i in 0..V::DIM {
            let half = k >> i & 1;
            enter = enter.max(self.near[i][half]);
            exit = exit.min(self.far[i][half]);
        }
        (enter <= exit).then_some((enter, exit))
    }
}

/// Counts and reports a ray-cell test; a miss is also reported as a prune.
fn bound_test<P: Primitive, O: Observer<P::Point>>(
    probe: &mut RayProbe<'_, P>,
    node: NodeId,
    interval: Option<(f64, f64)>,
    observer: &mut O,
) {
    probe.cost.bound_tests += 1;
    observer.on(Event::RayBoundTest {
        node,
        interval: interval.map(|(a, b)| (a as f32, b as f32)),
    });
    if interval.is_none() {
        observer.on(Event::Prune {
            node,
            reason: PruneReason::RayMissed,
            at: PruneAt::Test,
        });
    }
}
