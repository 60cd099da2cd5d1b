//! Every structure reports its events in the order `observe.rs` documents (its section "The
//! order of events"): many seeded random queries of every kind, on random scenes of 2D
//! segments and 3D triangles built with every option that changes the walk, each recorded
//! event stream read by a small state machine that follows that structure's grammar and
//! fails at the first event out of order.
//!
//! Each reader below is the grammar of one structure, written as code: its state is where it
//! is in the grammar and the stack (or queue) of nodes waiting. What a walk decides (which
//! child it refuses, whether a popped node is pruned, where it stops) the reader takes from
//! the events; what the structure fixes (a node's children in stored order, a leaf's list, a
//! node's depth) it takes from the structure's [`Outline`].

use std::collections::HashSet;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::bvh::{BvhOptions, NodeVolume, SphereFit, SplitMethod};
use bvhlab::structure::kdtree::{AxisRule, KdTreeOptions};
use bvhlab::structure::{
    BspOptions, GridOptions, OrthtreeOptions, PrimitiveResult, PruneAt, PruneReason, RangeShape,
};
use bvhlab::{
    Aabb, BruteForce, BspTree, Bvh, Event, Grid, KdTree, NodeId, NodeOutline, NodeShape, Obb,
    Orthtree, Outline, Primitive, Ray, Recorder, Segment2, SpatialIndex, Sphere, Triangle3, Vector,
};
use bvhlab_tests::scenes::{random_segments, random_triangles};
use bvhlab_tests::{random_ray, random_vector, rng};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

// ---- reading a stream ----

/// A recorded stream, read one event at a time.
struct Stream<'e, V: Vector> {
    events: &'e [Event<V>],
    at: usize,
    what: &'e str,
}

impl<'e, V: Vector> Stream<'e, V> {
    fn new(events: &'e [Event<V>], what: &'e str) -> Self {
        Self {
            events,
            at: 0,
            what,
        }
    }

    fn peek(&self) -> Option<Event<V>> {
        self.events.get(self.at).copied()
    }

    /// Stops the test at the current event, naming what the grammar expected there.
    #[track_caller]
    fn fail(&self, expected: &str) -> ! {
        let from = self.at.saturating_sub(4);
        let before = &self.events[from..self.at.min(self.events.len())];
        panic!(
            "{}: event {} is {:?}, but the grammar expects {expected} (the events before it: \
             {before:?})",
            self.what,
            self.at,
            self.events.get(self.at)
        )
    }

    /// Takes the next event if `ok` accepts it.
    fn take_if(&mut self, ok: impl FnOnce(&Event<V>) -> bool) -> Option<Event<V>> {
        let event = self.peek().filter(|e| ok(e))?;
        self.at += 1;
        Some(event)
    }

    /// Takes the next event, which `ok` must accept.
    #[track_caller]
    fn take(&mut self, expected: &str, ok: impl FnOnce(&Event<V>) -> bool) -> Event<V> {
        match self.take_if(ok) {
            Some(event) => event,
            None => self.fail(expected),
        }
    }

    /// [`take`](Self::take), naming the node (or primitive) the grammar expects on failure.
    #[track_caller]
    fn take_for(
        &mut self,
        expected: &str,
        n: impl std::fmt::Debug,
        ok: impl FnOnce(&Event<V>) -> bool,
    ) -> Event<V> {
        match self.take_if(ok) {
            Some(event) => event,
            None => self.fail(&format!("{expected} for {n:?}")),
        }
    }

    /// The stream must be over.
    #[track_caller]
    fn end(&self) {
        if self.at != self.events.len() {
            self.fail("the end");
        }
    }
}

/// Which prune reasons a place in the grammar accepts.
type Reason = fn(PruneReason) -> bool;

/// A prune of `node` at `at` for a reason `reason` accepts.
fn is_prune<V: Vector>(event: &Event<V>, node: NodeId, at: PruneAt, reason: Reason) -> bool {
    matches!(*event, Event::Prune { node: n, reason: r, at: a }
        if n == node && a == at && reason(r))
}

/// Takes `Prune(node, at)` if it comes next.
fn pruned<V: Vector>(s: &mut Stream<'_, V>, node: NodeId, at: PruneAt, reason: Reason) -> bool {
    s.take_if(|e| is_prune(e, node, at, reason)).is_some()
}

fn missed(r: PruneReason) -> bool {
    r == PruneReason::RayMissed
}

fn beyond(r: PruneReason) -> bool {
    matches!(r, PruneReason::BeyondBestHit { .. })
}

fn missed_or_beyond(r: PruneReason) -> bool {
    missed(r) || beyond(r)
}

fn no_nearer(r: PruneReason) -> bool {
    matches!(r, PruneReason::NoNearer { .. })
}

fn no_overlap(r: PruneReason) -> bool {
    r == PruneReason::NoOverlap
}

fn already_hit(r: PruneReason) -> bool {
    r == PruneReason::AlreadyHit
}

// ---- what the structure fixes ----

const ROOT: NodeId = NodeId(0);

/// A structure's nodes, as its outline lists them.
struct Tree<V: Vector> {
    nodes: Vec<NodeOutline<V>>,
}

impl<V: Vector> Tree<V> {
    fn of<S: Outline>(s: &S) -> Self
    where
        S::Prim: Primitive<Point = V>,
    {
        Self { nodes: s.outline() }
    }

    fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    fn node(&self, n: NodeId) -> &NodeOutline<V> {
        &self.nodes[n.index()]
    }

    fn children(&self, n: NodeId) -> &[NodeId] {
        &self.node(n).children
    }

    /// A leaf's (or cell's) list; empty for an inner node and for an id the structure lacks.
    fn prims(&self, n: NodeId) -> &[u32] {
        self.nodes.get(n.index()).map_or(&[], |o| &o.primitives)
    }

    /// The depth of `n`, if the structure has it.
    fn depth(&self, n: NodeId) -> Option<u32> {
        self.nodes.get(n.index()).map(|o| o.depth)
    }

    fn is_leaf(&self, n: NodeId) -> bool {
        self.node(n).is_leaf()
    }

    fn is_empty_leaf(&self, n: NodeId) -> bool {
        self.is_leaf(n) && self.prims(n).is_empty()
    }
}

/// Takes `EnterNode(n)` at `n`'s depth.
fn enter<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, n: NodeId) {
    let depth = t.node(n).depth;
    s.take_for("EnterNode(n) at its depth", n, |e| {
        *e == Event::EnterNode { node: n, depth }
    });
}

/// Takes `RayBoundTest(n)`.
fn ray_test<V: Vector>(s: &mut Stream<'_, V>, n: NodeId) {
    s.take_for(
        "RayBoundTest(n)",
        n,
        |e| matches!(*e, Event::RayBoundTest { node, .. } if node == n),
    );
}

/// Takes `DistanceBoundTest(n)`; its distance.
fn distance_test<V: Vector>(s: &mut Stream<'_, V>, n: NodeId) -> f32 {
    match s.take_for(
        "DistanceBoundTest(n)",
        n,
        |e| matches!(*e, Event::DistanceBoundTest { node, .. } if node == n),
    ) {
        Event::DistanceBoundTest { distance, .. } => distance,
        _ => unreachable!("taken as a distance test"),
    }
}

// ---- leaves ----

