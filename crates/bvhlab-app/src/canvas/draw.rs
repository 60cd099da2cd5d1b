//! Drawing the canvas: the static layer (structure and scene, tessellated once per view) and,
//! each frame, the query marks, bounding volumes, queries and handles.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, Ray2};
use egui::{Color32, Stroke};

use super::steps;
use crate::app::LabApp;
use crate::lane::Lane;
use crate::paint::{WorldPainter, clipped_plane, colors};
use crate::pseudocode::Task;
use crate::query::NodeMark;
use crate::structures::StructureKind;
use crate::tool::{Interaction, Tool};
use crate::view::View;
use crate::volumes::{Fits, ObbPair, SlabExplain};

/// The most shapes the static layer anti-aliases (see [`tessellate`]).
const FEATHERING_LIMIT: usize = 4000;

/// A hue per leaf, for leaf colouring.
fn leaf_colour(leaf: u32) -> Color32 {
    let hue = (leaf as f32 * 0.618_034).fract();
    egui::ecolor::Hsva::new(hue, 0.65, 0.95, 1.0).into()
}

/// What the static layer was drawn for: when none of it changes (while a ray or a query
/// point is dragged), the cached mesh is reused.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerKey {
    revision: u64,
    settings: crate::structures::BuildSettings,
    view: View,
    display: crate::app::Display,
    selection: Vec<usize>,
    pixels_per_point: f32,
}

/// The structure's nodes and the scene's primitives, tessellated once into one mesh and
/// reused while only the queries change, so that a frame during a ray drag costs about the
/// same with 10 or 10,000 segments.
pub struct StaticLayer {
    key: LayerKey,
    mesh: std::sync::Arc<egui::Mesh>,
}

/// Draws lane `index` (0: the main structure, 1: the comparison) through `view`.
pub(super) fn draw(
    app: &mut LabApp,
    index: usize,
    view: View,
    painter: &egui::Painter,
    hover: Option<egui::Pos2>,
) {
    let building = app.task == Task::Build && !app.playback.at_end;
    let mut display = app.display;
    // While a build is stepped through, the structure appears node by node instead.
    display.structure &= !building;
    let key = LayerKey {
        revision: app.scene.revision(),
        settings: app.lane_at(index).settings,
        view,
        display,
        selection: app.selection.clone(),
        pixels_per_point: painter.ctx().pixels_per_point(),
    };
    let cached = app
        .lane_at(index)
        .static_layer
        .as_ref()
        .is_some_and(|l| l.key == key);
    if !cached {
        let mut wp = WorldPainter::new(&view);
        static_shapes(app, index, &mut wp);
        let mesh = tessellate(painter.ctx(), wp.shapes, view.rect);
        let layer = StaticLayer {
            key,
            mesh: std::sync::Arc::new(mesh),
        };
        if let Some(l) = lane_mut(app, index) {
            l.static_layer = Some(layer);
        }
    }
    if let Some(layer) = &app.lane_at(index).static_layer {
        painter.add(egui::Shape::Mesh(layer.mesh.clone()));
    }
    let mut wp = WorldPainter::new(&view);
    let hovered = app
        .hovered
        .filter(|(at, _)| *at == index)
        .map(|(_, node)| node);
    query_shapes(app, index, hovered, &mut wp, painter);
    if app.tool == Tool::Obb
        && let Some(pair) = &app.obb_pair
    {
        draw_obb_pair(pair, &mut wp);
    }
    draw_in_progress(app, &mut wp, hover.map(|h| view.to_world(h)));
    painter.extend(wp.shapes);
}

/// The shapes of lane `index` that make a picture for export (SVG): the whole canvas,
/// untessellated.
pub fn picture(
    app: &mut LabApp,
    index: usize,
    view: View,
    painter: &egui::Painter,
) -> Vec<egui::Shape> {
    let mut wp = WorldPainter::new(&view);
    static_shapes(app, index, &mut wp);
    query_shapes(app, index, None, &mut wp, painter);
    wp.shapes
}

