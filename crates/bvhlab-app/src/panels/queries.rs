//! The 2D queries: clearing the ray and the point, k, and each answer with what it cost
//! beside brute force.

use egui::{Grid, RichText};

use super::{Panel, coords_editor, legend};
use crate::model::lab2d::Lab2d;
use crate::model::outcome::NodeMark;
use crate::model::structures::StructureKind;
use crate::model::{Action2d, HalfAction};
use crate::paint::colors;
use crate::ui_state::Cx;

/// The queries panel.
pub struct Queries;

impl Panel for Queries {
    fn title(&self) -> &'static str {
        "Queries"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        query_section(cx, ui);
    }
}

fn query_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    ui.horizontal(|ui| {
        if ui.button("Clear ray").clicked() {
            cx.act(Action2d::SetRay(None));
        }
        if ui.button("Clear point").clicked() {
            cx.act(Action2d::SetPoint(None));
        }
        let mut k = lab.half.k;
        if ui
            .add(egui::Slider::new(&mut k, 1..=8).text("k nearest"))
            .changed()
        {
            cx.act(HalfAction::SetK(k));
        }
    });
    coordinates(cx, ui);
    ray_answer(lab, ui);
    point_answer(lab, ui);
    let lane = &lab.half.lane;
    if lane.ray_outcome.is_none() && lane.point_outcome.is_none() {
        ui.label("Use the Ray tool or the Query point tool on the canvas.");
        return;
    }
    ui.label(format!(
        "Stepping through: {} (right panel).",
        super::step_through::task_label(lab.half.task)
    ));
    if let Some(marks) = lane.marks() {
        ui.horizontal_wrapped(|ui| {
            legend(
                ui,
                colors::VISITED,
                format!("visited {}", marks.count(NodeMark::Visited)),
            );
            legend(
                ui,
                colors::CULLED,
                format!(
                    "culled {} ({} missed)",
                    marks.count(NodeMark::Culled),
                    if lane.settings.kind.is_bvh() {
                        "bounding volume"
                    } else {
                        "cell"
                    }
                ),
            );
            legend(
                ui,
                colors::PRUNED,
                format!("pruned {}", marks.count(NodeMark::Pruned)),
            );
            legend(
                ui,
                colors::TESTED,
                format!("primitives tested {}", marks.tested.len()),
            );
            if marks.mailbox_skips > 0 {
                ui.label(format!("mailbox skips {}", marks.mailbox_skips));
            }
        });
    }
}

/// The answer's cost beside brute force's, and whether they agree; the rows are named as
/// `kind` counts (nodes or cells, BV, cell or plane tests).
pub fn counters(
    ui: &mut egui::Ui,
    id: &str,
    kind: StructureKind,
    cost: bvhlab::QueryCost,
    brute: bvhlab::QueryCost,
    agrees: bool,
) {
    Grid::new(("counters", id)).striped(true).show(ui, |ui| {
        ui.strong("");
        ui.strong("structure");
        ui.strong("brute force");
        ui.end_row();
        for (name, a, b) in [
            (kind.nodes_name(), cost.nodes_visited, brute.nodes_visited),
            (kind.bound_tests_name(), cost.bound_tests, brute.bound_tests),
            ("primitive tests", cost.prim_tests, brute.prim_tests),
        ] {
            ui.label(name);
            ui.label(a.to_string());
            ui.label(b.to_string());
            ui.end_row();
        }
    });
    if agrees {
        ui.label(RichText::new("Same answer as brute force.").color(colors::VISITED));
    } else {
        ui.label(
            RichText::new("Differs from brute force: please report this scene.")
                .color(colors::CULLED),
        );
    }
}

/// The ray's handles and the point, to type exactly (as the 3D panel takes them).
fn coordinates(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    if let Some(mut ray) = lab.ray {
        let e = coords_editor(ui, "ray e", ray.origin.as_mut());
        let s = coords_editor(ui, "ray s", ray.target.as_mut());
        if e || s {
            cx.act(Action2d::SetRay(Some(ray)));
        }
    }
    if let Some(mut p) = lab.point
        && coords_editor(ui, "point q", p.as_mut())
    {
        cx.act(Action2d::SetPoint(Some(p)));
    }
}

fn ray_answer(lab: &Lab2d, ui: &mut egui::Ui) {
    if let Some(Err(e)) = lab.ray.map(|r| r.ray()) {
        // e and s coincide (a drag that ended where it began): say why nothing is answered.
        ui.label(format!("No ray: {e}. Drag s away from e."));
    }
    if let Some(o) = &lab.half.lane.ray_outcome {
        let e = o.ray.origin();
        let d = o.ray.dir();
        ui.label(format!(
            "Ray e = ({:.2}, {:.2}), d = ({:.3}, {:.3})",
            e.x, e.y, d.x, d.y
        ));
        match o.hit {
            Some(h) => {
                let p = o.ray.at(h.t);
                let shape = lab.prims().owner.get(h.prim).copied();
                ui.label(
                    RichText::new(format!(
                        "Hit: primitive {} (shape {}) at t = {:.4}, point ({:.3}, {:.3})",
                        h.prim,
                        shape.map_or("?".to_owned(), |s| s.to_string()),
                        h.t,
                        p.x,
                        p.y
                    ))
                    .color(colors::ANSWER),
                );
            }
            None => {
                ui.label("Miss: the ray hits nothing.");
            }
        }
        let kind = lab.half.lane.settings.kind;
        counters(ui, "ray", kind, o.cost, o.brute_cost, o.agrees());
    }
}

fn point_answer(lab: &Lab2d, ui: &mut egui::Ui) {
    if let Some(o) = &lab.half.lane.point_outcome {
        ui.label(format!(
            "Query point q = ({:.2}, {:.2})",
            o.point.x, o.point.y
        ));
        for (rank, n) in o.nearest.iter().enumerate() {
            ui.label(
                RichText::new(format!(
                    "#{}: primitive {} at distance {:.4}, closest point ({:.3}, {:.3})",
                    rank + 1,
                    n.prim,
                    n.distance,
                    n.point.x,
                    n.point.y
                ))
                .color(colors::ANSWER),
            );
        }
        if o.nearest.is_empty() {
            ui.label("No primitives: nothing is nearest.");
        }
        let kind = lab.half.lane.settings.kind;
        counters(ui, "point", kind, o.cost, o.brute_cost, o.agrees());
    }
}
