//! The quadtree (the 2D octree): what the core's `quadtree/ray.rs`, `nearest.rs`,
//! `range.rs` and `collide.rs` run.
//!
//! A cell is split into four equal squares, and a primitive is listed in every child it
//! touches, so the queries skip a primitive already tested (mailboxing). Empty leaves are
//! never queued. (Primitives with a non-finite coordinate sit in no cell; every query tests
//! them first, as the leaf loop does.)

use bvhlab::Event;
use bvhlab::Vector;
use bvhlab::structure::PruneAt;

use super::listing::{Classify, Listing, ROOT, Step, listing, primitive_step};
use super::{Algorithm, Pseudocode, Task};

static FIRST_HIT: Listing = listing!(
    "Quadtree (octree in 3D): first hit, front to back",
    "Lecture §3: depth first; a ray interacts with a child when the child holds the ray \
     origin or the ray crosses into it; visit those children nearest first. A hit beyond \
     its leaf is not final: the search stops only at a cell that begins after the best hit \
     (children ordered by entry t, as in Revelles, Ureña and Lastra, 2000).",
    [
        _          "intersect(quadtree, ray)         // the first hit",
        _          "    t = inf; hit = null          // the best hit so far",
        TestRoot   "    [tEnter, tExit] = the ray inside the root cell",
        MissRoot   "    if (the ray misses it) return null",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (cell, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > t) continue  // behind the best hit",
        _          "        if (cell is a leaf)",
        _          "            for (p in cell.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp))",
        HitBeyond  "                    if (tp > tExit) not final yet  // beyond the cell",
        NewBest    "                    if (tp < t) { t = tp; hit = p }",
        _          "        else",
        _          "            for (c in the 4 children; 8 in 3D)",
        TestChild  "                [tc, tcExit] = the ray inside c",
        SkipChild  "                if (the ray misses c) skip c",
        Queue      "            push the non-empty ones, smallest tc on top",
        _          "    return hit",
    ]
);

static ANY_HIT: Listing = listing!(
    "Quadtree (octree in 3D): any hit, front to back",
    "The first-hit traversal without the best hit: it stops at the first hit found, which \
     is all a shadow ray needs.",
    [
        _          "anyHit(quadtree, ray, tMax)      // e.g. a shadow ray",
        TestRoot   "    [tEnter, tExit] = the ray inside the root cell",
        MissRoot   "    if (the ray misses it) return null",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (cell, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > tMax) continue",
        _          "        if (cell is a leaf)",
        _          "            for (p in cell.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        _          "                    return p",
        _          "        else",
        _          "            for (c in the 4 children; 8 in 3D)",
        TestChild  "                [tc, tcExit] = the ray inside c",
        SkipChild  "                if (the ray misses c) skip c",
        Queue      "            push the non-empty ones, smallest tc on top",
        _          "    return null",
    ]
);

static ALL_HITS: Listing = listing!(
    "Quadtree (octree in 3D): all hits, front to back",
    "The first-hit traversal without the best hit: every cell the ray reaches before tMax \
     is visited; the mailbox keeps a primitive listed in several cells from being reported \
     twice.",
    [
        _          "allHits(quadtree, ray, tMax)",
        _          "    hits = []",
        TestRoot   "    [tEnter, tExit] = the ray inside the root cell",
        MissRoot   "    if (the ray misses it) return hits",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (cell, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > tMax) continue",
        _          "        if (cell is a leaf)",
        _          "            for (p in cell.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        _          "                    hits.add(p, tp)",
        _          "        else",
        _          "            for (c in the 4 children; 8 in 3D)",
        TestChild  "                [tc, tcExit] = the ray inside c",
        SkipChild  "                if (the ray misses c) skip c",
        Queue      "            push the non-empty ones, smallest tc on top",
        _          "    return hits sorted by t",
    ]
);

