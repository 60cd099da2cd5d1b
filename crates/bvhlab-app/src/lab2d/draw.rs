//! Drawing the canvas from the lab's state: the static layer (structure and scene,
//! tessellated once per view: [`super::layer`]) and, each frame, the query marks, bounding
//! volumes, queries, handles and the drag in progress.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, FitKind, NodeId, NodeOutline, Ray2, Segment2};
use egui::{Color32, Stroke};

use super::interaction::Interaction;
use super::layer::{LayerKey, StaticLayer};
use super::{CanvasState, Screen, overlay, volumes};
use crate::model::build_job::Structure;
use crate::model::lab2d::Lab2d;
use crate::model::lane::Lane;
use crate::model::outcome::NodeMark;
use crate::model::predict::About;
use crate::model::structures::StructureKind;
use crate::model::tools::Tool;
use crate::paint::{WorldPainter, clipped_plane, colors};
use crate::pseudocode::Task;

/// A hue per leaf, for leaf colouring.
fn leaf_colour(leaf: u32) -> Color32 {
    let hue = (leaf as f32 * 0.618_034).fract();
    egui::ecolor::Hsva::new(hue, 0.65, 0.95, 1.0).into()
}

/// Whether a build is being stepped through (the structure then appears node by node).
fn building(lab: &Lab2d) -> bool {
    lab.half.task == Task::Build && !lab.half.playback.at_end
}

/// Draws lane `index` (0: the main structure, 1: the comparison) through `screen`, with the
/// node `hovered` (here or in the tree diagram) lit, and in the main lane what Predict's
/// question is `asked` about.
#[allow(clippy::too_many_arguments)] // the lab, the view's state and what this frame lights
pub(super) fn draw(
    lab: &Lab2d,
    canvas: &mut CanvasState,
    hovered: Option<(usize, NodeId)>,
    asked: &About,
    index: usize,
    screen: Screen,
    painter: &egui::Painter,
    hover: Option<egui::Pos2>,
) {
    let mut display = lab.display;
    display.structure &= !building(lab);
    let key = LayerKey {
        revision: lab.scene.revision(),
        settings: lab.half.lane_at(index).settings,
        built: lab
            .half
            .lane_at(index)
            .current(lab.scene.revision())
            .is_some(),
        updates: lab.half.lane_at(index).log.total(),
        screen,
        display,
        selection: lab.selection.clone(),
        pixels_per_point: painter.ctx().pixels_per_point(),
    };
    let layer = &mut canvas.layers[index.min(1)];
    if layer.as_ref().is_none_or(|l| l.key != key) {
        let mut wp = WorldPainter::new(&screen);
        static_shapes(lab, index, &mut wp);
        *layer = Some(StaticLayer::tessellate(
            key,
            painter.ctx(),
            wp.shapes,
            screen.rect,
        ));
    }
    if let Some(layer) = layer {
        painter.add(layer.shape());
    }
    let mut wp = WorldPainter::new(&screen);
    let hovered = hovered.filter(|(at, _)| *at == index).map(|(_, node)| node);
    let volume = canvas.volume_hover;
    query_shapes(lab, index, hovered, volume, asked, &mut wp, painter);
    if lab.tool == Tool::Obb
        && let Some(pair) = &lab.obb_pair
    {
        volumes::draw_obb_pair(pair, &mut wp);
    }
    super::collision::draw_collision(lab, &mut wp);
    draw_in_progress(
        &canvas.interaction,
        &mut wp,
        hover.map(|h| screen.to_world(h)),
    );
    painter.extend(wp.shapes);
}

/// The shapes of lane `index` that make a picture for export (SVG): the whole canvas,
/// untessellated, with what Predict's question is `asked` about.
pub fn picture(
    lab: &Lab2d,
    index: usize,
    asked: &About,
    screen: Screen,
    painter: &egui::Painter,
) -> Vec<egui::Shape> {
    let mut wp = WorldPainter::new(&screen);
    static_shapes(lab, index, &mut wp);
    query_shapes(lab, index, None, None, asked, &mut wp, painter);
    wp.shapes
}

