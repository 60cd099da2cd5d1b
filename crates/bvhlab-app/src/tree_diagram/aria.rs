//! The tree diagram for a screen reader: the diagram's widget becomes a tree (ARIA's `tree`),
//! and each node a tree item with its level, its id, what it is (leaf or inner, its volume in
//! numbers, its primitives: the tooltip's words) and what the query did to it at the step
//! shown (visited, culled, pruned, waiting). A large tree is summarised: its top levels are
//! listed (up to [`MAX_ITEMS`] items), then the nodes the query visited and the current one.

use bvhlab::{NodeId, NodeOutline, Vector};
use egui::accesskit::Role;

use super::TreeHighlight;
use super::describe::describe;
use super::layout::Layout;

/// The most nodes listed as tree items.
const MAX_ITEMS: usize = 200;

/// Makes the diagram's widget `id` a tree of `outline`'s nodes, in `ui` (only when the lab
/// builds its accessibility tree: nothing is done otherwise).
pub(super) fn tree<V: Vector>(
    ui: &mut egui::Ui,
    id: egui::Id,
    outline: &[NodeOutline<V>],
    layout: &Layout,
    highlight: &TreeHighlight<'_>,
    summary: &str,
) {
    // Nothing is worked out on a frame that builds no accessibility tree.
    let described = ui.ctx().accesskit_node_builder(id, |node| {
        let listed = listed(outline, layout, highlight);
        node.set_role(Role::Tree);
        node.set_label("Tree diagram");
        let shown = if listed.len() < outline.len() {
            format!(
                "; {} of its nodes are listed (the top levels, and those the query went into)",
                listed.len()
            )
        } else {
            String::new()
        };
        node.set_description(format!("{summary}{shown}."));
        listed
    });
    let Some(listed) = described else {
        return;
    };
    for index in listed {
        let node = &outline[index];
        let mark = highlight
            .marks
            .and_then(|m| m.nodes.get(index).copied().flatten());
        let exists = highlight
            .existing
            .is_none_or(|e| e.get(index) == Some(&true));
        let mut text = describe(node, layout.depth(index), mark, exists).replace('\n', "; ");
        if highlight.current == Some(NodeId(index as u32)) {
            text.push_str("; the step shown is here");
        }
        if highlight.asked.contains(&NodeId(index as u32)) {
            text.push_str("; Predict's question is about it");
        }
        let item = ui.new_child(
            egui::UiBuilder::new()
                .id_salt(("tree item", index))
                .accessibility_parent(id),
        );
        ui.ctx().accesskit_node_builder(item.unique_id(), |n| {
            n.set_role(Role::TreeItem);
            n.set_level(layout.depth(index) as usize + 1);
            n.set_label(text);
            if !node.is_leaf() {
                n.set_expanded(true);
            }
        });
    }
}

/// The nodes listed, in depth-first order: every node of a small tree; of a large one, the
/// levels from the root down while they fit in [`MAX_ITEMS`], and every node the query
/// marked or is at.
fn listed<V: Vector>(
    outline: &[NodeOutline<V>],
    layout: &Layout,
    highlight: &TreeHighlight<'_>,
) -> Vec<usize> {
    if outline.len() <= MAX_ITEMS {
        return (0..outline.len()).collect();
    }
    let mut per_depth = std::collections::BTreeMap::<u32, usize>::new();
    for index in 0..outline.len() {
        *per_depth.entry(layout.depth(index)).or_default() += 1;
    }
    let mut deepest = 0;
    let mut count = 0;
    for (&depth, &n) in &per_depth {
        if count + n > MAX_ITEMS {
            break;
        }
        count += n;
        deepest = depth;
    }
    (0..outline.len())
        .filter(|&index| {
            layout.depth(index) <= deepest
                || highlight.current == Some(NodeId(index as u32))
                || highlight.asked.contains(&NodeId(index as u32))
                || highlight
                    .marks
                    .and_then(|m| m.nodes.get(index).copied().flatten())
                    .is_some()
        })
        .collect()
}
