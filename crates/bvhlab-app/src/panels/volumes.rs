//! Lecture §2, bounding volumes, in the lecture's order: the selection's centroid, Ritter and
//! Welzl spheres, AABB, PCA box and convex hull with their sizes and colours (pointing at a
//! row lights the volume on the canvas); the ray-sphere quadratic for each sphere; the slab
//! test of the ray against the AABB, axis by axis, with the naive formula beside the core's
//! and its failure cases; two OBBs under the separating-axis test.

use bvhlab::volume::AxisSource;
use bvhlab::{Aabb2, FitKind, FitReport, Ray, Vector};
use egui::{Grid, RichText, Sense, vec2};

use super::Panel;
use crate::lab3d::volumes::SLAB_COLORS;
use crate::model::Action2d;
use crate::model::lab2d::RayHandles;
use crate::model::tools::Tool;
use crate::model::volumes::{Fits, SlabExplain};
use crate::paint::colors;
use crate::ui_state::Cx;

/// The coordinate axes' names, in the slab table and its sentences.
const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The bounding volumes panel (lecture §2).
pub struct Volumes;

impl Panel for Volumes {
    fn title(&self) -> &'static str {
        "§2 Bounding volumes"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        volumes_section(cx, ui);
    }
}

fn volumes_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    let mut display = lab.display;
    ui.checkbox(&mut display.volumes, "Show the bounding volumes")
        .on_hover_text("Of the selected shapes; of every shape when nothing is selected.");
    if display != lab.display {
        cx.act(Action2d::SetDisplay(display));
    }
    let mut t = lab.volumes;
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut t.centroid, "sphere (centroid)");
        ui.checkbox(&mut t.ritter, "Ritter");
        ui.checkbox(&mut t.welzl, "Welzl");
        ui.checkbox(&mut t.aabb, "AABB");
        ui.checkbox(&mut t.obb, "OBB (PCA)");
        ui.checkbox(&mut t.hull, "convex hull");
    });
    if t != lab.volumes {
        cx.act(Action2d::SetVolumes(t));
    }
    let Some(fits) = lab.fits() else {
        ui.label("Draw or select a shape to fit volumes to it.");
        return;
    };
    fits_table(cx, &fits.report, ["area", "perimeter"], ui);
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

    ray_sphere(cx, fits, ui);
    slab_test(cx, fits, ui);
    sat_demo(cx, ui);
    super::collision2d::collision_section(cx, ui);
}

/// A table row's first cell: a small square in the colour `kind` is drawn in, then `name`.
pub(super) fn named_swatch(ui: &mut egui::Ui, kind: FitKind, name: &str) -> egui::Response {
    ui.horizontal(|ui| {
        let (rect, _) = ui.allocate_exact_size(vec2(12.0, 12.0), Sense::hover());
        // Outlined in the text's colour: the white of Welzl's sphere vanished on the light
        // panel without it.
        let outline = egui::Stroke::new(1.0, ui.visuals().weak_text_color());
        ui.painter().rect(
            rect.shrink(1.0),
            2.0,
            colors::volume(kind),
            outline,
            egui::StrokeKind::Inside,
        );
        ui.label(name);
    })
    .response
}

/// Lights `kind` on the canvas while the pointer is over its row (`cells`, the row's cells).
pub(super) fn hover_row(cx: &mut Cx<'_>, ui: &egui::Ui, kind: FitKind, cells: &[egui::Response]) {
    let row = cells
        .iter()
        .map(|r| r.rect)
        .reduce(egui::Rect::union)
        .unwrap_or(egui::Rect::NOTHING);
    if ui.rect_contains_pointer(row) {
        cx.ui.canvas.volume_hover = Some(kind);
    }
}

/// Each volume's size and tightness, a row per volume, with its colour in the view; `sizes`
/// names the measure and the boundary's ("area" and "perimeter" in 2D).
pub(super) fn fits_table(cx: &mut Cx<'_>, report: &FitReport, sizes: [&str; 2], ui: &mut egui::Ui) {
    Grid::new("fits")
        .striped(true)
        .show(ui, |ui| {
            ui.strong("bounding volume");
            ui.strong(sizes[0]);
            ui.strong(sizes[1]);
            ui.strong("tightness");
            ui.end_row();
            for kind in FitKind::ALL {
                if let Some(m) = report.get(kind) {
                    let cells = [
                        named_swatch(ui, kind, kind.label()),
                        ui.label(format!("{:.3}", m.measure)),
                        ui.label(format!("{:.3}", m.boundary_measure)),
                        ui.label(
                            m.tightness
                                .map_or("–".to_owned(), |t| format!("{:.0} %", t * 100.0)),
                        ),
                    ];
                    hover_row(cx, ui, kind, &cells);
                    ui.end_row();
                }
            }
        })
        .response
        .on_hover_text(format!(
            "Tightness: the convex hull's {0} over the volume's {0}. Point at a row to light \
             its volume in the view.",
            sizes[0]
        ));
}