/// What changes only with the scene, the structure, the view and the switches: the
/// structure's nodes (not while a build is stepped through) and the scene.
fn static_shapes(lab: &Lab2d, index: usize, wp: &mut WorldPainter<'_>) {
    let lane = lab.half.lane_at(index);
    if lab.display.structure && !building(lab) {
        draw_structure(lab, lane, lab.display.max_depth, wp);
    }
    draw_scene(lab, lane, wp);
}

/// What changes with the query and the playback step: a build's progress or the query's
/// marks and step, what Predict's question is `asked` about (in the main lane, which
/// Predict follows), the `hovered` node, the bounding volumes (the `volume` hovered in their
/// table lit), the ray and the point.
fn query_shapes(
    lab: &Lab2d,
    index: usize,
    hovered: Option<NodeId>,
    volume: Option<FitKind>,
    asked: &About,
    wp: &mut WorldPainter<'_>,
    painter: &egui::Painter,
) {
    let this = lab.half.lane_at(index);
    if building(lab) {
        overlay::draw_build_state(lab, this, wp);
    }
    if lab.display.query_marks && !building(lab) {
        draw_marks(lab, this, lab.display.max_depth, wp);
        overlay::draw_step(lab, this, lab.half.playback.at_end, wp, painter);
    }
    if index == 0 {
        overlay::draw_asked(lab, this, asked, wp, painter);
    }
    if let Some(node) = hovered {
        overlay::draw_hovered(lab, this, node, wp);
    }
    if index == 0 && (lab.display.volumes || lab.display.slab_test || volume.is_some()) {
        volumes::draw_volumes(lab, volume, wp);
    }
    draw_queries(lab, this, wp, painter);
}

/// Whether lane `index`'s canvas draws splitting planes: a k-d tree, quadtree or BSP tree
/// is built and its nodes are drawn (for the legend).
pub(super) fn draws_splits(lab: &Lab2d, index: usize) -> bool {
    lab.display.structure
        && !building(lab)
        && built(lab, lab.half.lane_at(index)).is_some_and(|(s, outline)| {
            !s.settings.kind.is_bvh()
                && s.settings.kind != StructureKind::Grid
                && outline
                    .iter()
                    .any(|n| !n.splits.is_empty() && n.depth < lab.display.max_depth)
        })
}

/// The lane's structure built on the scene as it is, with its nodes.
pub(super) fn built<'a>(
    lab: &Lab2d,
    lane: &'a Lane<Segment2>,
) -> Option<(&'a Structure<Segment2>, &'a [NodeOutline<Vec2>])> {
    let structure = lane.current(lab.scene.revision())?;
    Some((structure, structure.outline.as_deref()?))
}

fn draw_structure(lab: &Lab2d, lane: &Lane<Segment2>, max_depth: u32, wp: &mut WorldPainter<'_>) {
    let Some((built, outline)) = built(lab, lane) else {
        return;
    };
    let stroke = Stroke::new(1.0, colors::STRUCTURE);
    let split_stroke = Stroke::new(1.5, colors::SPLIT);
    // Dashes over the part of a plane in view only: zoomed in, a whole plane would be
    // thousands of dashes off screen.
    let (lo, hi) = wp.screen.visible_world();
    let visible = Aabb2::new(lo, hi);
    if built.settings.kind == StructureKind::Grid {
        draw_grid_lines(outline, wp, stroke);
        return;
    }
    // Space partitions (k-d tree, quadtree, BSP tree): the cells are what the splits cut out
    // of the root's box, so the root box and the split lines draw them all. BVHs draw every
    // node's volume.
    let space = !built.settings.kind.is_bvh();
    for node in outline {
        if node.depth > max_depth {
            continue;
        }
        if !space || node.parent.is_none() {
            wp.node_shape(&node.shape, stroke);
        }
        if node.splits.is_empty() || node.depth >= max_depth {
            continue;
        }
        let region = node.shape.aabb();
        let (lo, hi) = (region.min.max(visible.min), region.max.min(visible.max));
        if lo.cmpgt(hi).any() {
            continue;
        }
        let shown = Aabb2::new(lo, hi);
        let clip = ancestor_half_planes(outline, node.id);
        for split in &node.splits {
            if let Some((a, b)) = clipped_plane(split.normal, split.offset, &shown, &clip) {
                wp.dashed_line(a, b, split_stroke);
            }
        }
    }
}

