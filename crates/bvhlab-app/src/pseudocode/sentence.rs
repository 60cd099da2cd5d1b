//! A sentence for each event, in the lecture's words: what the "Step through" panel says at
//! each step (and what a screen reader hears).

use bvhlab::structure::{PrimitiveResult, PruneAt, PruneReason};
use bvhlab::{Event, Vector};

use super::{Task, Variant};
use crate::model::structures::StructureKind;

/// A sentence for an event of `kind` running `task` in `variant`, in the lecture's words: a
/// queued child's key is its `tEnter` along a ray or its distance from the point; a grid's
/// leaves are its cells.
pub fn describe<V: Vector>(
    event: &Event<V>,
    kind: StructureKind,
    task: Task,
    variant: Variant,
) -> String {
    // A grid's nodes are its cells.
    let unit = if kind == StructureKind::Grid {
        "cell"
    } else {
        "node"
    };
    match *event {
        Event::EnterNode { node, depth } => format!("enter {unit} {} (depth {depth})", node.0),
        Event::RayBoundTest { node, interval } => match interval {
            Some((a, b)) => format!(
                "ray meets {unit} {}'s volume for t in [{a:.3}, {b:.3}]",
                node.0
            ),
            None => format!("ray misses {unit} {}'s volume", node.0),
        },
        Event::DistanceBoundTest { node, distance } => {
            format!("{unit} {}'s volume is {distance:.3} from the point", node.0)
        }
        Event::ChildQueued {
            parent,
            child,
            key,
            rank,
        } => {
            // The slides' recursions and the range query order children by nothing but
            // their place (their key is 0).
            let key = match task {
                _ if variant != Variant::Full => String::new(),
                Task::FirstHit | Task::AnyHit | Task::AllHits => format!("tEnter {key:.3}, "),
                Task::Nearest => format!("distance {key:.3}, "),
                Task::Range | Task::Build => String::new(),
            };
            format!(
                "queue child {} of node {} ({key}visit order {})",
                child.0,
                parent.0,
                rank + 1
            )
        }
        Event::Prune { node, reason, at } => match at {
            PruneAt::Test => format!("skip {unit} {}: {}", node.0, why(reason)),
            PruneAt::Pop => format!("pop {unit} {} and skip it: {}", node.0, why(reason)),
            PruneAt::Stop => format!("stop, skipping {unit} {}: {}", node.0, why(reason)),
        },
        Event::PrimitiveTest { prim, result } => match result {
            PrimitiveResult::Hit(t) => format!("test primitive {prim}: hit at t = {t:.3}"),
            PrimitiveResult::Miss => format!("test primitive {prim}: miss"),
            PrimitiveResult::Distance(d) => format!("test primitive {prim}: distance {d:.3}"),
            PrimitiveResult::Overlap => format!("test primitive {prim}: inside the range"),
            PrimitiveResult::NoOverlap => format!("test primitive {prim}: outside the range"),
            PrimitiveResult::AlreadyTested => {
                format!("primitive {prim} was already tested in another cell (mailbox)")
            }
        },
        Event::NewBest { prim, value } => format!("new best: primitive {prim} at {value:.3}"),
        Event::HitBeyondRegion { prim, t, t_exit } => format!(
            "primitive {prim} is hit at t = {t:.3}, beyond this region (exits at {t_exit:.3}): keep looking"
        ),
        Event::CellEnter {
            coords,
            t_enter,
            t_exit,
            ..
        } => {
            let cell = if V::DIM == 3 {
                format!("({}, {}, {})", coords[0], coords[1], coords[2])
            } else {
                format!("({}, {})", coords[0], coords[1])
            };
            format!("enter cell {cell} for t in [{t_enter:.3}, {t_exit:.3}]")
        }
        Event::PlaneCrossed { node, t } => {
            format!("the ray crosses node {}'s plane at t = {t:.3}", node.0)
        }
        Event::BuildNode {
            node, depth, prims, ..
        } => format!(
            "make node {} (depth {depth}) over {prims} primitives",
            node.0
        ),
        Event::BuildSplit {
            node,
            normal,
            offset,
            left,
            right,
            ..
        } => format!(
            "split node {} by {}: {left} below, {right} above",
            node.0,
            split_plane(normal, offset)
        ),
        Event::BuildLeaf { node, prims } if kind == StructureKind::Grid => {
            format!("cell {} lists {prims} primitive(s)", node.0)
        }
        Event::BuildLeaf { node, prims } => {
            format!("node {} becomes a leaf with {prims} primitive(s)", node.0)
        }
        Event::PairTest { a, b, overlap } => format!("test pair ({a}, {b}): {overlap}"),
        Event::NodePairTest { a, b, overlap } => {
            format!("test nodes ({}, {}): {overlap}", a.0, b.0)
        }
    }
}

/// The split plane `normal · p = offset` in words: "the split plane y = 1.250" for an
/// axis-aligned one, its normal and offset otherwise (a BSP tree's).
fn split_plane<V: Vector>(normal: V, offset: f32) -> String {
    let axes = ["x", "y", "z"];
    for (axis, name) in axes.iter().enumerate().take(V::DIM) {
        let mut unit = V::ZERO;
        unit.set_coord(axis, 1.0);
        if normal == unit {
            return format!("the split plane {name} = {offset:.3}");
        }
    }
    let coords: Vec<String> = (0..V::DIM)
        .map(|i| format!("{:.2}", normal.coord(i)))
        .collect();
    format!(
        "a split plane with normal ({}) at offset {offset:.3}",
        coords.join(", ")
    )
}

fn why(reason: PruneReason) -> String {
    match reason {
        PruneReason::RayMissed => "the ray misses it".to_owned(),
        PruneReason::BeyondBestHit { t_enter, best_t } => {
            format!("the ray enters at t = {t_enter:.3}, beyond the best hit t = {best_t:.3}")
        }
        PruneReason::NoNearer { distance, best } => {
            format!("its volume is {distance:.3} away, no nearer than the best {best:.3}")
        }
        PruneReason::NoOverlap => "it does not overlap the range".to_owned(),
        PruneReason::AlreadyHit => "a hit was already found".to_owned(),
    }
}
