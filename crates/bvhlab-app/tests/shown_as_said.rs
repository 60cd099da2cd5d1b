//! Issue 29, "Lessons that never lie": what the panels and lessons say is what the canvas
//! shows. Split planes are told from the scene; a preset gives the structure it is named
//! after; every hit listed is drawn; brute force is not said to be an empty tree; the three
//! sphere fits differ where the lesson shows them; the separating axis has one name; and the
//! lab's messages to its parent go to the parent's origin.

use crate::common::{self, act, label_containing, labels, painted, settle, shows};

use bvhlab::FitKind;
use bvhlab::glam::Vec2;
use bvhlab_app::LabApp;
use bvhlab_app::embed::target::ParentOrigin;
use bvhlab_app::lessons;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::structures::{BuildSettings, StructureKind};
use bvhlab_app::model::{Action, Action2d, HalfAction, Lab, LessonAction};
use bvhlab_app::paint::{SPLIT_DASH, SPLIT_NAME, colors};
use egui::epaint::Shape;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// `lab` in a headless harness, after its first frames.
fn harness(lab: Lab) -> Harness<'static, LabApp> {
    let mut h = Harness::builder()
        .with_size(common::WINDOW)
        .build_ui_state(|ui, app: &mut LabApp| app.show(ui), LabApp::new(lab));
    h.run();
    h
}

/// The lab with `preset` loaded as a student loads it (its selection and switches too).
fn loaded(preset: Preset) -> Lab {
    let mut lab = Lab::default();
    lab.apply(Action2d::LoadPreset(preset).into())
        .expect("a preset loads");
    lab
}

/// Every shape in `shapes`, nested lists flattened.
fn flat(shapes: impl IntoIterator<Item = Shape>) -> Vec<Shape> {
    fn walk(shape: Shape, out: &mut Vec<Shape>) {
        match shape {
            Shape::Vec(shapes) => shapes.into_iter().for_each(|s| walk(s, out)),
            other => out.push(other),
        }
    }
    let mut out = Vec::new();
    shapes.into_iter().for_each(|s| walk(s, &mut out));
    out
}

#[test]
fn split_planes_are_dashed_in_their_own_colour_and_named_in_the_legend() {
    let mut h = harness(loaded(Preset::KdHandful));
    let screen = h.state().canvas_screen();
    let scene: Vec<[Vec2; 2]> = h
        .state()
        .lab()
        .two()
        .prims()
        .segments
        .iter()
        .map(|s| [s.a, s.b])
        .collect();
    // The canvas's shapes before its static layer is tessellated (the SVG export's).
    let ctx = h.ctx.clone();
    let painter = egui::Painter::new(ctx, egui::LayerId::background(), screen.rect);
    let shapes = flat(bvhlab_app::lab2d::picture(
        h.state().lab().two(),
        &bvhlab_app::model::predict::About::default(),
        screen.rect,
        &painter,
    ));
    let on_scene = |a: egui::Pos2, b: egui::Pos2| {
        let (a, b) = (screen.to_world(a), screen.to_world(b));
        scene.iter().any(|&[p, q]| {
            let near = |u: Vec2, v: Vec2| (u - v).length() < 1e-3;
            (near(a, p) && near(b, q)) || (near(a, q) && near(b, p))
        })
    };
    let (mut scene_colours, mut split_pieces) = (Vec::new(), Vec::new());
    for shape in &shapes {
        if let Shape::LineSegment {
            points: [a, b],
            stroke,
        } = shape
        {
            if on_scene(*a, *b) {
                scene_colours.push(stroke.color);
            } else {
                split_pieces.push((*a, *b, stroke.color));
            }
        }
    }
    assert!(!scene_colours.is_empty(), "the scene's segments are drawn");
    let splits: usize = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .current(h.state().lab().two().scene.revision())
        .and_then(|s| s.outline.as_deref())
        .expect("the k-d tree's nodes")
        .iter()
        .map(|n| n.splits.len())
        .sum();
    assert!(splits >= 3, "{splits} split planes");
    // Dashed: many short pieces, each at most a dash long.
    assert!(
        split_pieces.len() >= 3 * splits,
        "{} pieces for {splits} planes",
        split_pieces.len()
    );
    for (a, b, color) in &split_pieces {
        assert!(a.distance(*b) <= SPLIT_DASH.0 + 0.5, "{a:?} to {b:?}");
        assert_eq!(
            *color,
            colors::SPLIT,
            "every split piece in the split colour"
        );
        assert!(!scene_colours.contains(color), "no segment shares it");
    }
    // What is painted: the static layer's mesh carries the split colour, and the legend names
    // the planes with a dashed swatch in it.
    let painted_shapes = flat(h.output().shapes.iter().map(|c| c.shape.clone()));
    let in_mesh = painted_shapes.iter().any(|s| match s {
        Shape::Mesh(m) => m.vertices.iter().any(|v| v.color == colors::SPLIT),
        _ => false,
    });
    assert!(in_mesh, "the canvas paints the split colour");
    let legend = painted(&h)
        .into_iter()
        .find(|t| t.text == SPLIT_NAME)
        .expect("the legend names the split planes");
    let swatch_dashes = painted_shapes
        .iter()
        .filter(|s| {
            matches!(s, Shape::LineSegment { points: [a, _], stroke }
                if stroke.color == colors::SPLIT
                    && (a.y - legend.rect.center().y).abs() < 8.0
                    && a.x < legend.rect.left())
        })
        .count();
    assert!(
        swatch_dashes >= 2,
        "a dashed swatch: {swatch_dashes} dashes"
    );

    // An AABB tree draws no planes, and the legend does not name them.
    act(
        &mut h,
        HalfAction::SetStructure(BuildSettings {
            kind: StructureKind::AabbTree,
            ..BuildSettings::default()
        }),
    );
    assert!(!painted(&h).iter().any(|t| t.text == SPLIT_NAME));
}

