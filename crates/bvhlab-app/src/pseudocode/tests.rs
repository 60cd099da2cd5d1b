//! The listings' shape (every step names one line, lines fit the panel, the slides' lines are
//! verbatim) and the classifiers' reading of hand-made event sequences that real queries
//! produce rarely (the integration test `tests/pseudocode.rs` runs the real ones).

use bvhlab::glam::Vec2;
use bvhlab::structure::{PrimitiveResult, PruneAt, PruneReason};
use bvhlab::{Event, NodeId};

use super::listing::Step;
use super::{Task, Variant, algorithm, line_of, pseudocode, variants};
use crate::model::structures::StructureKind;

const VARIANTS: [Variant; 3] = [Variant::Full, Variant::Lecture, Variant::LecturePruned];

/// Every (kind, task, variant) that has an algorithm.
fn all_algorithms() -> Vec<(StructureKind, Task, Variant)> {
    let mut out = Vec::new();
    for kind in StructureKind::ALL {
        for task in Task::ALL {
            for variant in VARIANTS {
                if algorithm::<Vec2>(kind, task, variant).is_some() {
                    out.push((kind, task, variant));
                }
            }
        }
    }
    out
}

#[test]
fn every_listing_names_each_step_once_and_fits_the_panel() {
    for (kind, task, variant) in all_algorithms() {
        let Some(a) = algorithm::<Vec2>(kind, task, variant) else {
            continue;
        };
        let code = &a.listing.code;
        let what = format!("{kind:?} {task:?} {variant:?}");
        assert_eq!(code.lines.len(), a.listing.steps.len(), "{what}");
        assert!(!code.title.is_empty() && !code.note.is_empty(), "{what}");
        for (i, line) in code.lines.iter().enumerate() {
            assert!(
                line.chars().count() <= 70,
                "{what}: line {i} too long: {line}"
            );
            assert!(
                !line.contains('\t') && line.trim_end() == *line,
                "{what}: {line:?}"
            );
        }
        for (i, step) in a.listing.steps.iter().enumerate() {
            if *step != Step::Plain {
                assert_eq!(a.listing.line(*step), Some(i), "{what}: {step:?} twice");
            }
        }
        assert_eq!(a.listing.line(Step::Plain), None);
    }
}

#[test]
fn full_exists_everywhere_and_the_slides_only_for_bvh_first_hit_and_nearest() {
    for kind in StructureKind::ALL {
        for task in Task::ALL {
            let found = variants(kind, task);
            let mut expected = vec![Variant::Full];
            if kind.is_bvh() && task == Task::FirstHit {
                expected.push(Variant::Lecture);
            }
            if kind.is_bvh() && task == Task::Nearest {
                expected.extend([Variant::Lecture, Variant::LecturePruned]);
            }
            assert_eq!(found, expected, "{kind:?} {task:?}");
            for variant in VARIANTS {
                assert_eq!(
                    pseudocode(kind, task, variant).is_some(),
                    expected.contains(&variant),
                    "{kind:?} {task:?} {variant:?}"
                );
            }
        }
    }
    // The three BVHs share their text; k-d and BSP trees share their queries.
    let shared =
        |a, b, task| pseudocode(a, task, Variant::Full) == pseudocode(b, task, Variant::Full);
    assert!(shared(
        StructureKind::SphereTree,
        StructureKind::ObbTree,
        Task::Nearest
    ));
    assert!(shared(
        StructureKind::KdTree,
        StructureKind::Bsp,
        Task::FirstHit
    ));
    assert!(!shared(
        StructureKind::KdTree,
        StructureKind::Bsp,
        Task::Build
    ));
}

/// The slide's lines, from LECTURE.md §3.
const SLIDE_INTERSECT: &[&str] = &[
    "intersect(bvNode, ray, t)",
    "{",
    "    if (bvNode == null || !bvNode.intersect(ray, t))",
    "        return false;",
    "    else",
    "    {",
    "        i1 = intersect(bvNode.left, ray, t1);   // check left BV",
    "        i2 = intersect(bvNode.right, ray, t2);  // check right BV",
    "        if (i1 && i2) { t = min(t1, t2); return true; }",
    "        if (i1) { t = t1; return true; }",
    "        if (i2) { t = t2; return true; }",
    "        return false;",
    "    }",
    "}",
];

