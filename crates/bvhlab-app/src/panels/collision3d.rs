//! The collision query of two trees in 3D: the volumes' part (A) against a copy of it (B),
//! moved and turned by typed numbers, both built as the same kind of BVH; the walk stepped
//! event by event (which node pairs are tested, which are disjoint and cut off, which
//! triangle pairs are tested and which meet), with its counts beside brute force's.

use bvhlab::structure::Event;
use egui::{DragValue, Grid};

use crate::model::Action3d;
use crate::model::collision::{CollisionRun, CollisionSoFar, CollisionTree};
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
    ui.horizontal_wrapped(|ui| {
        ui.label("Both trees are");
        for tree in CollisionTree::ALL {
            ui.radio_value(&mut edited.tree, tree, tree.label());
        }
    });
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
        Some(run) => stepper(ui, run, &mut edited),
    }
    if edited != collision && edited.is_valid() {
        cx.act(Action3d::SetCollision(Some(edited)));
    }
}

/// The copy's move and turn, each number named for screen readers by its row.
fn pose_editor(ui: &mut egui::Ui, c: &mut Collision3d) {
    let speed = (c.offset.abs().max_element() * 0.02).max(0.01);
    for (what, v, speed, suffix) in [
        ("B moved by", &mut c.offset, speed, ""),
        ("B turned about x, y, z", &mut c.degrees, 1.0, "°"),
    ] {
        ui.horizontal(|ui| {
            let row = ui.label(what).id;
            for (axis, value) in ["x", "y", "z"].into_iter().zip(v.as_mut()) {
                ui.add(
                    DragValue::new(value)
                        .speed(speed)
                        .prefix(format!("{axis} "))
                        .suffix(suffix)
                        .max_decimals(3),
                )
                .labelled_by(row);
            }
        });
    }
}

/// The walk, step by step: the buttons, the step in words, and the counts so far and in
/// all beside brute force's.
fn stepper(ui: &mut egui::Ui, run: &CollisionRun<bvhlab::glam::Vec3>, c: &mut Collision3d) {
    let total = run.events.len();
    let shown = c.step.map_or(total, |s| s.min(total));
    ui.horizontal_wrapped(|ui| {
        if ui.button("First test").clicked() {
            c.step = Some(0);
        }
        if ui.button("Previous test").clicked() {
            c.step = Some(shown.saturating_sub(1));
        }
        if ui.button("Next test").clicked() {
            c.step = (shown + 1 < total).then_some(shown + 1);
        }
        if ui.button("All tests (the answer)").clicked() {
            c.step = None;
        }
        ui.label(format!("step {shown} of {total}"));
    });
    ui.label(describe(run, shown));
    let now = run.so_far(shown);
    let all = run.so_far(total);
    counts(ui, now, all, run);
}

/// The event just shown, in words.
fn describe(run: &CollisionRun<bvhlab::glam::Vec3>, shown: usize) -> String {
    let Some(event) = shown.checked_sub(1).and_then(|i| run.events.get(i)) else {
        return "Press \"Next test\": the walk starts with the two roots.".to_owned();
    };
    match *event {
        Event::NodePairTest {
            a,
            b,
            overlap: true,
        } => format!(
            "Nodes A {} and B {}: their volumes overlap, so the larger is opened and each of \
             its children paired with the other (two leaves: their triangles are tested).",
            a.0, b.0
        ),
        Event::NodePairTest {
            a,
            b,
            overlap: false,
        } => format!(
            "Nodes A {} and B {}: their volumes are disjoint, so nothing below them can \
             touch: every pair under them is cut off.",
            a.0, b.0
        ),
        Event::PairTest { a, b, overlap } => format!(
            "Triangles A {a} and B {b}: {}.",
            if overlap {
                "they meet (in the answer)"
            } else {
                "they do not meet"
            }
        ),
        _ => String::new(),
    }
}

/// The counts so far and in all, and brute force's.
fn counts(
    ui: &mut egui::Ui,
    now: CollisionSoFar,
    all: CollisionSoFar,
    run: &CollisionRun<bvhlab::glam::Vec3>,
) {
    Grid::new("collision counts").striped(true).show(ui, |ui| {
        for h in ["", "so far", "in all", "brute force"] {
            ui.strong(h);
        }
        ui.end_row();
        let brute_meeting = run
            .brute
            .as_ref()
            .map_or_else(|| "not run".to_owned(), |b| b.len().to_string());
        for (name, so_far, total, brute) in [
            (
                "node pairs tested",
                now.node_pairs,
                all.node_pairs,
                "–".to_owned(),
            ),
            (
                "... disjoint (cut off)",
                now.disjoint,
                all.disjoint,
                "–".to_owned(),
            ),
            (
                "triangle pairs tested",
                now.primitive_pairs,
                all.primitive_pairs,
                run.brute_tests.to_string(),
            ),
            ("... meeting", now.meeting, all.meeting, brute_meeting),
        ] {
            ui.label(name);
            ui.label(so_far.to_string());
            ui.label(total.to_string());
            ui.label(brute);
            ui.end_row();
        }
    });
    ui.label(match run.agrees() {
        Some(true) => format!(
            "Same {} pairs as brute force, with {} of its {} triangle tests.",
            run.pairs.len(),
            all.primitive_pairs,
            run.brute_tests
        ),
        Some(false) => {
            "The trees' answer differs from brute force's: please report this.".to_owned()
        }
        None => format!(
            "Brute force would test all {} triangle pairs; it runs up to {}.",
            run.brute_tests,
            crate::model::collision::BRUTE_FORCE_PAIRS_CAP
        ),
    });
}
