//! Headless UI tests of issue 21 ("A student's first hour"): the bounding volumes section
//! read as the lecture reads (colours that match the canvas, the lecture's slab-test failure
//! case, ray-sphere in its own place, a preset where the centroid sphere is visibly looser),
//! buttons that stay put while they are clicked, and the lecture's words in the panels.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, BoundingVolume, Event, FitKind, Sphere2};
use bvhlab_app::LabApp;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::volumes::VolumeToggles;
use bvhlab_app::model::{Action2d, HalfAction, PlaybackAction};
use bvhlab_app::paint::colors;
use bvhlab_app::pseudocode::Task;
use egui::accesskit::Role;
use egui::epaint::{CircleShape, RectShape};
use egui::{Color32, Pos2, Shape};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use crate::common;
use common::*;

const SPHERES: [FitKind; 3] = [
    FitKind::SphereCentroid,
    FitKind::SphereRitter,
    FitKind::SphereWelzl,
];

const ALL_ON: VolumeToggles = VolumeToggles {
    centroid: true,
    ritter: true,
    welzl: true,
    aabb: true,
    obb: true,
    hull: true,
};

/// The lab on the "Bounding volumes compared" preset, every volume switched on.
fn volumes_lab() -> Harness<'static, LabApp> {
    let mut h = lab();
    choose(&mut h, "Preset", "Bounding volumes compared (§2)");
    act(&mut h, Action2d::SetVolumes(ALL_ON));
    h
}

/// Every shape painted in the last frame, nested lists flattened.
fn painted(h: &Harness<'_, LabApp>) -> Vec<Shape> {
    fn flatten(shape: &Shape, out: &mut Vec<Shape>) {
        match shape {
            Shape::Vec(shapes) => shapes.iter().for_each(|s| flatten(s, out)),
            other => out.push(other.clone()),
        }
    }
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        flatten(&clipped.shape, &mut out);
    }
    out
}

/// The sphere `kind` of the selection, as the core fits it.
fn sphere(h: &Harness<'_, LabApp>, kind: FitKind) -> Sphere2 {
    let fits = h.state().lab().two().fits().expect("a shape to fit");
    match kind {
        FitKind::SphereCentroid => fits.centroid,
        FitKind::SphereRitter => fits.ritter,
        _ => fits.welzl,
    }
}

/// The circles drawn for the sphere `kind`: in its colour, at its centre and radius.
fn sphere_outlines(h: &Harness<'_, LabApp>, kind: FitKind) -> Vec<CircleShape> {
    let screen = h.state().canvas_screen();
    let s = sphere(h, kind);
    let (center, radius) = (screen.to_screen(s.center), screen.screen_length(s.radius));
    painted(h)
        .into_iter()
        .filter_map(|shape| match shape {
            Shape::Circle(c)
                if c.stroke.color == colors::volume(kind)
                    && (c.center - center).length() < 0.5
                    && (c.radius - radius).abs() < 0.5 =>
            {
                Some(c)
            }
            _ => None,
        })
        .collect()
}

/// The one label whose text is exactly `text`.
fn label_rect(h: &Harness<'_, LabApp>, text: &str) -> egui::Rect {
    let found: Vec<egui::Rect> = h
        .query_all_by_role(Role::Label)
        .filter(|n| n.accesskit_node().value().as_deref() == Some(text))
        .map(|n| n.rect())
        .collect();
    assert_eq!(found.len(), 1, "one label {text:?}");
    found[0]
}

/// How far apart two colours are (the sum of the channel differences, alpha ignored).
fn distance(a: Color32, b: Color32) -> u32 {
    let (a, b) = (a.to_srgba_unmultiplied(), b.to_srgba_unmultiplied());
    (0..3).map(|i| u32::from(a[i].abs_diff(b[i]))).sum()
}