/// The form of a leaf's (or a cell's, or brute force's) primitive tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tests {
    /// `{PrimitiveTest(p) [NewBest(p)]}`, hits and misses.
    FirstHit,
    /// `{PrimitiveTest(p) [HitBeyondRegion(p)] [NewBest(p)]}` (quadtree, grid).
    FirstHitBeyond,
    /// `{PrimitiveTest(p)}`, ending at the first hit.
    AnyHit,
    /// `{PrimitiveTest(p)}`.
    AllHits,
    /// `{PrimitiveTest(p) [NewBest(p)]}`, distances.
    Nearest,
    /// `{PrimitiveTest(p)}`, overlaps.
    Range,
}

/// What a query has tested: each primitive once (a repeat is reported `AlreadyTested`), and
/// the last `NewBest`.
#[derive(Default)]
struct Tested {
    prims: HashSet<u32>,
    best: Option<u32>,
}

/// Reads the tests of `prims`, in their order; true when an any-hit query found its hit
/// (nothing of the leaf follows it).
fn leaf<V: Vector>(s: &mut Stream<'_, V>, prims: &[u32], tests: Tests, seen: &mut Tested) -> bool {
    for &p in prims {
        let repeat = seen.prims.contains(&p);
        let event = s.take_for(
            "PrimitiveTest(p) of the leaf's next primitive (AlreadyTested exactly when tested \
             before)",
            p,
            |e| match *e {
                Event::PrimitiveTest { prim, result } if prim == p => match result {
                    PrimitiveResult::AlreadyTested => repeat,
                    PrimitiveResult::Hit(_) | PrimitiveResult::Miss => {
                        !repeat && !matches!(tests, Tests::Nearest | Tests::Range)
                    }
                    PrimitiveResult::Distance(_) => !repeat && tests == Tests::Nearest,
                    PrimitiveResult::Overlap | PrimitiveResult::NoOverlap => {
                        !repeat && tests == Tests::Range
                    }
                },
                _ => false,
            },
        );
        seen.prims.insert(p);
        let Event::PrimitiveTest { result, .. } = event else {
            unreachable!("taken as a primitive test")
        };
        let value = match result {
            PrimitiveResult::Hit(t) => t,
            PrimitiveResult::Distance(d) => d,
            _ => continue,
        };
        if tests == Tests::AnyHit {
            return true;
        }
        if tests == Tests::FirstHitBeyond {
            s.take_if(
                |e| matches!(*e, Event::HitBeyondRegion { prim, t, .. } if prim == p && t == value),
            );
        }
        if matches!(
            tests,
            Tests::FirstHit | Tests::FirstHitBeyond | Tests::Nearest
        ) && s
            .take_if(|e| {
                matches!(*e, Event::NewBest { prim, value: v }
                    if prim == p && v.to_bits() == value.to_bits())
            })
            .is_some()
        {
            seen.best = Some(p);
        }
    }
    false
}

/// `{ChildQueued(n, c)}`: ranks 0, 1, ...; each child in `allowed` at most once; keys
/// non-decreasing when `sorted`. The children, in visiting order, with their keys.
fn queued<V: Vector>(
    s: &mut Stream<'_, V>,
    n: NodeId,
    allowed: &[NodeId],
    sorted: bool,
) -> Vec<(NodeId, f32)> {
    let mut order: Vec<(NodeId, f32)> = Vec::new();
    while let Some(Event::ChildQueued { .. }) = s.peek() {
        let last = order.last().map_or(f32::NEG_INFINITY, |q| q.1);
        let event = s.take_for(
            "ChildQueued(n, c): a child not refused, not queued yet, at the next rank, in key \
             order",
            n,
            |e| {
                matches!(*e, Event::ChildQueued { parent, child, key, rank }
                    if parent == n
                        && allowed.contains(&child)
                        && order.iter().all(|q| q.0 != child)
                        && rank as usize == order.len()
                        && (!sorted || key >= last))
            },
        );
        if let Event::ChildQueued { child, key, .. } = event {
            order.push((child, key));
        }
    }
    order
}

/// `stop = {Prune(m, at Stop)} end`: every node left, top of the stack first.
fn stop<V: Vector>(s: &mut Stream<'_, V>, stack: &mut Vec<NodeId>, reason: Reason) {
    while let Some(m) = stack.pop() {
        s.take_for("Prune(n, at Stop) of the top of the stack", m, |e| {
            is_prune(e, m, PruneAt::Stop, reason)
        });
    }
    s.end();
}

// ---- the queries ----

/// What a query asks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    FirstHit,
    AnyHit,
    AllHits,
    Nearest,
    Range,
}

/// One query.
#[derive(Clone, Copy, Debug)]
enum Query<V: Vector> {
    Ray(Kind, Ray<V>, f32),
    Nearest(V, usize),
    Range(RangeShape<V>),
}

impl<V: Vector> Query<V> {
    fn kind(&self) -> Kind {
        match self {
            Query::Ray(kind, ..) => *kind,
            Query::Nearest(..) => Kind::Nearest,
            Query::Range(..) => Kind::Range,
        }
    }
}

/// Runs `q` on `s`, recording its events.
fn record<S: SpatialIndex>(
    s: &S,
    q: &Query<<S::Prim as Primitive>::Point>,
) -> Vec<Event<<S::Prim as Primitive>::Point>> {
    let mut rec = Recorder::default();
    match *q {
        Query::Ray(Kind::AnyHit, ray, t_max) => {
            s.ray_any_hit_observed(&ray, t_max, &mut rec);
        }
        Query::Ray(Kind::AllHits, ray, t_max) => {
            s.ray_all_hits_observed(&ray, t_max, &mut rec);
        }
        Query::Ray(_, ray, t_max) => {
            s.ray_first_hit_observed(&ray, t_max, &mut rec);
        }
        Query::Nearest(point, k) => {
            s.k_nearest_observed(point, k, &mut rec);
        }
        Query::Range(shape) => {
            s.range_observed(&shape, &mut rec);
        }
    }
    rec.events
}

/// Rays (random, and aimed at a primitive, so that many hit), with `t_max` infinite or not;
/// points for 1, 2 and 5 nearest; boxes and balls.
fn queries<P: Primitive>(rng: &mut ChaCha8Rng, prims: &[P], rays: usize) -> Vec<Query<P::Point>> {
    let mut out = Vec::new();
    for i in 0..rays {
        let ray = if i % 2 == 0 || prims.is_empty() {
            random_ray(rng, 14.0)
        } else {
            let target = prims[rng.random_range(0..prims.len())].centroid();
            let from: P::Point = random_vector(rng, 14.0);
            match Ray::new(from, target - from) {
                Ok(ray) => ray,
                Err(_) => continue,
            }
        };
        let t_max = if i % 3 == 2 {
            rng.random_range(1.0f32..30.0)
        } else {
            f32::INFINITY
        };
        for kind in [Kind::FirstHit, Kind::AnyHit, Kind::AllHits] {
            out.push(Query::Ray(kind, ray, t_max));
        }
    }
    for k in [1, 2, 5, 1] {
        out.push(Query::Nearest(random_vector(rng, 14.0), k));
    }
    for _ in 0..3 {
        let c: P::Point = random_vector(rng, 12.0);
        let r = rng.random_range(0.5f32..5.0);
        out.push(Query::Range(RangeShape::Box(Aabb::new(
            c - P::Point::splat(r),
            c + P::Point::splat(0.5 * r),
        ))));
        out.push(Query::Range(RangeShape::Ball(Sphere::new(c, r))));
    }
    out
}