/// What changes only with the scene, the structure, the view and the switches: the
/// structure's nodes (not while a build is stepped through) and the scene.
fn static_shapes(app: &LabApp, index: usize, wp: &mut WorldPainter<'_>) {
    let building = app.task == Task::Build && !app.playback.at_end;
    if app.display.structure && !building {
        draw_structure(app.lane_at(index), app.display.max_depth, wp);
    }
    draw_scene(app, app.lane_at(index), wp);
}

/// What changes with the query and the playback step: a build's progress or the query's
/// marks and step, the `hovered` node, the bounding volumes, the ray and the point.
fn query_shapes(
    app: &mut LabApp,
    index: usize,
    hovered: Option<bvhlab::NodeId>,
    wp: &mut WorldPainter<'_>,
    painter: &egui::Painter,
) {
    let building = app.task == Task::Build && !app.playback.at_end;
    let this = app.lane_at(index);
    if building {
        steps::draw_build_state(this, wp);
    }
    if app.display.query_marks && !building {
        draw_marks(this, app.display.max_depth, wp);
        steps::draw_step(this, app.playback.at_end, wp);
    }
    if let Some(node) = hovered {
        steps::draw_hovered(this, node, wp);
    }
    if index == 0 && (app.display.volumes || app.display.slab_test) {
        draw_volumes(app, wp);
    }
    draw_queries(app, app.lane_at(index), wp, painter);
}

fn lane_mut(app: &mut LabApp, index: usize) -> Option<&mut Lane> {
    match index {
        0 => Some(&mut app.lane),
        1 => app.compare.as_mut(),
        _ => None,
    }
}

/// Tessellates `shapes` into one mesh, culled to `clip`, as egui would each frame.
///
/// Above [`FEATHERING_LIMIT`] shapes the edges are not anti-aliased: feathering doubles the
/// vertices, and egui copies and uploads every vertex each frame.
fn tessellate(ctx: &egui::Context, shapes: Vec<egui::Shape>, clip: egui::Rect) -> egui::Mesh {
    let mut options = ctx.tessellation_options(|o| *o);
    options.feathering &= shapes.len() <= FEATHERING_LIMIT;
    let mut tessellator =
        egui::epaint::Tessellator::new(ctx.pixels_per_point(), options, [1, 1], Vec::new());
    tessellator.set_clip_rect(clip);
    let mut mesh = egui::Mesh::default();
    for shape in shapes {
        tessellator.tessellate_shape(shape, &mut mesh);
    }
    mesh
}

fn draw_structure(lane: &Lane, max_depth: u32, wp: &mut WorldPainter<'_>) {
    let Some(built) = &lane.built else { return };
    let stroke = Stroke::new(1.0, colors::STRUCTURE);
    let split_stroke = Stroke::new(1.0, colors::STRUCTURE.gamma_multiply(1.6));
    if built.settings.kind == StructureKind::Grid {
        draw_grid_lines(&built.outline, wp, stroke);
        return;
    }
    // Space partitions (k-d tree, quadtree, BSP tree): the cells are what the splits cut out
    // of the root's box, so the root box and the split lines draw them all. BVHs draw every
    // node's volume.
    let space = !built.settings.kind.is_bvh();
    for node in &built.outline {
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
        let clip = ancestor_half_planes(&built.outline, node.id);
        for split in &node.splits {
            if let Some((a, b)) = clipped_plane(split.normal, split.offset, &region, &clip) {
                wp.line(a, b, split_stroke);
            }
        }
    }
}

