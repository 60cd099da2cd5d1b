//! Ray queries on the grid: walk the cells along the ray and test what they list.
//!
//! The lecture's rule: a hit found in a cell counts only if it lies inside that cell, since
//! a primitive listed in this cell may be hit further along, in a later cell, behind a nearer
//! primitive that a cell in between lists. So a hit beyond the current cell is kept as a
//! candidate ([`Event::HitBeyondRegion`]) and the walk goes on; it stops at the first cell
//! that begins after the best hit ([`PruneReason::BeyondBestHit`]): then every cell that
//! could hold a nearer hit has been searched. Each primitive is tested once per ray even when
//! several cells list it (mailboxing, Amanatides and Woo 1987, §4).

use std::ops::ControlFlow;

use super::dda::CellVisit;
use super::layout::Grid;
use super::probe::RayProbe;
use super::tolerance::RayTolerance;
use crate::structure::query::by_t_then_prim;
use crate::structure::{Event, Hit, HitTracker, NodeId, Observer, PruneAt, PruneReason, Traced};
use crate::{Primitive, Ray};

/// Reports entering a cell.
fn enter<P: Primitive, O: Observer<P::Point>>(
    visit: &CellVisit,
    probe: &mut RayProbe<'_, P>,
    observer: &mut O,
) {
    probe.cost.nodes_visited += 1;
    observer.on(Event::CellEnter {
        cell: NodeId(visit.cell),
        coords: visit.coords,
        t_enter: visit.t_enter as f32,
        t_exit: visit.t_exit as f32,
    });
}

/// Whether the walk may stop before `visit`: the cell begins after `limit` (the best hit, or
/// `t_max`) by more than the hits' rounding error. Reports the prune.
fn beyond<V: crate::Vector, O: Observer<V>>(
    visit: &CellVisit,
    limit: f32,
    tol: &RayTolerance,
    observer: &mut O,
) -> bool {
    let limit64 = f64::from(limit);
    let beyond = visit.t_enter > limit64 + tol.hit_slack(limit64);
    if beyond {
        observer.on(Event::Prune {
            node: NodeId(visit.cell),
            reason: PruneReason::BeyondBestHit {
                t_enter: visit.t_enter as f32,
                best_t: limit,
            },
            at: PruneAt::Stop,
        });
    }
    beyond
}

impl<P: Primitive> Grid<P> {
    /// The first hit: walk front to back, stop at the first cell beyond the best hit.
    pub(super) fn walk_first_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut probe = RayProbe::new(&self.prims, ray, t_max);
        let mut best = HitTracker::new(t_max);
        for &i in &self.unplaced {
            if let Some(t) = probe.test(i, observer)
                && best.offer(i as usize, t)
            {
                observer.on(Event::NewBest { prim: i, value: t });
            }
        }
        let tol = RayTolerance::new(ray, &self.bounds);
        probe.cost.bound_tests += 1;
        self.walk_ray(ray, &tol, |visit| {
            if beyond(&visit, best.limit(), &tol, observer) {
                return ControlFlow::Break(());
            }
            enter(&visit, &mut probe, observer);
            for &i in self.cell_primitives(visit.cell as usize) {
                if let Some(t) = probe.test(i, observer) {
                    if f64::from(t) > visit.t_exit {
                        observer.on(Event::HitBeyondRegion {
                            prim: i,
                            t,
                            t_exit: visit.t_exit as f32,
                        });
                    }
                    if best.offer(i as usize, t) {
                        observer.on(Event::NewBest { prim: i, value: t });
                    }
                }
            }
            ControlFlow::Continue(())
        });
        Traced {
            answer: best.best(),
            cost: probe.cost,
        }
    }

    /// Any hit: walk front to back and stop at the first hit in `[0, t_max]`.
    pub(super) fn walk_any_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut probe = RayProbe::new(&self.prims, ray, t_max);
        let mut found = None;
        for &i in &self.unplaced {
            if let Some(t) = probe.test(i, observer) {
                return Traced {
                    answer: Some(Hit::unplaced(i as usize, t)),
                    cost: probe.cost,
                };
            }
        }
        let tol = RayTolerance::new(ray, &self.bounds);
        probe.cost.bound_tests += 1;
        self.walk_ray(ray, &tol, |visit| {
            if beyond(&visit, t_max, &tol, observer) {
                return ControlFlow::Break(());
            }
            enter(&visit, &mut probe, observer);
            for &i in self.cell_primitives(visit.cell as usize) {
                if let Some(t) = probe.test(i, observer) {
                    found = Some(Hit::unplaced(i as usize, t));
                    return ControlFlow::Break(());
                }
            }
            ControlFlow::Continue(())
        });
        Traced {
            answer: found,
            cost: probe.cost,
        }
    }

    /// All hits: walk every cell up to `t_max`, collect each primitive's hit once.
    pub(super) fn walk_all_hits<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        let mut probe = RayProbe::new(&self.prims, ray, t_max);
        let mut hits = Vec::new();
        for &i in &self.unplaced {
            if let Some(t) = probe.test(i, observer) {
                hits.push(Hit::unplaced(i as usize, t));
            }
        }
        let tol = RayTolerance::new(ray, &self.bounds);
        probe.cost.bound_tests += 1;
        self.walk_ray(ray, &tol, |visit| {
            if beyond(&visit, t_max, &tol, observer) {
                return ControlFlow::Break(());
            }
            enter(&visit, &mut probe, observer);
            for &i in self.cell_primitives(visit.cell as usize) {
                if let Some(t) = probe.test(i, observer) {
                    hits.push(Hit::unplaced(i as usize, t));
                }
            }
            ControlFlow::Continue(())
        });
        hits.sort_by(by_t_then_prim);
        Traced {
            answer: hits,
            cost: probe.cost,
        }
    }
}
