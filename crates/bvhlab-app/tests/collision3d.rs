//! The collision query of two trees in 3D (issue 32, part 2): a brushed part of the bunny
//! against a moved and turned copy, with sphere, AABB and OBB trees, answered as brute force
//! over every triangle pair (worked out here), stepped test by test, and drawn.

use bvhlab::glam::{EulerRot, Mat3, Vec3};
use bvhlab::structure::Event;
use bvhlab::{Primitive, Triangle3};
use bvhlab_app::LabApp;
use bvhlab_app::model::collision::CollisionTree;
use bvhlab_app::model::collision3d::Collision3d;
use bvhlab_app::model::{Action3d, HalfAction};
use bvhlab_app::paint::colors;
use egui_kittest::Harness;

use crate::common::{act, click, labels, settle, shows};
use crate::view3d::{lab_3d, three};

/// The lab in 3D with the bunny's brush showing its volumes, about `q` with radius `r`, and
/// the collision query on.
fn brushed(q: Vec3, r: f32) -> Harness<'static, LabApp> {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "the brush (triangles within r of q)");
    act(&mut h, Action3d::SetPoint(Some(q)));
    act(&mut h, HalfAction::SetRadius(r));
    click(
        &mut h,
        "Collision of two trees: the part (A) against a moved copy (B)",
    );
    settle(&mut h);
    h
}

