//! The mesh that moves (the twisting torus), in the mesh panel: the "Animate" switch, refit
//! or rebuild every frame, what the last update cost and the tree's SAH cost against the last
//! build's, with a plot of the SAH cost over the frames ([`crate::model::refit`]'s log).

use egui::{Color32, RichText, Sense, Stroke};

use crate::model::lab3d::Lab3d;
use crate::model::refit::{EditKind, EditLog, UpdateMode};
use crate::model::{Action3d, HalfAction};
use crate::paint::colors;
use crate::ui_state::Cx;

/// The plot's height, in points.
const PLOT_HEIGHT: f32 = 70.0;

/// The motion's section, when the mesh moves.
pub fn motion_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    if !lab.mesh.as_ref().is_some_and(crate::model::motion::moves) {
        return;
    }
    ui.separator();
    let motion = lab.motion;
    ui.horizontal(|ui| {
        let mut on = motion.on;
        if ui
            .checkbox(&mut on, "Animate")
            .on_hover_text("twist the torus a little more every frame")
            .changed()
        {
            cx.act(Action3d::Animate(on));
        }
        ui.label(
            RichText::new(format!(
                "t = {:.1} s, frame {}",
                motion.seconds, motion.frames
            ))
            .weak(),
        );
    });
    let lane = &lab.half.lane;
    ui.horizontal(|ui| {
        ui.label("every frame:");
        let mut mode = lane.update;
        for m in UpdateMode::ALL {
            ui.radio_value(&mut mode, m, m.label());
        }
        if mode != lane.update {
            cx.act(HalfAction::SetUpdateMode { lane: 0, mode });
        }
        if ui
            .button("Rebuild now")
            .on_hover_text("build the tree again for the mesh as it is now")
            .clicked()
        {
            cx.act(HalfAction::RebuildNow);
        }
    });
    if let Some(note) = &lane.refit_note {
        ui.colored_label(colors::PRUNED, note);
    }
    update_lines(lab, &lane.log, ui);
    sah_plot(ui, &lane.log);
}

/// The last update's time and SAH cost, and the cost's ratio to the last build's.
fn update_lines(lab: &Lab3d, log: &EditLog, ui: &mut egui::Ui) {
    let Some(last) = log.last() else { return };
    let how = match last.how {
        EditKind::Refit => "refit",
        EditKind::Rebuild => "rebuild",
    };
    ui.label(format!("last update: {how}, {:.2} ms", last.millis));
    for kind in [EditKind::Refit, EditKind::Rebuild] {
        if let Some(mean) = log.mean_millis(kind) {
            let name = if kind == EditKind::Refit {
                "refits"
            } else {
                "rebuilds"
            };
            ui.label(
                RichText::new(format!(
                    "{name}: {} of the last {}, {mean:.2} ms each on average",
                    log.count(kind),
                    log.len()
                ))
                .weak(),
            );
        }
    }
    let built = lab
        .half
        .lane
        .current(lab.revision())
        .and_then(|s| s.build_sah_cost);
    match (last.sah_cost, built) {
        (Some(now), Some(then)) if then > 0.0 => {
            let ratio = now / then;
            let color = if ratio > 1.5 {
                colors::CULLED
            } else if ratio > 1.1 {
                colors::PRUNED
            } else {
                colors::VISITED
            };
            ui.horizontal(|ui| {
                ui.label(format!("SAH cost {now:.1}:"));
                ui.colored_label(color, format!("×{ratio:.2} the last build's ({then:.1})"));
            });
        }
        (Some(now), _) => {
            ui.label(format!("SAH cost {now:.1}"));
        }
        (None, _) => {}
    }
}

/// The SAH cost after each update kept in `log`: a line, with a dot at each rebuild.
fn sah_plot(ui: &mut egui::Ui, log: &EditLog) {
    let costs: Vec<(f32, bool)> = log
        .entries()
        .filter_map(|e| e.sah_cost.map(|c| (c, e.how == EditKind::Rebuild)))
        .collect();
    if costs.len() < 2 {
        return;
    }
    let (lo, hi) = costs
        .iter()
        .fold((f32::INFINITY, 0.0f32), |(lo, hi), (c, _)| {
            (lo.min(*c), hi.max(*c))
        });
    // From a little under the lowest cost, so that the growth shows.
    let (lo, hi) = (lo * 0.95, hi.max(lo * 1.05));
    let width = ui.available_width().clamp(120.0, 320.0);
    let (response, painter) = ui.allocate_painter(egui::vec2(width, PLOT_HEIGHT), Sense::hover());
    let rect = response.rect;
    painter.rect_filled(rect, 2.0, Color32::from_gray(28));
    let n = crate::model::refit::EDIT_LOG_LEN.max(costs.len()) as f32;
    let at = |i: usize, c: f32| {
        egui::pos2(
            rect.left() + rect.width() * i as f32 / (n - 1.0),
            rect.bottom() - 4.0 - (rect.height() - 8.0) * (c - lo) / (hi - lo),
        )
    };
    let points: Vec<egui::Pos2> = costs
        .iter()
        .enumerate()
        .map(|(i, (c, _))| at(i, *c))
        .collect();
    painter.add(egui::Shape::line(points, Stroke::new(1.5, colors::QUERY)));
    for (i, (c, rebuilt)) in costs.iter().enumerate() {
        if *rebuilt {
            painter.circle_filled(at(i, *c), 2.5, colors::SELECTED);
        }
    }
    response.on_hover_text(format!(
        "SAH cost after each of the last {} updates (yellow dots: rebuilds), from {lo:.0} to {hi:.0}",
        costs.len()
    ));
    ui.label(
        RichText::new(format!(
            "SAH cost over the last {} frames (dots: rebuilds)",
            costs.len()
        ))
        .weak(),
    );
}
