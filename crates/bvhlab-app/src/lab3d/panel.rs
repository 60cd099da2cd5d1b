//! The 3D controls (the mesh, the structure, what is drawn, the ray and the point, the
//! answer), the status line, and the view itself.

use bvhlab::Ray3;
use bvhlab::glam::Vec3;
use egui::{CollapsingHeader, RichText};

use super::Tool3d;
use super::build::thousands;
use super::mesh::MeshSource;
use crate::app::LabApp;
use crate::paint::colors;
use crate::pseudocode::Task;
use crate::recording::Answer;

/// The file types the mesh dialog offers.
pub const MESH_FILE_TYPES: &str = ".obj,.ply,.stl,.gltf,.glb";

/// Whether a file name looks like a mesh the lab reads.
pub fn is_mesh_file(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    [".obj", ".ply", ".stl", ".gltf", ".glb"]
        .iter()
        .any(|ext| lower.ends_with(ext))
}

/// The left panel in 3D.
pub fn controls(app: &mut LabApp, ui: &mut egui::Ui) {
    CollapsingHeader::new("Mesh")
        .default_open(true)
        .show(ui, |ui| mesh_section(app, ui));
    CollapsingHeader::new("Structure")
        .default_open(true)
        .show(ui, |ui| structure_section(app, ui));
    CollapsingHeader::new("Ray and point")
        .default_open(true)
        .show(ui, |ui| query_section(app, ui));
    CollapsingHeader::new("Traversal-cost heat map")
        .default_open(true)
        .show(ui, |ui| super::heat::section(app, ui));
}

fn mesh_section(app: &mut LabApp, ui: &mut egui::Ui) {
    let lab = &mut app.lab3d;
    let current = lab
        .mesh
        .as_ref()
        .map_or_else(|| "loading…".to_owned(), |m| m.name.clone());
    egui::ComboBox::from_label("built-in")
        .selected_text(&current)
        .show_ui(ui, |ui| {
            for b in bvhlab_meshio::builtin::list() {
                if ui
                    .selectable_label(current == b.name, b.name)
                    .on_hover_text(b.about)
                    .clicked()
                {
                    lab.open(MeshSource::Builtin(b.slug.to_owned()));
                }
            }
        });
    if ui
        .button("Open mesh file…")
        .on_hover_text("OBJ, PLY, STL, glTF or GLB; or drop the file on the page")
        .clicked()
    {
        open_mesh_dialog(app, ui.ctx());
    }
    let lab = &app.lab3d;
    if let Some(m) = &lab.mesh {
        ui.label(format!(
            "{} triangles, {} vertices{}",
            thousands(m.stats.triangles),
            thousands(m.stats.vertices),
            if m.stats.degenerate_triangles > 0 {
                format!(", {} degenerate", thousands(m.stats.degenerate_triangles))
            } else {
                String::new()
            }
        ));
    }
    if lab.pending.is_some() {
        ui.label("Loading…");
    }
}

/// Opens the browser's file dialog for a mesh; natively, says to drop the file.
fn open_mesh_dialog(app: &mut LabApp, ctx: &egui::Context) {
    #[cfg(target_arch = "wasm32")]
    if let Err(e) = crate::web::pick_file(ctx, MESH_FILE_TYPES) {
        app.message = Some(format!("The file dialog could not be opened: {e}."));
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        app.message =
            Some("Drop an OBJ, PLY, STL or glTF file on the window to open it.".to_owned());
    }
}

fn structure_section(app: &mut LabApp, ui: &mut egui::Ui) {
    crate::panels::settings_editor(&mut app.lab3d.settings, 3, ui);
    let lab = &mut app.lab3d;
    if let Some(job) = &lab.job {
        ui.add(
            egui::ProgressBar::new(job.fraction())
                .show_percentage()
                .text(format!("building the {}…", job.settings.kind.label_in(3))),
        );
    } else if let Some(built) = &lab.built {
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
        let d = &mut lab.display;
        ui.checkbox(&mut d.structure, "show the structure");
        let deepest = s.max_depth as u32;
        ui.add(egui::Slider::new(&mut d.depth, 0..=deepest.max(1)).text("level"));
        ui.checkbox(&mut d.marks, "colour visited, culled and pruned nodes");
        ui.checkbox(&mut d.xray, "x-ray mesh (see volumes inside)");
    }
}