/// The slide's lines, from LECTURE.md §3.
const SLIDE_MIN_DISTANCE: &[&str] = &[
    "minDistance(bvNode, point, currentMin)",
    "{",
    "    d1 = minDistance(bvNode.left, point, currentMin);",
    "    d2 = minDistance(bvNode.right, point, currentMin);",
    "    if (min(d1, d2) > currentMin) {",
    "        return currentMin",
    "    }",
    "    return min(d1, d2)",
    "}",
];

#[test]
fn the_lecture_variants_are_the_slides_plus_marked_lines() {
    let cases = [
        (Task::FirstHit, Variant::Lecture, SLIDE_INTERSECT),
        (Task::Nearest, Variant::Lecture, SLIDE_MIN_DISTANCE),
        (Task::Nearest, Variant::LecturePruned, SLIDE_MIN_DISTANCE),
    ];
    for (task, variant, slide) in cases {
        let code = pseudocode(StructureKind::AabbTree, task, variant).expect("exists");
        let on_slide: Vec<&str> = code
            .lines
            .iter()
            .copied()
            .filter(|l| !l.ends_with("// not on the slide"))
            .collect();
        assert_eq!(on_slide, slide, "{task:?} {variant:?}");
        assert!(code.lines.len() > slide.len(), "the leaf case is added");
    }
}

/// The text of the line `events[step]` highlights.
fn text(kind: StructureKind, task: Task, events: &[Event<Vec2>], step: usize) -> &'static str {
    let line = line_of(kind, task, Variant::Full, events, step).expect("a line");
    pseudocode(kind, task, Variant::Full).expect("exists").lines[line]
}

const fn prune(node: u32, reason: PruneReason, at: PruneAt) -> Event<Vec2> {
    Event::Prune {
        node: NodeId(node),
        reason,
        at,
    }
}

const fn enter(node: u32) -> Event<Vec2> {
    Event::EnterNode {
        node: NodeId(node),
        depth: 1,
    }
}

const fn distance_test(node: u32) -> Event<Vec2> {
    Event::DistanceBoundTest {
        node: NodeId(node),
        distance: 1.0,
    }
}

// The two tests below once checked how the classifiers told these prunes apart from the
// events before them; a prune now says where it happened, and they check that this alone
// decides the line, whatever came before.

#[test]
fn a_plane_tree_first_hit_reads_the_end_of_the_search_from_the_prune() {
    let beyond = PruneReason::BeyondBestHit {
        t_enter: 5.0,
        best_t: 2.0,
    };
    let hit = Event::PrimitiveTest {
        prim: 3,
        result: PrimitiveResult::Hit(2.0),
    };
    let kd = StructureKind::KdTree;
    // After a leaf's tests: the hit is final, and everything left is skipped.
    let events = [
        enter(4),
        hit,
        prune(5, beyond, PruneAt::Stop),
        prune(6, beyond, PruneAt::Stop),
    ];
    assert!(text(kd, Task::FirstHit, &events, 2).contains("return hit"));
    assert!(text(kd, Task::FirstHit, &events, 3).contains("return hit"));
    // A region popped behind the best hit, after an inner node's children were queued or
    // right after a leaf's tests alike.
    let queued = Event::ChildQueued {
        parent: NodeId(4),
        child: NodeId(5),
        key: 5.0,
        rank: 0,
    };
    let events = [
        enter(4),
        Event::PlaneCrossed {
            node: NodeId(4),
            t: 5.0,
        },
        queued,
        prune(5, beyond, PruneAt::Pop),
    ];
    assert!(text(kd, Task::FirstHit, &events, 3).contains("continue"));
    let events = [enter(4), hit, prune(5, beyond, PruneAt::Pop)];
    assert!(text(kd, Task::FirstHit, &events, 2).contains("continue"));
    // All hits never stops early.
    assert!(text(kd, Task::AllHits, &events, 2).contains("continue"));
}

