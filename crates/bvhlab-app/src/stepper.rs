//! The "Step through" panel: what to step through, the transport, the pseudocode with the
//! current line, the counters against brute force, the stack or queue, the best so far, and
//! for builds the split and its SAH cost curve.

use bvhlab::Vector;
use egui::{Color32, RichText};

use crate::app::LabApp;
use crate::lane::Lane;
use crate::paint::colors;
use crate::playback::{Counters, Frontier, Snapshot, describe};
use crate::pseudocode::{Task, Variant};
use crate::recording::Recording;
use crate::structures::StructureKind;

/// Every task, in menu order, with its label.
pub const TASKS: [(Task, &str); 6] = [
    (Task::FirstHit, "ray: first hit"),
    (Task::AnyHit, "ray: any hit"),
    (Task::AllHits, "ray: all hits"),
    (Task::Nearest, "point: k nearest"),
    (Task::Range, "point: within a radius"),
    (Task::Build, "build the structure"),
];

/// A variant's label.
pub fn variant_label(v: Variant) -> &'static str {
    match v {
        Variant::Full => "full (near first, pruning)",
        Variant::Lecture => "the slides' version",
        Variant::LecturePruned => "the slides' + pruning",
    }
}

/// The label of a task.
pub fn task_label(task: Task) -> &'static str {
    TASKS
        .iter()
        .find(|(t, _)| *t == task)
        .map_or("?", |(_, l)| *l)
}

/// The panel.
pub fn stepper(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.heading("Step through");
    task_picker(app, ui);
    if app.dimension == crate::app::Dimension::Three {
        ui.separator();
        transport(app, ui);
        ui.separator();
        let lab = &app.lab3d;
        recording_state(
            lab.recording.as_ref(),
            lab.snapshot.as_ref(),
            lab.settings.kind,
            0,
            ui,
        );
        return;
    }
    compare_picker(app, ui);
    ui.separator();
    transport(app, ui);
    ui.separator();
    crate::export_ui::export_buttons(app, ui);
    ui.separator();
    let lanes: Vec<&Lane> = app.lanes().collect();
    for (i, lane) in lanes.iter().enumerate() {
        if lanes.len() > 1 {
            ui.label(
                RichText::new(lane.settings.kind.label())
                    .strong()
                    .color(colors::QUERY),
            );
        }
        lane_state(lane, i, ui);
        ui.separator();
    }
}

/// Chooses what playback steps through, and the algorithm's variant.
pub fn task_picker(app: &mut LabApp, ui: &mut egui::Ui) {
    egui::ComboBox::from_label("step through")
        .selected_text(task_label(app.task))
        .show_ui(ui, |ui| {
            for (task, label) in TASKS {
                ui.selectable_value(&mut app.task, task, label);
            }
        });
    let kind = if app.dimension == crate::app::Dimension::Three {
        app.lab3d.settings.kind
    } else {
        app.lane.settings.kind
    };
    let variants = crate::pseudocode::variants(kind, app.task);
    if variants.len() > 1 {
        ui.horizontal_wrapped(|ui| {
            for v in variants {
                ui.radio_value(&mut app.variant, v, variant_label(v));
            }
        });
    }
    if app.task == Task::Range && app.dimension == crate::app::Dimension::Two {
        ui.add(
            egui::Slider::new(&mut app.radius, 0.0..=50.0)
                .logarithmic(true)
                .text("radius"),
        );
    }
}

fn compare_picker(app: &mut LabApp, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        ui.checkbox(&mut app.show_tree, "tree diagram");
        ui.checkbox(&mut app.link_hover, "hover finds nodes")
            .on_hover_text("hovering the canvas highlights the node under the pointer, and its place in the tree");
    });
    ui.horizontal(|ui| {
        let mut on = app.compare.is_some();
        if ui.checkbox(&mut on, "compare with").changed() {
            // The canvas halves (or doubles): frame the scene in the new width.
            app.fit_pending = true;
            app.compare = on.then(|| {
                let mut settings = app.lane.settings;
                settings.kind = if settings.kind == StructureKind::SphereTree {
                    StructureKind::AabbTree
                } else {
                    StructureKind::SphereTree
                };
                Lane::new(settings)
            });
        }
        if let Some(other) = &mut app.compare {
            egui::ComboBox::from_label("second structure")
                .selected_text(other.settings.kind.label())
                .show_ui(ui, |ui| {
                    for kind in StructureKind::ALL {
                        ui.selectable_value(&mut other.settings.kind, kind, kind.label());
                    }
                });
        }
    });
}

