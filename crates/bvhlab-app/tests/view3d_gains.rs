//! What the 3D half gained in the redesign, checked from the outside: the tree diagram below
//! the view, linked to it both ways; a second structure to compare with, side by side on the
//! same question; and the view exported as SVG for slides.

use crate::common;

use bvhlab::RayCast;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::{BruteForce, NodeId, NodeOutline, Ray3, SpatialIndex, Triangle3};
use bvhlab_app::LabApp;
use bvhlab_app::lab3d::draw::{Draw3d, rgba};
use bvhlab_app::lab3d::picture::picture;
use bvhlab_app::lab3d::wire::{self, Segment};
use bvhlab_app::model::build_job::Structure;
use bvhlab_app::model::lab3d::Lab3d;
use bvhlab_app::model::mesh::MeshSource;
use bvhlab_app::model::orbit_camera::OrbitCamera;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::{Action, Action3d, Dimension, HalfAction, PlaybackAction};
use bvhlab_app::paint::colors;
use bvhlab_app::pseudocode::Task;
use common::{act, click, lab, label_containing, labels, settle};
use egui::{Pos2, Rect, pos2};
use egui_kittest::Harness;
use roxmltree::{Document, Node};

// ---------- the lab in 3D ----------

fn three<'a>(h: &'a Harness<'_, LabApp>) -> &'a Lab3d {
    h.state().lab().three()
}

/// Lane `index`'s structure, when built on the mesh shown with the lane's settings.
fn built_at<'a>(h: &'a Harness<'_, LabApp>, index: usize) -> Option<&'a Structure<Triangle3>> {
    let lab = three(h);
    lab.half.lane_at(index).current(lab.revision())
}

/// Frames run until every lane's structure is built (or a limit, which fails).
fn until_built(h: &mut Harness<'_, LabApp>) {
    for _ in 0..2_000 {
        let lab = three(h);
        let all = (0..lab.half.lane_count()).all(|i| built_at(h, i).is_some());
        if all && !lab.busy() {
            settle(h);
            return;
        }
        h.step();
    }
    panic!("the structures were not built in 2,000 frames");
}

/// The lab switched to 3D, the bunny loaded and built, and its tree diagram shown (the 3D
/// view opens without it, to keep the room for the view).
fn lab_3d() -> Harness<'static, LabApp> {
    let mut h = lab();
    click(&mut h, "3D: meshes");
    assert_eq!(h.state().lab().dimension(), Dimension::Three);
    until_built(&mut h);
    assert!(
        !h.state().ui.panels.tree3d,
        "the 3D tree diagram starts hidden"
    );
    assert!(
        !labels(&h).iter().any(|l| l.contains(" leaves, ")),
        "no diagram yet"
    );
    click(&mut h, "tree diagram");
    assert!(h.state().ui.panels.tree3d && h.state().ui.panels.tree);
    h
}

/// The box (or sphere, or cell) of `shape` as the wire segments the view draws.
fn wire_of(shape: &bvhlab::NodeShape<Vec3>) -> Vec<Segment> {
    let mut out = Vec::new();
    wire::shape(shape, [0.0; 4], 0.0, &mut out);
    out
}

/// Whether every segment of `wire` is drawn on top of the mesh in the hover colour.
fn lit(drawn: &Draw3d, wire: &[Segment]) -> bool {
    let selected = rgba(colors::SELECTED, 1.0);
    wire.iter().all(|w| {
        drawn
            .overlay
            .iter()
            .any(|s| s.a == w.a && s.b == w.b && s.color == selected)
    })
}

/// The triangles in the subtree of `node`.
fn subtree_triangles(outline: &[NodeOutline<Vec3>], node: NodeId) -> Vec<u32> {
    let mut out = Vec::new();
    let mut stack = vec![node];
    while let Some(id) = stack.pop() {
        let n = &outline[id.index()];
        out.extend(&n.primitives);
        stack.extend(&n.children);
    }
    out.sort_unstable();
    out
}

/// The triangles the draw list lights in the hover colour.
fn lit_triangles(drawn: &Draw3d) -> Vec<u32> {
    let selected = rgba(colors::SELECTED, 1.0);
    let mut out: Vec<u32> = drawn
        .highlights
        .iter()
        .filter(|(_, c)| *c == selected)
        .map(|(t, _)| *t)
        .collect();
    out.sort_unstable();
    out
}