#[test]
fn a_quadtree_nearest_reads_a_childs_prune_and_the_end_of_the_search_from_the_prune() {
    let no_nearer = PruneReason::NoNearer {
        distance: 3.0,
        best: 1.0,
    };
    let q = StructureKind::Quadtree;
    // The children are measured, then queued or pruned at their test, nearest first.
    let events = [
        enter(0),
        distance_test(1),
        distance_test(2),
        distance_test(3),
        distance_test(4),
        Event::ChildQueued {
            parent: NodeId(0),
            child: NodeId(2),
            key: 0.0,
            rank: 0,
        },
        prune(4, no_nearer, PruneAt::Test),
    ];
    assert!(text(q, Task::Nearest, &events, 6).contains("skip c"));
    assert!(text(q, Task::Nearest, &events[..6], 5).contains("push"));
    // A popped cell no nearer than the best: the search ends.
    let ended = [
        enter(2),
        distance_test(5),
        prune(3, no_nearer, PruneAt::Pop),
    ];
    assert!(text(q, Task::Nearest, &ended, 2).contains("return best"));
    // The root, pruned at its pop (unplaced primitives already gave a nearer best).
    let root = [distance_test(0), prune(0, no_nearer, PruneAt::Pop)];
    assert!(text(q, Task::Nearest, &root, 1).contains("return best"));
}

#[test]
fn a_prune_reads_the_same_line_whatever_comes_before_it() {
    let missed = prune(7, PruneReason::RayMissed, PruneAt::Test);
    let hit = Event::PrimitiveTest {
        prim: 1,
        result: PrimitiveResult::Hit(1.0),
    };
    for before in [vec![], vec![enter(3)], vec![enter(3), hit]] {
        let mut events = before.clone();
        events.push(missed);
        let step = events.len() - 1;
        let bvh = text(StructureKind::AabbTree, Task::FirstHit, &events, step);
        assert!(bvh.contains("the ray misses c"), "{before:?}: {bvh}");
        let quad = text(StructureKind::Quadtree, Task::FirstHit, &events, step);
        assert!(quad.contains("misses c"), "{before:?}: {quad}");
    }
}

#[test]
fn events_an_algorithm_does_not_emit_have_no_line() {
    let pair = Event::<Vec2>::PairTest {
        a: 0,
        b: 1,
        overlap: true,
    };
    for (kind, task, variant) in all_algorithms() {
        assert_eq!(line_of(kind, task, variant, &[pair], 0), None);
        assert_eq!(
            line_of(kind, task, variant, &[pair], 1),
            None,
            "past the end"
        );
    }
    let cross = [Event::<Vec2>::PlaneCrossed {
        node: NodeId(0),
        t: 1.0,
    }];
    assert_eq!(
        line_of(
            StructureKind::AabbTree,
            Task::FirstHit,
            Variant::Full,
            &cross,
            0
        ),
        None
    );
    assert_eq!(
        line_of(
            StructureKind::Grid,
            Task::FirstHit,
            Variant::Lecture,
            &[enter(0)],
            0
        ),
        None
    );
}

/// Issue 21: the grid's walk read "stop, skipping node 1"; a grid's nodes are its cells.
#[test]
fn a_grid_step_names_cells_and_a_tree_step_names_nodes() {
    let stop: Event<Vec2> = Event::Prune {
        node: NodeId(1),
        reason: PruneReason::RayMissed,
        at: PruneAt::Stop,
    };
    let grid = super::describe(&stop, StructureKind::Grid, Task::FirstHit, Variant::Full);
    assert!(grid.starts_with("stop, skipping cell 1"), "{grid}");
    let tree = super::describe(&stop, StructureKind::KdTree, Task::FirstHit, Variant::Full);
    assert!(tree.starts_with("stop, skipping node 1"), "{tree}");
}
