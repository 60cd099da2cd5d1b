//! Lecture §3, the structure: which one, its build options, how it is drawn, and what it
//! came out as (nodes, depth, references, SAH cost, memory, build time, leaf sizes). The
//! picker is the same in both halves.

use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SphereFit;
use egui::Grid;

use super::Panel;
use crate::model::dimension::thousands;
use crate::model::structures::{BuildSettings, KdSplit, StructureKind};
use crate::model::{Action2d, Action3d, HalfAction};
use crate::ui_state::Cx;

/// The 2D structure panel.
pub struct Structure2d;

impl Panel for Structure2d {
    fn title(&self) -> &'static str {
        "§3 Spatial structure"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        let lab = cx.lab.two();
        let mut settings = lab.half.lane.settings;
        settings_editor(&mut settings, 2, ui);
        if settings != lab.half.lane.settings {
            cx.act(HalfAction::SetStructure(settings));
        }
        structure_display(cx, ui);
        super::refit::update_section(cx, &lab.half, lab.scene.revision(), "shapes", ui);
    }
}

/// The 3D structure panel.
pub struct Structure3d;

impl Panel for Structure3d {
    fn title(&self) -> &'static str {
        "Structure"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        structure_section(cx, ui);
    }
}

/// The structure picker and its build options, for a scene in `dim` dimensions.
pub fn settings_editor(s: &mut BuildSettings, dim: usize, ui: &mut egui::Ui) {
    egui::ComboBox::from_label("Structure")
        .selected_text(s.kind.label_in(dim))
        .show_ui(ui, |ui| {
            for kind in StructureKind::ALL {
                ui.selectable_value(&mut s.kind, kind, kind.label_in(dim));
            }
        });
    if s.kind.is_bvh() {
        ui.horizontal_wrapped(|ui| {
            ui.label("Split:");
            ui.radio_value(
                &mut s.bvh_split,
                SplitMethod::SpatialMedian,
                "longest axis, middle (lecture)",
            );
            ui.radio_value(&mut s.bvh_split, SplitMethod::ObjectMedian, "object median");
            ui.radio_value(&mut s.bvh_split, SplitMethod::BinnedSah, "SAH");
        });
        if s.kind == StructureKind::SphereTree {
            ui.horizontal(|ui| {
                ui.label("Node spheres:");
                ui.radio_value(&mut s.sphere_fit, SphereFit::Ritter, "Ritter");
                ui.radio_value(&mut s.sphere_fit, SphereFit::Welzl, "Welzl");
            });
        }
    }
    if s.kind == StructureKind::KdTree {
        ui.horizontal_wrapped(|ui| {
            ui.label("Planes:");
            ui.radio_value(
                &mut s.kd_split,
                KdSplit::MedianRoundRobin,
                if dim == 3 {
                    "median, x/y/z in turn"
                } else {
                    "median, x/y in turn"
                },
            );
            ui.radio_value(
                &mut s.kd_split,
                KdSplit::MedianLongest,
                "median, longest axis",
            );
            ui.radio_value(&mut s.kd_split, KdSplit::Sah, "SAH");
        });
    }
    if s.kind == StructureKind::Grid {
        ui.add(egui::Slider::new(&mut s.grid_cells, 0..=128).text("cells per axis (0: automatic)"));
    } else if s.kind != StructureKind::BruteForce
        && !(s.kind == StructureKind::KdTree && s.kd_split == KdSplit::Sah)
    {
        ui.add(egui::Slider::new(&mut s.leaf_size, 1..=16).text("leaf size"));
    }
    if s.kind == StructureKind::Quadtree {
        ui.add(egui::Slider::new(&mut s.quadtree_depth, 1..=14).text("max depth"));
    }
}

/// Brute force, which has no tree: no nodes to draw or colour, no depth, no leaves to count
/// (the core's one "leaf" of every primitive is its list, not a node).
fn brute_force_display(
    cx: &mut Cx<'_>,
    built: &crate::model::build_job::Structure<bvhlab::Segment2>,
    ui: &mut egui::Ui,
) {
    let lab = cx.lab.two();
    let mut d = lab.display;
    ui.checkbox(&mut d.query_marks, "mark query steps");
    if d != lab.display {
        cx.act(Action2d::SetDisplay(d));
    }
    let stats = &built.stats;
    ui.label(super::tree::brute_force_words(stats.primitives, "segments"));
    Grid::new("stats").striped(true).show(ui, |ui| {
        ui.label("memory");
        ui.label(format!("{:.1} KiB", stats.memory_bytes as f64 / 1024.0));
        ui.end_row();
        ui.label("build time");
        ui.label(format!("{:.2} ms", built.build_ms));
        ui.end_row();
    });
}