fn query_section(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        ui.label("A click:");
        let lab = &mut app.lab3d;
        if ui
            .radio_value(&mut lab.tool, Tool3d::Ray, "casts a ray")
            .clicked()
        {
            app.ask_about_ray();
        }
        let lab = &mut app.lab3d;
        if ui
            .radio_value(&mut lab.tool, Tool3d::Point, "places the point")
            .clicked()
        {
            app.ask_about_point();
        }
    });
    ui.label(
        RichText::new("Drag to orbit, shift-drag to pan, scroll to zoom. Drag the gizmo's dots to move the ray or point; its coloured arrows move it along x, y or z.")
            .small()
            .weak(),
    );
    let lab = &mut app.lab3d;
    if let Some(ray) = lab.ray {
        let mut origin = ray.origin();
        let mut dir = ray.dir();
        let a = vec3_editor(ui, "origin", &mut origin);
        let b = vec3_editor(ui, "direction", &mut dir);
        if a || b {
            match Ray3::new(origin, dir) {
                Ok(r) => lab.ray = Some(r),
                Err(e) => app.message = Some(format!("That ray cannot be cast: {e}.")),
            }
        }
    }
    let lab = &mut app.lab3d;
    if let Some(mut p) = lab.point
        && vec3_editor(ui, "point", &mut p)
    {
        lab.point = Some(p);
    }
    if app.task == Task::Nearest {
        ui.add(egui::Slider::new(&mut app.k, 1..=16).text("k nearest"));
    }
    if app.task == Task::Range {
        let size = app
            .lab3d
            .mesh
            .as_ref()
            .map_or(1.0, super::mesh::Mesh3d::size);
        ui.add(
            egui::Slider::new(&mut app.lab3d.radius, 0.0..=size)
                .logarithmic(true)
                .text("radius"),
        );
    }
    answer(app, ui);
}

/// Three number fields; whether one changed.
fn vec3_editor(ui: &mut egui::Ui, label: &str, v: &mut Vec3) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        for (axis, c) in ["x", "y", "z"]
            .into_iter()
            .zip([&mut v.x, &mut v.y, &mut v.z])
        {
            // Each field is named for screen readers ("origin x", ...), and shows its axis.
            let name = ui.label(RichText::new(axis).weak()).id;
            changed |= ui
                .add(egui::DragValue::new(c).speed(0.01).max_decimals(4))
                .labelled_by(name)
                .changed();
        }
        changed
    })
    .inner
}

/// The answer and what it cost, against brute force.
fn answer(app: &LabApp, ui: &mut egui::Ui) {
    let lab = &app.lab3d;
    let rec = match &lab.recording {
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
        ui.label(format!(
            "{} nodes, {} BV tests, {} triangle tests (brute force: {} triangle tests)",
            rec.cost.nodes_visited,
            rec.cost.bound_tests,
            rec.cost.prim_tests,
            rec.brute_cost.prim_tests
        ));
    }
}

/// The status line's 3D part: the mesh and the build.
pub fn status(app: &LabApp) -> String {
    let lab = &app.lab3d;
    match (&lab.mesh, &lab.job, &lab.built) {
        (None, _, _) => "Loading the mesh…".to_owned(),
        (Some(m), Some(job), _) => format!(
            "{}: building the {} ({:.0}%)",
            m.name,
            job.settings.kind.label_in(3),
            job.fraction() * 100.0
        ),
        (Some(m), None, Some(b)) => format!(
            "{}: {} triangles, {} built in {:.0} ms",
            m.name,
            thousands(m.triangle_count()),
            b.settings.kind.label_in(3),
            b.build_ms
        ),
        (Some(m), None, None) => format!("{}: no structure", m.name),
    }
}
