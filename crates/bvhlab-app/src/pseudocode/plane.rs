//! k-d trees and BSP trees: binary trees of half-spaces, whose queries the core writes once
//! (`plane_tree/ray.rs`, `nearest.rs`, `range.rs`; the k-d tree is the
//! special case with axis-aligned planes, see `kdtree/mod.rs`).
//!
//! A node's region is cut by its plane, and a primitive that straddles the plane is listed on
//! both sides, so the queries skip a primitive already tested (mailboxing). For a k-d tree a
//! node's box is its cell; for a BSP tree, whose regions are convex polygons, it is the box of
//! the node's primitives.

use bvhlab::Event;
use bvhlab::Vector;
use bvhlab::structure::PruneAt;

use super::listing::{Classify, Listing, ROOT, Step, listing, primitive_step};
use super::{Algorithm, Pseudocode, Task};

static FIRST_HIT: Listing = listing!(
    "k-d / BSP tree: first hit, front to back",
    "Lecture §3: visit the child that holds the ray origin first, and stop at the first hit \
     inside the current node. The ray's [tEnter, tExit] is cut where it crosses each plane \
     (Jansen 1986; Havran's thesis, 2000; pbrt-v3 §4.4.3). A hit beyond the leaf is kept, \
     but a nearer one may lie in a region the ray reaches before it.",
    [
        _          "intersect(root, ray)             // the first hit",
        _          "    t = inf; hit = null          // the best hit so far",
        TestRoot   "    [tEnter, tExit] = the ray inside root's box",
        MissRoot   "    if (the ray misses the box) return null",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (node, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > t) continue  // behind the best hit",
        _          "        if (node is a leaf)",
        _          "            for (p in node.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp) && tp < t)",
        NewBest    "                    t = tp; hit = p  // a nearer hit",
        _          "            if (t < where the next region on the stack begins)",
        Stop       "                return hit   // it lies in this region: done",
        HitBeyond  "            if (t > tExit) keep it: a nearer hit may lie ahead",
        _          "        else",
        Cross      "            tSplit = where the ray crosses node's plane",
        _          "            near = the child on the ray origin's side",
        _          "            // near: [tEnter, tSplit], far: [tSplit, tExit]",
        Queue      "            push the children the ray reaches, near on top",
        SkipChild  "            skip a child the ray does not reach",
        _          "    return hit",
    ]
);

static ANY_HIT: Listing = listing!(
    "k-d / BSP tree: any hit, front to back",
    "The first-hit traversal without the best hit: it stops at the first hit found, which \
     is all a shadow ray needs.",
    [
        _          "anyHit(root, ray, tMax)          // e.g. a shadow ray",
        TestRoot   "    [tEnter, tExit] = the ray inside root's box",
        MissRoot   "    if (the ray misses the box) return null",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (node, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > tMax) continue",
        _          "        if (node is a leaf)",
        _          "            for (p in node.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        Stop       "                    return p  // skip all still on the stack",
        _          "        else",
        Cross      "            tSplit = where the ray crosses node's plane",
        _          "            // near: [tEnter, tSplit], far: [tSplit, tExit]",
        Queue      "            push the children the ray reaches, near on top",
        SkipChild  "            skip a child the ray does not reach",
        _          "    return null",
    ]
);

static ALL_HITS: Listing = listing!(
    "k-d / BSP tree: all hits, front to back",
    "The first-hit traversal without the best hit: every region the ray reaches before tMax \
     is visited; the mailbox keeps a primitive listed in several leaves from being reported \
     twice.",
    [
        _          "allHits(root, ray, tMax)",
        _          "    hits = []",
        TestRoot   "    [tEnter, tExit] = the ray inside root's box",
        MissRoot   "    if (the ray misses the box) return hits",
        _          "    stack = [(root, tEnter, tExit)]",
        _          "    while (stack not empty)",
        Enter      "        (node, tEnter, tExit) = stack.pop()",
        SkipPopped "        if (tEnter > tMax) continue",
        _          "        if (node is a leaf)",
        _          "            for (p in node.primitives)",
        Mailbox    "                if (p was tested already) skip p  // mailbox",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        _          "                    hits.add(p, tp)",
        _          "        else",
        Cross      "            tSplit = where the ray crosses node's plane",
        _          "            // near: [tEnter, tSplit], far: [tSplit, tExit]",
        Queue      "            push the children the ray reaches, near on top",
        SkipChild  "            skip a child the ray does not reach",
        _          "    return hits sorted by t",
    ]
);

