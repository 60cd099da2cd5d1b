//! The collision query of two trees in 3D: the volumes' part (A) against a copy of it (B),
//! moved and turned by typed numbers, both built as the same kind of BVH; the walk stepped
//! event by event (which node pairs are tested, which are disjoint and cut off, which
//! triangle pairs are tested and which meet), with its counts beside brute force's.

use crate::model::Action3d;
use crate::model::collision3d::{Collision3d, MAX_COLLISION_TRIANGLES};
use crate::ui_state::Cx;

/// The section, under the separating-axis test.
pub(super) fn collision_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.separator();
    let lab = cx.lab.three();
    let Some(part) = lab.part_fits() else { return };
    let mut on = lab.collision.is_some();
    if ui
        .checkbox(
            &mut on,
            "Collision of two trees: the part (A) against a moved copy (B)",
        )
        .changed()
    {
        let collision = on.then(|| {
            part.fits.as_ref().map_or_else(
                || Collision3d::beside(&bvhlab::Aabb3::default()),
                |f| Collision3d::beside(&f.aabb),
            )
        });
        cx.act(Action3d::SetCollision(collision));
    }
    let Some(collision) = lab.collision else {
        return;
    };
    let mut edited = collision;
    super::collision::tree_choice(ui, &mut edited.tree);
    pose_editor(ui, &mut edited);
    let run = lab.collision_run().and_then(|c| c.run.as_ref());
    match run {
        None if part.triangles.len() > MAX_COLLISION_TRIANGLES => {
            ui.label(format!(
                "The part has {} triangles: brush a part of at most {MAX_COLLISION_TRIANGLES} \
                 (two trees over more take seconds at every move of the copy).",
                part.triangles.len()
            ));
        }
        None => {
            ui.label("The part is empty: brush some triangles first.");
        }
        Some(run) => super::collision::stepper(ui, run, &mut edited.step, "triangle"),
    }
    if edited != collision && edited.is_valid() {
        cx.act(Action3d::SetCollision(Some(edited)));
    }
}

/// The copy's move and turn, each number named for screen readers by its row and axis.
fn pose_editor(ui: &mut egui::Ui, c: &mut Collision3d) {
    let speed = (c.offset.abs().max_element() * 0.02).max(0.01);
    for (what, v, speed, suffix) in [
        ("B moved by", &mut c.offset, speed, ""),
        ("B turned about x, y, z", &mut c.degrees, 1.0, "°"),
    ] {
        let mut values = v.to_array();
        super::xyz_fields(ui, what, &mut values, |d| {
            d.speed(speed).suffix(suffix).max_decimals(3)
        });
        *v = bvhlab::glam::Vec3::from_array(values);
    }
}
