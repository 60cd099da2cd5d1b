//! The 3D traversal-cost heat map's controls (shown, what a pixel counts, where it is
//! computed) and its legend.

use super::Panel;
use crate::lab3d::heat::{MOVING_GPU_EVERY, MOVING_PIXEL, Shown};
use crate::model::Action3d;
use crate::model::heat::{Device, Metric};
use crate::render3d::heatmap::legend;
use crate::ui_state::Cx;

/// The heat map panel.
pub struct Heat;

impl Panel for Heat {
    fn title(&self) -> &'static str {
        "Traversal-cost heat map"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        let settings = cx.lab.three().heat;
        let mut chosen = settings;
        ui.checkbox(&mut chosen.on, "show the heat map")
            .on_hover_text("each pixel: how much work its camera ray needed for the first hit");
        if chosen.on {
            ui.horizontal(|ui| {
                ui.radio_value(&mut chosen.metric, Metric::Nodes, "nodes visited");
                ui.radio_value(&mut chosen.metric, Metric::PrimitiveTests, "triangle tests");
            });
            ui.horizontal(|ui| {
                ui.label("computed on:");
                ui.radio_value(&mut chosen.device, Device::Auto, "GPU where it can");
                ui.radio_value(&mut chosen.device, Device::Cpu, "CPU");
            });
        }
        if chosen != settings {
            cx.act(Action3d::SetHeat(chosen));
        }
        if !settings.on {
            return;
        }
        let map = &cx.ui.view3d.heat;
        if let Some(e) = map.gpu_error() {
            ui.colored_label(crate::paint::colors::PRUNED, e);
        }
        match map.shown() {
            Shown::Gpu(max) => {
                ui.label("traced on the GPU (WGSL compute shader)");
                if let Some(top) = max {
                    legend(ui, top.max(1), map.metric());
                }
            }
            Shown::Cpu {
                fraction,
                size,
                max,
            } => {
                ui.label(format!(
                    "traced on the CPU: {:.0}% of {}×{} rays",
                    fraction * 100.0,
                    size[0],
                    size[1]
                ));
                legend(ui, max.max(1), map.metric());
            }
            Shown::Nothing => {}
        }
        if let Some(every) = map.moving_every() {
            let how = if matches!(map.shown(), Shown::Gpu(_)) {
                format!("traced on the GPU at most every {MOVING_GPU_EVERY} frames")
            } else {
                format!(
                    "the CPU traces one frame's tree whole, one ray per {MOVING_PIXEL}×{MOVING_PIXEL} pixels"
                )
            };
            ui.colored_label(
                crate::paint::colors::PRUNED,
                format!("The mesh moves: a new image every {every} frames ({how})."),
            );
        }
    }
}
