//! The playback's state drawn on the canvas: the current node, the nodes waiting on the
//! stack or queue, the best answer so far, a build's progress, and the node hovered in the
//! tree diagram (or on the canvas) with its primitives.

use bvhlab::glam::Vec2;
use bvhlab::{Event, NodeId, NodeOutline, Segment2};
use egui::Stroke;

use super::draw::built;
use crate::model::lab2d::Lab2d;
use crate::model::lane::Lane;
use crate::model::predict::About;
use crate::model::structures::StructureKind;
use crate::paint::{WorldPainter, clipped_plane, colors};
use crate::pseudocode::Task;

/// Every primitive in the subtree under `node` (leaves list them), without repeats.
pub fn subtree_primitives(outline: &[NodeOutline<Vec2>], node: NodeId) -> Vec<u32> {
    let mut out = Vec::new();
    let mut stack = vec![node];
    while let Some(n) = stack.pop() {
        let Some(o) = outline.get(n.index()) else {
            continue;
        };
        out.extend_from_slice(&o.primitives);
        stack.extend(o.children.iter().copied());
    }
    out.sort_unstable();
    out.dedup();
    out
}

fn prim_stroke(
    lab: &Lab2d,
    prim: u32,
    width: f32,
    color: egui::Color32,
    wp: &mut WorldPainter<'_>,
) {
    let Some(s) = lab.prims().segments.get(prim as usize) else {
        return;
    };
    if s.a == s.b {
        wp.dot(s.a, width + 1.5, color);
    } else {
        wp.line(s.a, s.b, Stroke::new(width, color));
    }
}

/// A hit of the ray on primitive `prim` at `at`: a dot in the answer's colour, and the
/// primitive's number beside it as the panel lists it ("#2"), so that each hit listed can be
/// found on the canvas without telling colours apart.
pub(super) fn hit_mark(wp: &mut WorldPainter<'_>, fonts: &egui::Painter, at: Vec2, prim: u32) {
    wp.dot(at, 6.0, colors::ANSWER);
    wp.text(fonts, at, &format!(" #{prim}"), colors::ANSWER);
}

/// Every hit of an all-hits question at the end of its recording (the panel lists them all),
/// or nothing when the lane's question is another one; whether it drew them.
pub(super) fn draw_all_hits(
    lane: &Lane<Segment2>,
    wp: &mut WorldPainter<'_>,
    fonts: &egui::Painter,
) -> bool {
    let (Some(rec), Some(snap)) = (lane.recorded(), &lane.snapshot) else {
        return false;
    };
    let (Task::AllHits, Some(ray)) = (rec.question.task, rec.question.ray) else {
        return false;
    };
    for &(prim, t) in &snap.best {
        hit_mark(wp, fonts, ray.at(t), prim);
    }
    true
}

/// The current node, the waiting nodes, and (while stepping) the best answer so far.
pub(super) fn draw_step(
    lab: &Lab2d,
    lane: &Lane<Segment2>,
    live: bool,
    wp: &mut WorldPainter<'_>,
    fonts: &egui::Painter,
) {
    let (Some((_, outline)), Some(snap), Some(rec)) =
        (built(lab, lane), &lane.snapshot, lane.recorded())
    else {
        return;
    };
    if rec.question.task == Task::Build {
        return;
    }
    for pending in &snap.frontier {
        if let Some(node) = outline.get(pending.node.index()) {
            wp.node_shape(&node.shape, Stroke::new(1.5, colors::WAITING));
        }
    }
    if live {
        return;
    }
    if let Some(node) = snap.current.and_then(|c| outline.get(c.index())) {
        wp.node_shape(&node.shape, Stroke::new(3.0, colors::CURRENT));
    }
    if let Some(Event::PrimitiveTest { prim, .. }) = snap.event {
        prim_stroke(lab, prim, 4.0, colors::CURRENT, wp);
    }
    let q = &rec.question;
    for &(prim, value) in &snap.best {
        match q.task {
            Task::FirstHit | Task::AnyHit | Task::AllHits => {
                if let Some(ray) = q.ray {
                    hit_mark(wp, fonts, ray.at(value), prim);
                }
            }
            Task::Nearest | Task::Range => {
                let (Some(p), Some(s)) = (q.point, lab.prims().segments.get(prim as usize)) else {
                    continue;
                };
                let c = s.project_point(p);
                wp.line(p, c, Stroke::new(1.5, colors::ANSWER));
                wp.dot(c, 4.0, colors::ANSWER);
            }
            Task::Build => {}
        }
    }
    if let (Some(p), Some(&(_, d)), Task::Nearest) = (q.point, snap.best.last(), q.task) {
        let r = wp.screen.screen_length(d);
        wp.ring(p, r, Stroke::new(1.0, colors::ANSWER.gamma_multiply(0.6)));
    }
}

