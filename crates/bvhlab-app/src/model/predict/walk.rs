//! Questions about a tree's walk: which node is taken next, whether the ray meets a volume
//! (and whether a node met is kept against the best hit so far), whether a node is kept
//! against the best distance so far, and which child is visited first.

use bvhlab::structure::{NodeId, PruneAt, PruneReason};
use bvhlab::{Event, Vector};

use super::question::{
    About, At, Choice, DISTINCT_ALONG_RAY, PredictQuestion, by_node, shown_apart, volume_word,
    yes_no,
};
use crate::model::question::{Task, Variant};
use crate::model::snapshot::Frontier;
use crate::model::structures::StructureKind;

/// Which node is taken from the stack or queue next, when two or more wait: `node` is the
/// one the step takes (entered, or pruned as it is taken).
pub(super) fn next_node<V: Vector>(at: &At<'_, V>, node: NodeId) -> Option<PredictQuestion> {
    let snapshot = at.snapshot;
    let frontier = snapshot.frontier_kind?;
    let first = snapshot.frontier.first()?;
    if !matches!(frontier, Frontier::Stack | Frontier::Queue)
        || snapshot.frontier.len() < 2
        || first.node != node
    {
        return None;
    }
    let unit = if at.kind == StructureKind::Grid {
        "cell"
    } else {
        "node"
    };
    // A queue's order is its keys: each answer shows its key, and the smallest must differ
    // from the others as shown.
    let queue = frontier == Frontier::Queue;
    let key_name = key_name(at);
    if queue
        && snapshot.frontier[1..]
            .iter()
            .any(|p| !shown_apart(p.key, first.key))
    {
        return None;
    }
    let choices = snapshot
        .frontier
        .iter()
        .map(|p| {
            let label = if queue {
                format!("{unit} {} ({key_name} {:.3})", p.node.0, p.key)
            } else {
                format!("{unit} {}", p.node.0)
            };
            (Choice::Node(p.node.0), label)
        })
        .collect();
    let (why, hint) = match frontier {
        Frontier::Queue => (
            format!(
                "the queue gives back the waiting {unit} with the smallest distance: {unit} {} ({:.3})",
                node.0, first.key
            ),
            "A priority queue gives back the smallest key, not the last one put in.",
        ),
        _ => (
            format!(
                "a stack gives back the {unit} pushed last: {unit} {}, queued by node {}",
                node.0, first.parent.0
            ),
            "A stack gives back the node pushed last; a node's children are pushed so that the nearer one is on top.",
        ),
    };
    Some(at.ask(
        format!(
            "{} {unit}s wait. Which one is taken next?",
            snapshot.frontier.len()
        ),
        by_node(choices),
        Choice::Node(node.0),
        1,
        why,
        hint,
        About::nodes(snapshot.frontier.iter().map(|p| p.node)),
    ))
}

