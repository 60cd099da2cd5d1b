//! The control panel, in the lecture's order: the scene, §2 bounding volumes, §3 the
//! structure, then the queries and what they cost; and the status line.

use bvhlab::FitKind;
use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SphereFit;
use bvhlab::volume::AxisSource;
use egui::{CollapsingHeader, Color32, Grid, RichText};

use crate::app::LabApp;
use crate::paint::colors;
use crate::presets::Preset;
use crate::query::NodeMark;
use crate::structures::{BuildSettings, KdSplit, StructureKind};
use crate::tool::{Interaction, Tool};
use crate::volumes::SlabExplain;

/// The whole control panel.
pub fn controls(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.heading("bvh-lab");
    ui.label("Bounding volumes and spatial data structures, after the lecture's slides.");
    CollapsingHeader::new("Scene")
        .default_open(true)
        .show(ui, |ui| scene_section(app, ui));
    CollapsingHeader::new("§2 Bounding volumes")
        .default_open(true)
        .show(ui, |ui| volumes_section(app, ui));
    CollapsingHeader::new("§3 Spatial structure")
        .default_open(true)
        .show(ui, |ui| structure_section(app, ui));
    CollapsingHeader::new("Queries")
        .default_open(true)
        .show(ui, |ui| query_section(app, ui));
    persist_section(app, ui);
}

/// The line at the bottom: the last message, or what the tool does; and the frame rate.
pub fn status_line(app: &mut LabApp, ui: &mut egui::Ui) {
    let three = app.dimension == crate::app::Dimension::Three;
    let message = app
        .message
        .clone()
        .or_else(|| app.lab3d.message.clone().filter(|_| three));
    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
        // The side panels fold away for small windows (and embedded labs).
        ui.toggle_value(&mut app.show_stepper, "Step through")
            .on_hover_text("Show or hide the \"Step through\" panel");
        ui.toggle_value(&mut app.show_controls, "Controls")
            .on_hover_text("Show or hide the controls");
        if let (Some(ms), Some(fps)) = (app.clock.median_ms(), app.clock.fps()) {
            ui.label(format!("frame {ms:.1} ms ({fps:.0} fps)"));
        }
        if let Some(r) = &app.renderer {
            ui.label(format!("{r} ·"));
        }
        // What is left, from the left: a message wraps (it must be read whole), a hint is
        // cut short.
        ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
            match message {
                Some(m) => {
                    ui.add(egui::Label::new(RichText::new(m).color(colors::SELECTED)).wrap())
                }
                None if three => {
                    ui.add(egui::Label::new(crate::lab3d::panel::status(app)).truncate())
                }
                None => ui.add(egui::Label::new(app.tool.hint()).truncate()),
            };
        });
    });
}

fn scene_section(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.label("Tool");
    let before = app.tool;
    ui.horizontal_wrapped(|ui| {
        for tool in Tool::ALL {
            ui.selectable_value(&mut app.tool, tool, tool.label());
        }
    });
    if app.tool != before {
        app.interaction = Interaction::None;
        app.message = None;
    }
    let mut preset = app.preset;
    egui::ComboBox::from_label("Preset")
        .selected_text(preset.label())
        .show_ui(ui, |ui| {
            for p in Preset::ALL {
                ui.selectable_value(&mut preset, p, p.label());
            }
        });
    if preset != app.preset {
        app.load_preset(preset);
    }
    ui.horizontal(|ui| {
        if ui.button("Reload preset").clicked() {
            app.load_preset(app.preset);
        }
        if ui.button("Fit view").clicked() {
            app.fit_pending = true;
        }
        if ui.button("Clear").clicked() {
            app.scene.clear();
            app.selection.clear();
        }
    });
    let n_sel = app.selection.len();
    if ui
        .add_enabled(
            n_sel > 0,
            egui::Button::new(format!("Delete selected ({n_sel})")),
        )
        .clicked()
    {
        let removed = std::mem::take(&mut app.selection);
        app.scene.remove(&removed);
    }
    let prims = app
        .lane
        .built
        .as_ref()
        .map_or(0, |b| b.prims.segments.len());
    ui.label(format!(
        "{} shapes, {prims} primitives (segments; a point is a segment of length 0).",
        app.scene.shapes().len()
    ));
}

