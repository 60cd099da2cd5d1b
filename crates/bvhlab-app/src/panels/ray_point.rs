//! The 3D ray and query point: what a click does, their exact coordinates, k and the
//! radius, and the answer with what it cost beside brute force.

use bvhlab::Ray3;
use egui::RichText;

use super::{Panel, coords_editor};
use crate::model::dimension::thousands;
use crate::model::lab3d::Lab3d;
use crate::model::mesh::Mesh3d;
use crate::model::recording::Answer;
use crate::model::tools::Tool3d;
use crate::model::{Action, Action3d, HalfAction};
use crate::paint::colors;
use crate::pseudocode::Task;
use crate::ui_state::Cx;

/// The ray-and-point panel.
pub struct RayPoint;

impl Panel for RayPoint {
    fn title(&self) -> &'static str {
        "Ray and point"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        query_section(cx, ui);
    }
}

fn query_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    ui.horizontal(|ui| {
        ui.label("A click:");
        let mut tool = lab.tool;
        let ray = ui
            .radio_value(&mut tool, Tool3d::Ray, "casts a ray")
            .clicked();
        let point = ui
            .radio_value(&mut tool, Tool3d::Point, "places the point")
            .clicked();
        if ray || point {
            cx.act(Action3d::SetTool(tool));
        }
    });
    ui.label(
        RichText::new("Drag to orbit, shift-drag to pan, scroll to zoom. Drag the gizmo's dots to move the ray or point; its coloured arrows move it along x, y or z.")
            .weak(),
    );
    if let Some(ray) = lab.ray {
        let mut origin = ray.origin();
        let mut dir = ray.dir();
        let a = coords_editor(ui, "origin", origin.as_mut());
        let b = coords_editor(ui, "direction", dir.as_mut());
        if a || b {
            cx.act(match Ray3::new(origin, dir) {
                Ok(r) => Action3d::SetRay(Some(r)).into(),
                Err(e) => Action::SetMessage(Some(format!("That ray cannot be cast: {e}."))),
            });
        }
    }
    if let Some(mut p) = lab.point
        && coords_editor(ui, "point", p.as_mut())
    {
        cx.act(Action3d::SetPoint(Some(p)));
    }
    let half = &lab.half;
    if half.task == Task::Nearest {
        let mut k = half.k;
        if ui
            .add(egui::Slider::new(&mut k, 1..=16).text("k nearest"))
            .changed()
        {
            cx.act(HalfAction::SetK(k));
        }
    }
    if half.task == Task::Range {
        let size = lab.mesh.as_ref().map_or(1.0, Mesh3d::size);
        let mut radius = half.radius;
        if ui
            .add(
                egui::Slider::new(&mut radius, 0.0..=size)
                    .logarithmic(true)
                    .text("radius"),
            )
            .changed()
        {
            cx.act(HalfAction::SetRadius(radius));
        }
    }
    answer(lab, ui);
}

/// The answer and what it cost, against brute force.
fn answer(lab: &Lab3d, ui: &mut egui::Ui) {
    let rec = match &lab.half.lane.recording {
        Some(Ok(rec)) => rec,
        Some(Err(why)) => {
            ui.colored_label(colors::PRUNED, why);
            return;
        }
        None => return,
    };
    match &rec.answer {
        Answer::Hit(Some(hit)) => {
            let ray = rec.question.ray;
            ui.label(format!(
                "first hit: triangle {} at t = {:.4}",
                hit.prim, hit.t
            ));
            if let (Some(ray), Some(tri)) = (ray, lab.triangle(hit.prim as u32)) {
                let p = ray.at(hit.t);
                let n = bvhlab::Primitive::normal(&tri).normalize_or_zero();
                ui.label(format!("point ({:.3}, {:.3}, {:.3})", p.x, p.y, p.z));
                ui.label(format!("normal ({:.3}, {:.3}, {:.3})", n.x, n.y, n.z));
            }
        }
        Answer::Hit(None) => {
            ui.label("the ray misses the mesh");
        }
        Answer::Nearest(list) => {
            for n in list.iter().take(4) {
                ui.label(format!(
                    "triangle {} at distance {:.4}, closest point ({:.3}, {:.3}, {:.3})",
                    n.prim, n.distance, n.point.x, n.point.y, n.point.z
                ));
            }
        }
        Answer::Hits(hits) => {
            ui.label(format!("{} hits along the ray", hits.len()));
        }
        Answer::Indices(list) => {
            ui.label(format!("{} triangles within the radius", list.len()));
        }
        Answer::Nodes(n) => {
            ui.label(format!("the build makes {} nodes", thousands(*n)));
        }
    }
    let agree = rec.agrees();
    ui.colored_label(
        if agree {
            colors::VISITED
        } else {
            colors::CULLED
        },
        if agree {
            "same answer as brute force"
        } else {
            "DIFFERS from brute force"
        },
    );
    if rec.question.task != Task::Build {
        let kind = lab.half.lane.settings.kind;
        ui.label(format!(
            "{} {}, {} {}, {} triangle tests (brute force: {} triangle tests)",
            rec.cost.nodes_visited,
            kind.nodes_name(),
            rec.cost.bound_tests,
            kind.bound_tests_name(),
            rec.cost.prim_tests,
            rec.brute_cost.prim_tests
        ));
    }
}
