//! The collision query in the 3D view: the copy B as its triangles' edges, the node pair the
//! walk is at (green when their volumes overlap, red when they are disjoint, as visited and
//! culled nodes are), the triangle pair being tested (white), and every pair found meeting
//! so far (the answer's magenta: A's triangles lit, B's edges thick).

use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use bvhlab::structure::{Event, NodeOutline};
use egui::Color32;

use super::draw::{Draw3d, rgba};
use super::wire::{self, Segment};
use crate::model::lab3d::Lab3d;
use crate::paint::colors;

/// The copy's colour.
pub const COPY: Color32 = Color32::from_rgb(150, 200, 255);
/// The most of the copy's triangles drawn (each as three edges).
const COPY_TRIANGLE_CAP: usize = 20_000;

/// The legend's entries while the query is on.
pub fn legend(lab: &Lab3d) -> Vec<(Color32, &'static str)> {
    if lab.collision_run().and_then(|c| c.run.as_ref()).is_none() {
        return Vec::new();
    }
    vec![
        (COPY, "copy B"),
        (colors::VISITED, "node pair overlaps"),
        (colors::CULLED, "node pair disjoint"),
        (colors::CURRENT, "triangle pair tested"),
        (colors::ANSWER, "triangles meeting"),
    ]
}

fn edges(t: &Triangle3, color: [f32; 4], width: f32, out: &mut Vec<Segment>) {
    for (a, b) in [(t.a, t.b), (t.b, t.c), (t.c, t.a)] {
        out.push(Segment { a, b, color, width });
    }
}

fn node_shape(nodes: &[NodeOutline<Vec3>], id: u32, color: [f32; 4], d: &mut Draw3d) {
    if let Some(node) = nodes.get(id as usize) {
        wire::shape(&node.shape, color, 2.5, &mut d.overlay);
    }
}

/// Adds the copy, the step's node or triangle pair and the pairs met so far to `d`.
pub(super) fn draw_collision(lab: &Lab3d, d: &mut Draw3d) {
    let (Some(cache), Some(collision)) = (lab.collision_run(), lab.collision) else {
        return;
    };
    let Some(run) = &cache.run else { return };
    let faint = rgba(COPY, 0.45);
    for t in cache.copy.iter().take(COPY_TRIANGLE_CAP) {
        edges(t, faint, 1.0, &mut d.lines);
    }
    let shown = collision
        .step
        .map_or(run.events.len(), |s| s.min(run.events.len()));
    let answer = rgba(colors::ANSWER, 1.0);
    for (a, b) in run.meeting_so_far(shown) {
        if let Some(&t) = cache.part.get(a as usize) {
            d.highlights.push((t, answer));
        }
        if let Some(t) = cache.copy.get(b as usize) {
            edges(t, answer, 2.5, &mut d.overlay);
        }
    }
    // The step shown: the last event taken.
    match shown.checked_sub(1).and_then(|i| run.events.get(i)) {
        Some(&Event::NodePairTest { a, b, overlap }) => {
            let color = rgba(
                if overlap {
                    colors::VISITED
                } else {
                    colors::CULLED
                },
                1.0,
            );
            node_shape(&run.nodes_a, a.0, color, d);
            node_shape(&run.nodes_b, b.0, color, d);
        }
        Some(&Event::PairTest { a, b, .. }) => {
            let current = rgba(colors::CURRENT, 1.0);
            if let Some(&t) = cache.part.get(a as usize) {
                d.highlights.push((t, current));
            }
            if let Some(t) = cache.copy.get(b as usize) {
                edges(t, current, 3.0, &mut d.overlay);
            }
        }
        _ => {}
    }
}