#[test]
fn volume_table_swatches_match_the_canvas_and_hovering_a_row_lights_its_volume() {
    let mut h = volumes_lab();
    // Each volume its own colour, none the tree's boxes' blue, the selection's yellow or the
    // ray's cyan.
    for (i, &a) in FitKind::ALL.iter().enumerate() {
        for &b in &FitKind::ALL[i + 1..] {
            let d = distance(colors::volume(a), colors::volume(b));
            assert!(d > 90, "{a:?} and {b:?} look alike ({d})");
        }
        for (other, name) in [
            (colors::STRUCTURE, "the tree's boxes"),
            (colors::SELECTED, "the selection"),
            (colors::QUERY, "the ray"),
        ] {
            let d = distance(colors::volume(a), other);
            assert!(d > 90, "{a:?} looks like {name} ({d})");
        }
    }

    let shapes = painted(&h);
    for kind in FitKind::ALL {
        let color = colors::volume(kind);
        // The swatch: a square of the volume's colour just left of its row's name.
        let name = label_rect(&h, kind.label());
        let swatch = shapes.iter().any(|s| match s {
            Shape::Rect(RectShape { rect, fill, .. }) => {
                *fill == color
                    && rect.right() <= name.left() + 0.5
                    && name.left() - rect.right() < 20.0
                    && (rect.center().y - name.center().y).abs() < 6.0
            }
            _ => false,
        });
        assert!(
            swatch,
            "{kind:?} has a swatch in its colour beside its name"
        );
        // The view's legend (a strip above the canvas, issue 29) names it beside a square of
        // the same colour.
        let strip = h.state().ui.legend_rect.expect("the legend is shown");
        let canvas = h.state().canvas_screen().rect;
        assert!(!strip.intersects(canvas), "the legend is off the canvas");
        let legend = shapes.iter().find_map(|s| match s {
            Shape::Text(t)
                if t.galley.text() == colors::volume_name(kind) && strip.contains(t.pos) =>
            {
                Some(t.pos)
            }
            _ => None,
        });
        let legend = legend.unwrap_or_else(|| panic!("{kind:?} is in the canvas's legend"));
        let legend_square = shapes.iter().any(|s| match s {
            Shape::Rect(RectShape { rect, fill, .. }) => {
                *fill == color
                    && (legend.x - rect.right()) < 12.0
                    && rect.right() <= legend.x
                    && (rect.center().y - legend.y).abs() < 12.0
            }
            _ => false,
        });
        assert!(legend_square, "{kind:?}'s legend entry has its colour");
    }
    // The spheres are drawn in their colours, each where the core fitted it.
    for kind in SPHERES {
        let drawn = sphere_outlines(&h, kind);
        assert_eq!(drawn.len(), 1, "{kind:?} drawn once");
        assert!(drawn[0].stroke.width < 2.0, "not lit yet");
    }
    // The AABB is drawn in its colour, not in the tree's boxes'.
    let screen = h.state().canvas_screen();
    let aabb = h.state().lab().two().fits().expect("fits").aabb;
    let aabb_rect =
        egui::Rect::from_two_pos(screen.to_screen(aabb.min), screen.to_screen(aabb.max));
    assert!(shapes.iter().any(|s| matches!(s,
        Shape::Rect(r) if r.stroke.color == colors::volume(FitKind::Aabb)
            && (r.rect.min - aabb_rect.min).length() < 0.5
            && (r.rect.max - aabb_rect.max).length() < 0.5)));

    // Pointing at Welzl's row lights Welzl's sphere, and only it.
    h.hover_at(label_rect(&h, FitKind::SphereWelzl.label()).center());
    settle(&mut h);
    assert_eq!(h.state().ui.canvas.volume_hover, Some(FitKind::SphereWelzl));
    assert!(sphere_outlines(&h, FitKind::SphereWelzl)[0].stroke.width > 3.0);
    assert!(sphere_outlines(&h, FitKind::SphereCentroid)[0].stroke.width < 2.0);
    // Away from the table: nothing is lit.
    let canvas = h.state().canvas_screen().rect;
    h.hover_at(canvas.left_bottom() + egui::vec2(10.0, -10.0));
    settle(&mut h);
    assert_eq!(h.state().ui.canvas.volume_hover, None);
    assert!(sphere_outlines(&h, FitKind::SphereWelzl)[0].stroke.width < 2.0);

    // A volume switched off is not drawn, but pointing at its row shows it.
    act(
        &mut h,
        Action2d::SetVolumes(VolumeToggles {
            ritter: false,
            ..ALL_ON
        }),
    );
    assert!(sphere_outlines(&h, FitKind::SphereRitter).is_empty());
    h.hover_at(label_rect(&h, FitKind::SphereRitter.label()).center());
    settle(&mut h);
    assert_eq!(sphere_outlines(&h, FitKind::SphereRitter).len(), 1);
    let strip = h.state().ui.legend_rect.expect("the legend is shown");
    let ritter = colors::volume_name(FitKind::SphereRitter);
    assert!(
        !painted(&h).iter().any(|s| matches!(s,
            Shape::Text(t) if t.galley.text() == ritter && strip.contains(t.pos))),
        "the legend lists only the volumes switched on"
    );
}

