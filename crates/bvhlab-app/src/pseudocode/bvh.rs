//! Bounding volume hierarchies (sphere, AABB and OBB trees share these): what the core's
//! traversals run, in the slides' notation.
//!
//! The core makes the slides' recursive `intersect` and `minDistance` iterative with a stack,
//! tests both children's volumes before descending, visits the nearer child first and skips
//! a node that cannot hold anything better than the best so far (see `bvh/walk/ray.rs`,
//! `nearest.rs` and `range.rs` in the core).

use bvhlab::Event;
use bvhlab::Vector;
use bvhlab::structure::{PruneAt, PruneReason};

use super::listing::{Classify, Listing, ROOT, Step, listing};
use super::{Algorithm, Pseudocode, Task};

static FIRST_HIT: Listing = listing!(
    "BVH: first hit along a ray (near child first)",
    "The slides' intersect(bvNode, ray, t) (lecture §3) with what the slide's note says real \
     implementations add: the nearer child is visited first, and a node the ray enters \
     beyond the best hit so far is skipped. A stack replaces the recursion.",
    [
        _          "intersect(root, ray)             // the first hit",
        _          "    t = inf; hit = null          // the best hit so far",
        TestRoot   "    i = root.intersect(ray, tEnter)  // enters at tEnter",
        MissRoot   "    if (!i) return null          // the ray misses the scene",
        _          "    stack = [(root, tEnter)]",
        _          "    while (stack not empty)",
        Enter      "        (bvNode, tEnter) = stack.pop()",
        SkipPopped "        if (tEnter > t) continue  // behind the best hit",
        _          "        if (bvNode is a leaf)",
        _          "            for (p in bvNode.primitives)",
        TestPrim   "                if (p.intersect(ray, tp) && tp < t)",
        NewBest    "                    t = tp; hit = p  // a nearer hit",
        _          "        else",
        _          "            for (c in [bvNode.left, bvNode.right])",
        TestChild  "                i = c.intersect(ray, tc)  // enters at tc",
        SkipChild  "                if (!i) skip c            // the ray misses c",
        SkipBeyond "                else if (tc > t) skip c   // behind the best hit",
        Queue      "            push the others, nearer tc on top (popped first)",
        _          "    return hit",
    ]
);

static ANY_HIT: Listing = listing!(
    "BVH: any hit along a ray",
    "The first-hit traversal without the best hit: it stops at the first hit found, which \
     is all a shadow ray needs (is anything between the point and the light?).",
    [
        _          "anyHit(root, ray, tMax)          // e.g. a shadow ray",
        TestRoot   "    i = root.intersect(ray, tEnter)  // enters at tEnter",
        MissRoot   "    if (!i || tEnter > tMax) return null",
        _          "    stack = [(root, tEnter)]",
        _          "    while (stack not empty)",
        Enter      "        bvNode = stack.pop()",
        _          "        if (bvNode is a leaf)",
        _          "            for (p in bvNode.primitives)",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        Stop       "                    return p  // skip all still on the stack",
        _          "        else",
        _          "            for (c in [bvNode.left, bvNode.right])",
        TestChild  "                i = c.intersect(ray, tc)  // enters at tc",
        SkipChild  "                if (!i) skip c            // the ray misses c",
        SkipBeyond "                else if (tc > tMax) skip c",
        Queue      "            push the others, nearer tc on top (popped first)",
        _          "    return null",
    ]
);

static ALL_HITS: Listing = listing!(
    "BVH: all hits along a ray",
    "The first-hit traversal without the best hit: every node the ray enters before tMax is \
     visited, and the hits are sorted at the end.",
    [
        _          "allHits(root, ray, tMax)",
        _          "    hits = []",
        TestRoot   "    i = root.intersect(ray, tEnter)  // enters at tEnter",
        MissRoot   "    if (!i || tEnter > tMax) return hits",
        _          "    stack = [(root, tEnter)]",
        _          "    while (stack not empty)",
        Enter      "        bvNode = stack.pop()",
        _          "        if (bvNode is a leaf)",
        _          "            for (p in bvNode.primitives)",
        TestPrim   "                if (p.intersect(ray, tp) && tp <= tMax)",
        _          "                    hits.add(p, tp)",
        _          "        else",
        _          "            for (c in [bvNode.left, bvNode.right])",
        TestChild  "                i = c.intersect(ray, tc)  // enters at tc",
        SkipChild  "                if (!i) skip c            // the ray misses c",
        SkipBeyond "                else if (tc > tMax) skip c",
        Queue      "            push the others, nearer tc on top (popped first)",
        _          "    return hits sorted by t",
    ]
);

