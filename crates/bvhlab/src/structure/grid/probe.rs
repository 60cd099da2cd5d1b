//! Per-query bookkeeping shared by the two space partitions, the uniform grid and the 2^D
//! tree: primitive tests that report themselves, count their cost and skip primitives already
//! tested (a partition lists a primitive in several cells), the pairs of a collision query,
//! and the box the cells tile.
//!
//! Primitives with a NaN or infinite coordinate ([`Primitive::has_finite_coordinates`]) are in no cell and
//! no list of either structure: no query answers with them, as brute force does not.

use crate::primitive::contract;
use std::cmp::Ordering;
use std::collections::HashSet;

use crate::structure::{
    Event, Mailbox, Nearest, NearestSet, Observer, PrimitiveResult, QueryCost, RangeShape, Traced,
};
use crate::volume::Aabb;
use crate::{BoundingVolume, Primitive, Ray, Vector};

/// A primitive index as the observer events carry it.
pub(crate) fn prim_id(i: usize) -> u32 {
    i as u32
}

/// The box around the finite primitives, and how many of them there are.
pub(crate) fn finite_bounds<P: Primitive>(prims: &[P]) -> (Aabb<P::Point>, usize) {
    prims
        .iter()
        .filter(|prim| prim.has_finite_coordinates())
        .fold((Aabb::EMPTY, 0), |(bounds, count), prim| {
            (bounds.merge(&prim.bounds()), count + 1)
        })
}

/// Tests one primitive against the region, reporting the test.
pub(crate) fn test_range<P: Primitive, O: Observer<P::Point>>(
    (i, prim): (u32, &P),
    shape: &RangeShape<P::Point>,
    cost: &mut QueryCost,
    found: &mut Vec<usize>,
    observer: &mut O,
) {
    cost.prim_tests += 1;
    let overlap = shape.overlaps_primitive(prim);
    observer.on(Event::PrimitiveTest {
        prim: i,
        result: if overlap {
            PrimitiveResult::Overlap
        } else {
            PrimitiveResult::NoOverlap
        },
    });
    if overlap {
        found.push(i as usize);
    }
}

/// Tests primitives against one ray, each once per query (mailboxing), reporting every test
/// and counting it.
pub(crate) struct RayProbe<'a, P: Primitive> {
    prims: &'a [P],
    ray: &'a Ray<P::Point>,
    t_max: f32,
    mailbox: Mailbox,
    /// What the query has cost so far.
    pub cost: QueryCost,
}

impl<'a, P: Primitive> RayProbe<'a, P> {
    /// A probe for hits with `0 <= t <= t_max`.
    pub(crate) fn new(prims: &'a [P], ray: &'a Ray<P::Point>, t_max: f32) -> Self {
        Self {
            prims,
            ray,
            t_max,
            mailbox: Mailbox::new(),
            cost: QueryCost::default(),
        }
    }

    /// Tests primitive `i` unless this query already has (then reports `AlreadyTested`);
    /// returns its hit when it lies in `[0, t_max]`.
    pub(crate) fn test<O: Observer<P::Point>>(&mut self, i: u32, observer: &mut O) -> Option<f32> {
        if !self.mailbox.admit(i, observer) {
            return None;
        }
        self.cost.prim_tests += 1;
        let t = contract::ray_hit(&self.prims[i as usize], self.ray).filter(|&t| t <= self.t_max);
        observer.on(Event::PrimitiveTest {
            prim: i,
            result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
        });
        t
    }
}

/// Measures primitives' distances to one query point, each once per query (mailboxing),
/// keeping the k nearest, reporting every test and counting it.
pub(crate) struct NearestProbe<'a, P: Primitive> {
    prims: &'a [P],
    point: P::Point,
    mailbox: Mailbox,
    nearest: NearestSet<P::Point>,
    /// What the query has cost so far.
    pub cost: QueryCost,
}

impl<'a, P: Primitive> NearestProbe<'a, P> {
    /// A probe for the `k` primitives nearest to `point`.
    pub(crate) fn new(prims: &'a [P], point: P::Point, k: usize) -> Self {
        Self {
            prims,
            point,
            mailbox: Mailbox::new(),
            nearest: NearestSet::new(k),
            cost: QueryCost::default(),
        }
    }