/// A uniform grid as lines: one per cell boundary across the whole grid.
fn draw_grid_lines(cells: &[NodeOutline<Vec2>], wp: &mut WorldPainter<'_>, stroke: Stroke) {
    let boxes: Vec<Aabb2> = cells.iter().map(|c| c.shape.aabb()).collect();
    let Some(bounds) = boxes.iter().copied().reduce(|a, b| a.merge(&b)) else {
        return;
    };
    let mut xs: Vec<f32> = boxes.iter().flat_map(|b| [b.min.x, b.max.x]).collect();
    let mut ys: Vec<f32> = boxes.iter().flat_map(|b| [b.min.y, b.max.y]).collect();
    for v in [&mut xs, &mut ys] {
        v.sort_by(f32::total_cmp);
        v.dedup();
    }
    for x in xs {
        wp.line(
            Vec2::new(x, bounds.min.y),
            Vec2::new(x, bounds.max.y),
            stroke,
        );
    }
    for y in ys {
        wp.line(
            Vec2::new(bounds.min.x, y),
            Vec2::new(bounds.max.x, y),
            stroke,
        );
    }
}

/// The nodes the query visited, culled and pruned, and the primitives it tested.
fn draw_marks(lab: &Lab2d, lane: &Lane<Segment2>, max_depth: u32, wp: &mut WorldPainter<'_>) {
    let (Some((_, outline)), Some(marks)) = (built(lab, lane), lane.marks()) else {
        return;
    };
    for (i, mark) in marks.nodes.iter().enumerate() {
        let Some(mark) = mark else { continue };
        let Some(node) = outline.get(i) else {
            continue;
        };
        if node.depth > max_depth {
            continue;
        }
        let color = match mark {
            NodeMark::Visited => colors::VISITED,
            NodeMark::Culled => colors::CULLED,
            NodeMark::Pruned => colors::PRUNED,
        };
        wp.node_fill(&node.shape, color.gamma_multiply(0.08));
        wp.node_shape(&node.shape, Stroke::new(1.5, color));
    }
    for &(p, _) in &marks.tested {
        if let Some(s) = lab.prims().segments.get(p as usize) {
            if s.a == s.b {
                wp.dot(s.a, 3.5, colors::TESTED);
            } else {
                wp.line(s.a, s.b, Stroke::new(2.5, colors::TESTED));
            }
        }
    }
}

/// The half-planes of a BSP node's ancestors, which bound the node's region: each ancestor's
/// split, kept on the side the node lies.
fn ancestor_half_planes(outline: &[NodeOutline<Vec2>], id: NodeId) -> Vec<(Vec2, f32, bool)> {
    let mut out = Vec::new();
    let mut child = id;
    while let Some(parent) = outline[child.index()].parent {
        let p = &outline[parent.index()];
        if let ([split], Some(side)) = (
            p.splits.as_slice(),
            p.children.iter().position(|&c| c == child),
        ) {
            out.push((split.normal, split.offset, side == 1));
        }
        child = parent;
    }
    out
}