#[test]
fn the_kd_tree_preset_chosen_again_opens_its_kd_tree() {
    // As lessons leave it: the k-d tree's scene under an AABB tree.
    let mut lab = loaded(Preset::KdHandful);
    lab.apply(
        HalfAction::SetStructure(BuildSettings {
            kind: StructureKind::AabbTree,
            ..BuildSettings::default()
        })
        .into(),
    )
    .expect("an AABB tree");
    let mut h = harness(lab);
    let name = Preset::KdHandful.label();
    common::click(&mut h, "Preset");
    // The menu's entry (the last of the nodes named so: the combo box shows it too).
    h.get_all_by_label(name)
        .last()
        .expect("the menu's entry")
        .click();
    settle(&mut h);
    let two = h.state().lab().two();
    assert_eq!(two.preset, Preset::KdHandful);
    assert_eq!(two.half.lane.settings.kind, StructureKind::KdTree);
}

/// The hits the Step through panel lists ("hits so far: #2 at t = 2.817, #0 at t = 6.460").
fn hits_listed(h: &Harness<'_, LabApp>) -> Vec<String> {
    let line = label_containing(h, "hits so far: ");
    let list = line.split("hits so far: ").nth(1).expect("the list");
    assert!(!list.contains("more"), "{line}");
    list.split(", ")
        .filter(|item| *item != "none")
        .map(|item| item.split(' ').next().expect("#n").to_owned())
        .collect()
}

/// The hits marked on the canvas: the primitives' numbers beside their dots.
fn hits_drawn(h: &Harness<'_, LabApp>) -> Vec<String> {
    let canvas = h.state().canvas_screen().rect;
    let mut drawn: Vec<String> = painted(h)
        .into_iter()
        .filter(|t| canvas.contains(t.rect.center()) && t.color == colors::ANSWER)
        .map(|t| t.text.trim().to_owned())
        .filter(|t| t.starts_with('#'))
        .collect();
    drawn.sort();
    drawn
}

#[test]
fn every_hit_listed_in_the_grid_lessons_all_hits_step_is_drawn() {
    let lesson = lessons::find("grid").expect("the grid lesson");
    let step = 1;
    assert_eq!(
        lesson.steps[step].goals.first().map(|g| g.text.as_str()),
        Some("task = all-hits")
    );
    let solution = lesson.steps[step].solution.clone().expect("a solution");
    let mut last = None;
    for (what, setup) in [("start", None), ("solution", Some(solution))] {
        let mut lab = Lab::default();
        lab.apply(Action::Lesson(LessonAction::Open {
            lesson: lesson.clone(),
            step,
        }))
        .expect("the step opens");
        if let Some(setup) = setup {
            let problems = lab.apply_setup(&setup, "the test");
            assert!(problems.is_empty(), "{problems:?}");
        }
        let h = harness(lab);
        let mut listed = hits_listed(&h);
        listed.sort();
        assert_eq!(hits_drawn(&h), listed, "{what}: drawn as listed");
        last = Some(h);
    }
    let h = last.expect("the solution's lab");
    assert!(
        hits_listed(&h).len() >= 2,
        "the solution's ray hits more than once"
    );
    // The counter the lesson's text names is in the Step through panel's table.
    assert!(lesson.steps[step].text.contains("\"mailbox skips\""));
    let all = labels(&h);
    let table = all
        .iter()
        .position(|l| l == "Step through")
        .expect("the panel");
    assert!(
        all[table..].iter().any(|l| l == "mailbox skips"),
        "{:?}",
        &all[table..]
    );
}