fn volumes_section(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.checkbox(&mut app.display.volumes, "Show the bounding volumes")
        .on_hover_text("Of the selected shapes; of every shape when nothing is selected.");
    let t = &mut app.volume_toggles;
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut t.centroid, "sphere (centroid)");
        ui.checkbox(&mut t.ritter, "Ritter");
        ui.checkbox(&mut t.welzl, "Welzl");
        ui.checkbox(&mut t.aabb, "AABB");
        ui.checkbox(&mut t.obb, "OBB (PCA)");
        ui.checkbox(&mut t.hull, "convex hull");
    });
    let Some(fits) = app.fits() else {
        ui.label("Draw or select a shape to fit volumes to it.");
        return;
    };
    Grid::new("fits")
        .striped(true)
        .show(ui, |ui| {
            ui.strong("volume");
            ui.strong("area");
            ui.strong("perimeter");
            ui.strong("tightness");
            ui.end_row();
            for kind in FitKind::ALL {
                if let Some(m) = fits.report.get(kind) {
                    ui.label(kind.label());
                    ui.label(format!("{:.3}", m.measure));
                    ui.label(format!("{:.3}", m.boundary_measure));
                    ui.label(
                        m.tightness
                            .map_or("–".to_owned(), |t| format!("{:.0} %", t * 100.0)),
                    );
                    ui.end_row();
                }
            }
        })
        .response
        .on_hover_text("Tightness: the convex hull's area over the volume's area.");
    let pca = &fits.pca;
    let [c0, c1] = pca.covariance;
    ui.label(format!(
        "OBB from PCA: mean c = ({:.2}, {:.2}); covariance [[{:.3}, {:.3}], [{:.3}, {:.3}]]; \
         variances {:.3} (max) and {:.3} (min) along ({:.2}, {:.2}) and ({:.2}, {:.2}).",
        pca.mean.x,
        pca.mean.y,
        c0.x,
        c1.x,
        c0.y,
        c1.y,
        pca.variances.x,
        pca.variances.y,
        pca.axes[0].x,
        pca.axes[0].y,
        pca.axes[1].x,
        pca.axes[1].y,
    ));

    ray_tests(app, &fits, ui);
    sat_demo(app, ui);
}

fn ray_tests(app: &mut LabApp, fits: &crate::volumes::Fits, ui: &mut egui::Ui) {
    ui.separator();
    ui.checkbox(
        &mut app.display.slab_test,
        "Slab test of the ray against the AABB",
    );
    match app.ray.map(|r| r.ray()) {
        None => {
            ui.label("Draw a ray (Ray tool) to run the ray tests.");
        }
        Some(Err(e)) => {
            ui.label(format!("No ray: {e}"));
        }
        Some(Ok(ray)) => {
            slab_details(&SlabExplain::new(&fits.aabb, &ray), ui);
            ui.horizontal_wrapped(|ui| {
                if ui.button("Ray parallel to x").clicked()
                    && let Some(r) = app.ray.as_mut()
                {
                    r.target.y = r.origin.y;
                }
                if ui
                    .button("…and on the slab line y = y_min")
                    .on_hover_text(
                        "x_d stays, y_d = 0 and y_e = y_min: the naive formula computes 0/0.",
                    )
                    .clicked()
                    && let Some(r) = app.ray.as_mut()
                {
                    r.origin.y = fits.aabb.min.y;
                    r.target.y = fits.aabb.min.y;
                    if r.target.x == r.origin.x {
                        r.target.x += 1.0;
                    }
                }
            });
            let q = fits.centroid.ray_quadratic(&ray);
            ui.label(format!(
                "Ray-sphere (centroid sphere): a t² + b t + c = 0 with a = {:.3}, b = {:.3}, \
                 c = {:.3}; discriminant {:.3}: {}.",
                q.a,
                q.b,
                q.c,
                q.discriminant(),
                q.roots()
                    .map_or("no real root: miss".to_owned(), |(t0, t1)| format!(
                        "t = {t0:.3}, {t1:.3}"
                    ))
            ));
        }
    }
}