// ---------- (1) the tree diagram ----------

#[test]
fn the_tree_diagram_shows_the_bunnys_tree_and_is_linked_to_the_view_both_ways() {
    let mut h = lab_3d();
    let structure = built_at(&h, 0).expect("built");
    assert_eq!(structure.settings.kind, StructureKind::AabbTree);
    let outline = structure
        .outline
        .clone()
        .expect("the bunny's tree is listed");
    // The summary above the diagram is the outline's.
    let leaves = outline.iter().filter(|n| n.is_leaf()).count();
    let levels = outline.iter().map(|n| n.depth).max().expect("nodes") + 1;
    assert_eq!(
        label_containing(&h, " leaves, "),
        format!("{} nodes, {leaves} leaves, {levels} levels", outline.len())
    );
    assert_eq!(outline.len(), structure.node_count);

    // Hovering an inner node in the diagram lights its box and its triangles in the view.
    let node = outline
        .iter()
        .find(|n| n.depth == 2 && !n.is_leaf())
        .expect("an inner node two levels down")
        .id;
    let tree_rect = h.state().ui.tree_rect.expect("the tree panel is shown");
    let at = h.state().ui.trees.three[0]
        .node_screen_pos(node)
        .expect("drawn");
    assert!(tree_rect.contains(at), "{at:?} in {tree_rect:?}");
    let box_wire = wire_of(&outline[node.index()].shape);
    let triangles = subtree_triangles(&outline, node);
    assert!(triangles.len() > 4 && triangles.len() < outline.len());
    {
        let drawn = &h.state().ui.view3d.drawn;
        assert_eq!(drawn.len(), 1, "one view");
        assert!(!lit(&drawn[0], &box_wire), "not lit before the hover");
        assert!(lit_triangles(&drawn[0]).is_empty());
    }
    h.hover_at(at);
    h.step();
    h.step();
    assert_eq!(h.state().ui.hovered, Some((0, node)), "the diagram's hover");
    let drawn = &h.state().ui.view3d.drawn[0];
    assert!(lit(drawn, &box_wire), "the node's box is lit in the view");
    assert_eq!(lit_triangles(drawn), triangles, "and its triangles");

    // Hovering the bunny in the view finds the leaf holding the triangle under the pointer:
    // the view lights it, and the diagram is told (the next frame, as it is drawn first).
    let rect = h.state().ui.view3d.rect;
    let at = rect.center() + egui::vec2(3.0, -7.0);
    let lab = three(&h);
    let ray = lab
        .camera
        .ray_through(
            Vec2::new(at.x - rect.min.x, at.y - rect.min.y),
            Vec2::new(rect.width(), rect.height()),
        )
        .expect("a ray");
    let hit = BruteForce::build(lab.triangles())
        .ray_first_hit(&ray, f32::INFINITY)
        .expect("the middle of the view is on the bunny");
    let leaf = outline
        .iter()
        .find(|n| n.is_leaf() && n.primitives.contains(&(hit.prim as u32)))
        .expect("a leaf lists the triangle")
        .id;
    h.hover_at(at);
    h.step();
    h.step();
    assert_eq!(h.state().ui.hovered, Some((0, leaf)), "the view's hover");
    assert_eq!(h.state().ui.linked, Some((0, leaf)), "shown in the diagram");
    let drawn = &h.state().ui.view3d.drawn[0];
    assert!(lit(drawn, &wire_of(&outline[leaf.index()].shape)));
    assert!(lit_triangles(drawn).contains(&(hit.prim as u32)));
    // The link can be switched off.
    click(&mut h, "hover finds nodes");
    h.hover_at(at);
    h.step();
    h.step();
    assert_eq!(h.state().ui.hovered, None);
    assert!(lit_triangles(&h.state().ui.view3d.drawn[0]).is_empty());
}

// ---------- (2) comparing two structures ----------