/// Drags a ray across the preset's shape and turns the slab test on.
fn ray_and_slab_test(h: &mut Harness<'_, LabApp>) {
    let from = screen(h, Vec2::new(-9.0, -4.0));
    let to = screen(h, Vec2::new(8.0, 3.0));
    drag(h, from, to);
    assert!(h.state().lab().two().ray.is_some());
    click(h, "Slab test of the ray against the AABB");
    assert!(h.state().lab().two().display.slab_test);
}

/// The slab table's row `name`: min, max, e, d, the core's interval and the naive one.
fn slab_row(h: &Harness<'_, LabApp>, name: &str) -> Vec<String> {
    let all = labels(h);
    let header = all
        .iter()
        .position(|l| l == "naive: t in")
        .expect("the slab table");
    assert_eq!(
        all[header - 5..=header],
        ["min", "max", "e", "d", "core: t in", "naive: t in"],
        "the naive formula has its own column beside the core's"
    );
    let at = header
        + 1
        + all[header + 1..]
            .iter()
            .position(|l| l == name)
            .unwrap_or_else(|| panic!("a row {name:?}"));
    all[at + 1..at + 7].to_vec()
}

#[test]
fn the_slab_tests_failure_case_is_the_lectures_x_d_0_with_the_naive_nan_in_its_own_column() {
    let mut h = volumes_lab();
    ray_and_slab_test(&mut h);
    // A ray crossing the box: both columns agree.
    let x = slab_row(&h, "x");
    assert!(!x[5].contains("NaN"), "{x:?}");
    assert_eq!(x[4], x[5], "the naive formula is right here");

    // The lecture's case: x_d = 0, then the origin on the slab line x = x_min.
    click(&mut h, "Ray parallel to y (x_d = 0)");
    let r = h.state().lab().two().ray.expect("ray");
    assert_eq!(r.origin.x, r.target.x, "x_d = 0");
    label_containing(&h, "the ray is parallel to the x slab");
    let x = slab_row(&h, "x");
    assert!(!x[5].contains("NaN"), "1/0 = inf keeps it right: {x:?}");
    click(&mut h, "…and on the slab line x = x_min");
    let app = h.state();
    let r = app.lab().two().ray.expect("ray");
    let aabb = Aabb2::from_points(&app.lab().two().scene.vertices(&[]));
    assert_eq!((r.origin.x, r.target.x), (aabb.min.x, aabb.min.x));
    let x = slab_row(&h, "x");
    assert_eq!(x[3], "0.000", "x_d");
    assert_eq!(x[4], "[-inf, inf]", "the core: inside the slab for every t");
    assert_eq!(x[5], "[NaN, inf]", "the naive formula: 0/0 and 1/0");
    let y = slab_row(&h, "y");
    assert!(!y[5].contains("NaN"), "{y:?}");
    // The answers side by side: the core's hit, the naive formula's NaN comparison.
    let answer = slab_row(&h, "answer");
    assert_eq!(answer[4..], ["hit", "NaN compared"]);
    assert!(
        aabb.ray_interval(&r.ray().expect("valid")).is_some(),
        "the core: a hit"
    );

    // The other case is still offered: y_d = 0 on the line y = y_min.
    click(&mut h, "Ray parallel to x (y_d = 0)");
    click(&mut h, "…and on the slab line y = y_min");
    let r = h.state().lab().two().ray.expect("ray");
    assert_eq!((r.origin.y, r.target.y), (aabb.min.y, aabb.min.y));
    assert_eq!(slab_row(&h, "y")[5], "[NaN, inf]");
    assert!(!slab_row(&h, "x")[5].contains("NaN"));
}

