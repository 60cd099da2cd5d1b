//! The tree diagrams under the canvas, one per lane (side by side when comparing), linked to
//! the canvas both ways: a node hovered here lights up its region and primitives there, and a
//! region hovered there lights up its node here; playback's current node shows in both.

use crate::app::LabApp;
use crate::tree_view::{TreeDiagram, TreeHighlight};

/// What a lane's diagram highlights this frame.
fn highlight(app: &LabApp, index: usize) -> TreeHighlight<'_> {
    let lane = app.lane_at(index);
    let snap = lane.snapshot.as_ref();
    let building = snap.is_some_and(|s| !s.existing.is_empty()) && !app.playback.at_end;
    TreeHighlight {
        marks: snap.filter(|_| !building).map(|s| &s.marks),
        current: snap
            .and_then(|s| s.current)
            .filter(|_| !app.playback.at_end),
        linked: app
            .linked
            .filter(|(lane, _)| *lane == index)
            .map(|(_, node)| node),
        existing: snap.filter(|_| building).map(|s| s.existing.as_slice()),
        max_depth: app.display.max_depth,
    }
}

/// The panel's content: one diagram per lane.
pub fn tree_panel(app: &mut LabApp, ui: &mut egui::Ui) {
    let count = if app.compare.is_some() { 2 } else { 1 };
    let mut trees = std::mem::take(&mut app.trees);
    let mut hovered = None;
    app.tree_rect = Some(ui.max_rect());
    ui.columns(count, |columns| {
        for (i, column) in columns.iter_mut().enumerate() {
            let Some(built) = &app.lane_at(i).built else {
                continue;
            };
            let response = trees[i].show(column, &built.outline, &highlight(app, i));
            if let Some(node) = response.hovered {
                hovered = Some((i, node));
            }
        }
    });
    app.trees = trees;
    if hovered.is_some() {
        app.hovered = hovered;
    }
}

/// The diagrams fitted into `rect` (side by side when comparing), for export.
pub fn tree_picture(app: &mut LabApp, ctx: &egui::Context, rect: egui::Rect) -> Vec<egui::Shape> {
    let count = if app.compare.is_some() { 2 } else { 1 };
    let mut trees = std::mem::take(&mut app.trees);
    let mut shapes = Vec::new();
    let width = rect.width() / count as f32;
    for (i, tree) in trees.iter_mut().enumerate().take(count) {
        let Some(built) = &app.lane_at(i).built else {
            continue;
        };
        let part = egui::Rect::from_min_size(
            rect.min + egui::vec2(width * i as f32, 0.0),
            egui::vec2(width, rect.height()),
        );
        shapes.extend(tree.export_shapes(&built.outline, &highlight(app, i), part, ctx));
    }
    app.trees = trees;
    shapes
}

/// One diagram per lane.
pub type Trees = [TreeDiagram; 2];
