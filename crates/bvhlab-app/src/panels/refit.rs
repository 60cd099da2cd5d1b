//! Refit against rebuild, in the structure panel: what a lane does when the primitives move,
//! the SAH cost now against the last build's, a small plot of the cost over the edits
//! (refits and rebuilds marked apart), the last update's time, and "Rebuild now". The same
//! section serves both halves ([`update_section`] over a [`Half`]).

use std::fmt::Write as _;

use egui_plot::{AxisHints, Line, MarkerShape, Plot, PlotPoints, Points};

use crate::model::HalfAction;
use crate::model::dimension::LabPrimitive;
use crate::model::half::Half;
use crate::model::lane::Lane;
use crate::model::refit::{EditKind, EditLog, UpdateMode, refit_refused};
use crate::paint::colors;
use crate::ui_state::Cx;

/// How the lanes' points are coloured in the plot: the structure's, then the comparison's.
const LANE_COLOURS: [egui::Color32; 2] = [colors::QUERY, colors::PRUNED];

/// The section for `half` (the half shown), whose primitives are called `what` ("shapes").
pub fn update_section<P: LabPrimitive>(
    cx: &mut Cx<'_>,
    half: &Half<P>,
    revision: u64,
    what: &str,
    ui: &mut egui::Ui,
) {
    ui.separator();
    let two = half.compare.is_some();
    for index in 0..half.lane_count() {
        let lane = half.lane_at(index);
        let name = two.then(|| half.lane_name(index));
        mode_row(cx, lane, index, name.as_deref(), what, ui);
        lane_summary(lane, revision, ui);
    }
    let any_refit = half
        .lanes()
        .any(|l| l.update == UpdateMode::Refit && l.settings.kind.is_bvh());
    if half.lanes().any(|l| !l.log.is_empty()) {
        cost_plot(half, ui);
    }
    if any_refit
        && ui
            .button("Rebuild now")
            .on_hover_text("Build the tree again for where the primitives are now")
            .clicked()
    {
        cx.act(HalfAction::RebuildNow);
    }
}

/// "When shapes move: ( ) rebuild ( ) refit" for lane `index`, or why it only rebuilds.
fn mode_row<P: LabPrimitive>(
    cx: &mut Cx<'_>,
    lane: &Lane<P>,
    index: usize,
    name: Option<&str>,
    what: &str,
    ui: &mut egui::Ui,
) {
    if let Some(name) = name {
        ui.label(egui::RichText::new(name).color(LANE_COLOURS[index.min(1)]));
    }
    match refit_refused(lane.settings.kind) {
        None => {
            ui.horizontal_wrapped(|ui| {
                ui.label(format!("When {what} move:"));
                let mut mode = lane.update;
                for m in UpdateMode::ALL {
                    ui.radio_value(&mut mode, m, m.label());
                }
                if mode != lane.update {
                    cx.act(HalfAction::SetUpdateMode { lane: index, mode });
                }
            });
        }
        Some(why) => {
            ui.label(format!("When {what} move, it is rebuilt: {why}."));
        }
    }
}

/// The SAH cost against the last build's, the last update's time, and why the last update
/// in refit mode was a rebuild.
fn lane_summary<P: LabPrimitive>(lane: &Lane<P>, revision: u64, ui: &mut egui::Ui) {
    let Some(built) = lane.current(revision) else {
        return;
    };
    if let Some(cost) = built.stats.sah_cost {
        let ratio = built.build_sah_cost.map(|b| cost / b);
        let text = match ratio {
            Some(r) if built.refits > 0 => {
                format!(
                    "SAH cost {cost:.1}, {r:.2}x the last build's ({} refits since)",
                    built.refits
                )
            }
            _ => format!("SAH cost {cost:.1}, as built"),
        };
        ui.label(text);
    }
    if let Some(last) = lane.log.last() {
        ui.label(last_update(last.how, last.millis, &lane.log));
    }
    if lane.update == UpdateMode::Refit
        && let Some(note) = &lane.refit_note
        && lane.settings.kind.is_bvh()
    {
        ui.label(format!("Rebuilt instead of refitted: {note}."));
    }
}

