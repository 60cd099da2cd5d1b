//! The collision query's walk, stepped in either half: the buttons, the step in words, and
//! the counts so far and in all beside brute force's.

use bvhlab::Vector;
use bvhlab::structure::Event;
use egui::Grid;

use crate::model::collision::{BRUTE_FORCE_PAIRS_CAP, CollisionRun, CollisionSoFar, CollisionTree};

/// Which BVH both sides are built as, one radio button each.
pub(super) fn tree_choice(ui: &mut egui::Ui, tree: &mut CollisionTree) {
    ui.horizontal_wrapped(|ui| {
        ui.label("Both trees are");
        for kind in CollisionTree::ALL {
            ui.radio_value(tree, kind, kind.label());
        }
    });
}

/// The walk, step by step: the buttons (which set `step`: `None` is the whole walk), the
/// step in words, and the counts so far and in all beside brute force's; `primitive` names
/// what the trees hold ("triangle", "segment").
pub(super) fn stepper<V: Vector>(
    ui: &mut egui::Ui,
    run: &CollisionRun<V>,
    step: &mut Option<usize>,
    primitive: &str,
) {
    let total = run.events.len();
    let shown = step.map_or(total, |s| s.min(total));
    ui.horizontal_wrapped(|ui| {
        if ui.button("First test").clicked() {
            *step = Some(0);
        }
        if ui.button("Previous test").clicked() {
            *step = Some(shown.saturating_sub(1));
        }
        if ui.button("Next test").clicked() {
            *step = (shown + 1 < total).then_some(shown + 1);
        }
        if ui.button("All tests (the answer)").clicked() {
            *step = None;
        }
        ui.label(format!("step {shown} of {total}"));
    });
    ui.label(describe(run, shown, primitive));
    pseudocode(ui, current_line(run, shown));
    let now = run.so_far(shown);
    let all = run.so_far(total);
    counts(ui, now, all, run, primitive);
}

/// The walk as pseudocode (the core's `collide`, after Gottschalk, Lin and Manocha's `OBBTree`
/// descent: open the larger node).
const PSEUDOCODE: [&str; 11] = [
    "collide(A, B)                            // the collision query",
    "    stack = [(A.root, B.root)]",
    "    while (stack not empty)",
    "        (a, b) = stack.pop()",
    "        if (!a.bv.overlaps(b.bv)) continue   // disjoint: cut off",
    "        if (a and b are leaves)",
    "            for (p in a.prims, q in b.prims)",
    "                if (p.intersects(q)) add (p, q)",
    "        else",
    "            open the larger: push each child with the other",
    "    return the pairs added",
];

/// The line of [`PSEUDOCODE`] the step shown is at.
fn current_line<V: Vector>(run: &CollisionRun<V>, shown: usize) -> usize {
    if shown >= run.events.len() {
        return 10;
    }
    match shown.checked_sub(1).and_then(|i| run.events.get(i)) {
        None => 1,
        Some(Event::NodePairTest { overlap: false, .. }) => 4,
        Some(Event::NodePairTest { overlap: true, .. }) => {
            if matches!(run.events.get(shown), Some(Event::PairTest { .. })) {
                5
            } else {
                9
            }
        }
        Some(_) => 7,
    }
}

/// The pseudocode, the line at the step marked with `>` (not by colour alone).
fn pseudocode(ui: &mut egui::Ui, current: usize) {
    egui::Frame::NONE
        .fill(ui.visuals().extreme_bg_color)
        .inner_margin(egui::Margin::same(4))
        .show(ui, |ui| {
            for (i, line) in PSEUDOCODE.iter().enumerate() {
                let text = format!(
                    "{}{:>2} {line}",
                    if i == current { ">" } else { " " },
                    i + 1
                );
                let mut rich = egui::RichText::new(text).monospace();
                if i == current {
                    rich = rich.background_color(ui.visuals().selection.bg_fill);
                }
                ui.label(rich);
            }
        });
}

/// The event just shown, in words.
fn describe<V: Vector>(run: &CollisionRun<V>, shown: usize, primitive: &str) -> String {
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
             its children paired with the other (two leaves: their {primitive}s are tested).",
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
            "{}s A {a} and B {b}: {}.",
            capitalised(primitive),
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
fn counts<V: Vector>(
    ui: &mut egui::Ui,
    now: CollisionSoFar,
    all: CollisionSoFar,
    run: &CollisionRun<V>,
    primitive: &str,
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
        let pairs_tested = format!("{primitive} pairs tested");
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
                pairs_tested.as_str(),
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
            "Same {} pairs as brute force, with {} of its {} {primitive} tests.",
            run.pairs.len(),
            all.primitive_pairs,
            run.brute_tests
        ),
        Some(false) => {
            "The trees' answer differs from brute force's: please report this.".to_owned()
        }
        None => format!(
            "Brute force would test all {} {primitive} pairs; it runs up to {}.",
            run.brute_tests, BRUTE_FORCE_PAIRS_CAP
        ),
    });
}

/// `word` with its first letter in upper case.
fn capitalised(word: &str) -> String {
    let mut chars = word.chars();
    chars
        .next()
        .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}