    /// The k-th best distance so far (`inf` while fewer than k are known).
    pub(crate) fn bound(&self) -> f32 {
        self.nearest.bound()
    }

    /// Measures primitive `i` unless this query already has (then reports `AlreadyTested`),
    /// with brute force's formula, and offers it to the k nearest.
    pub(crate) fn test<O: Observer<P::Point>>(&mut self, i: u32, observer: &mut O) {
        if !self.mailbox.admit(i, observer) {
            return;
        }
        self.cost.prim_tests += 1;
        let q = contract::project_point(&self.prims[i as usize], self.point);
        let d = (q - self.point).length();
        observer.on(Event::PrimitiveTest {
            prim: i,
            result: PrimitiveResult::Distance(d),
        });
        if self.nearest.offer(i as usize, q, d) {
            observer.on(Event::NewBest { prim: i, value: d });
        }
    }

    /// The k nearest, nearest first, with the cost.
    pub(crate) fn finish(self) -> Traced<Vec<Nearest<P::Point>>> {
        Traced {
            answer: self.nearest.into_vec(),
            cost: self.cost,
        }
    }
}

/// A min-priority-queue entry (`BinaryHeap` is a max-heap, so the order is reversed): the
/// smallest key first, ties by the lower `tie` value, so that searches are deterministic.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Queued<T> {
    /// The priority: a distance.
    pub key: f64,
    /// Breaks ties: a node or cell index.
    pub tie: u32,
    /// What is queued.
    pub item: T,
}

impl<T> PartialEq for Queued<T> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<T> Eq for Queued<T> {}

impl<T> PartialOrd for Queued<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<T> Ord for Queued<T> {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .key
            .total_cmp(&self.key)
            .then(other.tie.cmp(&self.tie))
    }
}

/// The pairs of a collision query, each pair tested once (a pair of primitives can meet in
/// several pairs of cells).
#[derive(Debug, Default)]
pub(crate) struct PairCollector {
    tested: HashSet<(u32, u32)>,
    pairs: Vec<(usize, usize)>,
    /// What the query has cost so far.
    pub cost: QueryCost,
}

impl PairCollector {
    /// Tests primitive `a` of the first structure against `b` of the second, unless this
    /// query already has. With `prefilter`, a pair whose bounding boxes do not overlap is
    /// rejected without the exact test (it cannot share a point) and without an event.
    pub(crate) fn test<P: Primitive, O: Observer<P::Point>>(
        &mut self,
        (a, pa): (u32, &P),
        (b, pb): (u32, &P),
        prefilter: bool,
        observer: &mut O,
    ) {
        if !self.tested.insert((a, b)) {
            return;
        }
        if prefilter {
            self.cost.bound_tests += 1;
            if !pa.bounds().overlaps(&pb.bounds()) {
                return;
            }
        }
        self.cost.prim_tests += 1;
        let overlap = pa.intersects(pb);
        observer.on(Event::PairTest { a, b, overlap });
        if overlap {
            self.pairs.push((a as usize, b as usize));
        }
    }

    /// Tests the unplaced primitives of each side against every primitive of the other, as
    /// brute force does (no cell lists them).
    pub(crate) fn test_unplaced<P: Primitive, O: Observer<P::Point>>(
        &mut self,
        (a_prims, a_unplaced): (&[P], &[u32]),
        (b_prims, b_unplaced): (&[P], &[u32]),
        observer: &mut O,
    ) {
        for &a in a_unplaced {
            for (b, pb) in b_prims.iter().enumerate() {
                self.test((a, &a_prims[a as usize]), (prim_id(b), pb), false, observer);
            }
        }
        for &b in b_unplaced {
            for (a, pa) in a_prims.iter().enumerate() {
                self.test((prim_id(a), pa), (b, &b_prims[b as usize]), false, observer);
            }
        }
    }

    /// The pairs found, ascending, with the cost.
    pub(crate) fn finish(mut self) -> Traced<Vec<(usize, usize)>> {
        self.pairs.sort_unstable();
        Traced {
            answer: self.pairs,
            cost: self.cost,
        }
    }
}
