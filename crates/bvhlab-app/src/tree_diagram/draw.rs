//! Painting the diagram: edges, nodes coloured by what the query did to them, leaf
//! primitive counts when there is room, and rings for the playback's current node, the node
//! hovered on the canvas, the node under the pointer and the nodes Predict's question is
//! about (each with a question mark).
//!
//! Only rows and nodes on screen are visited (binary search in the layout's rows), and
//! where many nodes fall on one point column (a 10,000-leaf tree fitted into a few hundred
//! points), a node that would land on the same point as one just drawn in its row, in the
//! same look, is skipped (`Recent`): the picture is the same, and a row costs at most a
//! few shapes per point of width whatever the tree's size.

use std::ops::Range;
use std::sync::Arc;

use bvhlab::{NodeOutline, Vector};
use egui::{Color32, Galley, Pos2, Rect, Shape, Stroke, StrokeKind, vec2};

use super::TreeHighlight;
use super::camera::Camera;
use super::forest::NONE;
use super::layout::{Arrangement, Layout};
use crate::model::outcome::NodeMark;
use crate::paint::colors;

/// How much of its colour a faint node keeps (too deep, or not built yet).
const FAINT: f32 = 0.22;
/// Leaf primitive counts show once nodes are this far apart (points).
const LABEL_SPACING: f32 = 24.0;
/// Squares (leaves) and dots (inner nodes) smaller than this radius look alike.
const DISTINCT_FORMS: f32 = 2.5;
/// Grid cells closer than this (points) are drawn as runs, not one by one.
const TINY_CELL: f32 = 4.0;
/// The font size of leaf counts.
const LABEL_SIZE: f32 = 11.0;

/// Lays text out with the painter's or the context's fonts.
pub(super) type LayoutText<'f> = dyn FnMut(String, f32, Color32) -> Arc<Galley> + 'f;

/// One frame's picture of the diagram.
pub(super) struct Painting<'a, V: Vector> {
    /// Where the nodes are.
    pub(super) layout: &'a Layout,
    /// The nodes themselves (leaf or not, primitive counts).
    pub(super) outline: &'a [NodeOutline<V>],
    /// What to highlight.
    pub(super) highlight: &'a TreeHighlight<'a>,
    /// Layout to screen.
    pub(super) camera: Camera,
    /// What is on screen.
    pub(super) clip: Rect,
    /// The node under the pointer.
    pub(super) hovered: Option<usize>,
    /// Text and the hover ring.
    pub(super) ink: Color32,
}