/// "Last update: refit, 0.01 ms (refits average 0.01 ms, builds 0.20 ms)".
fn last_update(how: EditKind, millis: f64, log: &EditLog) -> String {
    let word = match how {
        EditKind::Refit => "refit",
        EditKind::Rebuild => "rebuild",
    };
    let mut text = format!("Last update: {word}, {}", millis_text(millis));
    let means: Vec<String> = [(EditKind::Refit, "refits"), (EditKind::Rebuild, "builds")]
        .into_iter()
        .filter_map(|(k, name)| {
            let n = log.count(k);
            log.mean_millis(k)
                .map(|m| format!("{n} {name} average {}", millis_text(m)))
        })
        .collect();
    if !means.is_empty() {
        let _ = write!(text, " ({})", means.join(", "));
    }
    text
}

/// Milliseconds with the digits that matter (a refit of a small scene takes microseconds).
pub fn millis_text(ms: f64) -> String {
    if ms >= 10.0 {
        format!("{ms:.0} ms")
    } else if ms >= 1.0 {
        format!("{ms:.1} ms")
    } else if ms >= 0.1 {
        format!("{ms:.2} ms")
    } else {
        format!("{ms:.3} ms")
    }
}

/// The SAH cost after each update of each lane: a line per lane, refits as small circles,
/// rebuilds as large diamonds.
fn cost_plot<P: LabPrimitive>(half: &Half<P>, ui: &mut egui::Ui) {
    ui.label("SAH cost over the edits (dots: refits; diamonds: rebuilds):");
    let shown = Plot::new("refit cost")
        .height(110.0)
        .allow_scroll(false)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_boxed_zoom(false)
        .include_y(0.0)
        .show_x(false)
        .custom_x_axes(vec![AxisHints::new_x().label("edit")])
        .custom_y_axes(vec![AxisHints::new_y().label("SAH")])
        .show(ui, |plot| {
            for (index, lane) in half.lanes().enumerate() {
                let colour = LANE_COLOURS[index.min(1)];
                let first = lane.log.total() - lane.log.len() as u64;
                let at = |i: usize, cost: f32| [(first + i as u64) as f64, f64::from(cost)];
                let points = |how: EditKind| -> Vec<[f64; 2]> {
                    lane.log
                        .entries()
                        .enumerate()
                        .filter(|(_, e)| e.how == how)
                        .filter_map(|(i, e)| Some(at(i, e.sah_cost?)))
                        .collect()
                };
                let line: Vec<[f64; 2]> = lane
                    .log
                    .entries()
                    .enumerate()
                    .filter_map(|(i, e)| Some(at(i, e.sah_cost?)))
                    .collect();
                let id = |s: &str| format!("{s} {index}");
                plot.line(Line::new(id("cost"), PlotPoints::from(line)).color(colour));
                plot.points(
                    Points::new(id("refits"), PlotPoints::from(points(EditKind::Refit)))
                        .shape(MarkerShape::Circle)
                        .radius(2.0)
                        .color(colour),
                );
                plot.points(
                    Points::new(id("rebuilds"), PlotPoints::from(points(EditKind::Rebuild)))
                        .shape(MarkerShape::Diamond)
                        .radius(4.5)
                        .filled(true)
                        .color(colors::ANSWER),
                );
            }
        });
    let lanes: Vec<String> = half
        .lanes()
        .enumerate()
        .map(|(index, lane)| {
            let costs: Vec<String> = lane
                .log
                .entries()
                .filter_map(|e| {
                    let how = match e.how {
                        EditKind::Refit => "refit",
                        EditKind::Rebuild => "rebuild",
                    };
                    Some(format!("{how} {:.2}", e.sah_cost?))
                })
                .collect();
            format!("{}: {}", half.lane_name(index), costs.join(", "))
        })
        .collect();
    crate::a11y::describe::figure(
        ui.ctx(),
        shown.response.id,
        "SAH cost over the edits",
        format!(
            "The SAH cost after each edit, oldest first. {}.",
            lanes.join(". ")
        ),
    );
}