// ---- brute force ----

/// Brute force tests the finite primitives, in input order (`finite`: their indices).
fn brute<V: Vector>(s: &mut Stream<'_, V>, finite: &[u32], kind: Kind) {
    let tests = match kind {
        Kind::FirstHit => Tests::FirstHit,
        Kind::AnyHit => Tests::AnyHit,
        Kind::AllHits => Tests::AllHits,
        Kind::Nearest => Tests::Nearest,
        Kind::Range => Tests::Range,
    };
    leaf(s, finite, tests, &mut Tested::default());
    s.end();
}

fn brute_collide<V: Vector>(s: &mut Stream<'_, V>, a: &[u32], b: &[u32]) {
    for &i in a {
        for &j in b {
            s.take_for(
                "PairTest(a, b), every pair in order",
                (i, j),
                |e| matches!(*e, Event::PairTest { a, b, .. } if a == i && b == j),
            );
        }
    }
    s.end();
}

// ---- BVH ----

/// `test(c)`: `RayBoundTest(c)` for rays, `DistanceBoundTest(c)` for the nearest query,
/// nothing for a range (its volume tests are silent).
fn bound_test<V: Vector>(s: &mut Stream<'_, V>, kind: Kind, c: NodeId) {
    match kind {
        Kind::Nearest => {
            distance_test(s, c);
        }
        Kind::Range => {}
        _ => ray_test(s, c),
    }
}

/// The BVH's observed walks (`bvh/traverse_ray.rs`, `traverse_nearest.rs`,
/// `traverse_range.rs`).
fn bvh<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, kind: Kind) {
    if t.is_empty() {
        return s.end();
    }
    let (refused, popped): (Reason, Reason) = match kind {
        Kind::Nearest => (no_nearer, no_nearer),
        Kind::Range => (no_overlap, |_| false),
        _ => (missed_or_beyond, beyond),
    };
    let tests = match kind {
        Kind::FirstHit => Tests::FirstHit,
        Kind::AnyHit => Tests::AnyHit,
        Kind::AllHits => Tests::AllHits,
        Kind::Nearest => Tests::Nearest,
        Kind::Range => Tests::Range,
    };
    let mut seen = Tested::default();
    // query = test(root) [Prune(root, at Test)] {pop}
    bound_test(s, kind, ROOT);
    let mut stack = Vec::new();
    if !pruned(s, ROOT, PruneAt::Test, refused) {
        stack.push(ROOT);
    }
    while let Some(n) = stack.pop() {
        // pop = Prune(n, at Pop) | EnterNode(n) (leaf | inner)
        if pruned(s, n, PruneAt::Pop, popped) {
            continue;
        }
        enter(s, t, n);
        if t.is_leaf(n) {
            if leaf(s, t.prims(n), tests, &mut seen) {
                return stop(s, &mut stack, already_hit);
            }
            continue;
        }
        // inner = test(c1) [Prune(c1, at Test)] test(c2) [Prune(c2, at Test)] {ChildQueued}
        let mut accepted = Vec::new();
        for &c in t.children(n) {
            bound_test(s, kind, c);
            if !pruned(s, c, PruneAt::Test, refused) {
                accepted.push(c);
            }
        }
        let order = queued(s, n, &accepted, kind != Kind::Range);
        if order.len() != accepted.len() {
            s.fail("ChildQueued for every child not refused");
        }
        stack.extend(order.iter().rev().map(|q| q.0));
    }
    s.end();
}

/// `calls = ChildQueued(n, c1, rank 0) call(c1) ChildQueued(n, c2, rank 1) call(c2)`.
fn calls<V: Vector>(
    s: &mut Stream<'_, V>,
    t: &Tree<V>,
    n: NodeId,
    call: &mut dyn FnMut(&mut Stream<'_, V>, NodeId),
) {
    for (rank, &c) in t.children(n).iter().enumerate() {
        s.take("ChildQueued(n, c, rank) just before the call into c", |e| {
            matches!(*e, Event::ChildQueued { parent, child, rank: r, .. }
                if parent == n && child == c && r as usize == rank)
        });
        call(s, c);
    }
}

/// `intersect(n) = EnterNode(n) RayBoundTest(n) (Prune(n, at Test) | leaf | calls)`.
fn intersect<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, n: NodeId, seen: &mut Tested) {
    enter(s, t, n);
    ray_test(s, n);
    if pruned(s, n, PruneAt::Test, missed) {
        return;
    }
    if t.is_leaf(n) {
        leaf(s, t.prims(n), Tests::FirstHit, seen);
        return;
    }
    calls(s, t, n, &mut |s, c| intersect(s, t, c, seen));
}

/// `minDistance(n) = EnterNode(n) (leaf | calls)`, or with the pruning
/// `pruned(n) = DistanceBoundTest(n) (Prune(n, at Test) | EnterNode(n) (leaf | calls))`.
fn min_distance<V: Vector>(
    s: &mut Stream<'_, V>,
    t: &Tree<V>,
    n: NodeId,
    pruning: bool,
    seen: &mut Tested,
) {
    if pruning {
        distance_test(s, n);
        if pruned(s, n, PruneAt::Test, no_nearer) {
            return;
        }
    }
    enter(s, t, n);
    if t.is_leaf(n) {
        leaf(s, t.prims(n), Tests::Nearest, seen);
        return;
    }
    calls(s, t, n, &mut |s, c| min_distance(s, t, c, pruning, seen));
}

/// The node-pair descent of every tree's collision query: the pair on top of the stack is
/// tested; two overlapping leaves test their primitive pairs (each pair once, in order; all
/// of them when `every_pair`); otherwise the larger node, or the inner one, is opened, its
/// first child's pair on top.
fn collide<V: Vector>(s: &mut Stream<'_, V>, (a, b): (&Tree<V>, &Tree<V>), every_pair: bool) {
    let mut pairs = HashSet::new();
    if a.is_empty() || b.is_empty() {
        return s.end();
    }
    let mut stack = vec![(ROOT, ROOT)];
    while let Some((x, y)) = stack.pop() {
        let event = s.take_for(
            "NodePairTest of the pair on top of the stack",
            (x, y),
            |e| matches!(*e, Event::NodePairTest { a, b, .. } if a == x && b == y),
        );
        let Event::NodePairTest { overlap: true, .. } = event else {
            continue;
        };
        let open_a = match (a.is_leaf(x), b.is_leaf(y)) {
            (true, true) => {
                pair_tests(s, (a.prims(x), b.prims(y)), every_pair, &mut pairs);
                continue;
            }
            (false, true) => true,
            (true, false) => false,
            // The larger node is opened: its first child's pair comes next.
            (false, false) => match s.peek() {
                Some(Event::NodePairTest { a: na, b: nb, .. })
                    if na == a.children(x)[0] && nb == y =>
                {
                    true
                }
                Some(Event::NodePairTest { a: na, b: nb, .. })
                    if na == x && nb == b.children(y)[0] =>
                {
                    false
                }
                _ => s.fail("NodePairTest of the first child of one node with the other node"),
            },
        };
        if open_a {
            stack.extend(a.children(x).iter().rev().map(|&c| (c, y)));
        } else {
            stack.extend(b.children(y).iter().rev().map(|&c| (x, c)));
        }
    }
    s.end();
}