static NEAREST: Listing = listing!(
    "Quadtree (octree in 3D): minDistance with pruning (best first)",
    "Lecture §3: descend to the cell of the query point, then search outward, skipping cells \
     farther than the best so far. A priority queue takes cells nearest first (Hjaltason and \
     Samet, 1999), so the search ends at the first cell no nearer than currentMin.",
    [
        _          "minDistance(quadtree, point, k)  // the k nearest, best first",
        _          "    best = []                    // the k nearest so far",
        _          "    currentMin = inf             // the k-th best distance",
        TestRoot   "    d = distance(point, root cell)",
        _          "    queue = [(root, d)]          // a priority queue",
        _          "    while (queue not empty)",
        Enter      "        (cell, d) = queue.popNearest()",
        SkipPopped "        if (d > currentMin) return best  // the rest is farther",
        _          "        if (cell is a leaf)",
        _          "            for (p in cell.primitives)",
        Mailbox    "                if (p was measured already) skip p  // mailbox",
        TestPrim   "                dp = p.distance(point)",
        _          "                if (dp < currentMin)",
        NewBest    "                    add p to best (keep k), update currentMin",
        _          "        else",
        _          "            for (c in the 4 children; 8 in 3D)",
        TestChild  "                dc = distance(point, c's cell)",
        _          "            for (c in the non-empty children, nearest first)",
        SkipChild  "                if (dc > currentMin) skip c  // nothing nearer",
        Queue      "                else queue.push(c, dc)",
        _          "    return best",
    ]
);

static RANGE: Listing = listing!(
    "Quadtree (octree in 3D): primitives in a range",
    "Descend into every cell the region overlaps; in the leaves, test each primitive exactly, \
     once (a primitive listed in several cells is mailboxed).",
    [
        _          "range(quadtree, region)          // a box or a ball",
        _          "    found = []",
        _          "    stack = [root]",
        _          "    while (stack not empty)",
        Enter      "        cell = stack.pop()",
        SkipPopped "        if (cell misses region) continue",
        _          "        if (cell is a leaf)",
        _          "            for (p in cell.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p overlaps region) found.add(p)",
        _          "        else",
        _          "            push the four children  // the first on top",
        _          "    return found",
    ]
);

/// The ray queries' events: a cell the ray misses is pruned at its test; a cell beyond the
/// best hit (or `tMax`) when it is popped.
fn classify_ray<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::RayBoundTest { node, .. } if node == ROOT => Step::TestRoot,
        Event::RayBoundTest { .. } => Step::TestChild,
        Event::Prune {
            node,
            at: PruneAt::Test,
            ..
        } if node == ROOT => Step::MissRoot,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::Prune {
            at: PruneAt::Pop, ..
        } => Step::SkipPopped,
        Event::EnterNode { .. } => Step::Enter,
        Event::ChildQueued { .. } => Step::Queue,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        Event::NewBest { .. } => Step::NewBest,
        Event::HitBeyondRegion { .. } => Step::HitBeyond,
        _ => return None,
    })
}

/// The nearest query's events: the children are measured, then queued or pruned at their
/// test, nearest first; a cell pruned when it is popped ends the search.
fn classify_nearest<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::DistanceBoundTest { node, .. } if node == ROOT => Step::TestRoot,
        Event::DistanceBoundTest { .. } => Step::TestChild,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::Prune {
            at: PruneAt::Pop, ..
        } => Step::SkipPopped,
        Event::EnterNode { .. } => Step::Enter,
        Event::ChildQueued { .. } => Step::Queue,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        Event::NewBest { .. } => Step::NewBest,
        _ => return None,
    })
}

/// The range query's events: a popped cell is tested silently and reported only when the
/// region misses it (a prune at the pop); children are pushed without events.
fn classify_range<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::Prune {
            at: PruneAt::Pop, ..
        } => Step::SkipPopped,
        Event::EnterNode { .. } => Step::Enter,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        _ => return None,
    })
}

/// The core's quadtree query for `task`; `None` for the build (see [`super::build`]).
pub(super) fn algorithm<V: Vector>(task: Task) -> Option<Algorithm<V>> {
    let (listing, classify): (_, Classify<V>) = match task {
        Task::FirstHit => (&FIRST_HIT, classify_ray),
        Task::AnyHit => (&ANY_HIT, classify_ray),
        Task::AllHits => (&ALL_HITS, classify_ray),
        Task::Nearest => (&NEAREST, classify_nearest),
        Task::Range => (&RANGE, classify_range),
        Task::Build => return None,
    };
    Some(Algorithm { listing, classify })
}
