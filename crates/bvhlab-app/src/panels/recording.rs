//! One lane's recording at the playback step, in the "Step through" panel: the step in
//! words, the pseudocode with the current line, the counters (this step, so far, in all,
//! brute force's), the nodes waiting, the best answer so far, and a build's split.

use bvhlab::Vector;
use egui::RichText;

use super::step_through::variant_label;
use crate::model::recording::Recording;
use crate::model::snapshot::{Counters, Frontier, Snapshot};
use crate::model::structures::StructureKind;
use crate::paint::colors;
use crate::pseudocode::Task;
use crate::pseudocode::describe;

/// One structure's recording at the playback step: the sentence, the listing with its line,
/// the counters, the waiting nodes, the best so far, and a build's split.
pub fn recording_state<V: Vector>(
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
        Some(e) => format!(
            "step {}: {}",
            snap.step,
            describe(e, kind, q.task, q.variant)
        ),
        None => format!("step 0 of {}: nothing done yet", rec.events.len()),
    });
    // The counters come before the listing, so that a short panel (an embedded lab) shows
    // them with the sentence.
    // A build tests nothing: its counters would all be zero.
    if q.task != Task::Build {
        counters_table(rec, snap, kind, index, ui);
    }
    if let Some(code) = crate::pseudocode::pseudocode(kind, q.task, q.variant) {
        pseudocode_view(code, line, index, ui);
    }
    if rec.variant_costs.len() > 1 {
        for (v, c) in &rec.variant_costs {
            ui.label(format!(
                "{}: {} nodes, {} {}, {} primitive tests",
                variant_label(*v),
                c.nodes_visited,
                c.bound_tests,
                kind.bound_tests_name(),
                c.prim_tests
            ));
        }
    }
    frontier_view(snap, ui);
    best_view(rec.question.task, snap, ui);
    if q.task == Task::Build {
        super::split::split_view(rec, kind, snap, index, ui);
    }
}

fn pseudocode_view(
    code: &crate::pseudocode::Pseudocode,
    line: Option<usize>,
    index: usize,
    ui: &mut egui::Ui,
) {
    ui.label(RichText::new(code.title).strong());
    // All of the listing in a tall panel; in a short one, part of it (scrolled to the
    // current line) so that the rest of the panel stays in reach.
    let max_height = (ui.clip_rect().height() * 0.45).max(90.0);
    let palette = crate::theme::code_palette(ui.ctx().theme());
    egui::Frame::new()
        .fill(palette.background)
        .inner_margin(6.0)
        .show(ui, |ui| {
            egui::ScrollArea::both()
                .id_salt(("code", index))
                .max_height(max_height)
                .auto_shrink([false, true])
                // Jumps to the current line: playing at 200 steps a second, an animated
                // scroll would never catch up.
                .animated(false)
                .show(ui, |ui| code_lines(code, line, index, palette, ui));
        });
    if !code.note.is_empty() {
        ui.label(RichText::new(code.note).weak());
    }
}

/// Below this width (points) the counters' headers are shortened so that the brute force
/// column stays in view.
const NARROW_COUNTERS: f32 = 330.0;