/// The pair tests of the primitives no node holds, before the descent.
fn unplaced_pairs<V: Vector>(
    s: &mut Stream<'_, V>,
    (a, b): (&[u32], &[u32]),
    pairs: &mut HashSet<(u32, u32)>,
) {
    while let Some(Event::PairTest { a: i, b: j, .. }) = s.peek() {
        s.take("PairTest of an unplaced primitive, once", |_| {
            (a.contains(&i) || b.contains(&j)) && pairs.insert((i, j))
        });
    }
}

/// `{PairTest(i, j)}` over `a × b` in order, each pair once per query.
fn pair_tests<V: Vector>(
    s: &mut Stream<'_, V>,
    (a, b): (&[u32], &[u32]),
    every_pair: bool,
    pairs: &mut HashSet<(u32, u32)>,
) {
    for &i in a {
        for &j in b {
            let new = !pairs.contains(&(i, j));
            let took = s
                .take_if(|e| new && matches!(*e, Event::PairTest { a, b, .. } if a == i && b == j))
                .is_some();
            if took {
                pairs.insert((i, j));
            } else if every_pair {
                s.fail("PairTest(i, j) of the next pair of the two leaves");
            }
        }
    }
}

// ---- k-d and BSP trees ----

/// The plane trees' walks (`bsp/traverse_ray.rs`, `traverse_nearest.rs`,
/// `traverse_range.rs`).
fn plane_tree<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, kind: Kind) {
    if t.is_empty() {
        return s.end();
    }
    let mut seen = Tested::default();
    match kind {
        Kind::Nearest => plane_nearest(s, t, &mut seen),
        Kind::Range => plane_range(s, t, &mut seen),
        _ => plane_ray(s, t, kind, &mut seen),
    }
}

fn plane_ray<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, kind: Kind, seen: &mut Tested) {
    // ray = RayBoundTest(root) (Prune(root, at Test) | {pop})
    ray_test(s, ROOT);
    if pruned(s, ROOT, PruneAt::Test, missed) {
        return s.end();
    }
    let tests = match kind {
        Kind::FirstHit => Tests::FirstHit,
        Kind::AnyHit => Tests::AnyHit,
        _ => Tests::AllHits,
    };
    let mut stack = vec![ROOT];
    while let Some(n) = stack.pop() {
        // pop = Prune(n, at Pop) | EnterNode(n) (leaf | inner)
        if pruned(s, n, PruneAt::Pop, beyond) {
            continue;
        }
        enter(s, t, n);
        if t.is_leaf(n) {
            if leaf(s, t.prims(n), tests, seen) {
                return stop(s, &mut stack, already_hit);
            }
            if kind == Kind::FirstHit {
                // (stop | [HitBeyondRegion(best)])
                if matches!(
                    s.peek(),
                    Some(Event::Prune {
                        at: PruneAt::Stop,
                        ..
                    })
                ) {
                    return stop(s, &mut stack, beyond);
                }
                let best = seen.best;
                s.take_if(
                    |e| matches!(*e, Event::HitBeyondRegion { prim, .. } if Some(prim) == best),
                );
            }
            continue;
        }
        // inner = PlaneCrossed(n) {ChildQueued(n, c)} {Prune(c, at Test)}
        s.take_for(
            "PlaneCrossed(n)",
            n,
            |e| matches!(*e, Event::PlaneCrossed { node, .. } if node == n),
        );
        let order = queued(s, n, t.children(n), true);
        for &c in t.children(n) {
            if order.iter().all(|q| q.0 != c) {
                s.take_for(
                    "Prune(n, at Test) of a child the ray does not reach",
                    c,
                    |e| is_prune(e, c, PruneAt::Test, missed),
                );
            }
        }
        stack.extend(order.iter().rev().map(|q| q.0));
    }
    s.end();
}

fn plane_nearest<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, seen: &mut Tested) {
    // nearest = DistanceBoundTest(root) {pop}
    distance_test(s, ROOT);
    let mut stack = vec![ROOT];
    while let Some(n) = stack.pop() {
        if pruned(s, n, PruneAt::Pop, no_nearer) {
            continue;
        }
        enter(s, t, n);
        if t.is_leaf(n) {
            leaf(s, t.prims(n), Tests::Nearest, seen);
            continue;
        }
        // inner = {DistanceBoundTest(c) (Prune(c, at Test) | ChildQueued(n, c))}, both children
        let mut order = Vec::new();
        let mut measured = Vec::new();
        for _ in 0..2 {
            let event = s.take("DistanceBoundTest(c) of a child not measured yet", |e| {
                matches!(*e, Event::DistanceBoundTest { node, .. }
                    if t.children(n).contains(&node) && !measured.contains(&node))
            });
            let Event::DistanceBoundTest { node: c, distance } = event else {
                unreachable!("taken as a distance test")
            };
            measured.push(c);
            if pruned(s, c, PruneAt::Test, no_nearer) {
                continue;
            }
            s.take(
                "Prune(c, at Test) or ChildQueued(n, c) at the next rank",
                |e| {
                    *e == Event::ChildQueued {
                        parent: n,
                        child: c,
                        key: distance,
                        rank: order.len() as u32,
                    }
                },
            );
            order.push(c);
        }
        stack.extend(order.into_iter().rev());
    }
    s.end();
}

fn plane_range<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, seen: &mut Tested) {
    // range = Prune(root, at Test) | {EnterNode(n) (leaf | inner)}
    if pruned(s, ROOT, PruneAt::Test, no_overlap) {
        return s.end();
    }
    let mut stack = vec![ROOT];
    while let Some(n) = stack.pop() {
        enter(s, t, n);
        if t.is_leaf(n) {
            leaf(s, t.prims(n), Tests::Range, seen);
            continue;
        }
        // inner = {Prune(c, at Test) | ChildQueued(n, c)}, below child then above
        let mut order = Vec::new();
        for &c in t.children(n) {
            if pruned(s, c, PruneAt::Test, no_overlap) {
                continue;
            }
            s.take(
                "Prune(c, at Test) or ChildQueued(n, c) at the next rank",
                |e| {
                    matches!(*e, Event::ChildQueued { parent, child, rank, .. }
                    if parent == n && child == c && rank as usize == order.len())
                },
            );
            order.push(c);
        }
        stack.extend(order.into_iter().rev());
    }
    s.end();
}

// ---- quadtrees and octrees ----

/// The 2^D tree's walks (`quadtree/ray.rs`, `nearest.rs`, `range.rs`).
fn orthtree<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, kind: Kind) {
    let mut seen = Tested::default();
    let tests = match kind {
        Kind::FirstHit => Tests::FirstHitBeyond,
        Kind::AnyHit => Tests::AnyHit,
        Kind::AllHits => Tests::AllHits,
        Kind::Nearest => Tests::Nearest,
        Kind::Range => Tests::Range,
    };
    if t.is_empty() {
        return s.end();
    }
    match kind {
        Kind::Nearest => orthtree_nearest(s, t, &mut seen),
        Kind::Range => orthtree_range(s, t, &mut seen),
        _ => orthtree_ray(s, t, tests, &mut seen),
    }
}

