//! The tree diagrams below the view, one per lane (side by side when comparing), in either
//! half, linked to the view both ways: a node hovered here lights up its region and
//! primitives there, and a region hovered there (in 3D: the leaf holding the triangle under
//! the pointer) lights up its node here; playback's current node shows in both.

use bvhlab::NodeOutline;
use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Obb, Sphere};

use crate::model::dimension::{Dimension, LabPrimitive, thousands};
use crate::model::half::Half;
use crate::model::lane::Lane;
use crate::model::structures::StructureKind;
use crate::tree_diagram::{TreeDiagram, TreeHighlight};
use crate::ui_state::{Cx, UiState};

/// The panel's least height: the diagram's least height, with room above it for the "Fit"
/// row and a grid's caption.
pub const MIN_PANEL_HEIGHT: f32 = crate::tree_diagram::MIN_HEIGHT + 60.0;
/// The panel's height when the lab opens.
pub const DEFAULT_PANEL_HEIGHT: f32 = 230.0;

/// What lane `index`'s diagram highlights this frame (`asked`: what Predict's question is
/// about, lit in the main lane's diagram, which Predict follows).
fn highlight<'a, P: LabPrimitive>(
    half: &'a Half<P>,
    lane: &'a Lane<P>,
    ui: &UiState,
    index: usize,
    max_depth: u32,
    asked: &'a [bvhlab::NodeId],
) -> TreeHighlight<'a> {
    let snap = lane.snapshot.as_ref();
    let live = half.playback.at_end;
    let building = snap.is_some_and(|s| !s.existing.is_empty()) && !live;
    TreeHighlight {
        marks: snap.filter(|_| !building).map(|s| &s.marks),
        current: snap.and_then(|s| s.current).filter(|_| !live),
        linked: ui
            .linked
            .filter(|(lane, _)| *lane == index)
            .map(|(_, node)| node),
        existing: snap.filter(|_| building).map(|s| s.existing.as_slice()),
        max_depth,
        asked: if index == 0 { asked } else { &[] },
    }
}

/// The lane's nodes, when its structure is built on the half's primitives as they are and
/// small enough to list; otherwise why there is no diagram (brute force has no tree, an empty
/// scene builds none: each said as it is, not one sentence for both).
fn outline<P: LabPrimitive>(
    lane: &Lane<P>,
    revision: u64,
    prims: usize,
) -> Result<&[NodeOutline<P::Point>], String> {
    match lane.current(revision) {
        None if lane.job.is_some() => Err("The structure is being built…".to_owned()),
        None => Err(lane
            .build_error
            .clone()
            .unwrap_or_else(|| "No structure yet.".to_owned())),
        Some(s) if s.settings.kind == StructureKind::BruteForce => {
            Err(brute_force_words(prims, P::NAME))
        }
        Some(_) if prims == 0 => Err(format!(
            "No tree to show: the scene has no {} to build one over.",
            P::NAME
        )),
        Some(s) => s.outline.as_deref().ok_or_else(|| {
            format!(
                "A tree over {} {} is too large to draw as a diagram (up to {}).",
                thousands(prims),
                P::NAME,
                thousands(P::MAX_LISTED)
            )
        }),
    }
}

/// What the tree panel and the structure panel say of brute force over `prims` primitives
/// (`name`: "segments", "triangles"): it has no tree, so neither a diagram nor leaves.
pub fn brute_force_words(prims: usize, name: &str) -> String {
    format!(
        "Brute force has no tree: it keeps the {} {name} in one list and tests every one.",
        thousands(prims)
    )
}

/// The panel's content: one diagram per lane of the half shown.
pub fn tree_panel(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab;
    resize_grip(ui);
    // The panel keeps the height it was given whatever it shows. (A panel is as high as its
    // content, and egui remembers that height: after "Clear" the one-line message made it a
    // strip, and the diagram, which fills the height it is given, kept it one.)
    ui.set_min_height(ui.available_height());
    cx.ui.tree_rect = Some(ui.max_rect());
    let asked = lab.predict_about().nodes;
    let (hovered, clicked) = match lab.dimension() {
        Dimension::Two => {
            let two = lab.two();
            let revision = two.scene.revision();
            let prims = two.prims().segments.len();
            let mut trees = std::mem::take(&mut cx.ui.trees.two);
            let seen = diagrams(
                &two.half,
                revision,
                prims,
                two.display.max_depth,
                &asked,
                cx.ui,
                &mut trees,
                ui,
            );
            cx.ui.trees.two = trees;
            seen
        }
        Dimension::Three => {
            let three = lab.three();
            let prims = three.triangles().len();
            let mut trees = std::mem::take(&mut cx.ui.trees.three);
            let seen = diagrams(
                &three.half,
                three.revision(),
                prims,
                u32::MAX,
                &asked,
                cx.ui,
                &mut trees,
                ui,
            );
            cx.ui.trees.three = trees;
            seen
        }
    };
    if hovered.is_some() {
        cx.ui.hovered = hovered;
    }
    // A click on a node answers "which node" while Predict asks it (the main structure's
    // diagram, which Predict follows).
    if let Some((0, node)) = clicked
        && let Some(question) = lab.predict_question()
    {
        let choice = crate::model::predict::Choice::Node(node.0);
        if question.label(choice).is_some() {
            cx.act(crate::model::predict::PredictAction::Answer(choice));
        }
    }
}