static NEAREST: Listing = listing!(
    "BVH: minDistance with pruning (the k nearest to a point)",
    "The slides' minDistance(bvNode, point, currentMin) (lecture §3) with the pruning the \
     slide leaves out: a node whose BV is farther than currentMin is skipped, and the nearer \
     child is visited first, so that currentMin drops early (Roussopoulos, Kelley and \
     Vincent, SIGMOD 1995). A node at exactly currentMin is still visited: a tie there goes \
     to the lower index.",
    [
        _          "minDistance(root, point, k)      // the k nearest; k = 1: nearest",
        _          "    best = []                    // the k nearest so far",
        _          "    currentMin = inf             // the k-th best distance",
        TestRoot   "    d = root.distance(point)     // 0 inside the BV",
        _          "    stack = [(root, d)]",
        _          "    while (stack not empty)",
        Enter      "        (bvNode, d) = stack.pop()",
        SkipPopped "        if (d > currentMin) continue  // nothing nearer inside",
        _          "        if (bvNode is a leaf)",
        _          "            for (p in bvNode.primitives)",
        TestPrim   "                dp = p.distance(point)",
        _          "                if (dp < currentMin)",
        NewBest    "                    add p to best (keep k), update currentMin",
        _          "        else",
        _          "            for (c in [bvNode.left, bvNode.right])",
        TestChild  "                dc = c.distance(point)",
        SkipChild  "                if (dc > currentMin) skip c  // nothing nearer",
        Queue      "            push the others, nearer dc on top (popped first)",
        _          "    return best",
    ]
);

static RANGE: Listing = listing!(
    "BVH: primitives in a range",
    "Depth first: a node whose BV misses the region is skipped with everything below it; \
     leaves test their primitives exactly.",
    [
        _         "range(root, region)              // a box or a ball",
        _         "    found = []",
        MissRoot  "    if (root's BV misses region) return found",
        _         "    stack = [root]",
        _         "    while (stack not empty)",
        Enter     "        bvNode = stack.pop()",
        _         "        if (bvNode is a leaf)",
        _         "            for (p in bvNode.primitives)",
        TestPrim  "                if (p overlaps region) found.add(p)",
        _         "        else",
        _         "            for (c in [bvNode.left, bvNode.right])",
        SkipChild "                if (c's BV misses region) skip c",
        Queue     "                else push c      // left is popped first",
        _         "    return found",
    ]
);

/// The ray queries' events (`bvh/walk/ray.rs`): a prune at its test is the root's miss
/// or a child's refusal (missed, or entered beyond the best hit); at a pop, a node behind the
/// best hit; at the stop, the any-hit query skipping what is left.
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
            reason: PruneReason::RayMissed,
            at: PruneAt::Test,
            ..
        } => Step::SkipChild,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipBeyond,
        Event::Prune {
            at: PruneAt::Pop, ..
        } => Step::SkipPopped,
        Event::Prune {
            at: PruneAt::Stop, ..
        } => Step::Stop,
        Event::EnterNode { .. } => Step::Enter,
        Event::ChildQueued { .. } => Step::Queue,
        Event::PrimitiveTest { .. } => Step::TestPrim,
        Event::NewBest { .. } => Step::NewBest,
        _ => return None,
    })
}

/// The nearest query's events (`bvh/walk/nearest.rs`): a child is pruned at its distance
/// test, a node behind the bound when it is popped (the root is never refused at its test:
/// the bound starts at infinity).
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
        Event::PrimitiveTest { .. } => Step::TestPrim,
        Event::NewBest { .. } => Step::NewBest,
        _ => return None,
    })
}

/// The range query's events (`bvh/walk/range.rs`): volumes are tested silently, and
/// only a miss is reported, as a prune at the test.
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
        Event::PrimitiveTest { .. } => Step::TestPrim,
        _ => return None,
    })
}

/// The core's BVH query for `task`; `None` for the build (see [`super::build`]).
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