fn transport(app: &mut LabApp, ui: &mut egui::Ui) {
    let len = app.steps();
    let p = &mut app.playback;
    ui.horizontal(|ui| {
        if ui.button("|<").on_hover_text("to the start").clicked() {
            p.go(0, len);
        }
        if ui.button("<").on_hover_text("one step back").clicked() {
            p.step_by(-1, len);
        }
        let play = if p.playing { "pause" } else { "play" };
        if ui.button(play).clicked() {
            p.toggle(len);
        }
        if ui.button(">").on_hover_text("one step forward").clicked() {
            p.step_by(1, len);
        }
        if ui.button(">|").on_hover_text("to the end (live)").clicked() {
            p.go(len, len);
        }
    });
    let mut step = p.shown(len);
    let slider = egui::Slider::new(&mut step, 0..=len).text(format!("step of {len}"));
    if ui.add(slider).changed() {
        p.playing = false;
        p.go(step, len);
    }
    ui.add(
        egui::Slider::new(&mut p.speed, 0.5..=200.0)
            .logarithmic(true)
            .text("steps per second"),
    );
}

fn lane_state(lane: &Lane, index: usize, ui: &mut egui::Ui) {
    recording_state(
        lane.recording.as_ref(),
        lane.snapshot.as_ref(),
        lane.settings.kind,
        index,
        ui,
    );
}

/// One structure's recording at the playback step: the sentence, the listing with its line,
/// the counters, the waiting nodes, the best so far, and a build's split.
fn recording_state<V: Vector>(
    recording: Option<&Result<Recording<V>, String>>,
    snapshot: Option<&Snapshot<V>>,
    kind: StructureKind,
    index: usize,
    ui: &mut egui::Ui,
) {
    let rec = match recording {
        Some(Ok(rec)) => rec,
        Some(Err(why)) => {
            ui.colored_label(colors::PRUNED, why);
            return;
        }
        None => return,
    };
    let Some(snap) = snapshot else { return };
    let q = rec.question;
    let line = snap
        .step
        .checked_sub(1)
        .and_then(|i| crate::pseudocode::line_of(kind, q.task, q.variant, &rec.events, i));
    ui.label(match &snap.event {
        Some(e) => format!("step {}: {}", snap.step, describe(e)),
        None => format!("step 0 of {}: nothing done yet", rec.events.len()),
    });
    if let Some(code) = crate::pseudocode::pseudocode(kind, q.task, q.variant) {
        pseudocode_view(code, line, index, ui);
    }
    // A build tests nothing: its counters would all be zero.
    if q.task != Task::Build {
        counters_table(rec, snap, index, ui);
    }
    if rec.variant_costs.len() > 1 {
        for (v, c) in &rec.variant_costs {
            ui.label(format!(
                "{}: {} nodes, {} BV tests, {} primitive tests",
                variant_label(*v),
                c.nodes_visited,
                c.bound_tests,
                c.prim_tests
            ));
        }
    }
    frontier_view(snap, ui);
    best_view(rec.question.task, snap, ui);
    if q.task == Task::Build {
        crate::build_view::split_view(rec, kind, snap, ui);
    }
}

fn pseudocode_view(
    code: &crate::pseudocode::Pseudocode,
    line: Option<usize>,
    index: usize,
    ui: &mut egui::Ui,
) {
    ui.label(RichText::new(code.title).strong());
    egui::Frame::new()
        .fill(Color32::from_rgb(20, 22, 28))
        .inner_margin(6.0)
        .show(ui, |ui| {
            egui::ScrollArea::horizontal()
                .id_salt(("code", index))
                .show(ui, |ui| code_lines(code, line, ui));
        });
    if !code.note.is_empty() {
        ui.label(RichText::new(code.note).small().weak());
    }
}