#[test]
fn the_slab_buttons_stay_put_so_two_clicks_in_a_row_both_land() {
    let mut h = volumes_lab();
    ray_and_slab_test(&mut h);
    for (first, second, axis) in [
        (
            "Ray parallel to y (x_d = 0)",
            "…and on the slab line x = x_min",
            0,
        ),
        (
            "Ray parallel to x (y_d = 0)",
            "…and on the slab line y = y_min",
            1,
        ),
    ] {
        // Both positions from one frame, as a student aims at them.
        let (a, b): (Pos2, Pos2) = (
            h.get_by_label(first).rect().center(),
            h.get_by_label(second).rect().center(),
        );
        click_at(&mut h, a);
        assert_eq!(
            h.get_by_label(second).rect().center(),
            b,
            "the first click moved {second:?}"
        );
        click_at(&mut h, b);
        let app = h.state();
        let r = app.lab().two().ray.expect("ray");
        let aabb = Aabb2::from_points(&app.lab().two().scene.vertices(&[]));
        assert_eq!(r.origin[axis], aabb.min[axis], "the second click landed");
        assert_eq!(r.target[axis], aabb.min[axis]);
        assert_eq!(h.get_by_label(first).rect().center(), a);
    }
}

#[test]
fn changing_the_task_moves_nothing_below_it() {
    let mut h = lab();
    drag_test_ray(&mut h);
    let transport = h.get_by_label("first step").rect();
    for task in [
        "ray: any hit",
        "point: within a radius",
        "build the structure",
        "point: k nearest",
        "ray: first hit",
    ] {
        choose(&mut h, "step through", task);
        assert_eq!(
            h.get_by_label("first step").rect(),
            transport,
            "choosing {task:?} moved the transport"
        );
    }
    // The variants and the radius keep their rows, greyed out where they do not apply.
    choose(&mut h, "step through", "ray: any hit");
    assert!(
        h.get_by_label("the slides' version")
            .accesskit_node()
            .is_disabled()
    );
    assert!(
        h.get_by_role_and_label(Role::Slider, "radius")
            .accesskit_node()
            .is_disabled()
    );
    choose(&mut h, "step through", "ray: first hit");
    assert!(
        !h.get_by_label("the slides' version")
            .accesskit_node()
            .is_disabled()
    );
}

#[test]
fn ray_sphere_has_its_own_section_before_a_ray_and_after() {
    let mut h = volumes_lab();
    // Before a ray: the heading, and what the section will show.
    let heading = label_rect(&h, "Ray-sphere test");
    let said = label_containing(&h, "to test it against each sphere");
    assert!(said.contains("a t² + b t + c = 0"), "{said}");
    assert!(said.contains("a = (s - e)·(s - e), b = 2 e·(s - e), c = e·e - r²"));
    // In the lecture's order: the spheres before the AABB's slab test.
    let slab = h
        .get_by_label("Slab test of the ray against the AABB")
        .rect();
    assert!(heading.bottom() <= slab.top());

    ray_and_slab_test(&mut h);
    let ray = h.state().lab().two().valid_ray().expect("a ray");
    let all = labels(&h);
    let start = all
        .iter()
        .position(|l| l == "b² - 4ac")
        .expect("the ray-sphere table");
    for (kind, name) in SPHERES.into_iter().zip(["centroid", "Ritter", "Welzl"]) {
        let q = sphere(&h, kind).ray_quadratic(&ray);
        let at = start
            + all[start..]
                .iter()
                .position(|l| l == name)
                .unwrap_or_else(|| panic!("a row for {name}"));
        let row = &all[at + 1..at + 7];
        assert_eq!(
            row[..4],
            [
                format!("{:.3}", q.a),
                format!("{:.3}", q.b),
                format!("{:.3}", q.c),
                format!("{:.3}", q.discriminant()),
            ],
            "{name}"
        );
        let (t0, t1) = q
            .roots()
            .expect("the ray crosses the shape, so every sphere");
        assert_eq!(row[4], format!("{t0:.3}, {t1:.3}"));
        assert_eq!(row[5], if t0 >= 0.0 { "hits" } else { "starts inside" });
    }
    assert!(
        !shows(&h, "Ray-sphere (centroid sphere):"),
        "not a line any more"
    );
}

