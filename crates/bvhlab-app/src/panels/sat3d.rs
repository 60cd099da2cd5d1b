//! The separating-axis test of two OBBs in 3D (lecture §2, "collision query with OOBBs"):
//! the boxes typed in numbers (or put on the brushed part's PCA box), then the 15 candidate
//! axes in a table, stepped one by one, the one looked at drawn in the view with both
//! boxes' shadows on it.

use bvhlab::glam::Vec3;
use egui::{Grid, RichText};

use crate::model::Action3d;
use crate::model::obb_pair3d::{BoxPose3, CANDIDATES, ObbPair3, axis_name};
use crate::paint::colors;
use crate::ui_state::Cx;

/// The section, under the 3D volumes.
pub(super) fn sat_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.separator();
    let lab = cx.lab.three();
    let mut on = lab.obb_pair.is_some();
    if ui
        .checkbox(&mut on, "Separating-axis test of two OBBs (15 axes)")
        .changed()
    {
        let pair = on.then(|| {
            let (center, size) = lab
                .mesh
                .as_ref()
                .map_or((Vec3::ZERO, 1.0), |m| (m.bounds().center(), m.size()));
            ObbPair3::around(center, size * 0.5)
        });
        cx.act(Action3d::SetObbPair(pair));
    }
    let Some(pair) = lab.obb_pair else { return };
    let mut edited = pair;
    let part_obb = lab
        .part_fits()
        .and_then(|p| p.fits.as_ref())
        .and_then(|f| BoxPose3::of_obb(&f.obb));
    for (name, pose) in [("A", &mut edited.a), ("B", &mut edited.b)] {
        pose_editor(ui, name, pose, part_obb);
    }
    axis_table(ui, &mut edited);
    if edited != pair && edited.is_valid() {
        cx.act(Action3d::SetObbPair(Some(edited)));
    }
}

/// One box's numbers: centre, half extents and turn, each dragged or typed; and a button
/// that puts the box on the brushed part's PCA box.
fn pose_editor(ui: &mut egui::Ui, name: &str, pose: &mut BoxPose3, part_obb: Option<BoxPose3>) {
    ui.horizontal_wrapped(|ui| {
        ui.strong(format!("Box {name}"));
        if let Some(fit) = part_obb
            && ui
                .button(format!("{name} = the part's OBB"))
                .on_hover_text("The PCA box of the mesh or of the brushed triangles.")
                .clicked()
        {
            *pose = fit;
        }
    });
    let speed = (pose.half.max_element() * 0.02).max(1e-3);
    for (what, v, speed, suffix, range) in [
        ("centre", &mut pose.center, speed, "", f32::MIN..=f32::MAX),
        ("half extents", &mut pose.half, speed, "", 0.0..=f32::MAX),
        (
            "turn about x, y, z",
            &mut pose.degrees,
            1.0,
            "°",
            -360.0..=360.0,
        ),
    ] {
        // Each field is named by its row and axis ("B turn about x, y, z: x"): a screen
        // reader says which box and which number.
        let mut values = v.to_array();
        super::xyz_fields(ui, &format!("{name} {what}"), &mut values, |d| {
            d.speed(speed)
                .range(range.clone())
                .suffix(suffix)
                .max_decimals(3)
        });
        *v = Vec3::from_array(values);
    }
}

/// The 15 candidates: both shadows, the gap and the verdict for each, the one looked at
/// marked, with buttons to step through them; then the core's answer in words.
fn axis_table(ui: &mut egui::Ui, pair: &mut ObbPair3) {
    let tests = pair.tests();
    ui.horizontal(|ui| {
        if ui.button("Previous axis").clicked() {
            pair.step = (pair.step + CANDIDATES.len() - 1) % CANDIDATES.len();
        }
        if ui.button("Next axis").clicked() {
            pair.step = (pair.step + 1) % CANDIDATES.len();
        }
        ui.label(format!(
            "axis {} of 15: {}",
            pair.step + 1,
            axis_name(CANDIDATES[pair.step])
        ));
    });
    egui::ScrollArea::vertical()
        .id_salt("sat 3d scroll")
        .max_height(260.0)
        .show(ui, |ui| {
            Grid::new("sat 3d").striped(true).show(ui, |ui| {
                for h in [
                    "#",
                    "axis",
                    "A projects to",
                    "B projects to",
                    "gap",
                    "separates",
                ] {
                    ui.strong(h);
                }
                ui.end_row();
                for (k, (source, test)) in CANDIDATES.iter().zip(&tests).enumerate() {
                    // The number, marked with a sign (not by colour alone) where it is looked
                    // at; a click looks at it.
                    let mark = if k == pair.step { ">" } else { "" };
                    if ui
                        .selectable_label(k == pair.step, format!("{mark}{}", k + 1))
                        .on_hover_text("Show this axis in the view")
                        .clicked()
                    {
                        pair.step = k;
                    }
                    let Some(test) = test else {
                        ui.label(axis_name(*source));
                        ui.label("—");
                        ui.label("—");
                        ui.label("—");
                        ui.label("skipped: parallel edges");
                        ui.end_row();
                        continue;
                    };
                    let color = if test.separates() {
                        colors::VISITED
                    } else {
                        ui.visuals().text_color()
                    };
                    ui.label(RichText::new(axis_name(*source)).color(color));
                    for (lo, hi) in [test.interval_a, test.interval_b] {
                        ui.label(format!("[{lo:.3}, {hi:.3}]"));
                    }
                    ui.label(RichText::new(format!("{:.3}", test.gap)).color(color));
                    ui.label(
                        RichText::new(if test.separates() { "yes" } else { "no" }).color(color),
                    );
                    ui.end_row();
                }
            });
        });
    let separating = tests.iter().flatten().filter(|t| t.separates()).count();
    let skipped = tests.iter().filter(|t| t.is_none()).count();
    match pair.separating() {
        Some(first) => ui.label(format!(
            "{} separates them: the boxes do not overlap (the test stops at the first; {separating} \
             of the {} axes tried separate).",
            axis_name(first),
            15 - skipped,
        )),
        None => ui.label(format!(
            "No axis separates them: the boxes overlap ({} axes tried{}).",
            15 - skipped,
            if skipped > 0 {
                format!(", {skipped} skipped because their edges are parallel")
            } else {
                String::new()
            }
        )),
    };
}