impl<V: Vector> Painting<'_, V> {
    /// Appends the shapes to `out`, bottom first.
    pub(super) fn paint(&self, out: &mut Vec<Shape>, text: &mut LayoutText<'_>) {
        let rows = self.visible_rows();
        let rows_with_edges = rows.start.max(1)..(rows.end + 1).min(self.layout.row_count());
        self.edges(out, rows_with_edges);
        self.nodes(out, rows, text);
        self.rings(out);
        self.asked(out, text);
    }

    /// Whether the node is drawn faint: deeper than the depth limit, or not built yet.
    pub(super) fn is_faint(&self, id: usize) -> bool {
        let h = self.highlight;
        self.layout.depth(id) > h.max_depth || h.existing.is_some_and(|e| e.get(id) != Some(&true))
    }

    /// What the query did to the node.
    pub(super) fn mark(&self, id: usize) -> Option<NodeMark> {
        self.highlight
            .marks
            .and_then(|m| m.nodes.get(id).copied().flatten())
    }

    /// The rows on screen, with a margin for dots and labels.
    fn visible_rows(&self) -> Range<usize> {
        let scales = self.camera.scales();
        let margin = (self.camera.node_radius() + LABEL_SIZE + 4.0) / scales.y;
        let top = self.camera.to_layout(self.clip.min)[1] - margin;
        let bottom = self.camera.to_layout(self.clip.max)[1] + margin;
        let count = self.layout.row_count();
        let lo = top.ceil().clamp(0.0, count as f32) as usize;
        let hi = (bottom.floor() + 1.0).clamp(0.0, count as f32) as usize;
        lo..hi.max(lo)
    }

    /// The x range on screen, with a margin for dots and labels.
    fn visible_x(&self) -> (f32, f32) {
        let margin = (self.camera.node_radius() + 2.0 * LABEL_SIZE) / self.camera.scales().x;
        let left = self.camera.to_layout(self.clip.min)[0] - margin;
        let right = self.camera.to_layout(self.clip.max)[0] + margin;
        (left, right)
    }

    fn edges(&self, out: &mut Vec<Shape>, rows: Range<usize>) {
        let (lo, hi) = self.visible_x();
        for r in rows {
            let mut recent = Recent::default();
            for &id in self.layout.edges_between(r, lo, hi) {
                let id = id as usize;
                let parent = self.layout.parent[id];
                if parent == NONE {
                    continue;
                }
                let a = self.camera.to_screen(self.layout.pos[parent]);
                let b = self.camera.to_screen(self.layout.pos[id]);
                let visited = self.mark(id) == Some(NodeMark::Visited);
                let mut color = if visited {
                    colors::VISITED
                } else {
                    colors::STRUCTURE
                };
                if self.is_faint(id) {
                    color = color.gamma_multiply(FAINT);
                }
                if !recent.first_at(Look::Edge(a.x.round() as i32, color), b.x) {
                    continue;
                }
                let width = if visited { 1.6 } else { 1.0 };
                out.push(Shape::line_segment([a, b], Stroke::new(width, color)));
            }
        }
    }

    fn nodes(&self, out: &mut Vec<Shape>, rows: Range<usize>, text: &mut LayoutText<'_>) {
        let (lo, hi) = self.visible_x();
        let radius = self.camera.node_radius();
        let scales = self.camera.scales();
        let labels = scales.x.min(scales.y) >= LABEL_SPACING;
        if self.is_grid() && scales.x < TINY_CELL {
            self.cell_runs(out, rows, radius);
            return;
        }
        for r in rows {
            let mut recent = Recent::default();
            for &id in self.layout.nodes_between(r, lo, hi) {
                let id = id as usize;
                let at = self.camera.to_screen(self.layout.pos[id]);
                let leaf = self.outline[id].is_leaf();
                let fill = self.fill(id);
                // Below a few points a square and a dot look alike.
                let form = leaf && radius >= DISTINCT_FORMS;
                if !recent.first_at(Look::Node(form, fill), at.x) {
                    continue;
                }
                if leaf {
                    let square = Rect::from_center_size(at, vec2(2.0 * radius, 2.0 * radius));
                    out.push(Shape::rect_filled(square, 0.0, fill));
                } else {
                    out.push(Shape::circle_filled(at, radius, fill));
                }
                if labels && leaf {
                    self.leaf_label(out, id, at, radius, text);
                }
            }
        }
    }

    /// Grid cells too small to tell apart, as one bar per run of neighbouring cells of one
    /// colour: a 173 by 173 grid fitted into 400 points is then a few hundred bars, not
    /// 30,000 squares.
    fn cell_runs(&self, out: &mut Vec<Shape>, rows: Range<usize>, radius: f32) {
        let (lo, hi) = self.visible_x();
        let step = self.camera.scales().x;
        let mut bar = |run: Option<(Pos2, f32, Color32)>| {
            if let Some((first, last_x, fill)) = run {
                let min = first - vec2(radius, radius);
                let max = Pos2::new(last_x + radius, first.y + radius);
                out.push(Shape::rect_filled(Rect::from_min_max(min, max), 0.0, fill));
            }
        };
        for r in rows {
            let mut run: Option<(Pos2, f32, Color32)> = None;
            for &id in self.layout.nodes_between(r, lo, hi) {
                let id = id as usize;
                let at = self.camera.to_screen(self.layout.pos[id]);
                let fill = self.fill(id);
                match &mut run {
                    Some((_, last_x, color)) if *color == fill && at.x - *last_x <= 1.5 * step => {
                        *last_x = at.x;
                    }
                    _ => bar(run.replace((at, at.x, fill))),
                }
            }
            bar(run);
        }
    }

    /// A leaf's primitive count: inside a grid cell, under a tree's leaf.
    fn leaf_label(
        &self,
        out: &mut Vec<Shape>,
        id: usize,
        at: Pos2,
        radius: f32,
        text: &mut LayoutText<'_>,
    ) {
        let count = self.outline[id].primitives.len().to_string();
        let galley = text(count, LABEL_SIZE, self.ink);
        let size = galley.size();
        let top_left = if self.is_grid() {
            at - 0.5 * size
        } else {
            at + vec2(-0.5 * size.x, radius + 1.0)
        };
        out.push(Shape::galley(top_left, galley, self.ink));
    }

    fn is_grid(&self) -> bool {
        matches!(self.layout.arrangement, Arrangement::Grid { .. })
    }

    /// The node's colour: the query's mark, dimmed when faint.
    fn fill(&self, id: usize) -> Color32 {
        let color = match self.mark(id) {
            Some(NodeMark::Visited) => colors::VISITED,
            Some(NodeMark::Culled) => colors::CULLED,
            Some(NodeMark::Pruned) => colors::PRUNED,
            None => colors::STRUCTURE,
        };
        if self.is_faint(id) {
            color.gamma_multiply(FAINT)
        } else {
            color
        }
    }

    /// Rings around the hovered, linked and current nodes (the last on top).
    fn rings(&self, out: &mut Vec<Shape>) {
        let h = self.highlight;
        let rings = [
            (self.hovered, 2.5, Stroke::new(1.5, self.ink)),
            (
                h.linked.map(bvhlab::NodeId::index),
                3.5,
                Stroke::new(2.5, colors::SELECTED),
            ),
            (
                h.current.map(bvhlab::NodeId::index),
                6.0,
                Stroke::new(3.0, colors::ANSWER),
            ),
        ];
        let radius = self.camera.node_radius();
        for (node, gap, stroke) in rings {
            let Some(id) = node.filter(|&id| id < self.layout.pos.len()) else {
                continue;
            };
            let at = self.camera.to_screen(self.layout.pos[id]);
            let r = radius + gap;
            if !self.clip.expand(r + stroke.width).contains(at) {
                continue;
            }
            out.push(self.ring(id, at, r, stroke));
        }
    }

    /// A ring of radius `r` around node `id` at `at`: a square for a leaf, a circle
    /// otherwise, as the node is drawn.
    fn ring(&self, id: usize, at: Pos2, r: f32, stroke: Stroke) -> Shape {
        if self.outline[id].is_leaf() {
            let square = Rect::from_center_size(at, vec2(2.0 * r, 2.0 * r));
            Shape::rect_stroke(square, 0.0, stroke, StrokeKind::Middle)
        } else {
            Shape::circle_stroke(at, r, stroke)
        }
    }

    /// A ring around each node Predict's question waiting is about, with a question mark
    /// beside it (the words say it without the colour).
    fn asked(&self, out: &mut Vec<Shape>, text: &mut LayoutText<'_>) {
        let radius = self.camera.node_radius();
        let stroke = Stroke::new(2.5, colors::ASKED);
        for node in self.highlight.asked {
            let id = node.index();
            let Some(&pos) = self.layout.pos.get(id) else {
                continue;
            };
            let at = self.camera.to_screen(pos);
            let r = radius + 4.5;
            if !self.clip.expand(r + LABEL_SIZE).contains(at) {
                continue;
            }
            out.push(self.ring(id, at, r, stroke));
            let galley = text("?".to_owned(), LABEL_SIZE + 2.0, colors::ASKED);
            let corner = at + vec2(r + 1.0, -r - galley.size().y * 0.5);
            out.push(Shape::galley(corner, galley, colors::ASKED));
        }
    }
}

/// How a node or edge looks, apart from where it is.
#[derive(Clone, Copy, PartialEq)]
enum Look {
    /// A leaf (square) or not (dot), in a colour.
    Node(bool, Color32),
    /// An edge from the parent's point column, in a colour.
    Edge(i32, Color32),
}

/// The point column each of the last few looks was drawn at, along one row: enough to skip
/// the nodes of a dense row that would repaint a point in the look it already has, even
/// where leaves and inner nodes, or visited and culled ones, alternate.
#[derive(Default)]
struct Recent {
    drawn: [Option<(Look, i32)>; 8],
    next: usize,
}

impl Recent {
    /// Whether `look` at `x` is new (then it is remembered, and should be drawn).
    fn first_at(&mut self, look: Look, x: f32) -> bool {
        let column = x.round() as i32;
        if let Some(slot) = self.drawn.iter_mut().flatten().find(|(l, _)| *l == look) {
            if slot.1 == column {
                return false;
            }
            slot.1 = column;
            return true;
        }
        self.drawn[self.next] = Some((look, column));
        self.next = (self.next + 1) % self.drawn.len();
        true
    }
}