#[test]
fn compare_with_makes_two_lanes_answering_the_same_question_like_brute_force() {
    let mut h = lab_3d();
    click(&mut h, "compare with");
    until_built(&mut h);
    let lab = three(&h);
    assert_eq!(lab.half.lane_count(), 2);
    assert_eq!(lab.half.lane.settings.kind, StructureKind::AabbTree);
    assert_eq!(
        lab.half.lane_at(1).settings.kind,
        StructureKind::SphereTree,
        "the checkbox compares with another structure"
    );
    // Two views side by side, and a tree diagram for each lane.
    assert_eq!(h.state().ui.view3d.drawn.len(), 2);
    let summaries = labels(&h)
        .into_iter()
        .filter(|l| l.contains(" leaves, "))
        .count();
    assert_eq!(summaries, 2, "{:#?}", labels(&h));
    // Framing the mesh put a ray and a point in it, for the questions below.
    assert!(lab.ray.is_some() && lab.point.is_some());
    for second in [
        StructureKind::SphereTree,
        StructureKind::KdTree,
        StructureKind::Grid,
    ] {
        let mut settings = three(&h).half.lane.settings;
        settings.kind = second;
        act(&mut h, HalfAction::SetCompare(Some(settings)));
        until_built(&mut h);
        for task in [
            Task::FirstHit,
            Task::AnyHit,
            Task::AllHits,
            Task::Nearest,
            Task::Range,
        ] {
            act(&mut h, HalfAction::SetTask(task));
            let half = &three(&h).half;
            let recordings: Vec<_> = half
                .lanes()
                .map(|lane| {
                    lane.recorded()
                        .unwrap_or_else(|| panic!("{second:?} {task:?}: {:?}", lane.recording))
                })
                .collect();
            assert_eq!(recordings.len(), 2);
            let [a, b] = [recordings[0], recordings[1]];
            let question = |r: &bvhlab_app::model::recording::Recording<Vec3>| {
                let q = r.question;
                (q.task, q.ray, q.point, q.k, q.radius)
            };
            assert_eq!(question(a), question(b), "{second:?} {task:?}");
            assert_eq!(a.question.task, task);
            assert_eq!(a.brute_answer, b.brute_answer, "{second:?} {task:?}");
            assert!(a.agrees() && b.agrees(), "{second:?} {task:?}");
            let reports = &h.state().report.playback;
            assert_eq!(reports.len(), 2);
            assert!(
                reports
                    .iter()
                    .all(|r| r.agrees && r.task == format!("{task:?}"))
            );
        }
    }
    // Both lanes step together.
    act(&mut h, HalfAction::SetTask(Task::FirstHit));
    act(&mut h, PlaybackAction::GoTo(0));
    act(&mut h, PlaybackAction::StepBy(1));
    let steps: Vec<usize> = h.state().report.playback.iter().map(|r| r.step).collect();
    assert_eq!(steps, [1, 1]);
    // Each half keeps its own comparison (and task).
    assert!(h.state().lab().two().half.compare.is_none());
    assert_eq!(h.state().lab().two().half.task, Task::FirstHit);
    // Unticking ends it.
    click(&mut h, "compare with");
    assert!(three(&h).half.compare.is_none());
    assert_eq!(h.state().ui.view3d.drawn.len(), 1);
}

// ---------- (3) the view as SVG ----------

/// The exported area: not at the origin, so a picture that ignored it would show.
const AREA: Rect = Rect {
    min: pos2(10.0, 20.0),
    max: pos2(490.0, 380.0),
};

/// Coordinates are written with two decimals; projections are of `f32`s hundreds of points
/// across.
const TOLERANCE: f32 = 0.02;

/// The built-in cube in a lab framed for [`AREA`], with its structure built and `more`
/// applied.
fn cube_lab(more: impl IntoIterator<Item = Action>) -> LabApp {
    let mut app = LabApp::with([
        Action3d::OpenMesh(MeshSource::Builtin("cube".to_owned())).into(),
        Action::Tick {
            seconds: 0.0,
            build_ms: 1e6,
        },
        Action3d::Frame {
            aspect: AREA.aspect_ratio(),
        }
        .into(),
    ]);
    for action in more {
        app.apply(action).expect("applies");
    }
    let lab = app.lab().three();
    assert_eq!(lab.triangles().len(), 12, "the cube");
    assert!(lab.placed());
    assert!(lab.half.lane.current(lab.revision()).is_some(), "built");
    app
}

/// Where a world point is in the picture.
fn on_screen(camera: &OrbitCamera, p: Vec3) -> Pos2 {
    let q = camera
        .project(p, Vec2::new(AREA.width(), AREA.height()))
        .expect("in front of the eye");
    AREA.min + egui::vec2(q.x, q.y)
}