/// A counter's name, how to read it from [`Counters`], its total and brute force's.
type CounterRow = (&'static str, fn(&Counters) -> u64, u64, u64);

/// The listing, one unwrapped line per label, the current one marked and scrolled to.
fn code_lines(code: &crate::pseudocode::Pseudocode, line: Option<usize>, ui: &mut egui::Ui) {
    ui.spacing_mut().item_spacing.y = 0.0;
    for (i, text) in code.lines.iter().enumerate() {
        let current = line == Some(i);
        // The arrow marks the line for screen readers and tests as well as the eye.
        let arrow = if current { '>' } else { ' ' };
        let mut rich = RichText::new(format!("{:>2}{arrow} {text}", i + 1)).monospace();
        if current {
            rich = rich
                .background_color(Color32::from_rgb(70, 60, 20))
                .color(Color32::WHITE);
        }
        let response =
            ui.add(egui::Label::new(rich.size(12.0)).wrap_mode(egui::TextWrapMode::Extend));
        if current {
            response.scroll_to_me(None);
        }
    }
}

fn counters_table<V: Vector>(
    rec: &Recording<V>,
    snap: &Snapshot<V>,
    index: usize,
    ui: &mut egui::Ui,
) {
    let total = rec.cost;
    let brute = rec.brute_cost;
    let build = rec.question.task == Task::Build;
    egui::Grid::new(("step counters", index))
        .striped(true)
        .show(ui, |ui| {
            ui.label("");
            ui.label("this step");
            ui.label("so far");
            if !build {
                ui.label("total");
                ui.label("brute force");
            }
            ui.end_row();
            let rows: [CounterRow; 3] = [
                (
                    "nodes visited",
                    |c| c.nodes,
                    total.nodes_visited,
                    brute.nodes_visited,
                ),
                (
                    "BV tests",
                    |c| c.bound_tests,
                    total.bound_tests,
                    brute.bound_tests,
                ),
                (
                    "primitive tests",
                    |c| c.prim_tests,
                    total.prim_tests,
                    brute.prim_tests,
                ),
            ];
            // A range query reports only the volumes it refuses, not every test.
            let unreported = rec.question.task == Task::Range;
            for (name, get, t, b) in rows {
                ui.label(name);
                if unreported && name == "BV tests" {
                    ui.label("-");
                    ui.label("-");
                } else {
                    ui.label(get(&snap.this_step).to_string());
                    ui.label(get(&snap.so_far).to_string());
                }
                if !build {
                    ui.label(t.to_string());
                    ui.label(b.to_string());
                }
                ui.end_row();
            }
        });
    if !build {
        let (text, color) = if rec.agrees() {
            ("answer agrees with brute force", colors::VISITED)
        } else {
            ("answer DIFFERS from brute force", colors::CULLED)
        };
        ui.colored_label(color, text);
    }
}

fn frontier_view<V: Vector>(snap: &Snapshot<V>, ui: &mut egui::Ui) {
    const SHOWN: usize = 12;
    if !snap.cells.is_empty() {
        let cells: Vec<String> = snap
            .cells
            .iter()
            .rev()
            .take(SHOWN)
            .map(|c| format!("({}, {})", c.coords[0], c.coords[1]))
            .collect();
        ui.label(format!(
            "cells along the ray ({}), latest first: {}",
            snap.cells.len(),
            cells.join(", ")
        ));
    }
    let Some(kind) = snap.frontier_kind else {
        return;
    };
    if kind == Frontier::Calls {
        let path: Vec<String> = snap.calls.iter().map(|n| n.0.to_string()).collect();
        ui.colored_label(
            colors::WAITING,
            format!("calls under way (root first): {}", path.join(" > ")),
        );
        return;
    }
    let name = match kind {
        Frontier::Stack => "stack (next first)",
        Frontier::Queue => "priority queue (nearest first)",
        Frontier::Calls => "calls still to make (next first)",
    };
    let items: Vec<String> = snap
        .frontier
        .iter()
        .take(SHOWN)
        .map(|p| {
            if p.key == 0.0 && kind == Frontier::Calls {
                format!("node {}", p.node.0)
            } else {
                format!("node {} ({:.3})", p.node.0, p.key)
            }
        })
        .collect();
    let more = snap.frontier.len().saturating_sub(SHOWN);
    let tail = if more > 0 {
        format!(" … and {more} more")
    } else {
        String::new()
    };
    ui.colored_label(
        colors::WAITING,
        format!(
            "{name}: {}{tail}",
            if items.is_empty() {
                "empty".to_owned()
            } else {
                items.join(", ")
            }
        ),
    );
}

fn best_view<V: Vector>(task: Task, snap: &Snapshot<V>, ui: &mut egui::Ui) {
    let what = match task {
        Task::FirstHit | Task::AnyHit => "best hit so far",
        Task::AllHits => "hits so far",
        Task::Nearest => "nearest so far",
        Task::Range => "inside so far",
        Task::Build => return,
    };
    if snap.best.is_empty() {
        ui.label(format!("{what}: none"));
        return;
    }
    let items: Vec<String> = snap
        .best
        .iter()
        .take(8)
        .map(|(p, v)| match task {
            Task::Range => format!("#{p}"),
            Task::Nearest => format!("#{p} at {v:.3}"),
            _ => format!("#{p} at t = {v:.3}"),
        })
        .collect();
    ui.colored_label(colors::ANSWER, format!("{what}: {}", items.join(", ")));
}