/// A counter's name, how to read it from [`Counters`], its total and brute force's.
type CounterRow = (&'static str, fn(&Counters) -> u64, u64, u64);

/// The listing, one unwrapped line per label, the current one marked and scrolled to.
fn code_lines(
    code: &crate::pseudocode::Pseudocode,
    line: Option<usize>,
    index: usize,
    palette: crate::theme::CodePalette,
    ui: &mut egui::Ui,
) {
    ui.spacing_mut().item_spacing.y = 0.0;
    let scrolled = ui.make_persistent_id(("code scrolled to", index));
    for (i, text) in code.lines.iter().enumerate() {
        let current = line == Some(i);
        // The arrow marks the line for screen readers and tests as well as the eye.
        let arrow = if current { '>' } else { ' ' };
        let mut rich = RichText::new(format!("{:>2}{arrow} {text}", i + 1))
            .monospace()
            .color(palette.text);
        if current {
            rich = rich
                .background_color(palette.current_background)
                .color(palette.current_text);
        }
        let response =
            ui.add(egui::Label::new(rich.size(12.0)).wrap_mode(egui::TextWrapMode::Extend));
        // Scrolled to once, when the line changes: scrolling while it looked out of view
        // kept the page repainting when the listing itself was below the panel's edge (out
        // of view whatever the listing's scroll).
        if current && ui.data(|d| d.get_temp::<usize>(scrolled)) != Some(i) {
            ui.data_mut(|d| d.insert_temp(scrolled, i));
            response.scroll_to_me(None);
        }
    }
}

fn counters_table<V: Vector>(
    rec: &Recording<V>,
    snap: &Snapshot<V>,
    kind: StructureKind,
    index: usize,
    ui: &mut egui::Ui,
) {
    let total = rec.cost;
    let brute = rec.brute_cost;
    let build = rec.question.task == Task::Build;
    // A narrow panel (an embedded lab) keeps every column in view with shorter headers.
    // The threshold is for rows named up to "primitive tests"; a k-d or BSP tree's "cell
    // and plane tests" is wider, and so is the table.
    let width = |text: &str| {
        let font = egui::TextStyle::Body.resolve(ui.style());
        ui.fonts_mut(|f| {
            f.layout_no_wrap(text.to_owned(), font, egui::Color32::WHITE)
                .size()
                .x
        })
    };
    let longer = (width(kind.bound_tests_name()) - width("primitive tests")).max(0.0);
    let narrow = ui.available_width() < NARROW_COUNTERS + longer;
    egui::Grid::new(("step counters", index))
        .striped(true)
        .spacing(egui::vec2(if narrow { 6.0 } else { 10.0 }, 4.0))
        .show(ui, |ui| {
            ui.label("");
            if narrow {
                ui.label("step").on_hover_text("this step");
            } else {
                ui.label("this step");
            }
            ui.label("so far");
            // A narrow panel leaves out the total: "so far" reaches it at the last step.
            if !build && !narrow {
                ui.label("total");
            }
            if !build {
                ui.label(if narrow {
                    "brute\nforce"
                } else {
                    "brute force"
                });
            }
            ui.end_row();
            let mut rows: Vec<CounterRow> = vec![
                (
                    kind.nodes_name(),
                    |c| c.nodes,
                    total.nodes_visited,
                    brute.nodes_visited,
                ),
                (
                    kind.bound_tests_name(),
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
            // A structure that lists a primitive in several cells remembers what it tested
            // (mailboxing): the tests it skipped are counted too (brute force skips none).
            if mailboxes(kind) && !build {
                rows.push((
                    "mailbox skips",
                    |c| c.mailbox_skips,
                    mailbox_skips(&rec.events),
                    0,
                ));
            }
            // A range query reports only the volumes it refuses, not every test.
            let unreported = rec.question.task == Task::Range;
            for (name, get, t, b) in rows {
                if narrow {
                    // Two lines ("primitive" over "tests"): the column is half as wide.
                    ui.label(name.replacen(' ', "\n", 1));
                } else {
                    ui.label(name);
                }
                if unreported && name == kind.bound_tests_name() {
                    ui.label("-");
                    ui.label("-");
                } else {
                    ui.label(get(&snap.this_step).to_string());
                    ui.label(get(&snap.so_far).to_string());
                }
                if !build && !narrow {
                    ui.label(t.to_string());
                }
                if !build {
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

/// Whether `kind` lists a primitive in several cells and so skips repeated tests.
fn mailboxes(kind: StructureKind) -> bool {
    matches!(
        kind,
        StructureKind::Grid | StructureKind::KdTree | StructureKind::Quadtree | StructureKind::Bsp
    )
}

/// The primitive tests a recording skipped because the primitive was tested already.
fn mailbox_skips<V: Vector>(events: &[bvhlab::Event<V>]) -> u64 {
    events
        .iter()
        .filter(|e| {
            matches!(
                e,
                bvhlab::Event::PrimitiveTest {
                    result: bvhlab::structure::PrimitiveResult::AlreadyTested,
                    ..
                }
            )
        })
        .count() as u64
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
    let tail = and_more(snap.frontier.len().saturating_sub(SHOWN));
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
    let tail = and_more(snap.best.len().saturating_sub(items.len()));
    ui.colored_label(
        colors::ANSWER,
        format!("{what}: {}{tail}", items.join(", ")),
    );
}

/// What a list cut short says after its last item: ` … and 3 more` (nothing when `more` is 0).
fn and_more(more: usize) -> String {
    if more > 0 {
        format!(" … and {more} more")
    } else {
        String::new()
    }
}