/// What a walk's keys are: the distance from the point, or where the ray enters.
fn key_name<V: Vector>(at: &At<'_, V>) -> &'static str {
    if matches!(at.recording.question.task, Task::Nearest | Task::Range) {
        "distance"
    } else {
        "entry t"
    }
}

/// Whether the ray meets `node`'s volume; in the full first-hit walk, once a hit is known,
/// whether the node is kept or pruned (missed, or met only beyond the best hit).
pub(super) fn ray_bound<V: Vector>(
    at: &At<'_, V>,
    node: NodeId,
    interval: Option<(f32, f32)>,
) -> PredictQuestion {
    let volume = volume_word(at.kind);
    let question = &at.recording.question;
    let best = at.snapshot.best.first().map(|b| b.1);
    let prunes = at.prune_follows(node);
    // Kept or pruned against the best hit hangs on where the ray enters the volume, which
    // cannot be shown as a number without saying that the ray meets it: asked only when the
    // entry and the best hit (drawn on the ray) are clearly apart; else only "does it meet".
    let apart = |best_t: f32| {
        interval.is_none_or(|(a, _)| (a - best_t).abs() >= DISTINCT_ALONG_RAY * best_t.abs())
    };
    match best {
        Some(best_t)
            if question.task == Task::FirstHit
                && question.variant == Variant::Full
                && apart(best_t) =>
        {
            let beyond = matches!(
                at.next(),
                Some(Event::Prune {
                    node: n,
                    at: PruneAt::Test,
                    reason: PruneReason::BeyondBestHit { .. },
                }) if n == node
            );
            let (answer, why) = match interval {
                None => (Choice::Missed, miss_why(at.kind, node)),
                Some((a, _)) if beyond => (
                    Choice::Beyond,
                    format!(
                        "the ray enters node {}'s {volume} at t = {a:.3}, after the best hit so far (t = {best_t:.3}): nothing in it can be nearer, so it is pruned",
                        node.0
                    ),
                ),
                Some((a, _)) => (
                    Choice::Kept,
                    format!(
                        "the ray enters node {}'s {volume} at t = {a:.3}, before the best hit so far (t = {best_t:.3}): it may hold a nearer hit, so it is kept",
                        node.0
                    ),
                ),
            };
            at.ask(
                format!(
                    "The best hit so far is at t = {best_t:.3}. What happens to node {} when the ray is tested against its {volume}?",
                    node.0
                ),
                vec![
                    (Choice::Missed, "the ray misses it: pruned".to_owned()),
                    (
                        Choice::Beyond,
                        "the ray meets it after the best hit: pruned".to_owned(),
                    ),
                    (
                        Choice::Kept,
                        "the ray meets it before the best hit: kept".to_owned(),
                    ),
                ],
                answer,
                1 + usize::from(prunes),
                why,
                "Find where the ray enters the volume, and compare that t with the best hit so far.",
                About::nodes([node]),
            )
        }
        _ => {
            let (answer, why) = match interval {
                Some((a, b)) => (
                    Choice::Yes,
                    format!(
                        "the ray is inside node {}'s {volume} for t in [{a:.3}, {b:.3}]",
                        node.0
                    ),
                ),
                None => (Choice::No, miss_why(at.kind, node)),
            };
            at.ask(
                format!("Does the ray meet node {}'s {volume}?", node.0),
                yes_no(),
                answer,
                1 + usize::from(interval.is_none() && prunes),
                why,
                slab_hint(at.kind),
                About::nodes([node]),
            )
        }
    }
}

/// Whether `node` is kept or pruned against the best distance so far (asked once there is
/// one: before, every node is kept).
pub(super) fn distance_bound<V: Vector>(
    at: &At<'_, V>,
    node: NodeId,
    distance: f32,
) -> Option<PredictQuestion> {
    let best = at.kth_best()?;
    if !shown_apart(distance, best) {
        return None;
    }
    let volume = volume_word(at.kind);
    let pruned = at.prune_follows(node);
    let (answer, why) = if pruned {
        (
            Choice::NoNearer,
            format!(
                "node {}'s {volume} is {distance:.3} from the point, no nearer than the best so far ({best:.3}): nothing in it can be nearer, so it is pruned",
                node.0
            ),
        )
    } else {
        (
            Choice::Kept,
            format!(
                "node {}'s {volume} is {distance:.3} from the point, nearer than the best so far ({best:.3}): it may hold something nearer, so it is kept",
                node.0
            ),
        )
    };
    Some(at.ask(
        format!(
            "The best distance so far is {best:.3}; node {0}'s {volume} is {distance:.3} from the point. Is node {0} kept or pruned?",
            node.0
        ),
        vec![
            (
                Choice::Kept,
                "kept: its volume is nearer than the best".to_owned(),
            ),
            (
                Choice::NoNearer,
                "pruned: its volume is no nearer than the best".to_owned(),
            ),
        ],
        answer,
        1 + usize::from(pruned),
        why,
        "Nothing in a volume is nearer than the volume itself: a node is worth visiting only if its volume is nearer than the best so far.",
        About::nodes([node]),
    ))
}

/// Which of `parent`'s children queued together is visited first (`child`, rank 0).
pub(super) fn child_order<V: Vector>(
    at: &At<'_, V>,
    parent: NodeId,
    child: NodeId,
) -> Option<PredictQuestion> {
    let siblings: Vec<(NodeId, f32)> = at.recording.events[at.step()..]
        .iter()
        .map_while(|e| match *e {
            Event::ChildQueued {
                parent: p,
                child,
                key,
                ..
            } if p == parent => Some((child, key)),
            _ => None,
        })
        .collect();
    if siblings.len() < 2 {
        return None;
    }
    let question = &at.recording.question;
    let nearest = question.task == Task::Nearest;
    let keyed = question.variant == Variant::Full
        && matches!(
            question.task,
            Task::FirstHit | Task::AnyHit | Task::AllHits | Task::Nearest
        );
    // Nearer first: each answer shows its key, and the first's must differ from the
    // others' as shown.
    let first_key = siblings[0].1;
    if keyed
        && siblings[1..]
            .iter()
            .any(|&(_, k)| !shown_apart(k, first_key))
    {
        return None;
    }
    let key_name = key_name(at);
    let why = if keyed {
        let keys: Vec<String> = siblings
            .iter()
            .map(|(c, k)| format!("node {}: {key_name} {k:.3}", c.0))
            .collect();
        format!("the nearer child is visited first ({})", keys.join("; "))
    } else {
        "this walk visits the children in their stored order, the first child first".to_owned()
    };
    let choices = siblings
        .iter()
        .map(|&(c, k)| {
            let label = if keyed {
                format!("node {} ({key_name} {k:.3})", c.0)
            } else {
                format!("node {}", c.0)
            };
            (Choice::Node(c.0), label)
        })
        .collect();
    Some(at.ask(
        format!(
            "Node {} has {} children to visit. Which one is visited first?",
            parent.0,
            siblings.len()
        ),
        by_node(choices),
        Choice::Node(child.0),
        siblings.len(),
        why,
        if !keyed {
            "This version of the walk does not sort the children: which one is stored first?"
        } else if nearest {
            "The walk goes nearer first: compare the distances from the point to the children's volumes."
        } else {
            "The walk goes near first: compare where the ray enters each child's volume."
        },
        About::nodes(siblings.iter().map(|&(c, _)| c)),
    ))
}

/// Why the ray misses a node's volume.
fn miss_why(kind: StructureKind, node: NodeId) -> String {
    match kind {
        StructureKind::SphereTree => format!(
            "the ray passes node {}'s circle farther from its centre than its radius: it misses it",
            node.0
        ),
        _ => format!(
            "the ray misses node {}'s {}: the t-intervals where it is between each pair of sides do not overlap",
            node.0,
            volume_word(kind)
        ),
    }
}

/// Where to look to see whether a ray meets a volume.
fn slab_hint(kind: StructureKind) -> &'static str {
    match kind {
        StructureKind::SphereTree => {
            "Compare the ray's closest approach to the circle's centre with its radius."
        }
        _ => {
            "Find where the ray is between each pair of parallel sides: it meets the box only if those t-intervals overlap."
        }
    }
}
