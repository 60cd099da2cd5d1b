//! Brute force: every query loops over all primitives. The baseline the lecture's structures
//! are measured against (§1: "we want to avoid testing every primitive").

use bvhlab::Event;
use bvhlab::Vector;

use super::listing::{Listing, Step, listing};
use super::{Algorithm, Pseudocode, Task};

const NOTE: &str = "No structure: every primitive is tested, so a query costs n tests \
    whatever it asks (lecture §1). The counters of every structure are compared with this.";

static FIRST_HIT: Listing = listing!("Brute force: first hit along a ray", NOTE, [
    _        "intersect(primitives, ray)",
    _        "    t = inf; hit = null          // the best hit so far",
    _        "    for (p in primitives)",
    TestPrim "        if (p.intersect(ray, tp) && tp < t)",
    NewBest  "            t = tp; hit = p      // a nearer hit",
    _        "    return hit",
]);

static ANY_HIT: Listing = listing!("Brute force: any hit along a ray", NOTE, [
    _        "anyHit(primitives, ray, tMax)    // e.g. a shadow ray",
    _        "    for (p in primitives)",
    TestPrim "        if (p.intersect(ray, tp) && tp <= tMax)",
    _        "            return p             // the first one found",
    _        "    return null",
]);

static ALL_HITS: Listing = listing!("Brute force: all hits along a ray", NOTE, [
    _        "allHits(primitives, ray, tMax)",
    _        "    hits = []",
    _        "    for (p in primitives)",
    TestPrim "        if (p.intersect(ray, tp) && tp <= tMax)",
    _        "            hits.add(p, tp)",
    _        "    return hits sorted by t",
]);

static NEAREST: Listing = listing!("Brute force: minDistance, the k nearest to a point", NOTE, [
    _        "minDistance(primitives, point, k)  // the k nearest; k = 1: nearest",
    _        "    best = []                    // the k nearest so far",
    _        "    currentMin = inf             // the k-th best distance",
    _        "    for (p in primitives)",
    TestPrim "        d = p.distance(point)",
    _        "        if (d < currentMin)",
    NewBest  "            add p to best (keep k), update currentMin",
    _        "    return best",
]);

static RANGE: Listing = listing!("Brute force: primitives in a range", NOTE, [
    _        "range(primitives, region)        // a box or a ball",
    _        "    found = []",
    _        "    for (p in primitives)",
    TestPrim "        if (p overlaps region)",
    _        "            found.add(p)",
    _        "    return found",
]);

/// Brute force's queries emit only primitive tests and improvements of the best.
fn classify<V: Vector>(event: &Event<V>) -> Option<Step> {
    match event {
        Event::PrimitiveTest { .. } => Some(Step::TestPrim),
        Event::NewBest { .. } => Some(Step::NewBest),
        _ => None,
    }
}

/// Brute force's query for `task`; `None` for the build (see [`super::build`]).
pub(super) fn algorithm<V: Vector>(task: Task) -> Option<Algorithm<V>> {
    let listing = match task {
        Task::FirstHit => &FIRST_HIT,
        Task::AnyHit => &ANY_HIT,
        Task::AllHits => &ALL_HITS,
        Task::Nearest => &NEAREST,
        Task::Range => &RANGE,
        Task::Build => return None,
    };
    Some(Algorithm { listing, classify })
}
