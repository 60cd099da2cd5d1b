//! A build's current decision in the "Step through" panel: the node, its split plane and the
//! two groups, and for a binned-SAH BVH the cost of every candidate plane as a plot with the
//! cheapest marked (`MacDonald` and Booth 1990; Wald 2007).

use std::ops::RangeInclusive;

use egui_plot::{AxisHints, GridInput, GridMark, HLine, Line, Plot, PlotPoints, Points, VLine};

use bvhlab::Vector;
use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SplitRecord;

use crate::model::recording::Recording;
use crate::model::snapshot::Snapshot;
use crate::model::structures::StructureKind;
use crate::paint::colors;

/// The current node's split and, where the builder logged one, its SAH cost curve (the plot
/// is lane `index`'s, one for every node).
pub fn split_view<V: Vector>(
    rec: &Recording<V>,
    kind: StructureKind,
    snap: &Snapshot<V>,
    index: usize,
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
    cost_plot(record, axis, index, ui);
}

/// The SAH cost of each candidate plane of `record`'s node along `axis`, the leaf cost, and
/// the cheapest plane, as lane `index`'s plot.
fn cost_plot(record: &SplitRecord, axis: &str, index: usize, ui: &mut egui::Ui) {
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
    let leaf = f64::from(record.leaf_cost);
    let top = curve.iter().map(|p| p[1]).fold(leaf, f64::max);
    // Room for the widest cost label and the axis name beside it from the first frame (the
    // plot otherwise learns its axis width a frame late, and a new node's first frame drew
    // "cost" over the numbers).
    let body = egui::TextStyle::Body.resolve(ui.style());
    let widest = ui.fonts_mut(|f| {
        f.layout_no_wrap(
            format!("{:.0}", top * 1.2),
            body.clone(),
            egui::Color32::WHITE,
        )
        .size()
    });
    let y_axis_width = widest.x + 8.0 + widest.y * 1.25 + 4.0;
    let described = describe_curve(&curve, leaf, chosen, axis);
    let shown = Plot::new(("sah curve", index))
        .height(170.0)
        .allow_scroll(false)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_boxed_zoom(false)
        .include_y(0.0)
        // Room inside the frame for the outermost points and their tick labels.
        .set_margin_fraction(egui::vec2(0.08, 0.12))
        // About five round ticks on each axis, every one labelled at full strength.
        .x_grid_spacer(round_ticks)
        .y_grid_spacer(round_ticks)
        .custom_x_axes(vec![
            AxisHints::new_x()
                .label(format!("plane position ({axis})"))
                .formatter(tick_label)
                .label_spacing(30.0..=40.0),
        ])
        .custom_y_axes(vec![
            AxisHints::new_y()
                .label("SAH cost")
                .formatter(tick_label)
                .min_thickness(y_axis_width)
                .label_spacing(16.0..=20.0),
        ])
        .show(ui, |plot| {
            plot.line(Line::new("cost", PlotPoints::from(curve.clone())).color(colors::QUERY));
            plot.points(Points::new("planes", PlotPoints::from(curve)).radius(2.0));
            plot.hline(HLine::new("leaf cost", leaf).color(colors::PRUNED));
            if let Some(best) = chosen {
                plot.vline(VLine::new("chosen", best[0]).color(colors::ANSWER));
                plot.points(
                    Points::new("cheapest", PlotPoints::from(vec![best]))
                        .radius(5.0)
                        .color(colors::ANSWER),
                );
            }
        });
    crate::a11y::describe::figure(
        ui.ctx(),
        shown.response.id,
        "The SAH cost of each candidate plane",
        described,
    );
}

/// The SAH curve in words: the planes tried, the cheapest and the leaf's cost.
fn describe_curve(curve: &[[f64; 2]], leaf: f64, chosen: Option<[f64; 2]>, axis: &str) -> String {
    use std::fmt::Write as _;
    let mut text = format!(
        "{} planes tried along {axis}; keeping a leaf costs {leaf:.1}.",
        curve.len()
    );
    if let Some([at, cost]) = chosen {
        let _ = write!(text, " The cheapest plane, at {at:.2}, costs {cost:.1}.");
    }
    let costs: Vec<String> = curve
        .iter()
        .map(|[x, c]| format!("{x:.2}: {c:.1}"))
        .collect();
    let _ = write!(text, " Position: cost, for each: {}.", costs.join("; "));
    text
}

/// A BVH split method in the lecture's words.
fn method_name(method: SplitMethod) -> &'static str {
    match method {
        SplitMethod::SpatialMedian => "Spatial median (the middle of the longest axis)",
        SplitMethod::ObjectMedian => "Object median (half the primitives on each side)",
        SplitMethod::BinnedSah => "SAH (binned)",
    }
}

/// About five ticks across the shown range, 1, 2 or 5 times a power of ten apart.
#[expect(
    clippy::needless_pass_by_value,
    reason = "egui_plot's grid spacers take their input by value"
)]
fn round_ticks(input: GridInput) -> Vec<GridMark> {
    let (lo, hi) = input.bounds;
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return Vec::new();
    }
    let rough = span / 5.0;
    let power = 10f64.powf(rough.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .find(|s| *s >= rough)
        .unwrap_or(10.0 * power);
    let (first, last) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    (first..=last)
        .map(|i| GridMark {
            value: i as f64 * step,
            step_size: step,
        })
        .collect()
}

/// A tick's label: as many decimals as the ticks' spacing needs, none for whole numbers,
/// and no "-0".
fn tick_label(mark: GridMark, _range: &RangeInclusive<f64>) -> String {
    let decimals = (-mark.step_size.log10()).ceil().clamp(0.0, 6.0) as usize;
    let text = format!("{:.*}", decimals, mark.value);
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0".to_owned()
    } else {
        text
    }
}
