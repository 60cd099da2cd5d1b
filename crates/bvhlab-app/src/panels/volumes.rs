//! Lecture §2, bounding volumes: the selection's centroid, Ritter and Welzl spheres, AABB,
//! PCA box and convex hull with their sizes; the slab test of the ray against the AABB, axis
//! by axis, with its failure case; the ray-sphere quadratic; two OBBs under the
//! separating-axis test.

use bvhlab::FitKind;
use bvhlab::volume::AxisSource;
use egui::{Grid, RichText};

use super::Panel;
use crate::model::Action2d;
use crate::model::tools::Tool;
use crate::model::volumes::{Fits, SlabExplain};
use crate::paint::colors;
use crate::ui_state::Cx;

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

    ray_tests(cx, fits, ui);
    sat_demo(cx, ui);
}

fn ray_tests(cx: &mut Cx<'_>, fits: &Fits, ui: &mut egui::Ui) {
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
            ui.label("Draw a ray (Ray tool) to run the ray tests.");
        }
        Some((_, Err(e))) => {
            ui.label(format!("No ray: {e}"));
        }
        Some((handles, Ok(ray))) => {
            slab_details(&SlabExplain::new(&fits.aabb, &ray), ui);
            ui.horizontal_wrapped(|ui| {
                if ui.button("Ray parallel to x").clicked() {
                    let mut r = handles;
                    r.target.y = r.origin.y;
                    cx.act(Action2d::SetRay(Some(r)));
                }
                if ui
                    .button("…and on the slab line y = y_min")
                    .on_hover_text(
                        "x_d stays, y_d = 0 and y_e = y_min: the naive formula computes 0/0.",
                    )
                    .clicked()
                {
                    let mut r = handles;
                    r.origin.y = fits.aabb.min.y;
                    r.target.y = fits.aabb.min.y;
                    if r.target.x == r.origin.x {
                        r.target.x += 1.0;
                    }
                    cx.act(Action2d::SetRay(Some(r)));
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