static NEAREST: Listing = listing!(
    "k-d / BSP tree: minDistance with pruning (branch and bound)",
    "Lecture §3: descend to the cell of the query point, then search outward, skipping a \
     subtree whose box is farther than currentMin (Friedman, Bentley and Finkel, 1977). The \
     box is a k-d node's cell, or the box of a BSP node's primitives.",
    [
        _          "minDistance(root, point, k)      // the k nearest; k = 1: nearest",
        _          "    best = []                    // the k nearest so far",
        _          "    currentMin = inf             // the k-th best distance",
        TestRoot   "    d = distance(point, root's box)",
        _          "    stack = [(root, d)]",
        _          "    while (stack not empty)",
        Enter      "        (node, d) = stack.pop()",
        SkipPopped "        if (d > currentMin) continue  // nothing nearer inside",
        _          "        if (node is a leaf)",
        _          "            for (p in node.primitives)",
        Mailbox    "                if (p was measured already) skip p  // mailbox",
        TestPrim   "                dp = p.distance(point)",
        _          "                if (dp < currentMin)",
        NewBest    "                    add p to best (keep k), update currentMin",
        _          "        else",
        _          "            for (c in children, point's side first)",
        TestChild  "                dc = distance(point, c's box)",
        SkipChild  "                if (dc > currentMin) skip c  // nothing nearer",
        Queue      "                else push c  // point's side is popped first",
        _          "    return best",
    ]
);

static RANGE: Listing = listing!(
    "k-d / BSP tree: primitives in a range",
    "Descend into every child whose box overlaps the region; in the leaves, test each \
     primitive exactly, once (a primitive listed in several leaves is mailboxed).",
    [
        _         "range(root, region)              // a box or a ball",
        _         "    found = []",
        MissRoot  "    if (root's box misses region) return found",
        _         "    stack = [root]",
        _         "    while (stack not empty)",
        Enter     "        node = stack.pop()",
        _         "        if (node is a leaf)",
        _         "            for (p in node.primitives)",
        Mailbox   "                if (p was tested already) skip p  // mailbox",
        TestPrim  "                if (p overlaps region) found.add(p)",
        _         "        else",
        _         "            for (c in [node.below, node.above])",
        SkipChild "                if (c's box misses region) skip c",
        Queue     "                else push c      // below is popped first",
        _         "    return found",
    ]
);

/// The ray queries' events: the root box's test and miss; a child the ray does not reach is
/// pruned at its test, right after its parent's children are queued; a region behind the
/// best hit (or `tMax`) when it is popped; and, once the answer is final, everything left on
/// the stack at the stop.
fn classify_ray<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::RayBoundTest { .. } => Step::TestRoot,
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
        Event::Prune {
            at: PruneAt::Stop, ..
        } => Step::Stop,
        Event::EnterNode { .. } => Step::Enter,
        Event::PlaneCrossed { .. } => Step::Cross,
        Event::ChildQueued { .. } => Step::Queue,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        Event::NewBest { .. } => Step::NewBest,
        Event::HitBeyondRegion { .. } => Step::HitBeyond,
        _ => return None,
    })
}

/// The nearest query's events: a child is pruned at its distance test, a subtree whose box
/// is now too far when it is popped.
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

/// The range query's events: boxes are tested silently, and only a miss is reported, as a
/// prune at the test.
fn classify_range<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::Prune {
            node,
            at: PruneAt::Test,
            ..
        } if node == ROOT => Step::MissRoot,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::EnterNode { .. } => Step::Enter,
        Event::ChildQueued { .. } => Step::Queue,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        _ => return None,
    })
}

/// The core's k-d / BSP query for `task`; `None` for the build (see [`super::build`]).
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
