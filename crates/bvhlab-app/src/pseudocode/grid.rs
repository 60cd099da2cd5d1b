//! The uniform grid: what the core's `grid/ray.rs` (with `dda.rs`), `nearest.rs`,
//! `range.rs` and `collide.rs` run.
//!
//! Each cell lists the primitives that overlap it, so a primitive spanning several cells is
//! listed in each ("Duplicate Triangle") and the queries test it once (mailboxing, Amanatides
//! and Woo 1987, §4). (Primitives with a non-finite coordinate sit in no cell; every query
//! tests them first, as the cell loop does.)

use bvhlab::Event;
use bvhlab::Vector;
use bvhlab::structure::PruneAt;

use super::listing::{Classify, Listing, Step, listing, primitive_step};
use super::{Algorithm, Pseudocode, Task};

static FIRST_HIT: Listing = listing!(
    "Uniform grid: first hit, cell by cell",
    "Lecture §3: walk the cells along the ray in order (the 3D-DDA of Amanatides and Woo, \
     1987); a hit found in a cell counts only if it lies inside that cell, since a nearer \
     primitive may be listed in a cell in between; test a duplicated primitive once \
     (mailboxing). The walk stops at the first cell that begins after the best hit.",
    [
        _         "intersect(grid, ray)             // the first hit",
        _         "    t = inf; hit = null          // the best hit so far",
        Enter     "    for (c in the cells along the ray, in order)  // 3D-DDA",
        Stop      "        if (c begins after t) return hit  // nothing nearer",
        _         "        for (p in c.primitives)",
        Mailbox   "            if (p was tested already) skip p  // mailbox",
        TestPrim  "            if (p.intersect(ray, tp))   // test p",
        _         "                // a hit counts only inside the current cell:",
        HitBeyond "                if (tp > c.tExit) not final yet: walk on",
        NewBest   "                if (tp < t) { t = tp; hit = p }",
        _         "    return hit",
    ]
);

static ANY_HIT: Listing = listing!(
    "Uniform grid: any hit, cell by cell",
    "The first-hit walk without the best hit: it stops at the first hit found, which is all \
     a shadow ray needs.",
    [
        _        "anyHit(grid, ray, tMax)          // e.g. a shadow ray",
        Enter    "    for (c in the cells along the ray, in order)  // 3D-DDA",
        Stop     "        if (c begins after tMax) return null",
        _        "        for (p in c.primitives)",
        Mailbox  "            if (p was tested already) skip p  // mailbox",
        TestPrim "            if (p.intersect(ray, tp) && tp <= tMax)  // test p",
        _        "                return p",
        _        "    return null",
    ]
);

static ALL_HITS: Listing = listing!(
    "Uniform grid: all hits, cell by cell",
    "The first-hit walk without the best hit, up to tMax: the mailbox keeps a primitive \
     listed in several cells from being reported twice.",
    [
        _        "allHits(grid, ray, tMax)",
        _        "    hits = []",
        Enter    "    for (c in the cells along the ray, in order)  // 3D-DDA",
        Stop     "        if (c begins after tMax) return hits sorted by t",
        _        "        for (p in c.primitives)",
        Mailbox  "            if (p was tested already) skip p  // mailbox",
        TestPrim "            if (p.intersect(ray, tp) && tp <= tMax)  // test p",
        _        "                hits.add(p, tp)",
        _        "    return hits sorted by t",
    ]
);

static NEAREST: Listing = listing!(
    "Uniform grid: minDistance with pruning, ring by ring",
    "Lecture §3's distance query on a grid: start in the query point's cell and search \
     outward, ring by ring (the cells ring steps away). Rings stop when even their nearest \
     cell is farther than currentMin; within a ring, a cell farther than currentMin is \
     skipped.",
    [
        _         "minDistance(grid, point, k)      // the k nearest, rings outward",
        _         "    best = []                    // the k nearest so far",
        _         "    currentMin = inf             // the k-th best distance",
        _         "    start = the cell of point (the nearest, if outside)",
        _         "    for (ring = 0, 1, 2, ...)    // cells ring steps from start",
        _         "        if (the ring's nearest distance > currentMin)",
        _         "            return best",
        _         "        for (c in the ring, within currentMin of point)",
        _         "            if (c lists primitives)",
        TestChild "                dc = distance(point, c's box)",
        SkipChild "                if (dc > currentMin) skip c  // nothing nearer",
        Enter     "            for (p in c.primitives)",
        Mailbox   "                if (p was measured already) skip p  // mailbox",
        TestPrim  "                dp = p.distance(point)",
        _         "                if (dp < currentMin)",
        NewBest   "                    add p to best (keep k), update currentMin",
        _         "    return best",
    ]
);

static RANGE: Listing = listing!(
    "Uniform grid: primitives in a range",
    "Only the cells the region's box covers are visited, in index order; a primitive listed \
     in several of them is tested once (mailboxing).",
    [
        _         "range(grid, region)              // a box or a ball",
        _         "    found = []",
        _         "    for (c in the cells that region's box covers)",
        SkipChild "        if (region is a ball that misses c) skip c",
        Enter     "        for (p in c.primitives)",
        Mailbox   "            if (p was tested already) skip p  // mailbox",
        TestPrim  "            if (p overlaps region) found.add(p)",
        _         "    return found",
    ]
);

/// The ray walk's events: a cell entered, its primitives tested, and the prune of the first
/// cell beyond the best hit (or `tMax`), at the stop: it ends the walk.
fn classify_ray<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::CellEnter { .. } => Step::Enter,
        Event::Prune {
            at: PruneAt::Stop, ..
        } => Step::Stop,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        Event::HitBeyondRegion { .. } => Step::HitBeyond,
        Event::NewBest { .. } => Step::NewBest,
        _ => return None,
    })
}

/// The rings' events: a non-empty cell is measured, then skipped at its test or entered; an
/// empty one is only entered.
fn classify_nearest<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::DistanceBoundTest { .. } => Step::TestChild,
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::EnterNode { .. } => Step::Enter,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        Event::NewBest { .. } => Step::NewBest,
        _ => return None,
    })
}

/// The range query's events: a cell a ball misses is pruned at its test, the others entered.
fn classify_range<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match *event {
        Event::Prune {
            at: PruneAt::Test, ..
        } => Step::SkipChild,
        Event::EnterNode { .. } => Step::Enter,
        Event::PrimitiveTest { result, .. } => primitive_step(result),
        _ => return None,
    })
}

/// The core's grid query for `task`; `None` for the build (see [`super::build`]).
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
