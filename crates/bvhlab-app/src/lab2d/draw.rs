//! Drawing the canvas from the lab's state: the static layer (structure and scene,
//! tessellated once per view: [`super::layer`]) and, each frame, the query marks, bounding
//! volumes, queries, handles and the drag in progress.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, NodeId, NodeOutline, Ray2, Segment2};
use egui::{Color32, Stroke};

use super::interaction::Interaction;
use super::layer::{LayerKey, StaticLayer};
use super::{CanvasState, Screen, overlay};
use crate::model::build_job::Structure;
use crate::model::lab2d::Lab2d;
use crate::model::lane::Lane;
use crate::model::outcome::NodeMark;
use crate::model::structures::StructureKind;
use crate::model::tools::Tool;
use crate::model::volumes::{ObbPair, SlabExplain};
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
/// node `hovered` (here or in the tree diagram) lit.
pub(super) fn draw(
    lab: &Lab2d,
    canvas: &mut CanvasState,
    hovered: Option<(usize, NodeId)>,
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
    query_shapes(lab, index, hovered, &mut wp, painter);
    if lab.tool == Tool::Obb
        && let Some(pair) = &lab.obb_pair
    {
        draw_obb_pair(pair, &mut wp);
    }
    draw_in_progress(
        &canvas.interaction,
        &mut wp,
        hover.map(|h| screen.to_world(h)),
    );
    painter.extend(wp.shapes);
}