fn orthtree_ray<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, tests: Tests, seen: &mut Tested) {
    // ray = RayBoundTest(root) (Prune(root, at Test) | {pop})
    ray_test(s, ROOT);
    if pruned(s, ROOT, PruneAt::Test, missed) {
        return s.end();
    }
    let mut stack = vec![ROOT];
    while let Some(n) = stack.pop() {
        if pruned(s, n, PruneAt::Pop, beyond) {
            continue;
        }
        enter(s, t, n);
        if t.is_leaf(n) {
            if leaf(s, t.prims(n), tests, seen) {
                return s.end();
            }
            continue;
        }
        // inner = {RayBoundTest(c) [Prune(c, at Test)]} {ChildQueued(n, c)}
        let mut met = Vec::new();
        for &c in t.children(n) {
            ray_test(s, c);
            if !pruned(s, c, PruneAt::Test, missed) && !t.is_empty_leaf(c) {
                met.push(c);
            }
        }
        let order = queued(s, n, &met, true);
        if order.len() != met.len() {
            s.fail("ChildQueued for every child met that is not an empty leaf");
        }
        stack.extend(order.iter().rev().map(|q| q.0));
    }
    s.end();
}

fn orthtree_nearest<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, seen: &mut Tested) {
    // nearest = DistanceBoundTest(root) {EnterNode(n) (leaf | inner)}
    //           [Prune(n, at Pop) end]
    let mut queue = vec![(ROOT, distance_test(s, ROOT))];
    while !queue.is_empty() {
        let nearest = queue.iter().map(|q| q.1).fold(f32::INFINITY, f32::min);
        let event = s.take(
            "EnterNode(n) or Prune(n, at Pop) of a nearest cell queued",
            |e| {
                let n = match *e {
                    Event::EnterNode { node, depth } if t.depth(node) == Some(depth) => node,
                    Event::Prune {
                        node,
                        at: PruneAt::Pop,
                        reason,
                    } if no_nearer(reason) => node,
                    _ => return false,
                };
                queue.iter().any(|q| q.0 == n && q.1 == nearest)
            },
        );
        let (Event::EnterNode { node: n, .. } | Event::Prune { node: n, .. }) = event else {
            unreachable!("taken as an entry or a prune")
        };
        queue.retain(|q| q.0 != n);
        if matches!(event, Event::Prune { .. }) {
            return s.end();
        }
        if t.is_leaf(n) {
            leaf(s, t.prims(n), Tests::Nearest, seen);
            continue;
        }
        // inner = {DistanceBoundTest(c)} {ChildQueued(n, c) | Prune(c, at Test)}
        let measured: Vec<(NodeId, f32)> = t
            .children(n)
            .iter()
            .map(|&c| (c, distance_test(s, c)))
            .collect();
        let non_empty: Vec<(NodeId, f32)> = measured
            .into_iter()
            .filter(|q| !t.is_empty_leaf(q.0))
            .collect();
        let mut done: Vec<NodeId> = Vec::new();
        let mut rank = 0;
        let mut last = f32::NEG_INFINITY;
        for _ in 0..non_empty.len() {
            let event = s.take(
                "ChildQueued(n, c) or Prune(c, at Test) of the next non-empty child, nearest \
                 first",
                |e| {
                    let (c, ok) = match *e {
                        Event::ChildQueued {
                            parent,
                            child,
                            key,
                            rank: r,
                        } => {
                            let d = non_empty.iter().find(|q| q.0 == child).map(|q| q.1);
                            (child, parent == n && r == rank && d == Some(key))
                        }
                        Event::Prune {
                            node,
                            at: PruneAt::Test,
                            reason,
                        } => (node, no_nearer(reason)),
                        _ => return false,
                    };
                    let d = non_empty.iter().find(|q| q.0 == c).map(|q| q.1);
                    ok && !done.contains(&c) && d.is_some_and(|d| d >= last)
                },
            );
            let (Event::ChildQueued { child: c, .. } | Event::Prune { node: c, .. }) = event else {
                unreachable!("taken as a queued or pruned child")
            };
            let d = non_empty.iter().find(|q| q.0 == c).map_or(last, |q| q.1);
            if matches!(event, Event::ChildQueued { .. }) {
                queue.push((c, d));
                rank += 1;
            }
            done.push(c);
            last = d;
        }
    }
    s.end();
}

fn orthtree_range<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, seen: &mut Tested) {
    // range = {Prune(n, at Pop) | EnterNode(n) [leaf]}, children pushed silently
    let mut stack = vec![ROOT];
    while let Some(n) = stack.pop() {
        if pruned(s, n, PruneAt::Pop, no_overlap) {
            continue;
        }
        enter(s, t, n);
        if t.is_leaf(n) {
            leaf(s, t.prims(n), Tests::Range, seen);
        } else {
            stack.extend(t.children(n).iter().rev());
        }
    }
    s.end();
}

// ---- the grid ----

/// The grid's walks (`grid/ray.rs`, `nearest.rs`, `range.rs`); `unplaced` are the primitives
/// that no cell holds (updates moved them out of the grid's box), tested first.
fn grid<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, unplaced: &[u32], kind: Kind) {
    let mut seen = Tested::default();
    let tests = match kind {
        Kind::FirstHit => Tests::FirstHitBeyond,
        Kind::AnyHit => Tests::AnyHit,
        Kind::AllHits => Tests::AllHits,
        Kind::Nearest => Tests::Nearest,
        Kind::Range => Tests::Range,
    };
    if leaf(s, unplaced, tests, &mut seen) {
        return s.end();
    }
    let mut visited: HashSet<NodeId> = HashSet::new();
    let mut last_enter = f32::NEG_INFINITY;
    let mut last_cell: Option<NodeId> = None;
    while let Some(event) = s.peek() {
        match (kind, event) {
            // ray = unplaced {CellEnter(c) cell} [Prune(c, at Stop)]
            (
                Kind::FirstHit | Kind::AnyHit | Kind::AllHits,
                Event::CellEnter { cell, t_enter, .. },
            ) => {
                s.take("CellEnter(c) of a new cell, front to back", |_| {
                    t_enter >= last_enter && visited.insert(cell)
                });
                last_enter = t_enter;
                if leaf(s, t.prims(cell), tests, &mut seen) {
                    break;
                }
            }
            (Kind::FirstHit | Kind::AnyHit | Kind::AllHits, Event::Prune { node, .. }) => {
                s.take("Prune(c, at Stop) of a cell beyond the best hit", |e| {
                    is_prune(e, node, PruneAt::Stop, beyond)
                });
                break;
            }
            // nearest = unplaced {ring cell}
            (Kind::Nearest, Event::DistanceBoundTest { node: c, .. }) => {
                s.take(
                    "DistanceBoundTest(c) of a new cell that lists primitives",
                    |_| !t.prims(c).is_empty() && visited.insert(c),
                );
                if !pruned(s, c, PruneAt::Test, no_nearer) {
                    s.take("Prune(c, at Test) or EnterNode(c)", |e| {
                        *e == Event::EnterNode { node: c, depth: 0 }
                    });
                    leaf(s, t.prims(c), tests, &mut seen);
                }
            }
            (Kind::Nearest, Event::EnterNode { node: c, .. }) => {
                s.take("EnterNode(c) of a new empty cell", |e| {
                    *e == (Event::EnterNode { node: c, depth: 0 })
                        && t.prims(c).is_empty()
                        && visited.insert(c)
                });
            }
            // range = unplaced {Prune(c, at Test) | EnterNode(c) {PrimitiveTest(p)}}, in order
            (Kind::Range, Event::Prune { node: c, .. } | Event::EnterNode { node: c, .. }) => {
                s.take("Prune(c, at Test) or EnterNode(c) of a later cell", |e| {
                    last_cell.is_none_or(|l| l < c)
                        && (is_prune(e, c, PruneAt::Test, no_overlap)
                            || *e == (Event::EnterNode { node: c, depth: 0 }))
                });
                last_cell = Some(c);
                if matches!(event, Event::EnterNode { .. }) {
                    leaf(s, t.prims(c), tests, &mut seen);
                }
            }
            _ => s.fail("an event of this query's grammar"),
        }
    }
    s.end();
}