/// Lecture §2, bounding sphere: the ray against each sphere, as the quadratic
/// a t² + b t + c = 0.
fn ray_sphere(cx: &mut Cx<'_>, fits: &Fits, ui: &mut egui::Ui) {
    ui.separator();
    ui.strong("Ray-sphere test");
    let ray = match cx.lab.two().ray.map(|r| r.ray()) {
        None => {
            ui.label(
                "Draw a ray (Ray tool) to test it against each sphere: p(t) = e + t (s - e) \
                 lies on a sphere of radius r when a t² + b t + c = 0, with (the sphere's \
                 centre moved to the origin first) a = (s - e)·(s - e), b = 2 e·(s - e), \
                 c = e·e - r². No real root: the ray misses the sphere.",
            );
            return;
        }
        Some(Err(e)) => {
            ui.label(format!("No ray: {e}"));
            return;
        }
        Some(Ok(ray)) => ray,
    };
    ray_sphere_table(cx, fits, &ray, ui);
}

/// Each sphere's quadratic for `ray`, its roots and what they mean, a row per sphere.
pub(super) fn ray_sphere_table<V: Vector>(
    cx: &mut Cx<'_>,
    fits: &Fits<V>,
    ray: &Ray<V>,
    ui: &mut egui::Ui,
) {
    let spheres = [
        (FitKind::SphereCentroid, &fits.centroid, "centroid"),
        (FitKind::SphereRitter, &fits.ritter, "Ritter"),
        (FitKind::SphereWelzl, &fits.welzl, "Welzl"),
    ];
    egui::ScrollArea::horizontal()
        .id_salt("ray-sphere scroll")
        .show(ui, |ui| {
            Grid::new("ray-sphere").striped(true).show(ui, |ui| {
                for h in ["sphere", "a", "b", "c", "b² - 4ac", "t", "ray"] {
                    ui.strong(h);
                }
                ui.end_row();
                for (kind, sphere, name) in spheres {
                    let q = sphere.ray_quadratic(ray);
                    let roots = q.roots();
                    let cells = [
                        named_swatch(ui, kind, name),
                        ui.label(format!("{:.3}", q.a)),
                        ui.label(format!("{:.3}", q.b)),
                        ui.label(format!("{:.3}", q.c)),
                        ui.label(format!("{:.3}", q.discriminant())),
                        ui.label(roots.map_or("no real root".to_owned(), |(t0, t1)| {
                            format!("{t0:.3}, {t1:.3}")
                        })),
                        ui.label(match roots {
                            None => "misses",
                            Some((_, t1)) if t1 < 0.0 => "misses (behind e)",
                            Some((t0, _)) if t0 < 0.0 => "starts inside",
                            Some(_) => "hits",
                        }),
                    ];
                    hover_row(cx, ui, kind, &cells);
                    ui.end_row();
                }
            });
        });
}

/// Lecture §2, AABB: the slab test, its table and its failure cases.
fn slab_test(cx: &mut Cx<'_>, fits: &Fits, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    ui.separator();
    let mut display = lab.display;
    ui.checkbox(
        &mut display.slab_test,
        "Slab test of the ray against the AABB",
    );
    if display != lab.display {
        cx.act(Action2d::SetDisplay(display));
    }
    match lab.ray.map(|r| (r, r.ray())) {
        None => {
            ui.label("Draw a ray (Ray tool) to run the slab test.");
        }
        Some((_, Err(e))) => {
            ui.label(format!("No ray: {e}"));
        }
        Some((handles, Ok(ray))) => {
            // The buttons come first: what they change is all below them, so they stay put
            // between two clicks.
            failure_buttons(cx, handles, &fits.aabb, ui);
            slab_details(&SlabExplain::new(&fits.aabb, &ray), ui);
        }
    }
}