/// A grip centred on the panel's top edge, where it is dragged to resize (egui's own edge
/// line is too faint to find).
fn resize_grip(ui: &egui::Ui) {
    let top = ui.max_rect().center_top();
    let grip = egui::Rect::from_center_size(top - egui::vec2(0.0, 1.0), egui::vec2(36.0, 4.0));
    let color = ui.visuals().widgets.inactive.fg_stroke.color;
    ui.painter().rect_filled(grip, 2.0, color);
}

/// A node of a lane, by the lane's index and the node's id.
type Picked = Option<(usize, bvhlab::NodeId)>;

/// Shows each lane's diagram in a column; the node hovered and the node clicked, if any.
#[allow(clippy::too_many_arguments)] // the half, its revision and size, and the UI's parts
fn diagrams<P: LabPrimitive>(
    half: &Half<P>,
    revision: u64,
    prims: usize,
    max_depth: u32,
    asked: &[bvhlab::NodeId],
    state: &UiState,
    trees: &mut [TreeDiagram; 2],
    ui: &mut egui::Ui,
) -> (Picked, Picked)
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    let mut hovered = None;
    let mut clicked = None;
    ui.columns(half.lane_count(), |columns| {
        for (i, column) in columns.iter_mut().enumerate() {
            let lane = half.lane_at(i);
            match outline(lane, revision, prims) {
                Ok(nodes) => {
                    let shown = highlight(half, lane, state, i, max_depth, asked);
                    let response = trees[i].show(column, nodes, &shown);
                    if let Some(node) = response.hovered {
                        hovered = Some((i, node));
                    }
                    if let Some(node) = response.clicked {
                        clicked = Some((i, node));
                    }
                }
                Err(why) => {
                    trees[i].forget();
                    column.label(why);
                }
            }
        }
    });
    (hovered, clicked)
}

/// The diagrams fitted into `rect` (side by side when comparing), for export.
pub fn tree_picture(cx: &mut Cx<'_>, ctx: &egui::Context, rect: egui::Rect) -> Vec<egui::Shape> {
    let lab = cx.lab;
    let asked = lab.predict_about().nodes;
    match lab.dimension() {
        Dimension::Two => {
            let two = lab.two();
            let mut trees = std::mem::take(&mut cx.ui.trees.two);
            let shapes = pictures(
                &two.half,
                two.scene.revision(),
                two.prims().segments.len(),
                two.display.max_depth,
                &asked,
                cx.ui,
                &mut trees,
                ctx,
                rect,
            );
            cx.ui.trees.two = trees;
            shapes
        }
        Dimension::Three => {
            let three = lab.three();
            let mut trees = std::mem::take(&mut cx.ui.trees.three);
            let shapes = pictures(
                &three.half,
                three.revision(),
                three.triangles().len(),
                u32::MAX,
                &asked,
                cx.ui,
                &mut trees,
                ctx,
                rect,
            );
            cx.ui.trees.three = trees;
            shapes
        }
    }
}

#[allow(clippy::too_many_arguments)] // as `diagrams`, with where to draw
fn pictures<P: LabPrimitive>(
    half: &Half<P>,
    revision: u64,
    prims: usize,
    max_depth: u32,
    asked: &[bvhlab::NodeId],
    state: &UiState,
    trees: &mut [TreeDiagram; 2],
    ctx: &egui::Context,
    rect: egui::Rect,
) -> Vec<egui::Shape> {
    let count = half.lane_count();
    let width = rect.width() / count as f32;
    let mut shapes = Vec::new();
    for (i, tree) in trees.iter_mut().enumerate().take(count) {
        let lane = half.lane_at(i);
        let Ok(nodes) = outline(lane, revision, prims) else {
            continue;
        };
        let part = egui::Rect::from_min_size(
            rect.min + egui::vec2(width * i as f32, 0.0),
            egui::vec2(width, rect.height()),
        );
        let shown = highlight(half, lane, state, i, max_depth, asked);
        shapes.extend(tree.export_shapes(nodes, &shown, part, ctx));
    }
    shapes
}