/// `collide = unplaced {NodePairTest(a, b) {PairTest}}`, the pairs of non-empty cells in order.
fn grid_collide<V: Vector>(
    s: &mut Stream<'_, V>,
    (a, b): (&Tree<V>, &Tree<V>),
    unplaced: (&[u32], &[u32]),
) {
    let mut pairs = HashSet::new();
    unplaced_pairs(s, unplaced, &mut pairs);
    let mut last: Option<(NodeId, NodeId)> = None;
    while s.peek().is_some() {
        let event = s.take(
            "NodePairTest(a, b) of two non-empty cells, after the last pair",
            |e| {
                matches!(*e, Event::NodePairTest { a: x, b: y, .. }
                if !a.prims(x).is_empty()
                    && !b.prims(y).is_empty()
                    && last.is_none_or(|l| l < (x, y)))
            },
        );
        let Event::NodePairTest {
            a: x,
            b: y,
            overlap,
        } = event
        else {
            unreachable!("taken as a node pair test")
        };
        last = Some((x, y));
        if overlap {
            pair_tests(s, (a.prims(x), b.prims(y)), false, &mut pairs);
        }
    }
    s.end();
}

// ---- builds ----

/// `node(n) = BuildNode(n, parent) (BuildSplit(n) {BuildSplit(n)} {node(c)} | BuildLeaf(n))`,
/// with `splits` plane reports per split.
fn build_node<V: Vector>(
    s: &mut Stream<'_, V>,
    t: &Tree<V>,
    n: NodeId,
    parent: Option<NodeId>,
    splits: usize,
) {
    let depth = t.node(n).depth;
    s.take_for(
        "BuildNode(n) with its parent and depth, depth first",
        n,
        |e| {
            matches!(*e, Event::BuildNode { node, parent: p, depth: d, .. }
            if node == n && p == parent && d == depth)
        },
    );
    if t.is_leaf(n) {
        let count = t.prims(n).len() as u32;
        s.take_for("BuildLeaf(n) with its primitives", n, |e| {
            *e == Event::BuildLeaf {
                node: n,
                prims: count,
            }
        });
        return;
    }
    for _ in 0..splits {
        s.take_for(
            "BuildSplit(n)",
            n,
            |e| matches!(*e, Event::BuildSplit { node, .. } if node == n),
        );
    }
    for &c in t.children(n) {
        build_node(s, t, c, Some(n), splits);
    }
}

fn tree_build<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>, splits: usize) {
    if !t.is_empty() {
        build_node(s, t, ROOT, None, splits);
    }
    s.end();
}

/// `grid = {BuildLeaf(c)}`: each non-empty cell, in index order.
fn grid_build<V: Vector>(s: &mut Stream<'_, V>, t: &Tree<V>) {
    for node in t.nodes.iter().filter(|n| !n.primitives.is_empty()) {
        let count = node.primitives.len() as u32;
        s.take("BuildLeaf(c) of the next non-empty cell", |e| {
            *e == Event::BuildLeaf {
                node: node.id,
                prims: count,
            }
        });
    }
    s.end();
}

// ---- the scenes and the runs ----

/// The scenes of one dimension: random ones of several sizes, one with a primitive whose
/// coordinates are NaN (left out of the trees, tested first by the quadtree and the grid),
/// and one of a primitive repeated (which no plane separates).
fn scenes<P: Primitive + Copy>(
    random: fn(&mut ChaCha8Rng, usize) -> Vec<P>,
    broken: P,
    seed: u64,
) -> Vec<(String, Vec<P>)> {
    let mut rng = rng(seed);
    let mut out: Vec<(String, Vec<P>)> = [0, 1, 30, 250]
        .into_iter()
        .map(|n| (format!("{n} random"), random(&mut rng, n)))
        .collect();
    let mut with_nan = random(&mut rng, 40);
    with_nan.insert(7, broken);
    out.push(("40 random and a NaN one".into(), with_nan));
    let one = random(&mut rng, 1)[0];
    let mut repeated = vec![one; 12];
    repeated.extend(random(&mut rng, 20));
    out.push(("one primitive 12 times, and 20 random".into(), repeated));
    out
}

/// What the checks read: how many events, and which kinds (a prune by where it happened and
/// why), so that a test knows every branch of its grammars came up.
#[derive(Default)]
struct Seen {
    events: usize,
    kinds: HashSet<String>,
}

impl Seen {
    fn add<V: Vector>(&mut self, events: &[Event<V>]) {
        self.events += events.len();
        for event in events {
            let kind = match *event {
                Event::Prune { reason, at, .. } => {
                    let why = match reason {
                        PruneReason::RayMissed => "RayMissed",
                        PruneReason::BeyondBestHit { .. } => "BeyondBestHit",
                        PruneReason::NoNearer { .. } => "NoNearer",
                        PruneReason::NoOverlap => "NoOverlap",
                        PruneReason::AlreadyHit => "AlreadyHit",
                    };
                    format!("Prune at {at:?}, {why}")
                }
                Event::PrimitiveTest {
                    result: PrimitiveResult::AlreadyTested,
                    ..
                } => "AlreadyTested".to_owned(),
                Event::EnterNode { .. } => "EnterNode".to_owned(),
                Event::RayBoundTest { .. } => "RayBoundTest".to_owned(),
                Event::DistanceBoundTest { .. } => "DistanceBoundTest".to_owned(),
                Event::ChildQueued { .. } => "ChildQueued".to_owned(),
                Event::PrimitiveTest { .. } => "PrimitiveTest".to_owned(),
                Event::PairTest { .. } => "PairTest".to_owned(),
                Event::NodePairTest { .. } => "NodePairTest".to_owned(),
                Event::NewBest { .. } => "NewBest".to_owned(),
                Event::HitBeyondRegion { .. } => "HitBeyondRegion".to_owned(),
                Event::CellEnter { .. } => "CellEnter".to_owned(),
                Event::PlaneCrossed { .. } => "PlaneCrossed".to_owned(),
                Event::BuildNode { .. } => "BuildNode".to_owned(),
                Event::BuildSplit { .. } => "BuildSplit".to_owned(),
                Event::BuildLeaf { .. } => "BuildLeaf".to_owned(),
            };
            self.kinds.insert(kind);
        }
    }

    /// At least `events` events were read, and every kind of `kinds` among them.
    #[track_caller]
    fn assert_saw(&self, events: usize, kinds: &[&str]) {
        assert!(
            self.events >= events,
            "only {} events were read",
            self.events
        );
        for kind in kinds {
            assert!(
                self.kinds.contains(*kind),
                "no {kind} came up, only {:?}",
                self.kinds
            );
        }
    }
}