fn structure_display(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    let Some(built) = lab.half.lane.current(lab.scene.revision()) else {
        return;
    };
    if built.settings.kind == StructureKind::BruteForce {
        brute_force_display(cx, built, ui);
        return;
    }
    let stats = &built.stats;
    let mut d = lab.display;
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut d.structure, "draw nodes");
        ui.checkbox(&mut d.leaf_colours, "colour by leaf");
        ui.checkbox(&mut d.query_marks, "mark query steps");
    });
    let deepest = stats.max_depth as u32;
    let mut depth = d.max_depth.min(deepest);
    if ui
        .add(egui::Slider::new(&mut depth, 0..=deepest).text("show depth ≤"))
        .changed()
    {
        d.max_depth = if depth == deepest { 64 } else { depth };
    }
    if d != lab.display {
        cx.act(Action2d::SetDisplay(d));
    }
    Grid::new("stats").striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("nodes (cells)", stats.nodes.to_string());
        row("leaves", stats.leaves.to_string());
        row("depth", stats.max_depth.to_string());
        row(
            "references",
            format!(
                "{} ({} duplicated)",
                stats.references,
                stats.duplicated_references()
            ),
        );
        row(
            "SAH cost",
            stats.sah_cost.map_or("–".to_owned(), |c| format!("{c:.2}")),
        );
        row(
            "memory",
            format!("{:.1} KiB", stats.memory_bytes as f64 / 1024.0),
        );
        row("build time", format!("{:.2} ms", built.build_ms));
    });
    if stats.leaf_sizes.len() > 1 {
        let bars: Vec<egui_plot::Bar> = stats
            .leaf_sizes
            .iter()
            .enumerate()
            .map(|(size, &count)| egui_plot::Bar::new(size as f64, count as f64).width(0.8))
            .collect();
        ui.label("Leaves by number of primitives:");
        let shown = egui_plot::Plot::new("leaf_sizes")
            .height(90.0)
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.bar_chart(egui_plot::BarChart::new("leaves", bars));
            });
        let counts: Vec<String> = stats
            .leaf_sizes
            .iter()
            .enumerate()
            .filter(|(_, count)| **count > 0)
            .map(|(size, count)| {
                if size == bvhlab::structure::Stats::LEAF_SIZE_LAST {
                    format!("{count} with {size} or more")
                } else {
                    format!("{count} with {size}")
                }
            })
            .collect();
        crate::a11y::describe::figure(
            ui.ctx(),
            shown.response.id,
            "Leaves by number of primitives",
            format!("Leaves: {}.", counts.join(", ")),
        );
    }
}

fn structure_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    let mut settings = lab.half.lane.settings;
    settings_editor(&mut settings, 3, ui);
    if settings != lab.half.lane.settings {
        cx.act(HalfAction::SetStructure(settings));
    }
    let lane = &lab.half.lane;
    if let Some(job) = &lane.job {
        ui.add(
            egui::ProgressBar::new(job.fraction())
                .show_percentage()
                .text(format!("building the {}…", job.settings.kind.label_in(3))),
        );
    } else if let Some(built) = lane
        .structure
        .as_ref()
        .filter(|b| b.settings.kind == StructureKind::BruteForce)
    {
        ui.label(super::tree::brute_force_words(
            built.stats.primitives,
            "triangles",
        ));
    } else if let Some(built) = &lane.structure {
        let s = &built.stats;
        ui.label(format!(
            "built in {:.0} ms{}: {} nodes, depth {}{}",
            built.build_ms,
            if built.frames > 1 {
                format!(" over {} frames", built.frames)
            } else {
                String::new()
            },
            thousands(s.nodes),
            s.max_depth,
            s.sah_cost
                .map_or(String::new(), |c| format!(", SAH cost {c:.1}")),
        ));
        ui.label(format!(
            "{:.1} bytes per triangle",
            s.memory_bytes as f64 / s.primitives.max(1) as f64
        ));
        let mut d = lab.display;
        ui.checkbox(&mut d.structure, "show the structure");
        let deepest = s.max_depth as u32;
        ui.add(egui::Slider::new(&mut d.depth, 0..=deepest.max(1)).text("level"));
        ui.checkbox(&mut d.marks, "colour visited, culled and pruned nodes");
        ui.checkbox(&mut d.xray, "x-ray mesh (see volumes inside)");
        if d != lab.display {
            cx.act(Action3d::SetDisplay(d));
        }
    }
}
