//! Lecture §2 on a mesh ("What happens in 3D?"): the volumes of the whole mesh or of the
//! brush's part (the triangles within the range radius of the query point), with their
//! volumes, surface areas and tightness; the PCA box's mean, covariance and axes; the ray
//! against each sphere as a quadratic; and the slab test with three slabs, axis by axis,
//! with the rays that make the naive formula fail.

use bvhlab::glam::Vec3;
use bvhlab::{Aabb3, Ray3};
use egui::Grid;

use super::Panel;
use super::volumes::{fits_table, ray_sphere_table, slab_details};
use crate::model::Action3d;
use crate::model::tools::Tool3d;
use crate::model::volumes::{Fits, SlabExplain};
use crate::model::volumes3d::{Part3d, Volumes3d};
use crate::ui_state::Cx;

/// The bounding volumes panel of the 3D half.
pub struct Volumes3dPanel;

impl Panel for Volumes3dPanel {
    fn title(&self) -> &'static str {
        "§2 Bounding volumes"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        let lab = cx.lab.three();
        let volumes = lab.volumes;
        let mut chosen = volumes;
        ui.checkbox(&mut chosen.shown, "Show the bounding volumes")
            .on_hover_text("Of the whole mesh, or of the brush's part of it.");
        if !volumes.shown {
            act_on_change(cx, volumes, chosen);
            super::sat3d::sat_section(cx, ui);
            ui.label(
                "The collision query of two trees takes the volumes' part: show the bounding \
                 volumes to try it.",
            );
            return;
        }
        ui.horizontal_wrapped(|ui| {
            ui.label("Fitted to");
            for part in [Part3d::Mesh, Part3d::Brush] {
                ui.radio_value(&mut chosen.part, part, part.label());
            }
        });
        let t = &mut chosen.toggles;
        ui.horizontal_wrapped(|ui| {
            ui.checkbox(&mut t.centroid, "sphere (centroid)");
            ui.checkbox(&mut t.ritter, "Ritter");
            ui.checkbox(&mut t.welzl, "Welzl");
            ui.checkbox(&mut t.aabb, "AABB");
            ui.checkbox(&mut t.obb, "OBB (PCA)");
            ui.checkbox(&mut t.hull, "convex hull");
        });
        if chosen.part == Part3d::Brush
            && volumes.part != Part3d::Brush
            && lab.tool != Tool3d::Point
        {
            // The brush follows the query point: its gizmo and keys come with the Point tool.
            cx.act(Action3d::SetTool(Tool3d::Point));
        }
        act_on_change(cx, volumes, chosen);
        part_and_fits(cx, ui);
        super::sat3d::sat_section(cx, ui);
        super::collision3d::collision_section(cx, ui);
    }
}

fn act_on_change(cx: &mut Cx<'_>, before: Volumes3d, after: Volumes3d) {
    if after != before {
        cx.act(Action3d::SetVolumes(after));
    }
}

/// What the part is, its fits' table and the PCA; then the ray against them.
fn part_and_fits(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    let Some(part) = lab.part_fits() else {
        ui.label("Open a mesh to fit volumes to it.");
        return;
    };
    let radius = lab.half.radius;
    match (lab.volumes.part, lab.point) {
        (Part3d::Brush, None) => {
            ui.label("Place the query point (Point tool: click the mesh) to brush a part.");
        }
        (Part3d::Brush, Some(_)) => {
            ui.label(format!(
                "The brush holds {} triangles ({} vertices) within r = {radius:.3} of q, lit \
                 yellow. Move q with its gizmo, or R and the arrow keys; change r under \
                 \"Ray & point\".",
                part.triangles.len(),
                part.vertices,
            ));
        }
        (Part3d::Mesh, _) => {
            ui.label(format!(
                "The whole mesh: {} triangles, {} vertices.",
                part.triangles.len(),
                part.vertices
            ));
        }
    }
    let Some(fits) = part.fits.clone() else {
        if lab.volumes.part == Part3d::Brush && lab.point.is_some() {
            ui.label("No triangle lies within r of q: move q onto the mesh or make r larger.");
        }
        return;
    };
    fits_table(cx, &fits.report, ["volume", "surface area"], ui);
    pca(&fits, ui);
    ray_tests(cx, &fits, ui);
}