/// Checks every query of `queries` on `s` with `read`.
fn check_queries<S, V>(
    s: &S,
    queries: &[Query<V>],
    what: &str,
    read: &dyn Fn(&mut Stream<'_, V>, Kind),
    seen: &mut Seen,
) where
    S: SpatialIndex,
    S::Prim: Primitive<Point = V>,
    V: Vector,
{
    for (i, q) in queries.iter().enumerate() {
        let events = record(s, q);
        let what = format!("{what}, query {i} ({q:?})");
        read(&mut Stream::new(&events, &what), q.kind());
        seen.add(&events);
    }
}

/// The BVH's walks, its slides' recursions, its collisions and its build, for one volume.
fn check_bvh<B, P>(scenes: &[(String, Vec<P>)], other: &[P], seed: u64, seen: &mut Seen)
where
    B: NodeVolume<Point = P::Point> + Into<NodeShape<P::Point>>,
    P: Primitive,
{
    let mut rng = rng(seed);
    let methods = [
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
        SplitMethod::BinnedSah,
    ];
    for (name, prims) in scenes {
        let qs = queries(&mut rng, prims, 10);
        for method in methods {
            for leaf_size in [1, 4] {
                let options = BvhOptions {
                    method,
                    leaf_size,
                    sphere_fit: if leaf_size == 1 {
                        SphereFit::Welzl
                    } else {
                        SphereFit::Ritter
                    },
                    ..BvhOptions::default()
                };
                let what = format!("{} over {name}, {options:?}", std::any::type_name::<B>());
                let mut rec = Recorder::default();
                let tree = Bvh::<B, P>::build_observed(prims, &options, &mut rec);
                let t = Tree::of(&tree);
                tree_build(
                    &mut Stream::new(&rec.events, &format!("{what}, build")),
                    &t,
                    1,
                );
                seen.add(&rec.events);
                check_queries(&tree, &qs, &what, &|s, kind| bvh(s, &t, kind), seen);
                // The slides' recursions.
                for (i, q) in qs.iter().enumerate() {
                    let what = format!("{what}, the slides' query {i} ({q:?})");
                    let mut streams = Vec::new();
                    match *q {
                        Query::Ray(Kind::FirstHit, ray, t_max) => {
                            let mut rec = Recorder::default();
                            tree.lecture_intersect_observed(&ray, t_max, &mut rec);
                            streams.push((rec.events, None));
                        }
                        Query::Nearest(point, _) => {
                            for pruning in [false, true] {
                                let mut rec = Recorder::default();
                                if pruning {
                                    tree.lecture_min_distance_pruned_observed(point, &mut rec);
                                } else {
                                    tree.lecture_min_distance_observed(point, &mut rec);
                                }
                                streams.push((rec.events, Some(pruning)));
                            }
                        }
                        _ => {}
                    }
                    for (events, pruning) in streams {
                        let s = &mut Stream::new(&events, &what);
                        let tested = &mut Tested::default();
                        if !t.is_empty() {
                            match pruning {
                                None => intersect(s, &t, ROOT, tested),
                                Some(pruning) => min_distance(s, &t, ROOT, pruning, tested),
                            }
                        }
                        s.end();
                        seen.add(&events);
                    }
                }
                let second = Bvh::<B, P>::build_with(other, &options);
                let t2 = Tree::of(&second);
                for (a, b, ta, tb) in [(&tree, &second, &t, &t2), (&second, &tree, &t2, &t)] {
                    let mut rec = Recorder::default();
                    a.collide_observed(b, &mut rec);
                    let what = format!("{what}, collide");
                    collide(&mut Stream::new(&rec.events, &what), (ta, tb), true);
                    seen.add(&rec.events);
                }
            }
        }
    }
}

/// The k-d and BSP trees' walks, collisions and builds.
fn check_plane_trees<P: Primitive>(
    scenes: &[(String, Vec<P>)],
    other: &[P],
    seed: u64,
    seen: &mut Seen,
) {
    let mut rng = rng(seed);
    let kd_options = [
        KdTreeOptions::median(AxisRule::LongestAxis),
        KdTreeOptions::median(AxisRule::RoundRobin),
        KdTreeOptions::sah(),
        KdTreeOptions {
            leaf_size: 1,
            ..KdTreeOptions::median(AxisRule::LongestAxis)
        },
    ];
    let bsp_options = [
        BspOptions::default(),
        BspOptions {
            leaf_size: 1,
            median_candidate: true,
            ..BspOptions::default()
        },
    ];
    for (name, prims) in scenes {
        let qs = queries(&mut rng, prims, 10);
        for options in &kd_options {
            let what = format!("k-d tree over {name}, {options:?}");
            let mut rec = Recorder::default();
            let tree = KdTree::build_observed(prims, options, &mut rec);
            let t = Tree::of(&tree);
            tree_build(
                &mut Stream::new(&rec.events, &format!("{what}, build")),
                &t,
                1,
            );
            seen.add(&rec.events);
            check_queries(&tree, &qs, &what, &|s, kind| plane_tree(s, &t, kind), seen);
            let second = KdTree::build_with(other, options);
            let mut rec = Recorder::default();
            tree.collide_observed(&second, &mut rec);
            let what = format!("{what}, collide");
            collide(
                &mut Stream::new(&rec.events, &what),
                (&t, &Tree::of(&second)),
                false,
            );
            seen.add(&rec.events);
        }
        for options in &bsp_options {
            let what = format!("BSP tree over {name}, {options:?}");
            let mut rec = Recorder::default();
            let tree = BspTree::build_observed(prims, options, &mut rec);
            let t = Tree::of(&tree);
            tree_build(
                &mut Stream::new(&rec.events, &format!("{what}, build")),
                &t,
                1,
            );
            seen.add(&rec.events);
            check_queries(&tree, &qs, &what, &|s, kind| plane_tree(s, &t, kind), seen);
            let second = BspTree::build_with(other, options);
            let mut rec = Recorder::default();
            second.collide_observed(&tree, &mut rec);
            let what = format!("{what}, collide");
            collide(
                &mut Stream::new(&rec.events, &what),
                (&Tree::of(&second), &t),
                false,
            );
            seen.add(&rec.events);
        }
    }
}

/// The quadtree's (octree's) walks, collisions and builds.
fn check_orthtree<P: Primitive>(
    scenes: &[(String, Vec<P>)],
    other: &[P],
    seed: u64,
    seen: &mut Seen,
) {
    let mut rng = rng(seed);
    let options = [
        OrthtreeOptions::default(),
        OrthtreeOptions {
            leaf_size: 1,
            ..OrthtreeOptions::default()
        },
        OrthtreeOptions {
            leaf_size: 2,
            max_depth: 2,
        },
    ];
    for (name, prims) in scenes {
        let qs = queries(&mut rng, prims, 10);
        for options in options {
            let what = format!("2^D tree over {name}, {options:?}");
            let mut rec = Recorder::default();
            let tree = Orthtree::build_observed(prims, &options, &mut rec);
            let t = Tree::of(&tree);
            let splits = P::Point::DIM;
            tree_build(
                &mut Stream::new(&rec.events, &format!("{what}, build")),
                &t,
                splits,
            );
            seen.add(&rec.events);
            check_queries(&tree, &qs, &what, &|s, kind| orthtree(s, &t, kind), seen);
            let second = Orthtree::build_with(other, &options);
            let mut rec = Recorder::default();
            tree.collide_observed(&second, &mut rec);
            let what = format!("{what}, collide");
            let t2 = Tree::of(&second);
            collide(&mut Stream::new(&rec.events, &what), (&t, &t2), false);
            seen.add(&rec.events);
        }
    }
}

/// The grid's walks, collisions and builds.
fn check_grid<P: Primitive>(scenes: &[(String, Vec<P>)], other: &[P], seed: u64, seen: &mut Seen) {
    let mut rng = rng(seed);
    let options = [
        GridOptions::default(),
        GridOptions {
            resolution: Some([4, 4, 4]),
            ..GridOptions::default()
        },
        GridOptions {
            resolution: Some([1, 1, 1]),
            ..GridOptions::default()
        },
        GridOptions {
            density: 12.0,
            ..GridOptions::default()
        },
    ];
    for (name, prims) in scenes {
        let qs = queries(&mut rng, prims, 10);
        for options in options {
            let what = format!("grid over {name}, {options:?}");
            let mut rec = Recorder::default();
            let grid = Grid::build_observed(prims, &options, &mut rec);
            let t = Tree::of(&grid);
            grid_build(&mut Stream::new(&rec.events, &format!("{what}, build")), &t);
            seen.add(&rec.events);
            let unplaced = grid.unplaced();
            check_queries(
                &grid,
                &qs,
                &what,
                &|s, kind| self::grid(s, &t, unplaced, kind),
                seen,
            );
            let second = Grid::build_with(other, &options);
            let mut rec = Recorder::default();
            grid.collide_observed(&second, &mut rec);
            let what = format!("{what}, collide");
            grid_collide(
                &mut Stream::new(&rec.events, &what),
                (&t, &Tree::of(&second)),
                (unplaced, second.unplaced()),
            );
            seen.add(&rec.events);
        }
    }
}

/// The indices of the primitives a query may test: those with finite coordinates.
fn finite_indices<P: Primitive>(prims: &[P]) -> Vec<u32> {
    (0..prims.len() as u32)
        .filter(|&i| prims[i as usize].has_finite_coordinates())
        .collect()
}

/// Brute force's queries and collisions.
fn check_brute<P: Primitive>(scenes: &[(String, Vec<P>)], other: &[P], seed: u64, seen: &mut Seen) {
    let mut rng = rng(seed);
    for (name, prims) in scenes {
        let qs = queries(&mut rng, prims, 6);
        let s = BruteForce::build(prims);
        let what = format!("brute force over {name}");
        let finite = finite_indices(prims);
        check_queries(&s, &qs, &what, &|st, kind| brute(st, &finite, kind), seen);
        let mut rec = Recorder::default();
        s.collide_observed(&BruteForce::build(other), &mut rec);
        brute_collide(
            &mut Stream::new(&rec.events, &format!("{what}, collide")),
            &finite,
            &finite_indices(other),
        );
        seen.add(&rec.events);
    }
}

fn segments() -> (Vec<(String, Vec<Segment2>)>, Vec<Segment2>) {
    let nan = Segment2::new(Vec2::new(f32::NAN, 1.0), Vec2::new(2.0, 3.0));
    let other = random_segments(&mut rng(99), 50);
    (scenes(random_segments, nan, 7), other)
}

fn triangles() -> (Vec<(String, Vec<Triangle3>)>, Vec<Triangle3>) {
    let nan = Triangle3::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, Vec3::Y);
    let other = random_triangles(&mut rng(98), 50);
    (scenes(random_triangles, nan, 8), other)
}

