//! The collision query on the canvas: the node pair the walk is at (green when their
//! volumes overlap, red when they are disjoint, as visited and culled nodes are), the
//! segment pair being tested (white), and every pair found meeting so far (the answer's
//! magenta).

use bvhlab::glam::Vec2;
use bvhlab::structure::{Event, NodeOutline};
use egui::Stroke;

use crate::model::lab2d::Lab2d;
use crate::paint::{WorldPainter, colors};

fn node(nodes: &[NodeOutline<Vec2>], id: u32, stroke: Stroke, wp: &mut WorldPainter<'_>) {
    if let Some(node) = nodes.get(id as usize) {
        wp.node_shape(&node.shape, stroke);
    }
}

/// Draws the step shown and the pairs met so far.
pub(super) fn draw_collision(lab: &Lab2d, wp: &mut WorldPainter<'_>) {
    let (Some(cache), Some(collision)) = (lab.collision_run(), lab.collision) else {
        return;
    };
    let Some(run) = &cache.run else { return };
    let segments = &lab.prims().segments;
    let segment = |ids: &[u32], i: u32| ids.get(i as usize).and_then(|&s| segments.get(s as usize));
    let shown = collision
        .step
        .map_or(run.events.len(), |s| s.min(run.events.len()));
    let answer = Stroke::new(4.0, colors::ANSWER);
    for (a, b) in run.meeting_so_far(shown) {
        for s in [segment(&cache.a, a), segment(&cache.b, b)]
            .into_iter()
            .flatten()
        {
            wp.line(s.a, s.b, answer);
        }
    }
    match shown.checked_sub(1).and_then(|i| run.events.get(i)) {
        Some(&Event::NodePairTest { a, b, overlap }) => {
            let color = if overlap {
                colors::VISITED
            } else {
                colors::CULLED
            };
            node(&run.nodes_a, a.0, Stroke::new(2.5, color), wp);
            node(&run.nodes_b, b.0, Stroke::new(2.5, color), wp);
        }
        Some(&Event::PairTest { a, b, .. }) => {
            let current = Stroke::new(5.0, colors::CURRENT);
            for s in [segment(&cache.a, a), segment(&cache.b, b)]
                .into_iter()
                .flatten()
            {
                wp.line(s.a, s.b, current);
            }
        }
        _ => {}
    }
}
