//! The collision query of two trees in 2D (issue 32, part 2): the selected shapes against
//! the others, with sphere, AABB and OBB trees, answered as brute force over every segment
//! pair (worked out here), after moves of the selection, stepped test by test and drawn.

use bvhlab::glam::Vec2;
use bvhlab::structure::Event;
use bvhlab::{Primitive, Segment2};
use bvhlab_app::LabApp;
use bvhlab_app::model::Action2d;
use bvhlab_app::model::collision::CollisionTree;
use bvhlab_app::model::collision2d::Collision2d;
use bvhlab_app::paint::colors;
use egui::{Color32, Shape};
use egui_kittest::Harness;

use crate::common::{act, click, lab, settle, shows};

/// The pairs (segment of the selection, segment of the rest) that meet, by their places in
/// each side's list, found here from the scene's shapes.
fn brute_pairs(h: &Harness<'_, LabApp>) -> Vec<(usize, usize)> {
    let two = h.state().lab().two();
    let (mut a, mut b): (Vec<Segment2>, Vec<Segment2>) = (Vec::new(), Vec::new());
    for (i, shape) in two.scene.shapes().iter().enumerate() {
        let side = if two.selection.contains(&i) {
            &mut a
        } else {
            &mut b
        };
        side.extend(shape.primitives());
    }
    let mut pairs = Vec::new();
    for (i, sa) in a.iter().enumerate() {
        for (j, sb) in b.iter().enumerate() {
            if sa.intersects(sb) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

/// The line segments painted last frame in `color`, `width` wide.
fn lines_painted(h: &Harness<'_, LabApp>, color: Color32, width: f32) -> usize {
    fn walk(shape: &Shape, color: Color32, width: f32) -> usize {
        match shape {
            Shape::Vec(all) => all.iter().map(|s| walk(s, color, width)).sum(),
            Shape::LineSegment { stroke, .. } => {
                usize::from(stroke.color == color && stroke.width == width)
            }
            _ => 0,
        }
    }
    h.output()
        .shapes
        .iter()
        .map(|c| walk(&c.shape, color, width))
        .sum()
}

#[test]
fn the_selection_against_the_rest_finds_the_pairs_brute_force_finds() {
    let mut h = lab();
    let shapes = h.state().lab().two().scene.shapes().len();
    act(&mut h, Action2d::Select(vec![0, 3, 7]));
    click(
        &mut h,
        "Collision of two trees: the selection (A) against the other shapes (B)",
    );
    settle(&mut h);
    assert!(shapes > 10);
    let mut met = 0;
    for tree in CollisionTree::ALL {
        act(
            &mut h,
            Action2d::SetCollision(Some(Collision2d { tree, step: None })),
        );
        for moves in 0..12 {
            let run = h
                .state()
                .lab()
                .two()
                .collision_run()
                .and_then(|c| c.run.clone())
                .expect("a run");
            assert_eq!(run.pairs, brute_pairs(&h), "{tree:?} after {moves} moves");
            assert_eq!(run.agrees(), Some(true));
            met += usize::from(!run.pairs.is_empty());
            let all = run.so_far(run.events.len());
            assert_eq!(all.meeting as usize, run.pairs.len());
            assert!(shows(
                &h,
                &format!("Same {} pairs as brute force", run.pairs.len())
            ));
            // A step right, as a keyboard user moves A.
            click(&mut h, "A right");
        }
    }
    assert!(met >= 3, "some positions meet: {met}");
}

#[test]
fn the_walk_is_stepped_and_the_pairs_met_are_drawn() {
    let mut h = lab();
    // Shapes 0 and 1 of the random scene, and every shape moved onto the first: pairs meet.
    act(&mut h, Action2d::Select(vec![0]));
    act(
        &mut h,
        Action2d::SetCollision(Some(Collision2d {
            tree: CollisionTree::Aabb,
            step: None,
        })),
    );
    let centre = |h: &Harness<'_, LabApp>, i: usize| {
        let s = &h.state().lab().two().scene.shapes()[i];
        s.points.iter().copied().sum::<Vec2>() / s.points.len() as f32
    };
    let delta = centre(&h, 1) - centre(&h, 0);
    act(&mut h, Action2d::MoveSelection(delta));
    let run = h
        .state()
        .lab()
        .two()
        .collision_run()
        .and_then(|c| c.run.clone())
        .expect("a run");
    assert!(!run.pairs.is_empty(), "A laid over shape 1 meets it");
    // The whole answer is drawn: each pair's two segments, thick, in the answer's colour.
    assert_eq!(lines_painted(&h, colors::ANSWER, 4.0), 2 * run.pairs.len());
    click(&mut h, "First test");
    assert_eq!(lines_painted(&h, colors::ANSWER, 4.0), 0, "nothing met yet");
    click(&mut h, "Next test");
    settle(&mut h);
    assert!(shows(&h, "Nodes A 0 and B 0"));
    let first_pair = run
        .events
        .iter()
        .position(|e| matches!(e, Event::PairTest { .. }))
        .expect("a pair tested");
    for _ in 1..=first_pair {
        click(&mut h, "Next test");
    }
    settle(&mut h);
    assert!(shows(&h, "Segments A "));
    assert_eq!(
        lines_painted(&h, colors::CURRENT, 5.0),
        2,
        "the pair tested, white"
    );
}