fn sat_demo(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.separator();
    if ui
        .selectable_label(app.tool == Tool::Obb, "Separating-axis test of two OBBs")
        .clicked()
    {
        app.tool = if app.tool == Tool::Obb {
            Tool::Select
        } else {
            Tool::Obb
        };
    }
    if app.tool == Tool::Obb
        && let Some(pair) = &app.obb_pair
    {
        let tests = pair.tests();
        Grid::new("sat").striped(true).show(ui, |ui| {
            ui.strong("axis");
            ui.strong("A projects to");
            ui.strong("B projects to");
            ui.strong("gap");
            ui.end_row();
            for test in &tests {
                let name = match test.source {
                    AxisSource::FaceA(i) => format!("A face {i}"),
                    AxisSource::FaceB(j) => format!("B face {j}"),
                    AxisSource::Edges(i, j) => format!("A{i} × B{j}"),
                };
                let color = if test.separates() {
                    colors::VISITED
                } else {
                    ui.visuals().text_color()
                };
                ui.label(RichText::new(name).color(color));
                ui.label(format!(
                    "[{:.2}, {:.2}]",
                    test.interval_a.0, test.interval_a.1
                ));
                ui.label(format!(
                    "[{:.2}, {:.2}]",
                    test.interval_b.0, test.interval_b.1
                ));
                ui.label(RichText::new(format!("{:.2}", test.gap)).color(color));
                ui.end_row();
            }
        });
        match tests.iter().position(bvhlab::AxisTest::separates) {
            Some(i) => ui.label(format!(
                "Axis {} separates them: the boxes do not overlap (the test stops there).",
                i + 1
            )),
            None => ui.label("No axis separates them: the boxes overlap."),
        };
    }
}

fn slab_details(s: &SlabExplain, ui: &mut egui::Ui) {
    Grid::new("slabs").striped(true).show(ui, |ui| {
        for h in ["", "min", "max", "e", "d", "t_min", "t_max"] {
            ui.strong(h);
        }
        ui.end_row();
        for (name, a, color) in [
            ("x", &s.axes[0], colors::SLAB_X),
            ("y", &s.axes[1], colors::SLAB_Y),
        ] {
            ui.label(RichText::new(name).color(color));
            for v in [a.lo, a.hi, a.origin, a.dir, a.t_min, a.t_max] {
                ui.label(format!("{v:.3}"));
            }
            ui.end_row();
        }
    });
    for (name, a) in [("x", &s.axes[0]), ("y", &s.axes[1])] {
        if a.parallel() {
            ui.label(format!(
                "{name}_d = 0: the ray is parallel to the {name} slab. 1/0 = ±inf keeps the test right{}",
                if a.naive_fails() {
                    format!(
                        ", except here: the origin lies on the slab line, so ({name}_min - {name}_e)/{name}_d = 0/0 = NaN. \
                         The core decides from the origin instead (inside the slab: t in (-inf, inf))."
                    )
                } else {
                    ".".to_owned()
                }
            ));
        } else if a.swapped() {
            ui.label(format!(
                "{name}_d < 0: the slab's ends swap (t_min uses {name}_max)."
            ));
        }
    }
    let verdict = if s.hits() { "hit" } else { "miss" };
    ui.label(format!(
        "max(t_xmin, t_ymin) = {:.3} {} min(t_xmax, t_ymax) = {:.3}: {verdict}.",
        s.t_enter,
        if s.hits() { "≤" } else { ">" },
        s.t_exit
    ));
    match s.naive_hits() {
        Some(naive) if naive != s.hits() => {
            ui.label(format!(
                "The naive formula says {}: wrong.",
                if naive { "hit" } else { "miss" }
            ));
        }
        None => {
            ui.label(RichText::new("The naive formula compares a NaN: its answer depends on how the comparison is written.").color(colors::CULLED));
        }
        Some(_) => {}
    }
}