/// "When does this fail?": a ray parallel to a slab, then one on the slab's line; the
/// lecture's `x_d = 0` first, then the same for y.
fn failure_buttons(cx: &mut Cx<'_>, handles: RayHandles, aabb: &Aabb2, ui: &mut egui::Ui) {
    for (axis, name, across) in [(0, "x", "y"), (1, "y", "x")] {
        ui.horizontal(|ui| {
            if ui
                .button(format!("Ray parallel to {across} ({name}_d = 0)"))
                .clicked()
            {
                let mut r = handles;
                r.target[axis] = r.origin[axis];
                if r.target == r.origin {
                    r.target[1 - axis] += 1.0;
                }
                cx.act(Action2d::SetRay(Some(r)));
            }
            if ui
                .button(format!("…and on the slab line {name} = {name}_min"))
                .on_hover_text(format!(
                    "{name}_d = 0 and {name}_e = {name}_min: the naive formula computes \
                     ({name}_min - {name}_e) / {name}_d = 0/0."
                ))
                .clicked()
            {
                let mut r = handles;
                r.origin[axis] = aabb.min[axis];
                r.target[axis] = aabb.min[axis];
                if r.target == r.origin {
                    r.target[1 - axis] += 1.0;
                }
                cx.act(Action2d::SetRay(Some(r)));
            }
        });
    }
}

fn sat_demo(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.two();
    ui.separator();
    if ui
        .selectable_label(lab.tool == Tool::Obb, "Separating-axis test of two OBBs")
        .clicked()
    {
        cx.ui.canvas.interaction = crate::lab2d::Interaction::None;
        cx.act(Action2d::SetTool(if lab.tool == Tool::Obb {
            Tool::Select
        } else {
            Tool::Obb
        }));
    }
    if lab.tool == Tool::Obb
        && let Some(pair) = &lab.obb_pair
    {
        let tests = pair.tests();
        Grid::new("sat").striped(true).show(ui, |ui| {
            ui.strong("axis");
            ui.strong("A projects to");
            ui.strong("B projects to");
            ui.strong("gap");
            ui.strong("separates");
            ui.end_row();
            for test in &tests {
                let name = axis_name(test.source);
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
                // Said in words too: the colour is not the only sign.
                ui.label(RichText::new(if test.separates() { "yes" } else { "no" }).color(color));
                ui.end_row();
            }
        });
        match tests.iter().find(|t| t.separates()) {
            Some(test) => ui.label(format!(
                "{} separates them: the boxes do not overlap (the test stops there).",
                axis_name(test.source)
            )),
            None => ui.label("No axis separates them: the boxes overlap."),
        };
    }
}

/// A separating-axis candidate's name, the same in the table's rows and in the sentence
/// under it: "A face 0" is the normal of the first box's face 0.
fn axis_name(source: AxisSource) -> String {
    match source {
        AxisSource::FaceA(i) => format!("A face {i}"),
        AxisSource::FaceB(j) => format!("B face {j}"),
        AxisSource::Edges(i, j) => format!("A{i} × B{j}"),
    }
}

/// `[lo, hi]` with two decimals: `NaN` and `inf` as IEEE floats print them.
fn interval(lo: f32, hi: f32) -> String {
    format!("[{lo:.2}, {hi:.2}]")
}

/// The slab test's table, axis by axis (x, y and in 3D z), and what it says in words.
pub(super) fn slab_details(s: &SlabExplain, ui: &mut egui::Ui) {
    let verdict = |hits: bool| if hits { "hit" } else { "miss" };
    egui::ScrollArea::horizontal()
        .id_salt("slabs scroll")
        .show(ui, |ui| {
            Grid::new("slabs").striped(true).show(ui, |ui| {
                for h in ["", "min", "max", "e", "d", "core: t in", "naive: t in"] {
                    ui.strong(h);
                }
                ui.end_row();
                for ((name, a), color) in AXIS_NAMES.iter().zip(&s.axes).zip(SLAB_COLORS) {
                    ui.label(RichText::new(*name).color(color));
                    for v in [a.lo, a.hi, a.origin, a.dir] {
                        ui.label(format!("{v:.3}"));
                    }
                    ui.label(interval(a.t_min, a.t_max));
                    let naive = RichText::new(interval(a.naive.0, a.naive.1));
                    ui.label(if a.naive_fails() {
                        naive.color(colors::CULLED)
                    } else {
                        naive
                    });
                    ui.end_row();
                }
                ui.label("answer");
                for _ in 0..4 {
                    ui.label("");
                }
                ui.label(verdict(s.hits()));
                ui.label(match s.naive_hits() {
                    Some(naive) => RichText::new(verdict(naive)),
                    None => RichText::new("NaN compared").color(colors::CULLED),
                });
                ui.end_row();
            });
        });
    for (name, a) in AXIS_NAMES.iter().zip(&s.axes) {
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
    let names = &AXIS_NAMES[..s.axes.len()];
    let listed = |end: &str| {
        let terms: Vec<String> = names.iter().map(|n| format!("t_{n}{end}")).collect();
        terms.join(", ")
    };
    ui.label(format!(
        "max({}) = {:.3} {} min({}) = {:.3}: {}.",
        listed("min"),
        s.t_enter,
        if s.hits() { "≤" } else { ">" },
        listed("max"),
        s.t_exit,
        verdict(s.hits()),
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