/// The SVG of the lab's 3D view, as the "View: SVG" button writes it.
fn svg_of(lab: &Lab3d) -> String {
    let shapes = picture(lab, &bvhlab_app::model::predict::About::default(), AREA);
    bvhlab_app::export::svg_document(&shapes, AREA, bvhlab_app::lab3d::BACKGROUND)
}

fn parse(text: &str) -> Document<'_> {
    Document::parse(text).unwrap_or_else(|e| panic!("not valid XML ({e}):\n{text}"))
}

fn number(node: Node<'_, '_>, name: &str) -> f32 {
    node.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", node.tag_name().name()))
        .parse()
        .expect("a number")
}

/// Whether `node`'s `which` paint (`#rrggbb`) is the colour `c` the view draws (straight, as
/// [`rgba`] gives it), within what premultiplied 8-bit alpha keeps of a translucent one.
fn painted(node: Node<'_, '_>, which: &str, c: egui::Color32) -> bool {
    let Some(hex) = node.attribute(which).and_then(|v| v.strip_prefix('#')) else {
        return false;
    };
    let want = rgba(c, 1.0).map(|v| (v * 255.0).round() as i16);
    (0..3).all(|i| {
        let got = i16::from_str_radix(&hex[2 * i..2 * i + 2], 16).expect("hex");
        (got - want[i]).abs() <= 3
    })
}

/// The lines drawn in `color`: their two ends.
fn lines_in(doc: &Document<'_>, color: egui::Color32) -> Vec<[Pos2; 2]> {
    doc.descendants()
        .filter(|n| n.has_tag_name("line") && painted(*n, "stroke", color))
        .map(|n| {
            [
                pos2(number(n, "x1"), number(n, "y1")),
                pos2(number(n, "x2"), number(n, "y2")),
            ]
        })
        .collect()
}

/// Every triangle of the `<path>`s (subpaths `M a L b L c Z`, as meshes are written).
fn path_triangles(doc: &Document<'_>) -> Vec<[Pos2; 3]> {
    let mut out = Vec::new();
    for path in doc.descendants().filter(|n| n.has_tag_name("path")) {
        let d = path.attribute("d").expect("d");
        for sub in d.split('Z').map(str::trim).filter(|s| !s.is_empty()) {
            let points: Vec<Pos2> = sub
                .split(['M', 'L'])
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(|pair| {
                    let (x, y) = pair.split_once([',', ' ']).expect("x,y");
                    pos2(x.trim().parse().expect("x"), y.trim().parse().expect("y"))
                })
                .collect();
            assert_eq!(points.len(), 3, "a triangle: {sub}");
            out.push([points[0], points[1], points[2]]);
        }
    }
    out
}

fn near(a: Pos2, b: Pos2) -> bool {
    (a - b).length() <= TOLERANCE
}

/// Whether two triangles have the same corners, in any order.
fn same_triangle(a: &[Pos2; 3], b: &[Pos2; 3]) -> bool {
    a.iter().all(|p| b.iter().any(|q| near(*p, *q)))
}

/// Whether `p` is inside the triangle (or on its edge).
fn covers(t: &[Pos2; 3], p: Pos2) -> bool {
    let side = |a: Pos2, b: Pos2| (b - a).x * (p - a).y - (b - a).y * (p - a).x;
    let s = [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])];
    s.iter().all(|&v| v >= -1e-3) || s.iter().all(|&v| v <= 1e-3)
}

/// A ray from beside the view towards the cube's centre, so that it is seen from the side.
fn side_ray(lab: &Lab3d) -> Ray3 {
    let mesh = lab.mesh.as_ref().expect("the cube");
    let bounds = mesh.bounds();
    let centre = (bounds.min + bounds.max) * 0.5;
    let basis = lab.camera.basis();
    let origin = centre + (basis.right * 1.2 + basis.up * 0.4) * mesh.size();
    Ray3::new(origin, centre + basis.up * mesh.size() * 0.1 - origin).expect("a ray")
}