fn draw_scene(lab: &Lab2d, lane: &Lane<Segment2>, wp: &mut WorldPainter<'_>) {
    let built = built(lab, lane).map(|(s, _)| s);
    let leaf_colours = lab.display.leaf_colours && built.is_some();
    let mut prim = 0usize;
    for (i, shape) in lab.scene.shapes().iter().enumerate() {
        let selected = lab.selection.binary_search(&i).is_ok();
        for s in shape.primitives() {
            let color = if selected {
                colors::SELECTED
            } else if leaf_colours {
                built
                    .and_then(|b| b.leaf_of.get(prim).copied().flatten())
                    .map_or(colors::SCENE, leaf_colour)
            } else {
                colors::SCENE
            };
            if s.a == s.b {
                wp.dot(s.a, 2.5, color);
            } else {
                wp.line(s.a, s.b, Stroke::new(1.5, color));
            }
            prim += 1;
        }
    }
}

/// The far end of the ray on screen: where it leaves the visible part of the world.
pub(super) fn visible_end(ray: &Ray2, screen: &Screen) -> Vec2 {
    let (lo, hi) = screen.visible_world();
    let visible = Aabb2::new(lo, hi);
    let t = visible
        .ray_interval(ray)
        .map_or(0.0, |(_, exit)| exit)
        .max(ray.dir().length().recip() * screen.world_length(40.0));
    ray.at(t)
}

fn draw_queries(
    lab: &Lab2d,
    lane: &Lane<Segment2>,
    wp: &mut WorldPainter<'_>,
    fonts: &egui::Painter,
) {
    let live = lab.half.playback.at_end;
    if let Some(handles) = lab.ray {
        if let Ok(ray) = handles.ray() {
            let end = visible_end(&ray, wp.screen);
            wp.line(ray.origin(), end, Stroke::new(2.0, colors::QUERY));
            // All hits: each one the panel lists; otherwise the first hit.
            if live
                && !overlay::draw_all_hits(lane, wp, fonts)
                && let Some(hit) = lane
                    .ray_outcome
                    .as_ref()
                    .and_then(crate::model::outcome::RayOutcome::hit_point)
            {
                wp.dot(hit, 6.0, colors::ANSWER);
            }
        }
        wp.dot(handles.origin, 5.0, colors::QUERY);
        wp.text(fonts, handles.origin, " e", colors::QUERY);
        wp.ring(handles.target, 5.0, Stroke::new(2.0, colors::QUERY));
        wp.text(fonts, handles.target, " s", colors::QUERY);
    }
    if let Some(outcome) = lane.point_outcome.as_ref().filter(|_| live) {
        for (rank, n) in outcome.nearest.iter().enumerate() {
            let stroke = Stroke::new(if rank == 0 { 2.0 } else { 1.0 }, colors::ANSWER);
            wp.line(outcome.point, n.point, stroke);
            wp.dot(n.point, 4.0, colors::ANSWER);
        }
        if let Some(best) = outcome.nearest.last() {
            // The ball of the current minimum: nothing outside it can be nearer.
            let radius = wp.screen.screen_length(best.distance);
            wp.ring(
                outcome.point,
                radius,
                Stroke::new(1.0, colors::ANSWER.gamma_multiply(0.6)),
            );
        }
    }
    if let Some(p) = lab.point {
        wp.dot(p, 5.0, colors::QUERY);
        wp.text(fonts, p, " q", colors::QUERY);
    }
}

fn draw_in_progress(interaction: &Interaction, wp: &mut WorldPainter<'_>, hover: Option<Vec2>) {
    let stroke = Stroke::new(1.5, colors::SELECTED);
    match interaction {
        Interaction::Segment(a) => {
            if let Some(h) = hover {
                wp.line(*a, h, stroke);
            }
        }
        Interaction::Chain(points) => {
            for w in points.windows(2) {
                wp.line(w[0], w[1], stroke);
            }
            if let (Some(&last), Some(h)) = (points.last(), hover) {
                wp.line(
                    last,
                    h,
                    Stroke::new(1.0, colors::SELECTED.gamma_multiply(0.6)),
                );
            }
            for &p in points {
                wp.dot(p, 3.0, colors::SELECTED);
            }
        }
        _ => {}
    }
}
