//! Headless UI tests of the lab (issue 4): the app driven as a student drives it, through the
//! pointer, the keyboard and the widgets, with what the panels show checked against the core
//! (the app's query outcomes, its scene, and a brute force run here on the scene's primitives).

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, BruteForce, Hit, Nearest, Ray2, SpatialIndex};
use bvhlab_app::LabApp;
use bvhlab_app::lab2d::Interaction;
use bvhlab_app::model::scene::ShapeKind;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::tools::Tool;
use egui::accesskit::Role;
use egui::{Key, Pos2, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use crate::common;
use common::*;

/// Brute force over the app's current scene, built here from the scene (not the app's copy).
fn scene_brute(app: &LabApp) -> BruteForce<bvhlab::Segment2> {
    BruteForce::build(&app.lab().two().scene.primitives().segments)
}

/// The first hit of `ray` by brute force over the app's scene.
fn brute_hit(app: &LabApp, ray: &Ray2) -> Option<Hit> {
    scene_brute(app)
        .ray_first_hit_observed(ray, f32::INFINITY, &mut ())
        .answer
}

/// The `k` nearest primitives of `q` by brute force over the app's scene.
fn brute_nearest(app: &LabApp, q: Vec2, k: usize) -> Vec<Nearest<Vec2>> {
    scene_brute(app).k_nearest_observed(q, k, &mut ()).answer
}

/// The hit line the Queries panel shows for `hit` on `ray`.
fn hit_text(app: &LabApp, ray: &Ray2, hit: Hit) -> String {
    let p = ray.at(hit.t);
    let shape = app.lab().two().scene.primitives().owner[hit.prim];
    format!(
        "Hit: primitive {} (shape {shape}) at t = {:.4}, point ({:.3}, {:.3})",
        hit.prim, hit.t, p.x, p.y
    )
}

/// The ray and point counters grids: (name, structure, brute force) per row, ray first.
fn counter_rows(h: &Harness<'_, LabApp>) -> Vec<(String, u64, u64)> {
    let mut all = labels(h);
    // The "Step through" panel has its own counters, per step; these are the query panel's.
    if let Some(end) = all.iter().position(|l| l == "Step through") {
        all.truncate(end);
    }
    let mut rows = Vec::new();
    for (i, l) in all.iter().enumerate() {
        if COUNTER_NAMES.contains(&l.as_str()) {
            let n = |j: usize| {
                all[i + j]
                    .parse::<u64>()
                    .unwrap_or_else(|e| panic!("{l}: {:?} is not a count ({e})", all[i + j]))
            };
            rows.push((l.clone(), n(1), n(2)));
        }
    }
    rows
}

/// The "N shapes, M primitives" line.
fn scene_line(shapes: usize, prims: usize) -> String {
    format!("{shapes} shapes, {prims} primitives")
}

/// A screen point in the canvas's margin left of the default scene, `dy` points down.
fn empty_margin(h: &Harness<'_, LabApp>, dy: f32) -> Pos2 {
    let rect = h.state().canvas_screen().rect;
    let p = pos2(rect.left() + 20.0, rect.top() + 40.0 + dy);
    let (lo, _) = LabApp::default()
        .lab()
        .two()
        .scene
        .bounds()
        .expect("a scene");
    assert!(world(h, p).x < lo.x, "the margin is left of the scene");
    assert!(world(h, p + vec2(30.0, 0.0)).x < lo.x, "and wide enough");
    p
}

#[test]
fn a_first_visit_opens_on_a_lecture_figure_and_offers_the_first_lesson() {
    let h = fresh_lab();
    let two = h.state().lab().two();
    // A handful of shapes under an AABB tree small enough to read every box and node.
    assert_eq!(two.preset, bvhlab_app::model::presets::Preset::BvhHandful);
    assert!(
        (5..=20).contains(&two.scene.shapes().len()),
        "{} shapes",
        two.scene.shapes().len()
    );
    assert_eq!(two.half.lane.settings.kind, StructureKind::AabbTree);
    let nodes = two.half.lane.structure.as_ref().expect("built").stats.nodes;
    assert!(nodes <= 64, "{nodes} nodes");
    assert_eq!(
        h.get_by_label("Preset").accesskit_node().value(),
        Some("AABB tree on a handful of shapes (§3)".to_owned())
    );
    // The Lessons panel says what a lesson is and offers the first one.
    label_containing(&h, "New here? A lesson walks the lecture");
    let first = h.get_by_label("1. §1 Queries: why not test every primitive?");
    assert_eq!(first.accesskit_node().role(), Role::Button);
}

#[test]
fn start_up_and_a_dragged_ray_show_the_core_answer_and_its_cost() {
    let mut h = lab();
    // Start-up: the default scene, structure and tool, and the panels say so.
    assert_eq!(h.state().lab().two().scene.shapes().len(), 200);
    assert_eq!(h.state().lab().two().tool, Tool::Ray);
    assert_eq!(
        h.state().lab().two().half.lane.settings.kind,
        StructureKind::AabbTree
    );
    label_containing(&h, &scene_line(200, 200));
    assert_eq!(
        h.get_by_label("Structure").accesskit_node().value(),
        Some("AABB tree".to_owned())
    );
    assert_eq!(
        h.get_by_label("Preset").accesskit_node().value(),
        Some("200 random segments".to_owned())
    );
    assert!(shows(
        &h,
        "Use the Ray tool or the Query point tool on the canvas."
    ));
    assert!(h.state().lab().two().half.lane.ray_outcome.is_none());

    let ray = drag_test_ray(&mut h);
    let app = h.state();
    let outcome = app
        .lab()
        .two()
        .half
        .lane
        .ray_outcome
        .as_ref()
        .expect("the ray was answered");
    assert_eq!(outcome.ray, ray);
    let hit = outcome.hit.expect("this ray crosses the scene");
    assert_eq!(Some(hit), brute_hit(app, &ray), "the structure's hit");
    assert_eq!(
        label_containing(&h, "Hit: primitive"),
        hit_text(app, &ray, hit)
    );
    let rows = counter_rows(&h);
    assert_eq!(
        rows,
        vec![
            (
                "nodes visited".to_owned(),
                outcome.cost.nodes_visited,
                outcome.brute_cost.nodes_visited
            ),
            (
                "BV tests".to_owned(),
                outcome.cost.bound_tests,
                outcome.brute_cost.bound_tests
            ),
            (
                "primitive tests".to_owned(),
                outcome.cost.prim_tests,
                outcome.brute_cost.prim_tests
            ),
        ]
    );
    // Brute force tests every primitive; the tree fewer.
    assert_eq!(outcome.brute_cost.prim_tests, 200);
    assert!(outcome.cost.prim_tests < 200);
    assert!(outcome.cost.nodes_visited > 0);
    label_containing(&h, "Same answer as brute force.");
    // The legend counts what the canvas marks.
    label_containing(&h, &format!("visited {}", outcome.cost.nodes_visited));
    label_containing(
        &h,
        &format!("primitives tested {}", outcome.cost.prim_tests),
    );
    // The report for the page agrees.
    let report = app.report.query.as_ref().expect("reported");
    assert_eq!(report.hit.as_ref().map(|r| r.primitive), Some(hit.prim));
    assert!(report.agrees);

    // Dragging the ray's target handle moves only the target.
    let target = h.state().lab().two().ray.expect("ray").target;
    let new_target = Vec2::new(20.0, 4.0);
    let (a, b) = (screen(&h, target), screen(&h, new_target));
    drag(&mut h, a, b);
    let handles = h.state().lab().two().ray.expect("ray");
    assert_eq!(handles.origin, ray.origin(), "the origin stays");
    assert!((handles.target - new_target).length() < 1e-3, "{handles:?}");
    let outcome = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .ray_outcome
        .as_ref()
        .expect("answered");
    let moved = handles.ray().expect("valid");
    assert_eq!(outcome.ray, moved);
    assert_eq!(outcome.hit, brute_hit(h.state(), &moved));
}

#[test]
fn every_structure_from_the_combo_gives_brute_forces_first_hit() {
    let mut h = lab();
    let ray = drag_test_ray(&mut h);
    let expected = brute_hit(h.state(), &ray).expect("this ray crosses the scene");
    for kind in StructureKind::ALL {
        choose(&mut h, "Structure", kind.label());
        assert_eq!(
            h.state().lab().two().half.lane.settings.kind,
            kind,
            "the combo picked {kind:?}"
        );
        assert_eq!(
            h.get_by_label("Structure").accesskit_node().value(),
            Some(kind.label().to_owned())
        );
        let app = h.state();
        assert_eq!(
            app.lab()
                .two()
                .half
                .lane
                .structure
                .as_ref()
                .map(|b| b.settings.kind),
            Some(kind),
            "rebuilt"
        );
        let outcome = app
            .lab()
            .two()
            .half
            .lane
            .ray_outcome
            .as_ref()
            .expect("answered");
        assert_eq!(outcome.hit, Some(expected), "{kind:?}");
        assert_eq!(
            label_containing(&h, "Hit: primitive"),
            hit_text(app, &ray, expected),
            "{kind:?}"
        );
        label_containing(&h, "Same answer as brute force.");
        let rows = counter_rows(&h);
        assert_eq!(rows[2].1, outcome.cost.prim_tests, "{kind:?}");
        assert_eq!(rows[2].2, 200, "{kind:?}");
    }
}

#[test]
fn drawing_segments_polygons_and_points() {
    let mut h = lab();
    // Segment: a drag in the empty margin adds one segment from the press to the release.
    click(&mut h, "Segment");
    assert_eq!(h.state().lab().two().tool, Tool::Segment);
    assert!(shows(&h, "Drag to draw a segment."));
    let (a, b) = (empty_margin(&h, 0.0), empty_margin(&h, 200.0));
    drag(&mut h, a, b);
    let app = h.state();
    assert_eq!(app.lab().two().scene.shapes().len(), 201);
    let seg = app.lab().two().scene.shapes().last().expect("added");
    assert_eq!(seg.kind, ShapeKind::Segment);
    assert_eq!(seg.points, vec![world(&h, a), world(&h, b)]);
    label_containing(&h, &scene_line(201, 201));

    // Polygon: three clicks and Enter close a triangle with those corners.
    click(&mut h, "Polygon");
    let corners = [
        empty_margin(&h, 300.0),
        empty_margin(&h, 300.0) + vec2(30.0, 60.0),
        empty_margin(&h, 380.0),
    ];
    for &c in &corners {
        click_at(&mut h, c);
    }
    assert!(matches!(&h.state().ui.canvas.interaction, Interaction::Chain(p) if p.len() == 3));
    assert_eq!(
        h.state().lab().two().scene.shapes().len(),
        201,
        "not closed yet"
    );
    press(&mut h, Key::Enter);
    let app = h.state();
    assert_eq!(app.ui.canvas.interaction, Interaction::None);
    let polygon = app.lab().two().scene.shapes().last().expect("added");
    assert_eq!(polygon.kind, ShapeKind::Polygon);
    let expected: Vec<Vec2> = corners.iter().map(|&c| world(&h, c)).collect();
    assert_eq!(polygon.points, expected);
    label_containing(&h, &scene_line(202, 204));

    // Esc cancels a chain: nothing is added, and Enter afterwards adds nothing either.
    click(&mut h, "Polyline");
    let start = empty_margin(&h, 450.0);
    click_at(&mut h, start);
    click_at(&mut h, start + vec2(20.0, 40.0));
    assert!(matches!(&h.state().ui.canvas.interaction, Interaction::Chain(p) if p.len() == 2));
    press(&mut h, Key::Escape);
    assert_eq!(h.state().ui.canvas.interaction, Interaction::None);
    press(&mut h, Key::Enter);
    assert_eq!(h.state().lab().two().scene.shapes().len(), 202);
    label_containing(&h, &scene_line(202, 204));

    // Points: three clicks make one cloud of three points.
    click(&mut h, "Points");
    let dots = [
        empty_margin(&h, 520.0),
        empty_margin(&h, 560.0),
        empty_margin(&h, 600.0),
    ];
    for &d in &dots {
        click_at(&mut h, d);
    }
    let app = h.state();
    assert_eq!(app.lab().two().scene.shapes().len(), 203, "one cloud");
    let cloud = app.lab().two().scene.shapes().last().expect("added");
    assert_eq!(cloud.kind, ShapeKind::Points);
    let expected: Vec<Vec2> = dots.iter().map(|&d| world(&h, d)).collect();
    assert_eq!(cloud.points, expected);
    label_containing(&h, &scene_line(203, 207));
}

#[test]
fn select_moves_and_deletes_a_shape() {
    let mut h = lab();
    click(&mut h, "Select / move");
    assert_eq!(h.state().lab().two().tool, Tool::Select);
    // A shape whose midpoint picks it (no other shape is nearer there).
    let grab = h.state().canvas_screen().world_length(10.0);
    let (index, mid) = {
        let scene = &h.state().lab().two().scene;
        scene
            .shapes()
            .iter()
            .enumerate()
            .map(|(i, s)| (i, (s.points[0] + s.points[1]) * 0.5))
            .find(|&(i, m)| {
                scene.pick(m, grab) == Some(i)
                    && scene
                        .shapes()
                        .iter()
                        .enumerate()
                        .all(|(j, s)| j == i || s.distance(m) > 2.0 * grab)
            })
            .expect("some shape stands alone")
    };
    let before = h.state().lab().two().scene.shapes()[index].clone();

    let at = screen(&h, mid);
    click_at(&mut h, at);
    assert_eq!(h.state().lab().two().selection, vec![index]);
    h.get_by_label("Delete selected (1)");

    // Drag it 90 points right and 45 up: in world units, (90, 45) / scale.
    let scale = h.state().canvas_screen().camera.scale;
    let from = screen(&h, mid);
    let to = from + vec2(90.0, -45.0);
    drag_path(&mut h, from, &[from + vec2(30.0, 10.0), to]);
    let after = h.state().lab().two().scene.shapes()[index].clone();
    let delta = Vec2::new(90.0, 45.0) / scale;
    for (p, q) in before.points.iter().zip(&after.points) {
        assert!(
            (*q - (*p + delta)).length() < 1e-3,
            "{p} moved to {q}, expected {}",
            *p + delta
        );
    }
    assert_eq!(
        h.state().lab().two().selection,
        vec![index],
        "still selected"
    );

    // Delete removes it, and the status line says so.
    press(&mut h, Key::Delete);
    let app = h.state();
    assert!(app.lab().two().selection.is_empty());
    assert_eq!(app.lab().two().scene.shapes().len(), 199);
    assert!(!app.lab().two().scene.shapes().contains(&after));
    label_containing(&h, "Removed 1 shape(s).");
    label_containing(&h, &scene_line(199, 199));
    h.get_by_label("Delete selected (0)");
}

/// Issue 21: overlays from one section buried the next idea. A preset is a section of the
/// lecture, so it starts without the last one's volumes, slab test, SAT boxes, ray or point.
#[test]
fn a_preset_starts_its_section_without_the_last_sections_overlays() {
    let mut h = lab();
    choose(&mut h, "Preset", "Bounding volumes compared (§2)");
    assert!(
        h.state().lab().two().display.volumes,
        "§2 shows its volumes"
    );
    let from = screen(&h, Vec2::new(-9.0, -4.0));
    let to = screen(&h, Vec2::new(8.0, 3.0));
    drag(&mut h, from, to);
    click(&mut h, "Slab test of the ray against the AABB");
    act(&mut h, bvhlab_app::model::Action2d::SetTool(Tool::Obb));
    let two = h.state().lab().two();
    assert!(two.display.slab_test && two.obb_pair.is_some() && two.ray.is_some());

    choose(&mut h, "Preset", "k-d tree on a handful of shapes (§3)");
    let two = h.state().lab().two();
    assert!(!two.display.volumes, "the volumes are off");
    assert!(!two.display.slab_test, "the slab test is off");
    assert!(two.obb_pair.is_none(), "the SAT boxes are gone");
    assert_ne!(two.tool, Tool::Obb, "the SAT tool is put away");
    assert!(
        two.ray.is_none() && two.point.is_none(),
        "no old ray or point"
    );

    choose(&mut h, "Preset", "Bounding volumes compared (§2)");
    assert!(
        h.state().lab().two().display.volumes,
        "back in §2, its volumes show"
    );
}

#[test]
fn query_point_shows_brute_forces_nearest_and_k_answers() {
    let mut h = lab();
    click(&mut h, "Query point");
    assert_eq!(h.state().lab().two().tool, Tool::Point);
    let at = screen(&h, Vec2::new(7.3, 12.1));
    click_at(&mut h, at);
    let q = world(&h, at);
    assert_eq!(h.state().lab().two().point, Some(q));
    let nearest = brute_nearest(h.state(), q, 1);
    let n = nearest[0];
    let line = label_containing(&h, "#1: primitive");
    assert_eq!(
        line,
        format!(
            "#1: primitive {} at distance {:.4}, closest point ({:.3}, {:.3})",
            n.prim, n.distance, n.point.x, n.point.y
        )
    );
    assert!(!shows(&h, "#2: primitive"));
    label_containing(&h, "Same answer as brute force.");

    // k = 3 through the slider (as a screen reader sets it).
    h.get_by_role_and_label(Role::Slider, "k nearest")
        .set_value_accesskit(3.0);
    settle(&mut h);
    assert_eq!(h.state().lab().two().half.k, 3);
    let nearest = brute_nearest(h.state(), q, 3);
    assert_eq!(nearest.len(), 3);
    for (rank, n) in nearest.iter().enumerate() {
        let line = label_containing(&h, &format!("#{}: primitive", rank + 1));
        assert!(
            line.starts_with(&format!(
                "#{}: primitive {} at distance {:.4}",
                rank + 1,
                n.prim,
                n.distance
            )),
            "{line}"
        );
    }
    assert!(!shows(&h, "#4: primitive"));
    assert_eq!(
        h.state()
            .lab()
            .two()
            .half
            .lane
            .point_outcome
            .as_ref()
            .map(|o| o.nearest.len()),
        Some(3)
    );
}

#[test]
fn bounding_volumes_preset_fits_and_the_slab_tests_nan() {
    let mut h = lab();
    choose(&mut h, "Preset", "Bounding volumes compared (§2)");
    let app = h.state();
    assert_eq!(app.lab().two().scene.shapes().len(), 1);
    assert_eq!(app.lab().two().selection, vec![0]);
    label_containing(&h, &scene_line(1, 11));
    assert_eq!(
        app.lab()
            .two()
            .half
            .lane
            .structure
            .as_ref()
            .map(|b| b.stats.primitives),
        Some(11),
        "the structure is rebuilt on the preset's scene"
    );

    // The fits table: four columns after the header, one row per volume.
    let all = labels(&h);
    let start = all
        .iter()
        .position(|l| l == "tightness")
        .expect("the fits table")
        + 1;
    let mut tightness = std::collections::HashMap::new();
    for row in all[start..].chunks(4).take(6) {
        let pct = row[3]
            .strip_suffix(" %")
            .and_then(|p| p.parse::<u32>().ok())
            .unwrap_or_else(|| panic!("a tightness, got {row:?}"));
        tightness.insert(row[0].clone(), pct);
    }
    assert_eq!(tightness.len(), 6, "{tightness:?}");
    assert_eq!(tightness["convex hull"], 100);
    for (name, pct) in &tightness {
        if name != "convex hull" {
            assert!(*pct < 100, "{name} at {pct} %");
        }
    }

    // A ray across the blob, then the slab test and its degenerate case.
    assert!(shows(&h, "Draw a ray (Ray tool) to run the slab test."));
    let from = screen(&h, Vec2::new(-9.0, -4.0));
    let to = screen(&h, Vec2::new(8.0, 3.0));
    drag(&mut h, from, to);
    assert!(h.state().lab().two().ray.is_some());
    click(&mut h, "Slab test of the ray against the AABB");
    assert!(h.state().lab().two().display.slab_test);
    assert!(!shows(&h, "0/0 = NaN"));
    click(&mut h, "Ray parallel to x (y_d = 0)");
    let r = h.state().lab().two().ray.expect("ray");
    assert_eq!(r.origin.y, r.target.y);
    label_containing(&h, "the ray is parallel to the y slab");
    click(&mut h, "…and on the slab line y = y_min");
    let app = h.state();
    let r = app.lab().two().ray.expect("ray");
    let aabb = Aabb2::from_points(&app.lab().two().scene.vertices(&[]));
    assert_eq!(r.origin.y, aabb.min.y);
    label_containing(&h, "0/0 = NaN");
    label_containing(&h, "The naive formula compares a NaN");
    // The core's slab test still reports the ray touching the box, and the panel says hit.
    let ray = r.ray().expect("valid");
    assert!(aabb.ray_interval(&ray).is_some(), "the core: a hit");
    assert!(label_containing(&h, "max(t_xmin, t_ymin)").ends_with(": hit."));
    let outcome = app
        .lab()
        .two()
        .half
        .lane
        .ray_outcome
        .as_ref()
        .expect("answered");
    assert_eq!(outcome.hit, brute_hit(app, &ray));
    assert!(outcome.agrees());
}

#[test]
fn two_obbs_separate_and_overlap_as_dragged() {
    let mut h = lab();
    click(&mut h, "Two OBBs (SAT)");
    assert_eq!(h.state().lab().two().tool, Tool::Obb);
    let pair = h.state().lab().two().obb_pair.expect("the demo's boxes");
    for axis in ["A face 0", "A face 1", "B face 0", "B face 1"] {
        assert!(
            labels(&h).iter().any(|l| l == axis),
            "the table's row {axis}"
        );
    }
    let overlap = "No axis separates them: the boxes overlap.";
    let separate = "separates them: the boxes do not overlap";

    // Box B onto box A: they overlap.
    let (a, b) = (screen(&h, pair.a.center), screen(&h, pair.b.center));
    drag(&mut h, b, a);
    let moved = h.state().lab().two().obb_pair.expect("pair");
    assert!((moved.b.center - pair.a.center).length() < 1e-3);
    assert_eq!(moved.a, pair.a, "box A stays");
    label_containing(&h, overlap);

    // Far away (250 points down): an axis separates them.
    drag(&mut h, a, a + vec2(0.0, 250.0));
    label_containing(&h, separate);
    assert!(!shows(&h, overlap));
    let far = h.state().lab().two().obb_pair.expect("pair");
    assert!(far.tests().iter().any(bvhlab::AxisTest::separates));

    // And back: they overlap again.
    drag(&mut h, a + vec2(0.0, 250.0), a);
    label_containing(&h, overlap);
    assert!(!shows(&h, separate));
}

#[test]
fn degenerate_rays_and_an_empty_scene_get_messages_not_panics() {
    let mut h = lab();
    // A press and release at one point is a click: no ray, nothing broken.
    let p = screen(&h, Vec2::new(5.0, 5.0));
    click_at(&mut h, p);
    assert!(h.state().lab().two().ray.is_none());
    assert!(h.state().lab().two().half.lane.ray_outcome.is_none());
    assert_eq!(h.state().ui.canvas.interaction, Interaction::None);

    // A drag that comes back to where it started: a ray of zero length.
    drag_path(&mut h, p, &[p + vec2(80.0, 30.0), p]);
    let handles = h.state().lab().two().ray.expect("the drag placed handles");
    assert_eq!(handles.origin, handles.target);
    let err = handles.ray().expect_err("zero length");
    assert!(h.state().lab().two().half.lane.ray_outcome.is_none());
    assert!(!shows(&h, "Hit: primitive"));
    // The §2 ray tests (ray-sphere and the slab test, each in its section) and the Queries
    // panel say why there is no answer.
    let no_ray = format!("No ray: {err}");
    assert_eq!(
        labels(&h).iter().filter(|l| l.starts_with(&no_ray)).count(),
        3,
        "{:#?}",
        labels(&h)
    );
    assert!(shows(&h, "Drag s away from e."));
    // It can be dragged out again into a proper ray.
    drag(&mut h, p, p + vec2(200.0, 10.0));
    assert!(h.state().lab().two().half.lane.ray_outcome.is_some());

    // Clear empties the scene; a ray then misses, with the counters at zero.
    click(&mut h, "Clear");
    assert!(h.state().lab().two().scene.shapes().is_empty());
    label_containing(&h, &scene_line(0, 0));
    assert!(!shows(&h, "Hit: primitive"));
    label_containing(&h, "Miss: the ray hits nothing.");
    drag(&mut h, p + vec2(0.0, 100.0), p + vec2(300.0, 60.0));
    label_containing(&h, "Miss: the ray hits nothing.");
    let outcome = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .ray_outcome
        .as_ref()
        .expect("answered");
    assert_eq!(outcome.hit, None);
    assert_eq!(outcome.brute_cost.prim_tests, 0);
    label_containing(&h, "Same answer as brute force.");
    assert!(shows(&h, "Draw or select a shape to fit volumes to it."));
    // A zero-length ray on the empty scene: still a message (only the Queries panel's now).
    let q = p + vec2(0.0, 200.0);
    drag_path(&mut h, q, &[q + vec2(50.0, 50.0), q]);
    assert!(h.state().lab().two().half.lane.ray_outcome.is_none());
    label_containing(&h, &no_ray);
    assert!(!shows(&h, "Miss: the ray hits nothing."));
    drag(&mut h, q, q + vec2(300.0, -40.0));
    label_containing(&h, "Miss: the ray hits nothing.");

    // A query point and the other structures on the empty scene.
    click(&mut h, "Query point");
    click_at(&mut h, p);
    label_containing(&h, "No primitives: nothing is nearest.");
    for kind in StructureKind::ALL {
        choose(&mut h, "Structure", kind.label());
        assert_eq!(h.state().lab().two().half.lane.settings.kind, kind);
        label_containing(&h, "Miss: the ray hits nothing.");
    }
}

#[test]
fn ten_thousand_segments_from_the_preset_menu() {
    let mut h = lab();
    choose(&mut h, "Preset", "10,000 random segments");
    assert_eq!(h.state().lab().two().scene.shapes().len(), 10_000);
    label_containing(&h, &scene_line(10_000, 10_000));
    assert_eq!(
        h.state()
            .lab()
            .two()
            .half
            .lane
            .structure
            .as_ref()
            .map(|b| b.stats.primitives),
        Some(10_000),
        "the structure is rebuilt on the new scene"
    );
    let from = screen(&h, Vec2::new(2.0, 37.0));
    let to = screen(&h, Vec2::new(98.0, 61.0));
    drag(&mut h, from, to);
    let app = h.state();
    let ray = app.lab().two().ray.expect("ray").ray().expect("valid");
    let outcome = app
        .lab()
        .two()
        .half
        .lane
        .ray_outcome
        .as_ref()
        .expect("answered");
    let hit = outcome.hit.expect("a ray across 10,000 segments hits");
    assert_eq!(Some(hit), brute_hit(app, &ray));
    assert_eq!(
        label_containing(&h, "Hit: primitive"),
        hit_text(app, &ray, hit)
    );
    label_containing(&h, "Same answer as brute force.");
    let rows = counter_rows(&h);
    assert_eq!(
        rows[2],
        (
            "primitive tests".to_owned(),
            outcome.cost.prim_tests,
            10_000
        )
    );
    assert!(outcome.cost.prim_tests < 1_000, "{:?}", outcome.cost);
}

#[test]
fn the_panel_shows_the_rays_handles_and_the_point_as_numbers() {
    let mut h = lab();
    drag_test_ray(&mut h);
    click(&mut h, "Query point");
    let q = screen(&h, Vec2::new(12.0, 4.0));
    click_at(&mut h, q);
    let two = h.state().lab().two();
    let handles = two.ray.expect("a ray");
    let point = two.point.expect("a point");
    // The fields show e's x and y, s's, and q's: what the panel would let the student type.
    let values: Vec<f64> = h
        .query_all_by_role(Role::SpinButton)
        .filter_map(|n| n.accesskit_node().numeric_value())
        .collect();
    for v in [
        handles.origin.x,
        handles.origin.y,
        handles.target.x,
        handles.target.y,
        point.x,
        point.y,
    ] {
        assert!(
            values
                .iter()
                .any(|&shown| (shown - f64::from(v)).abs() < 1e-4),
            "{v} among the fields {values:?}"
        );
    }
}

/// The versions of the algorithm offered in "Step through", with whether each is selected.
fn variant_radios(h: &Harness<'_, LabApp>) -> Vec<(String, bool)> {
    use egui::accesskit::Toggled;
    h.query_all_by_role(Role::RadioButton)
        .filter_map(|n| {
            let node = n.accesskit_node();
            let label = node.label()?;
            let known = ["full (near first", "the slides'"];
            known
                .iter()
                .any(|k| label.starts_with(k))
                .then(|| (label, node.toggled() == Some(Toggled::True)))
        })
        .collect()
}

/// Asserts that exactly one version is selected, and that it is the one the lab runs.
fn assert_one_variant_selected_and_run<P: bvhlab_app::model::dimension::LabPrimitive>(
    h: &Harness<'_, LabApp>,
    half: &bvhlab_app::model::half::Half<P>,
    what: &str,
) {
    use bvhlab_app::panels::step_through::variant_label;
    let radios = variant_radios(h);
    let selected: Vec<&String> = radios.iter().filter(|r| r.1).map(|r| &r.0).collect();
    assert_eq!(
        selected.len(),
        1,
        "{what}: one version selected: {radios:?}"
    );
    let runs = half.lane.recorded().expect("a recording").question.variant;
    assert_eq!(
        selected[0],
        variant_label(runs),
        "{what}: the one selected runs"
    );
    assert_eq!(half.variant, runs, "{what}");
}

/// Issue 21: after "the slides' + pruning" for a point and then a ray, neither "full" nor
/// "the slides' version" was selected while the lab ran the full one (2D and 3D).
#[test]
fn after_the_slides_pruned_nearest_a_ray_selects_the_version_that_runs() {
    use bvhlab::glam::Vec3;
    use bvhlab_app::model::mesh::MeshSource;
    use bvhlab_app::model::{Action3d, Dimension};
    use bvhlab_app::pseudocode::{Task, Variant};

    let mut h = lab();
    choose(&mut h, "Structure", StructureKind::AabbTree.label());
    click(&mut h, "Query point");
    let at = screen(&h, Vec2::new(7.3, 12.1));
    click_at(&mut h, at);
    click(&mut h, "the slides' + pruning");
    let half = &h.state().lab().two().half;
    assert_eq!(half.task, Task::Nearest);
    assert_one_variant_selected_and_run(&h, half, "2D nearest");
    assert_eq!(half.variant, Variant::LecturePruned);
    act(&mut h, bvhlab_app::model::Action2d::SetTool(Tool::Ray));
    drag_test_ray(&mut h);
    let half = &h.state().lab().two().half;
    assert_eq!(half.task, Task::FirstHit);
    assert_one_variant_selected_and_run(&h, half, "2D ray after the pruned nearest");
    assert_eq!(half.variant, Variant::Full);

    // 3D, with the same panel.
    act(
        &mut h,
        Action3d::OpenMesh(MeshSource::Builtin("tetrahedra".to_owned())),
    );
    for _ in 0..2_000 {
        let three = h.state().lab().three();
        if !three.busy() && three.half.lane.current(three.revision()).is_some() {
            break;
        }
        h.step();
    }
    settle(&mut h);
    assert_eq!(h.state().lab().dimension(), Dimension::Three);
    let mut settings = h.state().lab().three().half.lane.settings;
    settings.kind = StructureKind::AabbTree;
    act(
        &mut h,
        bvhlab_app::model::HalfAction::SetStructure(settings),
    );
    settle(&mut h);
    act(&mut h, Action3d::SetPoint(Some(Vec3::new(0.1, 0.2, 0.3))));
    click(&mut h, "the slides' + pruning");
    let half = &h.state().lab().three().half;
    assert_eq!(half.task, Task::Nearest);
    assert_one_variant_selected_and_run(&h, half, "3D nearest");
    assert_eq!(half.variant, Variant::LecturePruned);
    let ray = bvhlab::Ray3::new(Vec3::new(-5.0, 0.1, 0.2), Vec3::X).expect("a ray");
    act(&mut h, Action3d::SetRay(Some(ray)));
    let half = &h.state().lab().three().half;
    assert_eq!(half.task, Task::FirstHit);
    assert_one_variant_selected_and_run(&h, half, "3D ray after the pruned nearest");
    assert_eq!(half.variant, Variant::Full);
}

/// Ctrl+Z (Cmd+Z on a Mac), Ctrl+Shift+Z and Ctrl+Y.
fn press_with(h: &mut Harness<'_, LabApp>, modifiers: egui::Modifiers, key: Key) {
    h.key_press_modifiers(modifiers, key);
    settle(h);
}

const CTRL: egui::Modifiers = egui::Modifiers::COMMAND;

/// Whether the button labelled `label` can be pressed.
fn enabled(h: &Harness<'_, LabApp>, label: &str) -> bool {
    !h.get_by_label(label).accesskit_node().is_disabled()
}

/// Issue 21: "Clear" asked nothing and could not be undone. Ctrl+Z brings every shape back,
/// Ctrl+Shift+Z (or Ctrl+Y) clears again, the buttons beside "Clear" do the same, and the
/// status line says what was undone.
#[test]
fn clear_then_ctrl_z_brings_every_shape_back_and_redo_clears_again() {
    let mut h = lab();
    let shapes = h.state().lab().two().scene.shapes().to_vec();
    assert!(!shapes.is_empty());
    assert!(
        !enabled(&h, "Undo") && !enabled(&h, "Redo"),
        "nothing to undo yet"
    );
    click(&mut h, "Clear");
    assert!(h.state().lab().two().scene.shapes().is_empty());
    assert!(enabled(&h, "Undo") && !enabled(&h, "Redo"));

    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(
        h.state().lab().two().scene.shapes(),
        shapes,
        "every shape is back"
    );
    let said = h.state().lab().message().unwrap_or_default().to_owned();
    assert!(said.starts_with("Undid clearing the scene"), "{said}");
    label_containing(&h, "Undid clearing the scene");
    assert!(!enabled(&h, "Undo") && enabled(&h, "Redo"));
    // The structure is built on the shapes that came back.
    let two = h.state().lab().two();
    assert!(two.half.lane.current(two.scene.revision()).is_some());

    press_with(&mut h, CTRL | egui::Modifiers::SHIFT, Key::Z);
    assert!(
        h.state().lab().two().scene.shapes().is_empty(),
        "redo clears again"
    );
    label_containing(&h, "Redid clearing the scene.");
    click(&mut h, "Undo");
    assert_eq!(h.state().lab().two().scene.shapes(), shapes);
    press_with(&mut h, CTRL, Key::Y);
    assert!(
        h.state().lab().two().scene.shapes().is_empty(),
        "Ctrl+Y redoes too"
    );
    click(&mut h, "Undo");
    assert_eq!(h.state().lab().two().scene.shapes(), shapes);
    // Nothing left to undo: the status line says so, and nothing changes.
    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(h.state().lab().two().scene.shapes(), shapes);
    label_containing(&h, "There is no scene edit to undo.");
}

/// A new edit after an undo forgets what could be redone; a drag is one edit; a preset is
/// undone with the structure, ray and point it replaced.
#[test]
fn a_new_edit_after_undo_drops_the_redo_history() {
    use bvhlab_app::model::presets::Preset;
    use bvhlab_app::model::{Action2d, HalfAction};

    let mut h = lab();
    let start = h.state().lab().two().scene.shapes().to_vec();
    let segment = |x: f32| Action2d::AddShape {
        kind: ShapeKind::Segment,
        points: vec![Vec2::new(x, 0.0), Vec2::new(x, 1.0)],
    };
    act(&mut h, segment(1.0));
    act(&mut h, segment(2.0));
    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(h.state().lab().two().history().redo_len(), 1);
    assert!(enabled(&h, "Redo"));
    label_containing(&h, "Undid adding a segment");
    // A new edit: the undone one cannot come back.
    act(&mut h, segment(3.0));
    assert_eq!(h.state().lab().two().history().redo_len(), 0);
    assert!(!enabled(&h, "Redo"));
    press_with(&mut h, CTRL | egui::Modifiers::SHIFT, Key::Z);
    label_containing(&h, "There is no undone scene edit to redo.");
    let xs: Vec<f32> = h.state().lab().two().scene.shapes()[start.len()..]
        .iter()
        .map(|s| s.points[0].x)
        .collect();
    assert_eq!(xs, [1.0, 3.0]);
    press_with(&mut h, CTRL, Key::Z);
    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(h.state().lab().two().scene.shapes(), start);

    // A drag in select mode moves the shape many times: one edit. Two drags: two.
    click(&mut h, "Select / move");
    let shapes = h.state().lab().two().scene.shapes().to_vec();
    let grab = h.state().canvas_screen().world_length(10.0);
    let (index, mid) = shapes
        .iter()
        .enumerate()
        .map(|(i, s)| (i, (s.points[0] + s.points[1]) * 0.5))
        .find(|&(i, m)| {
            shapes
                .iter()
                .enumerate()
                .all(|(j, s)| j == i || s.distance(m) > 2.0 * grab)
        })
        .expect("some shape stands alone");
    let from = screen(&h, mid);
    drag(&mut h, from, from + vec2(60.0, 0.0));
    let once = h.state().lab().two().scene.shapes()[index].clone();
    drag(&mut h, from + vec2(60.0, 0.0), from + vec2(60.0, 60.0));
    assert_ne!(h.state().lab().two().scene.shapes()[index], once);
    press_with(&mut h, CTRL, Key::Z);
    label_containing(&h, "Undid moving a shape");
    assert_eq!(
        h.state().lab().two().scene.shapes()[index],
        once,
        "the second drag"
    );
    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(
        h.state().lab().two().scene.shapes(),
        shapes,
        "the first drag"
    );

    // A preset, undone, brings back the scene and the structure it replaced.
    let mut settings = h.state().lab().two().half.lane.settings;
    settings.kind = StructureKind::Grid;
    act(&mut h, HalfAction::SetStructure(settings));
    act(&mut h, Action2d::LoadPreset(Preset::KdHandful));
    assert_ne!(h.state().lab().two().scene.shapes(), shapes);
    press_with(&mut h, CTRL, Key::Z);
    assert_eq!(h.state().lab().two().scene.shapes(), shapes);
    assert_eq!(h.state().lab().two().half.lane.settings, settings);
    label_containing(&h, "Undid loading the preset");
}

/// The history keeps the last `MAX_UNDO` edits: older ones are forgotten.
#[test]
fn the_undo_history_is_bounded() {
    use bvhlab_app::model::history::MAX_UNDO;
    use bvhlab_app::model::{Action2d, Lab};

    let mut lab = Lab::default();
    let start = lab.two().scene.shapes().len();
    let extra = 7;
    for i in 0..MAX_UNDO + extra {
        lab.apply(
            Action2d::AddShape {
                kind: ShapeKind::Points,
                points: vec![Vec2::new(i as f32, -3.0)],
            }
            .into(),
        )
        .expect("adds");
    }
    assert_eq!(lab.two().history().undo_len(), MAX_UNDO);
    for _ in 0..MAX_UNDO {
        lab.apply(Action2d::Undo.into()).expect("undoes");
    }
    // The oldest edits were forgotten: their shapes stay.
    assert_eq!(lab.two().scene.shapes().len(), start + extra);
    assert_eq!(lab.two().history().undo_len(), 0);
    assert!(lab.apply(Action2d::Undo.into()).is_err(), "nothing more");
    assert_eq!(lab.two().history().redo_len(), MAX_UNDO);
    for _ in 0..MAX_UNDO {
        lab.apply(Action2d::Redo.into()).expect("redoes");
    }
    assert_eq!(lab.two().scene.shapes().len(), start + MAX_UNDO + extra);
    assert!(lab.apply(Action2d::Redo.into()).is_err());
}

/// The tree diagram's area, and the rectangles of the texts it drew (the leaves' counts),
/// with the rectangle each was clipped to.
fn tree_area_and_labels(h: &Harness<'_, LabApp>) -> (egui::Rect, Vec<(egui::Rect, egui::Rect)>) {
    let area = h.state().ui.trees.two[0].area().expect("a tree is drawn");
    let labels = h
        .output()
        .shapes
        .iter()
        .filter(|c| area.contains_rect(c.clip_rect))
        .filter_map(|c| match &c.shape {
            egui::Shape::Text(t) => Some((t.visual_bounding_rect(), c.clip_rect)),
            _ => None,
        })
        .collect();
    (area, labels)
}

/// Issue 21: after "Clear" (and after reloading that state) the tree diagram collapsed to a
/// thin strip at the bottom and never came back, and the deepest row's labels were cut off.
#[test]
fn after_clear_and_a_preset_the_tree_diagram_has_its_height_and_every_label_inside() {
    use bvhlab_app::model::Lab;
    use bvhlab_app::model::presets::Preset;
    use bvhlab_app::persist::SavedState;
    use bvhlab_app::tree_diagram::MIN_HEIGHT;

    let mut h = lab();
    click(&mut h, "Clear");
    assert!(h.state().ui.trees.two[0].area().is_none(), "no tree");
    // Reloading the cleared state (the UI's memory, such as panel sizes, stays).
    let saved = SavedState::capture(h.state().lab());
    let mut reloaded = Lab::default();
    reloaded
        .apply(saved.apply().expect("a captured state applies"))
        .expect("restores");
    assert!(reloaded.two().scene.shapes().is_empty());
    h.state_mut().replace_lab(reloaded);
    settle(&mut h);
    choose(&mut h, "Preset", Preset::KdHandful.label());
    settle(&mut h);
    let (area, labels) = tree_area_and_labels(&h);
    assert!(
        area.height() >= MIN_HEIGHT,
        "the diagram is {} points high",
        area.height()
    );
    let leaves = {
        let two = h.state().lab().two();
        let lane = &two.half.lane;
        let outline = lane
            .current(two.scene.revision())
            .and_then(|s| s.outline.as_ref())
            .expect("an outline");
        outline.iter().filter(|n| n.is_leaf()).count()
    };
    assert_eq!(
        labels.len(),
        leaves,
        "every leaf's count is drawn: {labels:?}"
    );
    for (text, clip) in labels {
        assert_eq!(clip, area, "the diagram is not clipped by its panel");
        assert!(area.contains_rect(text), "{text:?} lies inside {area:?}");
    }
    // The resize handle: a grip drawn on the panel's top edge, in a colour that shows.
    let panel = h.state().ui.tree_rect.expect("the panel is shown");
    let fill = h.ctx.global_style().visuals.panel_fill;
    let grip = h.output().shapes.iter().find_map(|c| match &c.shape {
        egui::Shape::Rect(r)
            if r.rect.width() >= 24.0
                && (r.rect.center() - panel.center_top()).length() <= 3.0
                && r.fill != fill
                && r.fill.a() > 0 =>
        {
            Some(r.rect)
        }
        _ => None,
    });
    assert!(grip.is_some(), "a grip on the tree panel's top edge");
}