#[test]
fn brute_force_reports_in_grammar_order() {
    let (s2, o2) = segments();
    let (s3, o3) = triangles();
    let mut seen = Seen::default();
    check_brute(&s2, &o2, 1, &mut seen);
    check_brute(&s3, &o3, 2, &mut seen);
    seen.assert_saw(40_000, &["PrimitiveTest", "NewBest", "PairTest"]);
}

#[test]
fn bvh_walks_recursions_and_builds_report_in_grammar_order() {
    let (s2, o2) = segments();
    let (s3, o3) = triangles();
    let mut seen = Seen::default();
    check_bvh::<Aabb<Vec2>, _>(&s2, &o2, 11, &mut seen);
    check_bvh::<Sphere<Vec2>, _>(&s2, &o2, 12, &mut seen);
    check_bvh::<Obb<Vec2>, _>(&s2, &o2, 13, &mut seen);
    check_bvh::<Aabb<Vec3>, _>(&s3, &o3, 14, &mut seen);
    check_bvh::<Sphere<Vec3>, _>(&s3, &o3, 15, &mut seen);
    check_bvh::<Obb<Vec3>, _>(&s3, &o3, 16, &mut seen);
    seen.assert_saw(
        500_000,
        &[
            "Prune at Test, RayMissed",
            "Prune at Test, BeyondBestHit",
            "Prune at Pop, BeyondBestHit",
            "Prune at Stop, AlreadyHit",
            "Prune at Test, NoNearer",
            "Prune at Pop, NoNearer",
            "Prune at Test, NoOverlap",
            "ChildQueued",
            "NewBest",
            "NodePairTest",
            "PairTest",
            "BuildSplit",
            "BuildLeaf",
        ],
    );
}

#[test]
fn kd_and_bsp_trees_report_in_grammar_order() {
    let (s2, o2) = segments();
    let (s3, o3) = triangles();
    let mut seen = Seen::default();
    check_plane_trees(&s2, &o2, 21, &mut seen);
    check_plane_trees(&s3, &o3, 22, &mut seen);
    seen.assert_saw(
        150_000,
        &[
            "Prune at Test, RayMissed",
            "Prune at Pop, BeyondBestHit",
            "Prune at Stop, BeyondBestHit",
            "Prune at Stop, AlreadyHit",
            "Prune at Test, NoNearer",
            "Prune at Pop, NoNearer",
            "Prune at Test, NoOverlap",
            "PlaneCrossed",
            "HitBeyondRegion",
            "AlreadyTested",
            "NodePairTest",
            "PairTest",
            "BuildSplit",
        ],
    );
}

#[test]
fn quadtrees_and_octrees_report_in_grammar_order() {
    let (s2, o2) = segments();
    let (s3, o3) = triangles();
    let mut seen = Seen::default();
    check_orthtree(&s2, &o2, 31, &mut seen);
    check_orthtree(&s3, &o3, 32, &mut seen);
    seen.assert_saw(
        60_000,
        &[
            "Prune at Test, RayMissed",
            "Prune at Pop, BeyondBestHit",
            "Prune at Test, NoNearer",
            "Prune at Pop, NoNearer",
            "Prune at Pop, NoOverlap",
            "HitBeyondRegion",
            "AlreadyTested",
            "NodePairTest",
            "PairTest",
            "BuildSplit",
        ],
    );
}

#[test]
fn grids_report_in_grammar_order() {
    let (s2, o2) = segments();
    let (s3, o3) = triangles();
    let mut seen = Seen::default();
    check_grid(&s2, &o2, 41, &mut seen);
    check_grid(&s3, &o3, 42, &mut seen);
    seen.assert_saw(
        40_000,
        &[
            "CellEnter",
            "Prune at Stop, BeyondBestHit",
            "Prune at Test, NoNearer",
            "Prune at Test, NoOverlap",
            "HitBeyondRegion",
            "AlreadyTested",
            "NodePairTest",
            "PairTest",
            "BuildLeaf",
        ],
    );
}
