//! The question of a build: does the node just made become a leaf, or across which axis is
//! it split?

use bvhlab::structure::NodeId;
use bvhlab::{Event, Vector};

use super::question::{AXES, About, At, Choice, PredictQuestion};
use crate::model::structures::StructureKind;

/// Whether a node just made becomes a leaf or how it is split.
pub(super) fn build_step<V: Vector>(at: &At<'_, V>, node: NodeId) -> Option<PredictQuestion> {
    let events = &at.recording.events;
    let step = at.step();
    let kind = at.kind;
    // Asked once, right after the node is made: a quadtree's second split is no news.
    let Some(Event::BuildNode {
        node: made, prims, ..
    }) = step.checked_sub(1).map(|s| events[s])
    else {
        return None;
    };
    if made != node || kind == StructureKind::Grid {
        return None;
    }
    let splits: Vec<(V, f32, u32, u32)> = events[step..]
        .iter()
        .map_while(|e| match *e {
            Event::BuildSplit {
                node: n,
                normal,
                offset,
                left,
                right,
                ..
            } if n == node => Some((normal, offset, left, right)),
            _ => None,
        })
        .collect();
    let dim = V::DIM;
    let axis_of = |normal: V| {
        (0..dim)
            .find(|&a| normal.coord(a) == 1.0 && (0..dim).all(|b| b == a || normal.coord(b) == 0.0))
    };
    let by_axis = matches!(
        kind,
        StructureKind::SphereTree
            | StructureKind::AabbTree
            | StructureKind::ObbTree
            | StructureKind::KdTree
    );
    let mut choices = vec![(Choice::Leaf, "it becomes a leaf".to_owned())];
    if by_axis {
        choices.extend((0..dim).map(|a| {
            (
                Choice::SplitAcross(a as u8),
                format!("it is split across {}", AXES[a]),
            )
        }));
    } else {
        choices.push((Choice::Split, "it is split".to_owned()));
    }
    let (answer, reveal, why) = match splits.first() {
        None => (
            Choice::Leaf,
            1,
            format!(
                "the builder stops at node {} with {prims} primitive(s): few enough for a leaf, or no split that pays",
                node.0
            ),
        ),
        Some(&(normal, offset, left, right)) => {
            let answer = match (by_axis, axis_of(normal)) {
                (true, Some(a)) => Choice::SplitAcross(a as u8),
                (true, None) => return None,
                (false, _) => Choice::Split,
            };
            let plane = axis_of(normal).map_or_else(
                || "its plane".to_owned(),
                |a| format!("{} = {offset:.3}", AXES[a]),
            );
            (
                answer,
                splits.len(),
                format!(
                    "the builder splits node {}'s {prims} primitives by {plane}: {left} on one side, {right} on the other",
                    node.0
                ),
            )
        }
    };
    Some(PredictQuestion {
        step,
        prompt: format!("Node {} holds {prims} primitive(s). What does the builder do with it?", node.0),
        choices,
        answer,
        reveal,
        why,
        hint: "A node with no more primitives than the leaf size becomes a leaf; otherwise the median builder splits the longest side of its centroids' box, and the SAH builder the cheapest plane.".to_owned(),
        about: About::nodes([node]),
    })
}
