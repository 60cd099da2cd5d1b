//! A build's current decision in the "Step through" panel: the node, its split plane and the
//! two groups, and for a binned-SAH BVH the cost of every candidate plane as a plot with the
//! cheapest marked (`MacDonald` and Booth 1990; Wald 2007).

use egui_plot::{HLine, Line, Plot, PlotPoints, Points, VLine};

use bvhlab::Vector;
use bvhlab::structure::SplitMethod;

use crate::model::recording::Recording;
use crate::model::snapshot::Snapshot;
use crate::model::structures::StructureKind;
use crate::paint::colors;

/// The current node's split and, where the builder logged one, its SAH cost curve, for
/// lane `lane` (each lane's plot keeps its own zoom: two lanes step the same node ids).
pub fn split_view<V: Vector>(
    rec: &Recording<V>,
    kind: StructureKind,
    snap: &Snapshot<V>,
    lane: usize,
    ui: &mut egui::Ui,
) {
    let Some(node) = snap.current else {
        ui.label("The build has not started.");
        return;
    };
    match snap.split {
        Some(split) if split.node == node => {
            // The axis the plane's normal points along most.
            let axis = (0..V::DIM)
                .max_by(|&a, &b| {
                    split
                        .normal
                        .coord(a)
                        .abs()
                        .total_cmp(&split.normal.coord(b).abs())
                })
                .and_then(|i| ["x", "y", "z"].get(i).copied())
                .unwrap_or("x");
            ui.label(format!(
                "node {}: split at {axis} = {:.3}: {} primitives below, {} above{}",
                node.0,
                split.offset,
                split.left,
                split.right,
                split
                    .cost
                    .map_or(String::new(), |c| format!(", SAH cost {c:.2}"))
            ));
        }
        _ => {
            ui.label(format!("node {}: no split yet (or a leaf)", node.0));
        }
    }
    let Some(record) = rec.splits.iter().find(|r| r.node == node) else {
        if kind.is_bvh() {
            ui.label(
                "No cost curve: median splits have none (choose the binned SAH split for one).",
            );
        }
        return;
    };
    if record.bin_costs.is_empty() {
        ui.label(format!(
            "{}: no cost curve, median splits have none; only the SAH split weighs \
             candidate planes by cost (leaf cost here {:.0}).",
            method_name(record.method),
            record.leaf_cost
        ));
        return;
    }
    let axis = ["x", "y", "z"].get(record.axis).copied().unwrap_or("?");
    ui.label(format!(
        "SAH cost of each candidate plane along {axis} (leaf cost {:.0}){}",
        record.leaf_cost,
        if record.made_leaf {
            ": no split pays, the node stays a leaf"
        } else {
            ""
        }
    ));
    let curve: Vec<[f64; 2]> = record
        .planes
        .iter()
        .zip(&record.bin_costs)
        .filter(|(_, c)| c.is_finite())
        .map(|(p, c)| [f64::from(*p), f64::from(*c)])
        .collect();
    let chosen = record.chosen_bin.and_then(|i| {
        Some([
            f64::from(*record.planes.get(i)?),
            f64::from(*record.bin_costs.get(i)?),
        ])
    });
    Plot::new(("sah curve", lane, node.0))
        .height(150.0)
        .allow_scroll(false)
        .allow_drag(false)
        .x_axis_label(format!("plane position ({axis})"))
        .y_axis_label("cost")
        .show(ui, |plot| {
            plot.line(Line::new("cost", PlotPoints::from(curve.clone())).color(colors::QUERY));
            plot.points(Points::new("planes", PlotPoints::from(curve)).radius(2.0));
            plot.hline(HLine::new("leaf cost", f64::from(record.leaf_cost)).color(colors::PRUNED));
            if let Some(best) = chosen {
                plot.vline(VLine::new("chosen", best[0]).color(colors::ANSWER));
                plot.points(
                    Points::new("cheapest", PlotPoints::from(vec![best]))
                        .radius(5.0)
                        .color(colors::ANSWER),
                );
            }
        });
}

/// A BVH split method in the lecture's words.
fn method_name(method: SplitMethod) -> &'static str {
    match method {
        SplitMethod::SpatialMedian => "Spatial median (the middle of the longest axis)",
        SplitMethod::ObjectMedian => "Object median (half the primitives on each side)",
        SplitMethod::BinnedSah => "SAH (binned)",
    }
}