/// The pairs of the part's triangles and the copy's that meet, found here: the copy placed
/// with a rotation matrix of its own (not the lab's quaternion), every pair tested.
fn brute_pairs(h: &Harness<'_, LabApp>, c: &Collision3d) -> Vec<(usize, usize)> {
    let lab = three(h);
    let part: Vec<Triangle3> = lab
        .part_fits()
        .expect("shown")
        .triangles
        .iter()
        .map(|&t| lab.triangles()[t as usize])
        .collect();
    let corners: Vec<Vec3> = part.iter().flat_map(|t| [t.a, t.b, t.c]).collect();
    let lo = corners.iter().fold(Vec3::INFINITY, |m, p| m.min(*p));
    let hi = corners.iter().fold(Vec3::NEG_INFINITY, |m, p| m.max(*p));
    let pivot = (lo + hi) * 0.5;
    let r = c.degrees * (std::f32::consts::PI / 180.0);
    let turn = Mat3::from_euler(EulerRot::XYZ, r.x, r.y, r.z);
    let at = |p: Vec3| turn * (p - pivot) + pivot + c.offset;
    let copy: Vec<Triangle3> = part
        .iter()
        .map(|t| Triangle3::new(at(t.a), at(t.b), at(t.c)))
        .collect();
    let mut pairs = Vec::new();
    for (i, a) in part.iter().enumerate() {
        for (j, b) in copy.iter().enumerate() {
            if a.intersects(b) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

fn collision(h: &Harness<'_, LabApp>) -> Collision3d {
    three(h).collision.expect("on")
}

#[test]
fn every_kind_of_tree_finds_the_pairs_brute_force_finds() {
    let q = Vec3::new(2.1, 5.3, -0.9);
    let mut h = brushed(q, 2.5);
    let size = three(&h).part_fits().expect("shown").triangles.len();
    assert!((200..1_000).contains(&size), "a part of {size} triangles");
    let mut met = 0;
    for (k, tree) in CollisionTree::ALL.into_iter().enumerate() {
        for (offset, degrees) in [
            (Vec3::new(1.0, 0.2, 0.0), Vec3::new(0.0, 30.0, 0.0)),
            (Vec3::new(0.3, -0.4, 0.5), Vec3::new(20.0, -10.0, 75.0)),
            (Vec3::new(40.0, 0.0, 0.0), Vec3::ZERO),
        ] {
            let c = Collision3d {
                offset,
                degrees,
                tree,
                step: None,
            };
            act(&mut h, Action3d::SetCollision(Some(c)));
            let expected = brute_pairs(&h, &c);
            let cache = three(&h).collision_run().expect("on");
            let run = cache.run.as_ref().expect("a run");
            // Within the rounding of two ways to turn the copy: the same pairs, or one pair
            // more or less that only touch.
            let differ = run.pairs.iter().filter(|p| !expected.contains(p)).count()
                + expected.iter().filter(|p| !run.pairs.contains(p)).count();
            assert!(
                differ <= 1,
                "{tree:?} {offset} {degrees}: {} against {}",
                run.pairs.len(),
                expected.len()
            );
            assert_eq!(run.agrees(), Some(true), "the lab's own brute force");
            met += usize::from(!run.pairs.is_empty());
            // The counts in the panel are the walk's.
            let all = run.so_far(run.events.len());
            assert_eq!(all.node_pairs, run.cost.bound_tests);
            assert_eq!(all.primitive_pairs, run.cost.prim_tests);
            assert_eq!(all.meeting as usize, run.pairs.len());
            assert!(
                all.primitive_pairs < run.brute_tests,
                "the trees test fewer pairs"
            );
            assert!(shows(
                &h,
                &format!("Same {} pairs as brute force", run.pairs.len())
            ));
            if offset.x > 10.0 {
                // Far apart: the roots are disjoint, and that is the whole walk.
                assert_eq!((all.node_pairs, all.disjoint), (1, 1), "{tree:?}");
            }
        }
        assert_eq!(met, 2 * (k + 1), "the two near copies meet A");
    }
}

#[test]
fn the_walk_is_stepped_test_by_test_and_drawn() {
    let mut h = brushed(Vec3::new(2.1, 5.3, -0.9), 2.0);
    click(&mut h, "First test");
    settle(&mut h);
    assert_eq!(collision(&h).step, Some(0));
    assert!(shows(&h, "the walk starts with the two roots"));
    click(&mut h, "Next test");
    settle(&mut h);
    // The roots, drawn in the colour of their verdict.
    let run = three(&h)
        .collision_run()
        .and_then(|c| c.run.clone())
        .expect("a run");
    let Event::NodePairTest { a, b, overlap } = run.events[0] else {
        panic!("the walk starts with a node pair: {:?}", run.events[0]);
    };
    assert_eq!((a.0, b.0), (0, 0));
    let verdict = bvhlab_app::lab3d::draw::rgba(
        if overlap {
            colors::VISITED
        } else {
            colors::CULLED
        },
        1.0,
    );
    let drawn = &h.state().ui.view3d.drawn[0];
    assert!(
        drawn
            .overlay
            .iter()
            .filter(|s| s.color == verdict && s.width == 2.5)
            .count()
            >= 24,
        "both roots' edges"
    );
    assert!(shows(&h, "Nodes A 0 and B 0"));
    // The pseudocode marks where the walk is: the roots overlap, so the larger is opened.
    assert!(overlap, "the near copy's roots overlap");
    assert!(
        shows(&h, ">10             open the larger"),
        "{:?}",
        labels(&h)
            .iter()
            .filter(|l| l.contains("open the larger"))
            .collect::<Vec<_>>()
    );
    // Step on to the first triangle pair: the counts so far follow the events.
    let first_pair = run
        .events
        .iter()
        .position(|e| matches!(e, Event::PairTest { .. }))
        .expect("the near copy is met");
    for _ in 1..=first_pair {
        click(&mut h, "Next test");
    }
    settle(&mut h);
    assert_eq!(collision(&h).step, Some(first_pair + 1));
    let so_far = run.so_far(first_pair + 1);
    assert_eq!(so_far.primitive_pairs, 1);
    assert!(shows(&h, "Triangles A "));
    assert!(shows(&h, "> 8                 if (p.intersects(q))"));
    let lit: Vec<u32> = h.state().ui.view3d.drawn[0]
        .highlights
        .iter()
        .map(|&(t, _)| t)
        .collect();
    let Event::PairTest { a, .. } = run.events[first_pair] else {
        unreachable!()
    };
    let cache_part = three(&h).collision_run().expect("on").part.clone();
    assert!(
        lit.contains(&cache_part[a as usize]),
        "A's triangle tested is lit"
    );
    click(&mut h, "All tests (the answer)");
    settle(&mut h);
    assert_eq!(collision(&h).step, None);
    assert!(shows(&h, ">11     return the pairs added"));
    assert!(
        labels(&h).iter().any(|l| l.contains("triangles meeting")),
        "the legend names it"
    );
    // A copy moved by a number that is not one is refused.
    let mut bad = collision(&h);
    bad.offset.x = f32::NAN;
    assert!(
        h.state_mut()
            .apply(Action3d::SetCollision(Some(bad)))
            .is_err()
    );
}

#[test]
fn an_empty_part_still_turns_the_query_on_and_a_brush_asked_for_starts_on_the_mesh() {
    // The brush off the mesh holds nothing: the query still turns on, and says so.
    let h = brushed(Vec3::splat(500.0), 1.0);
    assert!(three(&h).part_fits().expect("shown").fits.is_none());
    let c = collision(&h);
    assert!(c.is_valid(), "{c:?}");
    assert!(shows(&h, "The part is empty"));
    // The address's volumes=brush, with no point: the point the lab puts beside a new mesh
    // goes onto it, so the brush holds triangles from the start.
    let mut lab = bvhlab_app::model::Lab::default();
    let setup = bvhlab_app::model::Setup {
        mesh: Some("bunny".to_owned()),
        volumes: Some(bvhlab_app::model::volumes3d::Part3d::Brush),
        ..bvhlab_app::model::Setup::default()
    };
    assert!(lab.apply_setup(&setup, "the address").is_empty());
    crate::common::tick_lab(&mut lab);
    lab.apply(Action3d::Frame { aspect: 1.5 }.into())
        .expect("framed");
    crate::common::tick_lab(&mut lab);
    let part = lab.three().part_fits().expect("shown");
    assert!(!part.triangles.is_empty(), "the brush starts on the mesh");
}