/// The PCA box's source: the mean, the 3×3 covariance and the principal axes with their
/// variances.
fn pca(fits: &Fits<Vec3>, ui: &mut egui::Ui) {
    let pca = &fits.pca;
    ui.label(format!(
        "OBB from PCA: mean c = ({:.3}, {:.3}, {:.3}).",
        pca.mean.x, pca.mean.y, pca.mean.z
    ));
    Grid::new("covariance 3d").striped(true).show(ui, |ui| {
        ui.strong("covariance");
        for h in ["x", "y", "z"] {
            ui.strong(h);
        }
        ui.strong("axis");
        ui.strong("variance");
        ui.end_row();
        for (i, (row, axis)) in pca.covariance.iter().zip(&pca.axes).enumerate() {
            ui.label(["x", "y", "z"][i]);
            for v in row.to_array() {
                ui.label(format!("{v:.4}"));
            }
            ui.label(format!("({:.2}, {:.2}, {:.2})", axis.x, axis.y, axis.z));
            ui.label(format!(
                "{:.4}{}",
                pca.variances[i],
                ["  (max)", "", "  (min)"][i]
            ));
            ui.end_row();
        }
    });
}

/// The ray against the spheres (the quadratic) and against the AABB (the slab test).
fn ray_tests(cx: &mut Cx<'_>, fits: &Fits<Vec3>, ui: &mut egui::Ui) {
    ui.separator();
    ui.strong("Ray-sphere test");
    let Some(ray) = cx.lab.three().ray else {
        ui.label(
            "Cast a ray (Ray tool: click the view) to test it against each sphere: p(t) = e + \
             t d lies on a sphere when a t² + b t + c = 0.",
        );
        return;
    };
    ray_sphere_table(cx, fits, &ray, ui);
    ui.separator();
    let volumes = cx.lab.three().volumes;
    let mut chosen = volumes;
    ui.checkbox(
        &mut chosen.slab_test,
        "Slab test of the ray against the AABB (three slabs)",
    );
    act_on_change(cx, volumes, chosen);
    failure_buttons(cx, ray, &fits.aabb, ui);
    slab_details(&SlabExplain::new(&fits.aabb, &ray), ui);
}

/// "When does this fail?" in 3D: a ray parallel to a slab (`x_d = 0`), then one lying on
/// the slab's plane, for each axis.
fn failure_buttons(cx: &mut Cx<'_>, ray: Ray3, aabb: &Aabb3, ui: &mut egui::Ui) {
    for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
        ui.horizontal(|ui| {
            if ui
                .button(format!("Ray parallel to the {name} slab ({name}_d = 0)"))
                .clicked()
                && let Some(r) = parallel(ray, axis, None)
            {
                cx.act(Action3d::SetRay(Some(r)));
            }
            if ui
                .button(format!("…and on its plane {name} = {name}_min"))
                .on_hover_text(format!(
                    "{name}_d = 0 and {name}_e = {name}_min: the naive formula computes \
                     ({name}_min - {name}_e) / {name}_d = 0/0."
                ))
                .clicked()
                && let Some(r) = parallel(ray, axis, Some(aabb.min[axis]))
            {
                cx.act(Action3d::SetRay(Some(r)));
            }
        });
    }
}

/// `ray` turned parallel to the slab of `axis` (its direction's coordinate zeroed), its
/// origin moved onto the plane `axis = on` when given. `None` when no ray is left.
pub fn parallel(ray: Ray3, axis: usize, on: Option<f32>) -> Option<Ray3> {
    let mut dir = ray.dir();
    dir[axis] = 0.0;
    if dir.length_squared() == 0.0 {
        // The ray ran along the axis: any direction across it will do.
        dir[(axis + 1) % 3] = 1.0;
    }
    let mut origin = ray.origin();
    if let Some(plane) = on {
        origin[axis] = plane;
    }
    Ray3::new(origin, dir.normalize()).ok()
}