fn structure_section(app: &mut LabApp, ui: &mut egui::Ui) {
    settings_editor(&mut app.lane.settings, 2, ui);
    structure_display(app, ui);
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

fn structure_display(app: &mut LabApp, ui: &mut egui::Ui) {
    let Some(built) = &app.lane.built else { return };
    let stats = &built.stats;
    let d = &mut app.display;
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
        egui_plot::Plot::new("leaf_sizes")
            .height(90.0)
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.bar_chart(egui_plot::BarChart::new("leaves", bars));
            });
    }
}

fn query_section(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        if ui.button("Clear ray").clicked() {
            app.ray = None;
        }
        if ui.button("Clear point").clicked() {
            app.point = None;
        }
        ui.add(egui::Slider::new(&mut app.k, 1..=8).text("k nearest"));
    });
    ray_answer(app, ui);
    point_answer(app, ui);
    if app.lane.ray_outcome.is_none() && app.lane.point_outcome.is_none() {
        ui.label("Use the Ray tool or the Query point tool on the canvas.");
        return;
    }
    ui.label(format!(
        "Stepping through: {} (right panel).",
        crate::stepper::task_label(app.task)
    ));
    if let Some(marks) = app.lane.marks() {
        ui.horizontal_wrapped(|ui| {
            legend(
                ui,
                colors::VISITED,
                format!("visited {}", marks.count(NodeMark::Visited)),
            );
            legend(
                ui,
                colors::CULLED,
                format!("BV missed {}", marks.count(NodeMark::Culled)),
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

fn legend(ui: &mut egui::Ui, color: Color32, text: String) {
    ui.label(RichText::new("•").color(color));
    ui.label(text);
}

fn counters(
    ui: &mut egui::Ui,
    id: &str,
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
            ("nodes visited", cost.nodes_visited, brute.nodes_visited),
            ("BV tests", cost.bound_tests, brute.bound_tests),
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

fn ray_answer(app: &LabApp, ui: &mut egui::Ui) {
    if let Some(Err(e)) = app.ray.map(|r| r.ray()) {
        // e and s coincide (a drag that ended where it began): say why nothing is answered.
        ui.label(format!("No ray: {e}. Drag s away from e."));
    }
    if let Some(o) = &app.lane.ray_outcome {
        let e = o.ray.origin();
        let d = o.ray.dir();
        ui.label(format!(
            "Ray e = ({:.2}, {:.2}), d = ({:.3}, {:.3})",
            e.x, e.y, d.x, d.y
        ));
        match o.hit {
            Some(h) => {
                let p = o.ray.at(h.t);
                let shape = app
                    .lane
                    .built
                    .as_ref()
                    .and_then(|b| b.prims.owner.get(h.prim))
                    .copied();
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
        counters(ui, "ray", o.cost, o.brute_cost, o.agrees());
    }
}

fn point_answer(app: &LabApp, ui: &mut egui::Ui) {
    if let Some(o) = &app.lane.point_outcome {
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
        counters(ui, "point", o.cost, o.brute_cost, o.agrees());
    }
}

/// Save and share: export and import scene files, and a link that opens this state. Also
/// opens the files dropped on the window (this panel is drawn every frame, open or not).
fn persist_section(app: &mut LabApp, ui: &mut egui::Ui) {
    use crate::persist;
    CollapsingHeader::new("Save and share")
        .default_open(true)
        .show(ui, |ui| {
            ui.horizontal_wrapped(|ui| {
                if ui
                    .button("Export scene")
                    .on_hover_text("Save the scene, structures, queries and view as a .json file.")
                    .clicked()
                {
                    persist::export_scene(app);
                }
                if ui
                    .button("Import scene…")
                    .on_hover_text("Open a .json scene file (or drop it on the window).")
                    .clicked()
                {
                    persist::import_scene(app, ui.ctx());
                }
                if ui
                    .button("Copy share link")
                    .on_hover_text("A link that opens the lab in this state.")
                    .clicked()
                {
                    persist::copy_share_link(app, ui.ctx());
                }
            });
            if let Some(link) = persist::share_link_text(ui.ctx()) {
                ui.add(
                    egui::TextEdit::singleline(&mut &*link)
                        .desired_width(f32::INFINITY)
                        .id_salt("share link"),
                );
            }
            ui.label("Drop a .json scene file on the window to open it.");
        });
}