/// What Predict's question waiting is about: its nodes (or cells) and primitives lit in the
/// asked colour, each labelled with its number and a question mark.
pub(super) fn draw_asked(
    lab: &Lab2d,
    lane: &Lane<Segment2>,
    about: &About,
    wp: &mut WorldPainter<'_>,
    fonts: &egui::Painter,
) {
    if let Some((built, outline)) = built(lab, lane) {
        let unit = if built.settings.kind == StructureKind::Grid {
            "cell"
        } else {
            "node"
        };
        for id in &about.nodes {
            let Some(node) = outline.get(id.index()) else {
                continue;
            };
            wp.node_fill(&node.shape, colors::ASKED.gamma_multiply(0.10));
            wp.node_shape(&node.shape, Stroke::new(2.5, colors::ASKED));
            let b = node.shape.aabb();
            let corner = Vec2::new(b.min.x, b.max.y);
            asked_label(wp, fonts, corner, format!("{unit} {}?", id.0));
        }
    }
    for &prim in &about.prims {
        prim_stroke(lab, prim, 4.0, colors::ASKED, wp);
        if let Some(s) = lab.prims().segments.get(prim as usize) {
            let middle = (s.a + s.b) * 0.5;
            asked_label(wp, fonts, middle, format!(" primitive {prim}?"));
        }
    }
}

/// A label of what is asked about, just above `at`, kept inside the view so that it can be
/// read whole (a root's corner or a primitive at the scene's edge can sit on the view's).
fn asked_label(wp: &mut WorldPainter<'_>, fonts: &egui::Painter, at: Vec2, text: String) {
    let galley = fonts.layout_no_wrap(text, egui::FontId::proportional(13.0), colors::ASKED);
    let size = galley.size();
    let view = wp.screen.rect.shrink(2.0);
    let p = wp.screen.to_screen(at);
    let x = p.x.min(view.right() - size.x).max(view.left());
    let y = (p.y - size.y).min(view.bottom() - size.y).max(view.top());
    wp.add(egui::Shape::galley(egui::pos2(x, y), galley, colors::ASKED));
}

/// A build in progress: the nodes made so far, the current one, its split and which side
/// each of its primitives goes to.
pub(super) fn draw_build_state(lab: &Lab2d, lane: &Lane<Segment2>, wp: &mut WorldPainter<'_>) {
    let (Some((_, outline)), Some(snap)) = (built(lab, lane), &lane.snapshot) else {
        return;
    };
    let stroke = Stroke::new(1.0, colors::STRUCTURE);
    for (node, _) in outline.iter().zip(&snap.existing).filter(|(_, e)| **e) {
        wp.node_shape(&node.shape, stroke);
    }
    let Some(current) = snap.current.and_then(|c| outline.get(c.index())) else {
        return;
    };
    match (snap.split, current.children.as_slice()) {
        (Some(split), [first, second, ..]) if split.node == current.id => {
            for p in subtree_primitives(outline, *first) {
                prim_stroke(lab, p, 2.5, colors::FIRST_SIDE, wp);
            }
            for p in subtree_primitives(outline, *second) {
                prim_stroke(lab, p, 2.5, colors::SECOND_SIDE, wp);
            }
            let region = current.shape.aabb();
            if let Some((a, b)) = clipped_plane(split.normal, split.offset, &region, &[]) {
                wp.line(a, b, Stroke::new(2.5, colors::CURRENT));
            }
        }
        _ => {
            for p in subtree_primitives(outline, current.id) {
                prim_stroke(lab, p, 2.5, colors::TESTED, wp);
            }
        }
    }
    wp.node_shape(&current.shape, Stroke::new(3.0, colors::CURRENT));
}

/// The node hovered in the tree diagram or on the canvas, and its primitives.
pub(super) fn draw_hovered(
    lab: &Lab2d,
    lane: &Lane<Segment2>,
    node: NodeId,
    wp: &mut WorldPainter<'_>,
) {
    let Some((_, outline)) = built(lab, lane) else {
        return;
    };
    let Some(o) = outline.get(node.index()) else {
        return;
    };
    wp.node_fill(&o.shape, colors::SELECTED.gamma_multiply(0.12));
    wp.node_shape(&o.shape, Stroke::new(2.5, colors::SELECTED));
    for p in subtree_primitives(outline, node) {
        prim_stroke(lab, p, 2.5, colors::SELECTED, wp);
    }
}

/// The deepest node whose region holds `p` (for BVHs, whose volume does; the deepest,
/// smallest one when volumes overlap).
pub fn node_at(outline: &[NodeOutline<Vec2>], p: Vec2, max_depth: u32) -> Option<NodeId> {
    outline
        .iter()
        .filter(|n| n.depth <= max_depth && shape_contains(&n.shape, p))
        .max_by(|a, b| {
            a.depth
                .cmp(&b.depth)
                .then(area(&b.shape).total_cmp(&area(&a.shape)))
        })
        .map(|n| n.id)
}

fn shape_contains(shape: &bvhlab::NodeShape<Vec2>, p: Vec2) -> bool {
    use bvhlab::BoundingVolume;
    match shape {
        bvhlab::NodeShape::Aabb(b) => b.contains(p),
        bvhlab::NodeShape::Sphere(s) => s.contains(p),
        bvhlab::NodeShape::Obb(o) => o.contains(p),
    }
}

fn area(shape: &bvhlab::NodeShape<Vec2>) -> f32 {
    let b = shape.aabb();
    let d = b.max - b.min;
    d.x * d.y
}