#[test]
fn the_bounding_volumes_preset_has_a_looser_centroid_sphere_and_fit_view_shows_every_sphere() {
    let mut h = volumes_lab();
    let (centroid, welzl) = (
        sphere(&h, FitKind::SphereCentroid).radius,
        sphere(&h, FitKind::SphereWelzl).radius,
    );
    assert!(
        centroid >= 1.15 * welzl,
        "the centroid sphere ({centroid}) is visibly looser than Welzl's ({welzl})"
    );
    // Zoomed in on the shape, then "Fit view".
    let mut camera = h.state().lab().two().camera;
    camera.scale *= 3.0;
    act(&mut h, Action2d::SetCamera(camera));
    click(&mut h, "Fit view");
    let (lo, hi) = h.state().canvas_screen().visible_world();
    for kind in SPHERES {
        let s = sphere(&h, kind);
        assert!(
            (s.center - Vec2::splat(s.radius)).cmpge(lo).all()
                && (s.center + Vec2::splat(s.radius)).cmple(hi).all(),
            "{kind:?} {s:?} lies inside the view [{lo}, {hi}]"
        );
    }
}

/// The counters' row names in the queries panel (before the "Step through" panel).
fn counter_names(h: &Harness<'_, LabApp>) -> Vec<String> {
    let mut all = labels(h);
    if let Some(end) = all.iter().position(|l| l == "Step through") {
        all.truncate(end);
    }
    let at = all
        .iter()
        .position(|l| l == "brute force")
        .expect("the counters");
    vec![
        all[at + 1].clone(),
        all[at + 4].clone(),
        all[at + 7].clone(),
    ]
}

/// Moves the playback to just after the first event `pick` accepts, and returns the step's
/// sentence.
fn sentence_at(h: &mut Harness<'_, LabApp>, pick: impl Fn(&Event<Vec2>) -> bool) -> String {
    let rec = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .recorded()
        .expect("recorded");
    let i = rec.events.iter().position(pick).expect("such an event");
    act(h, PlaybackAction::GoTo(i + 1));
    label_containing(h, &format!("step {}: ", i + 1))
}

#[test]
fn the_panels_use_the_lectures_words() {
    let mut h = lab();
    drag_test_ray(&mut h);
    assert_eq!(
        counter_names(&h),
        ["nodes visited", "BV tests", "primitive tests"]
    );
    // A queued child's key is where the ray enters it.
    let said = sentence_at(&mut h, |e| matches!(e, Event::ChildQueued { .. }));
    assert!(said.contains("(tEnter "), "{said}");
    assert!(!said.contains("key"), "{said}");

    // A quadtree tests cells; a grid visits and tests cells.
    choose(&mut h, "Structure", StructureKind::Quadtree.label());
    assert_eq!(
        counter_names(&h),
        ["nodes visited", "cell tests", "primitive tests"]
    );
    choose(&mut h, "Structure", StructureKind::Grid.label());
    assert_eq!(
        counter_names(&h),
        ["cells visited", "cell tests", "primitive tests"]
    );
    assert!(!shows(&h, "BV tests"));
    // A grid's build fills cells, it makes no leaves.
    act(&mut h, HalfAction::SetTask(Task::Build));
    let said = sentence_at(&mut h, |e| matches!(e, Event::BuildLeaf { .. }));
    assert!(
        said.contains(": cell ") && said.contains(" lists "),
        "{said}"
    );
    assert!(!said.contains("leaf"), "{said}");

    // A k-d tree's build splits by a split plane, in words.
    choose(&mut h, "Structure", StructureKind::KdTree.label());
    act(&mut h, HalfAction::SetTask(Task::Build));
    let said = sentence_at(&mut h, |e| matches!(e, Event::BuildSplit { .. }));
    assert!(said.contains("by the split plane "), "{said}");
    assert!(!said.contains("·p"), "{said}");

    // The closest-point walk reads as the lecture's minDistance, with pruning.
    choose(&mut h, "Structure", StructureKind::AabbTree.label());
    act(&mut h, Action2d::SetPoint(Some(Vec2::new(10.0, 10.0))));
    act(&mut h, HalfAction::SetTask(Task::Nearest));
    assert!(shows(&h, "BVH: minDistance with pruning"));
    assert!(shows(&h, "minDistance(root, point, k)"));
    assert!(!labels(&h).iter().any(|l| l.contains("kNearest")));
    let said = sentence_at(&mut h, |e| matches!(e, Event::ChildQueued { .. }));
    assert!(said.contains("(distance "), "{said}");
}