#[test]
fn the_3d_view_exports_as_svg_with_the_ray_and_the_cubes_triangles() {
    let framed = cube_lab([]);
    let ray = side_ray(framed.lab().three());
    let app = cube_lab([Action3d::SetRay(Some(ray)).into()]);
    let lab = app.lab().three();
    let camera = lab.camera;
    let text = svg_of(lab);
    let doc = parse(&text);
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    assert_eq!(root.attribute("viewBox"), Some("10 20 480 360"));

    // The ray, from its origin to the first hit brute force finds.
    let hit = BruteForce::build(lab.triangles())
        .ray_first_hit(&ray, f32::INFINITY)
        .expect("the ray is aimed at the cube");
    let (from, to) = (
        on_screen(&camera, ray.origin()),
        on_screen(&camera, ray.at(hit.t)),
    );
    let rays = lines_in(&doc, colors::QUERY);
    assert!(
        rays.iter().any(|[a, b]| near(*a, from) && near(*b, to)),
        "the ray {from:?} -> {to:?} among {rays:?}"
    );
    // The hit's marker is there too.
    assert!(
        doc.descendants().any(|n| n.has_tag_name("circle")
            && painted(n, "fill", colors::ANSWER)
            && near(pos2(number(n, "cx"), number(n, "cy")), to)),
        "the hit's dot"
    );
    // The structure's level is drawn as lines.
    assert!(!lines_in(&doc, colors::STRUCTURE).is_empty());

    // Every triangle of the cube, projected, and nothing else.
    let drawn = path_triangles(&doc);
    assert_eq!(drawn.len(), 12, "{drawn:?}");
    for t in lab.triangles() {
        let want = [t.a, t.b, t.c].map(|p| on_screen(&camera, p));
        assert!(
            drawn.iter().any(|d| same_triangle(d, &want)),
            "{want:?} among {drawn:?}"
        );
    }
}

#[test]
fn the_svg_shows_what_is_in_front_of_the_eye_when_the_camera_is_inside_the_cube() {
    // The camera in the middle of the cube: every face is partly behind the eye, and the
    // picture still shows the faces around it (cut at the near plane, as the GPU cuts them),
    // and the ray from behind the eye to its hit.
    let framed = cube_lab([]);
    let mut camera = framed.lab().three().camera;
    let size = framed.lab().three().mesh.as_ref().expect("the cube").size();
    camera.distance = size * 0.05;
    let basis = camera.basis();
    let origin = camera.eye() - basis.forward * size * 0.2 + basis.right * size * 0.05;
    let ray = Ray3::new(origin, basis.forward + basis.up * 0.2).expect("a ray");
    let app = cube_lab([
        Action3d::SetCamera(camera).into(),
        Action3d::SetRay(Some(ray)).into(),
    ]);
    let lab = app.lab().three();
    let doc_text = svg_of(lab);
    let doc = parse(&doc_text);
    let triangles = path_triangles(&doc);
    for p in [
        AREA.center(),
        AREA.min + egui::vec2(5.0, 5.0),
        AREA.max - egui::vec2(5.0, 5.0),
    ] {
        assert!(
            triangles.iter().any(|t| covers(t, p)),
            "{p:?} is on no triangle: {triangles:?}"
        );
    }
    // The ray's visible part: it ends at the hit, and runs along the ray's projection.
    let hit = BruteForce::build(lab.triangles())
        .ray_first_hit(&ray, f32::INFINITY)
        .expect("the ray leaves the cube through a face");
    let depth = |p: Vec3| (p - camera.eye()).dot(basis.forward);
    assert!(depth(ray.origin()) < 0.0 && depth(ray.at(hit.t)) > 0.0);
    let end = on_screen(&camera, ray.at(hit.t));
    // A point of the ray between the eye's plane and the hit.
    let t_mid = (hit.t + ray.origin().distance(camera.eye()) / ray.dir().length()) * 0.5;
    assert!(depth(ray.at(t_mid)) > 0.0);
    let mid = on_screen(&camera, ray.at(t_mid));
    let rays = lines_in(&doc, colors::QUERY);
    // The segment runs from where the ray comes into view to its hit: through `mid`, and on
    // past it towards the eye.
    let along = rays.iter().any(|[a, b]| {
        let (u, v) = (*a - end, mid - end);
        near(*b, end)
            && (u.x * v.y - u.y * v.x).abs() <= 1e-3 * u.length() * v.length()
            && u.dot(v) > 0.0
            && u.length() >= v.length()
    });
    assert!(
        along,
        "the ray's visible part ending at {end:?} through {mid:?} among {rays:?}"
    );
}