/// The shapes of lane `index` that make a picture for export (SVG): the whole canvas,
/// untessellated.
pub fn picture(
    lab: &Lab2d,
    index: usize,
    screen: Screen,
    painter: &egui::Painter,
) -> Vec<egui::Shape> {
    let mut wp = WorldPainter::new(&screen);
    static_shapes(lab, index, &mut wp);
    query_shapes(lab, index, None, &mut wp, painter);
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
/// marks and step, the `hovered` node, the bounding volumes, the ray and the point.
fn query_shapes(
    lab: &Lab2d,
    index: usize,
    hovered: Option<NodeId>,
    wp: &mut WorldPainter<'_>,
    painter: &egui::Painter,
) {
    let this = lab.half.lane_at(index);
    if building(lab) {
        overlay::draw_build_state(lab, this, wp);
    }
    if lab.display.query_marks && !building(lab) {
        draw_marks(lab, this, lab.display.max_depth, wp);
        overlay::draw_step(lab, this, lab.half.playback.at_end, wp);
    }
    if let Some(node) = hovered {
        overlay::draw_hovered(lab, this, node, wp);
    }
    if index == 0 && (lab.display.volumes || lab.display.slab_test) {
        draw_volumes(lab, wp);
    }
    draw_queries(lab, this, wp, painter);
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
    let split_stroke = Stroke::new(1.0, colors::STRUCTURE.gamma_multiply(1.6));
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
        let clip = ancestor_half_planes(outline, node.id);
        for split in &node.splits {
            if let Some((a, b)) = clipped_plane(split.normal, split.offset, &region, &clip) {
                wp.line(a, b, split_stroke);
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
fn visible_end(ray: &Ray2, screen: &Screen) -> Vec2 {
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
            if live
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

fn draw_volumes(lab: &Lab2d, wp: &mut WorldPainter<'_>) {
    let Some(fits) = lab.fits() else { return };
    let t = &lab.volumes;
    if lab.display.volumes {
        let stroke = |c: Color32| Stroke::new(1.8, c);
        if t.hull {
            wp.polygon(
                fits.hull.vertices(),
                stroke(Color32::from_rgb(200, 120, 255)),
            );
        }
        if t.aabb {
            wp.aabb(&fits.aabb, stroke(Color32::from_rgb(120, 200, 255)));
        }
        if t.obb {
            wp.obb(&fits.obb, stroke(Color32::from_rgb(120, 255, 160)));
            // The principal axes, scaled by the standard deviation along each.
            for (axis, var) in fits
                .pca
                .axes
                .iter()
                .zip([fits.pca.variances.x, fits.pca.variances.y])
            {
                let len = var.max(0.0).sqrt();
                wp.line(
                    fits.pca.mean - *axis * len,
                    fits.pca.mean + *axis * len,
                    Stroke::new(1.0, Color32::from_rgb(120, 255, 160)),
                );
            }
        }
        if t.centroid {
            wp.sphere(&fits.centroid, stroke(Color32::from_rgb(255, 200, 120)));
            wp.dot(fits.centroid.center, 3.0, Color32::from_rgb(255, 200, 120));
        }
        if t.ritter {
            wp.sphere(&fits.ritter, stroke(Color32::from_rgb(255, 150, 150)));
        }
        if t.welzl {
            wp.sphere(&fits.welzl, stroke(Color32::from_rgb(255, 240, 120)));
        }
    }
    if lab.display.slab_test
        && let Some(ray) = lab.valid_ray()
    {
        draw_slab_test(&fits.aabb, &ray, wp);
    }
}

fn draw_slab_test(aabb: &Aabb2, ray: &Ray2, wp: &mut WorldPainter<'_>) {
    if aabb.is_empty() {
        return;
    }
    let (lo, hi) = wp.screen.visible_world();
    let thin = |c: Color32| Stroke::new(1.0, c.gamma_multiply(0.7));
    for x in [aabb.min.x, aabb.max.x] {
        wp.line(Vec2::new(x, lo.y), Vec2::new(x, hi.y), thin(colors::SLAB_X));
    }
    for y in [aabb.min.y, aabb.max.y] {
        wp.line(Vec2::new(lo.x, y), Vec2::new(hi.x, y), thin(colors::SLAB_Y));
    }
    let explain = SlabExplain::new(aabb, ray);
    let t_far_visible = (visible_end(ray, wp.screen) - ray.origin()).length() / ray.dir().length();
    let clamp = |t: f32| t.clamp(-t_far_visible, t_far_visible);
    let normal = ray.dir().normalize().perp();
    let offset = |px: f32| normal * wp.screen.world_length(px);
    for (axis, color, px) in [(0, colors::SLAB_X, 7.0), (1, colors::SLAB_Y, -7.0)] {
        let a = &explain.axes[axis];
        if a.t_min <= a.t_max {
            wp.line(
                ray.at(clamp(a.t_min)) + offset(px),
                ray.at(clamp(a.t_max)) + offset(px),
                Stroke::new(4.0, color),
            );
        }
    }
    if explain.hits() {
        wp.line(
            ray.at(clamp(explain.t_enter)),
            ray.at(clamp(explain.t_exit)),
            Stroke::new(5.0, colors::ANSWER),
        );
    }
}

fn draw_obb_pair(pair: &ObbPair, wp: &mut WorldPainter<'_>) {
    let tests = pair.tests();
    let separating = tests.iter().find(|t| t.separates());
    let color = if separating.is_some() {
        colors::VISITED
    } else {
        colors::CULLED
    };
    for pose in [pair.a, pair.b] {
        let obb = pose.obb();
        wp.convex_fill(&crate::paint::obb_corners(&obb), color.gamma_multiply(0.12));
        wp.obb(&obb, Stroke::new(2.0, color));
        wp.line(pose.center, pose.handle(), Stroke::new(1.0, color));
        wp.dot(pose.handle(), 5.0, color);
    }
    // The projections on the separating axis (or, when they overlap, on every axis).
    let shown: Vec<_> = separating.map_or_else(|| tests.clone(), |t| vec![*t]);
    let mid = (pair.a.center + pair.b.center) * 0.5;
    let reach = pair.a.half.length()
        + pair.b.half.length()
        + (pair.a.center - pair.b.center).length() * 0.5;
    for (k, test) in shown.iter().enumerate() {
        let axis = test.axis.normalize_or_zero();
        let base = mid - axis * axis.dot(mid) + axis.perp() * (reach + 0.6 * k as f32 + 0.5);
        wp.line(
            base + axis * (axis.dot(mid) - reach * 1.5),
            base + axis * (axis.dot(mid) + reach * 1.5),
            Stroke::new(1.0, Color32::GRAY),
        );
        for ((lo, hi), shift, c) in [
            (test.interval_a, 0.12, Color32::from_rgb(255, 200, 120)),
            (test.interval_b, -0.12, Color32::from_rgb(120, 200, 255)),
        ] {
            wp.line(
                base + axis * lo + axis.perp() * shift,
                base + axis * hi + axis.perp() * shift,
                Stroke::new(4.0, c),
            );
        }
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