#[test]
fn brute_force_says_it_has_no_tree_and_counts_no_leaves() {
    let mut h = common::lab();
    act(
        &mut h,
        HalfAction::SetStructure(BuildSettings {
            kind: StructureKind::BruteForce,
            ..BuildSettings::default()
        }),
    );
    let said =
        "Brute force has no tree: it keeps the 200 segments in one list and tests every one.";
    let times = labels(&h).iter().filter(|l| *l == said).count();
    assert_eq!(times, 2, "the structure and tree panels say it");
    assert!(!shows(&h, "empty scene"), "the scene is not empty");
    assert!(!shows(&h, "Leaves by number of primitives"));
    assert!(!shows(&h, "nodes (cells)"));
}

#[test]
fn the_three_sphere_fits_differ_where_lesson_2_shows_them() {
    let lesson = lessons::find("bounding-volumes").expect("lesson 2");
    let mut lab = Lab::default();
    lab.apply(Action::Lesson(LessonAction::Open {
        lesson: lesson.clone(),
        step: 0,
    }))
    .expect("the lesson opens");
    let two = lab.two();
    assert!(two.volumes.ritter, "Ritter's sphere is shown by default");
    assert!(two.display.volumes);
    // The core's own fits of the default selection.
    let fits = two.fits().expect("a selection");
    let (c, r, w) = (fits.centroid.radius, fits.ritter.radius, fits.welzl.radius);
    assert!(c >= 1.05 * r, "centroid {c} > Ritter {r} by 5 %");
    assert!(r >= 1.03 * w, "Ritter {r} > Welzl {w} by 3 %");
    // And the canvas's legend names all three.
    let h = harness(lab);
    for kind in [
        FitKind::SphereCentroid,
        FitKind::SphereRitter,
        FitKind::SphereWelzl,
    ] {
        let name = colors::volume_name(kind);
        assert!(painted(&h).iter().any(|t| t.text == name), "{name}");
    }
}

#[test]
fn the_separating_axis_is_named_as_the_table_names_it() {
    let lesson = lessons::find("bounding-volumes").expect("lesson 2");
    let step = lesson
        .steps
        .iter()
        .position(|s| {
            s.goals
                .iter()
                .any(|g| g.text.starts_with("separating-axes"))
        })
        .expect("the separating-axis step");
    let mut lab = Lab::default();
    lab.apply(Action::Lesson(LessonAction::Open {
        lesson: lesson.clone(),
        step,
    }))
    .expect("the step opens");
    let solution = lesson.steps[step].solution.clone().expect("a solution");
    assert!(lab.apply_setup(&solution, "the test").is_empty());
    let h = harness(lab);
    let all = labels(&h);
    let sentence = label_containing(&h, " separates them: ");
    let named = sentence
        .split(" separates them")
        .next()
        .expect("the axis's name");
    // The table: name, A's interval, B's interval, gap, separates.
    let rows: Vec<(&String, &String)> = all
        .iter()
        .enumerate()
        .filter(|(_, l)| l.len() == "A face 0".len() && l.contains(" face "))
        .map(|(i, l)| (l, &all[i + 4]))
        .collect();
    assert_eq!(rows.len(), 4, "{all:?}");
    let first = rows
        .iter()
        .find(|(_, separates)| *separates == "yes")
        .expect("a separating row");
    assert_eq!(named, first.0.as_str(), "{sentence}");
}

#[test]
fn the_labs_messages_go_to_its_parents_origin_once_known() {
    let own = "https://lab.example.org";
    let course = "https://course.example.edu".to_owned();
    let named = [course.clone()];
    let base = ParentOrigin {
        own,
        named: &named,
        first_command: None,
        ancestor: None,
    };
    // Embedded in the course page, which the browser names: only there.
    let embedded = ParentOrigin {
        ancestor: Some(&course),
        ..base.clone()
    };
    assert_eq!(embedded.targets(), std::slice::from_ref(&course));
    // The parent's first command names it too.
    let scripted = ParentOrigin {
        first_command: Some(&course),
        ..base.clone()
    };
    assert_eq!(scripted.targets(), std::slice::from_ref(&course));
    // A parent the address does not allow hears nothing (and nothing is posted in vain).
    let stranger = ParentOrigin {
        ancestor: Some("https://elsewhere.example.com"),
        ..base.clone()
    };
    assert!(stranger.targets().is_empty());
    // Same origin: the lab's own.
    let home = ParentOrigin {
        ancestor: Some(own),
        ..base.clone()
    };
    assert_eq!(home.targets(), [own.to_owned()]);
    // Not known: every allowed origin, as the embed protocol says (an opaque one left out).
    assert_eq!(base.targets(), [own.to_owned(), course.clone()]);
    let sandboxed = ParentOrigin {
        own: "null",
        ..base
    };
    assert_eq!(sandboxed.targets(), [course]);
}