/// A uniform grid as lines: one per cell boundary across the whole grid.
fn draw_grid_lines(cells: &[bvhlab::NodeOutline<Vec2>], wp: &mut WorldPainter<'_>, stroke: Stroke) {
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
fn draw_marks(lane: &Lane, max_depth: u32, wp: &mut WorldPainter<'_>) {
    let (Some(built), Some(marks)) = (&lane.built, lane.marks()) else {
        return;
    };
    for (i, mark) in marks.nodes.iter().enumerate() {
        let Some(mark) = mark else { continue };
        let Some(node) = built.outline.get(i) else {
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
        if let Some(s) = built.prims.segments.get(p as usize) {
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
fn ancestor_half_planes(
    outline: &[bvhlab::NodeOutline<Vec2>],
    id: bvhlab::NodeId,
) -> Vec<(Vec2, f32, bool)> {
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

fn draw_scene(app: &LabApp, lane: &Lane, wp: &mut WorldPainter<'_>) {
    let built = lane.built.as_ref();
    let leaf_colours = app.display.leaf_colours && built.is_some();
    let mut prim = 0usize;
    for (i, shape) in app.scene.shapes().iter().enumerate() {
        let selected = app.selection.contains(&i);
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
fn visible_end(ray: &Ray2, view: &View) -> Vec2 {
    let (lo, hi) = view.visible_world();
    let visible = Aabb2::new(lo, hi);
    let t = visible
        .ray_interval(ray)
        .map_or(0.0, |(_, exit)| exit)
        .max(ray.dir().length().recip() * view.world_length(40.0));
    ray.at(t)
}

fn draw_queries(app: &LabApp, lane: &Lane, wp: &mut WorldPainter<'_>, fonts: &egui::Painter) {
    let live = app.playback.at_end;
    if let Some(handles) = app.ray {
        if let Ok(ray) = handles.ray() {
            let end = visible_end(&ray, wp.view);
            wp.line(ray.origin(), end, Stroke::new(2.0, colors::QUERY));
            if live
                && let Some(hit) = lane
                    .ray_outcome
                    .as_ref()
                    .and_then(crate::query::RayOutcome::hit_point)
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
            let radius = wp.view.screen_length(best.distance);
            wp.ring(
                outcome.point,
                radius,
                Stroke::new(1.0, colors::ANSWER.gamma_multiply(0.6)),
            );
        }
    }
    if let Some(p) = app.point {
        wp.dot(p, 5.0, colors::QUERY);
        wp.text(fonts, p, " q", colors::QUERY);
    }
}

fn draw_volumes(app: &mut LabApp, wp: &mut WorldPainter<'_>) {
    let Some(fits) = app.fits() else { return };
    let t = &app.volume_toggles;
    if app.display.volumes {
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
    if app.display.slab_test
        && let Some(Ok(ray)) = app.ray.map(|r| r.ray())
    {
        draw_slab_test(&fits.aabb, &ray, wp);
    }
}

fn draw_slab_test(aabb: &Aabb2, ray: &Ray2, wp: &mut WorldPainter<'_>) {
    if aabb.is_empty() {
        return;
    }
    let (lo, hi) = wp.view.visible_world();
    let thin = |c: Color32| Stroke::new(1.0, c.gamma_multiply(0.7));
    for x in [aabb.min.x, aabb.max.x] {
        wp.line(Vec2::new(x, lo.y), Vec2::new(x, hi.y), thin(colors::SLAB_X));
    }
    for y in [aabb.min.y, aabb.max.y] {
        wp.line(Vec2::new(lo.x, y), Vec2::new(hi.x, y), thin(colors::SLAB_Y));
    }
    let explain = SlabExplain::new(aabb, ray);
    let t_far_visible = (visible_end(ray, wp.view) - ray.origin()).length() / ray.dir().length();
    let clamp = |t: f32| t.clamp(-t_far_visible, t_far_visible);
    let normal = ray.dir().normalize().perp();
    let offset = |px: f32| normal * wp.view.world_length(px);
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

fn draw_in_progress(app: &LabApp, wp: &mut WorldPainter<'_>, hover: Option<Vec2>) {
    let stroke = Stroke::new(1.5, colors::SELECTED);
    match &app.interaction {
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

impl LabApp {
    /// The bounding volumes of the selected shapes (all shapes when none is selected),
    /// cached until the scene or the selection changes.
    pub fn fits(&mut self) -> Option<Fits> {
        let key = (self.scene.revision(), self.selection.clone());
        if self.fits_cache.as_ref().is_none_or(|(k, _)| *k != key) {
            let fits = Fits::of(&self.scene.vertices(&self.selection));
            self.fits_cache = Some((key, fits));
        }
        self.fits_cache.as_ref().and_then(|(_, f)| f.clone())
    }
}
