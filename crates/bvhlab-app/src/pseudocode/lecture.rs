//! The slides' own BVH pseudocode (lecture §3, "BVH intersection query" and "BVH distance
//! query"), verbatim, with only the lines the slides leave implicit added and marked
//! `// not on the slide`.
//!
//! The core runs these recursions literally beside its real traversals, so that the lab can
//! count what the slides leave out. Their events, per call: `EnterNode`; for `intersect` the
//! node's `RayBoundTest` and, on a miss, `Prune` (at `Test`); for the pruned `minDistance`,
//! before the call's `EnterNode`, a `DistanceBoundTest` and, when the node is skipped, `Prune`
//! (at `Test`); a leaf's
//! `PrimitiveTest`s and `NewBest`s; an inner node's `ChildQueued` with rank 0 just before the
//! call into the left child and rank 1 just before the call into the right child.

use bvhlab::Event;
use bvhlab::Vector;
use bvhlab::structure::PruneAt;

use super::listing::{Listing, Step, listing};
use super::{Algorithm, Pseudocode, Task, Variant};

static INTERSECT: Listing = listing!(
    "BVH: the slides' intersect(bvNode, ray, t)",
    "Lecture §3, verbatim, plus the leaf case the slide leaves implicit (a leaf's children are \
     null, so without it no primitive would ever be tested). It visits the left subtree, then \
     the right, whatever was hit so far: real implementations visit the nearer child first \
     and skip a child the ray enters beyond the best hit (compare the full version).",
    [
        Enter     "intersect(bvNode, ray, t)",
        _         "{",
        TestChild "    if (bvNode == null || !bvNode.intersect(ray, t))",
        SkipChild "        return false;",
        _         "    else",
        _         "    {",
        _         "        if (bvNode.isLeaf()) {                  // not on the slide",
        _         "            hit = false;                        // not on the slide",
        _         "            for (p in bvNode.primitives)        // not on the slide",
        TestPrim  "                if (p.intersect(ray, tp))       // not on the slide",
        _         "                    if (!hit || tp < t)         // not on the slide",
        NewBest   "                        { t = tp; hit = true; } // not on the slide",
        _         "            return hit;                         // not on the slide",
        _         "        }                                       // not on the slide",
        CallLeft  "        i1 = intersect(bvNode.left, ray, t1);   // check left BV",
        CallRight "        i2 = intersect(bvNode.right, ray, t2);  // check right BV",
        _         "        if (i1 && i2) { t = min(t1, t2); return true; }",
        _         "        if (i1) { t = t1; return true; }",
        _         "        if (i2) { t = t2; return true; }",
        _         "        return false;",
        _         "    }",
        _         "}",
    ]
);

static MIN_DISTANCE: Listing = listing!(
    "BVH: the slides' minDistance(bvNode, point, currentMin)",
    "Lecture §3, verbatim, plus the leaf case the slide leaves implicit. It tests no bounding \
     volume, so it visits every node and measures every primitive: the slide leaves out the \
     pruning that makes it fast (compare the pruned and the full versions).",
    [
        Enter     "minDistance(bvNode, point, currentMin)",
        _         "{",
        _         "    if (bvNode.isLeaf()) {                  // not on the slide",
        _         "        d = currentMin;                     // not on the slide",
        _         "        for (p in bvNode.primitives)        // not on the slide",
        TestPrim  "            if (p.distance(point) < d)      // not on the slide",
        NewBest   "                d = p.distance(point);      // not on the slide",
        _         "        return d;                           // not on the slide",
        _         "    }                                       // not on the slide",
        CallLeft  "    d1 = minDistance(bvNode.left, point, currentMin);",
        CallRight "    d2 = minDistance(bvNode.right, point, currentMin);",
        _         "    if (min(d1, d2) > currentMin) {",
        _         "        return currentMin",
        _         "    }",
        _         "    return min(d1, d2)",
        _         "}",
    ]
);

static MIN_DISTANCE_PRUNED: Listing = listing!(
    "BVH: the slides' minDistance, with the pruning it leaves out",
    "Lecture §3 plus the pruning the slide's note asks for: a node whose BV is farther from \
     the point than currentMin is skipped (at exactly currentMin it is still visited: a tie \
     goes to the lower index). For the pruning to bite, the right call gets the left \
     subtree's result in currentMin. Still left then right: the full version also visits \
     the nearer child first.",
    [
        _         "minDistance(bvNode, point, currentMin)",
        _         "{",
        TestChild "    if (bvNode.distance(point) > currentMin)  // not on the slide",
        SkipChild "        return currentMin;                    // not on the slide",
        Enter     "    if (bvNode.isLeaf()) {                  // not on the slide",
        _         "        d = currentMin;                     // not on the slide",
        _         "        for (p in bvNode.primitives)        // not on the slide",
        TestPrim  "            if (p.distance(point) < d)      // not on the slide",
        NewBest   "                d = p.distance(point);      // not on the slide",
        _         "        return d;                           // not on the slide",
        _         "    }                                       // not on the slide",
        CallLeft  "    d1 = minDistance(bvNode.left, point, currentMin);",
        _         "    currentMin = min(currentMin, d1);       // not on the slide",
        CallRight "    d2 = minDistance(bvNode.right, point, currentMin);",
        _         "    if (min(d1, d2) > currentMin) {",
        _         "        return currentMin",
        _         "    }",
        _         "    return min(d1, d2)",
        _         "}",
    ]
);

/// The recursions' events: each bound test and prune (at the test) concerns the node of the
/// current call, and the rank of a queued child says which call follows.
fn classify<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::EnterNode { .. } => Step::Enter,
        Event::RayBoundTest { .. } | Event::DistanceBoundTest { .. } => Step::TestChild,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::PrimitiveTest { .. } => Step::TestPrim,
        Event::NewBest { .. } => Step::NewBest,
        Event::ChildQueued { rank: 0, .. } => Step::CallLeft,
        Event::ChildQueued { .. } => Step::CallRight,
        _ => return None,
    })
}

/// The slides' version of `task`: `intersect` for the first hit, `minDistance` (plain or
/// pruned) for the nearest; `None` for every other task and for [`Variant::Full`].
pub(super) fn algorithm<V: Vector>(task: Task, variant: Variant) -> Option<Algorithm<V>> {
    let listing = match (task, variant) {
        (Task::FirstHit, Variant::Lecture) => &INTERSECT,
        (Task::Nearest, Variant::Lecture) => &MIN_DISTANCE,
        (Task::Nearest, Variant::LecturePruned) => &MIN_DISTANCE_PRUNED,
        _ => return None,
    };
    Some(Algorithm { listing, classify })
}
