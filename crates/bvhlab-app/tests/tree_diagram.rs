//! The tree diagram alone in a headless harness: the pointer finds the node it is on, clicks,
//! pans, zooms and "Fit" move the picture as they should, the node hovered on the canvas is
//! brought into view, grids and empty scenes get their words, a 20,000-node tree is laid out,
//! and the exported picture colours exactly the nodes the query marked.

use bvhlab::glam::Vec2;
use bvhlab::{BruteForce, NodeId, NodeOutline, Ray2, SpatialIndex};
use bvhlab_app::model::outcome::{NodeMark, NodeMarks, RayOutcome};
use bvhlab_app::model::presets::random_segments;
use bvhlab_app::model::structures::{BuildSettings, Built, StructureKind};
use bvhlab_app::paint::colors;
use bvhlab_app::tree_diagram::{EMPTY_MESSAGE, TreeDiagram, TreeHighlight, TreeResponse};
use egui::accesskit::Role;
use egui::{Event, Modifiers, PointerButton, Pos2, Rect, Shape, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

const WINDOW: egui::Vec2 = vec2(700.0, 450.0);

/// The widget's state, its input, and what it answered.
struct Diagram {
    widget: TreeDiagram,
    outline: Vec<NodeOutline<Vec2>>,
    linked: Option<NodeId>,
    marks: Option<NodeMarks>,
    response: TreeResponse,
    /// The last click any frame reported (a click's frame is followed by quiet ones).
    clicked: Option<NodeId>,
}

fn outline(kind: StructureKind, segments: usize, leaf_size: usize) -> Vec<NodeOutline<Vec2>> {
    let prims = random_segments(segments, 30.0, 2.0, 11)
        .primitives()
        .segments;
    let settings = BuildSettings {
        kind,
        leaf_size,
        ..BuildSettings::default()
    };
    Built::build(&prims, &settings).outline()
}

fn harness(outline: Vec<NodeOutline<Vec2>>) -> Harness<'static, Diagram> {
    let state = Diagram {
        widget: TreeDiagram::default(),
        outline,
        linked: None,
        marks: None,
        response: TreeResponse::default(),
        clicked: None,
    };
    let mut h = Harness::builder().with_size(WINDOW).build_ui_state(
        |ui, s: &mut Diagram| {
            let highlight = TreeHighlight {
                linked: s.linked,
                marks: s.marks.as_ref(),
                ..TreeHighlight::default()
            };
            s.response = s.widget.show(ui, &s.outline, &highlight);
            s.clicked = s.response.clicked.or(s.clicked);
        },
        state,
    );
    h.run();
    h
}

fn at(h: &Harness<'_, Diagram>, id: usize) -> Pos2 {
    h.state()
        .widget
        .node_screen_pos(NodeId(id as u32))
        .expect("shown")
}

fn hover(h: &mut Harness<'_, Diagram>, p: Pos2) -> Option<NodeId> {
    h.hover_at(p);
    h.run();
    h.state().response.hovered
}

fn drag(h: &mut Harness<'_, Diagram>, from: Pos2, to: Pos2) {
    h.hover_at(from);
    h.step();
    h.drag_at(from);
    h.step();
    for i in 1..=8 {
        h.hover_at(from.lerp(to, i as f32 / 8.0));
        h.step();
    }
    h.drop_at(to);
    h.run();
}

fn labels(h: &Harness<'_, Diagram>) -> Vec<String> {
    h.query_all_by_role(Role::Label)
        .filter_map(|n| n.accesskit_node().value())
        .collect()
}

/// The diagram's area: everything below the toolbar, inside the window.
fn diagram_area(h: &Harness<'_, Diagram>) -> Rect {
    let toolbar = h.get_by_label("Fit the tree diagram").rect();
    Rect::from_min_max(pos2(0.0, toolbar.bottom()), WINDOW.to_pos2())
}

#[test]
fn hovering_and_clicking_a_node_report_it() {
    let outline = outline(StructureKind::AabbTree, 200, 2);
    let root = outline
        .iter()
        .position(|n| n.parent.is_none())
        .expect("a root");
    let leaf = outline
        .iter()
        .position(NodeOutline::is_leaf)
        .expect("a leaf");
    let deepest = (0..outline.len())
        .max_by_key(|&i| outline[i].depth)
        .expect("nodes");
    let mut h = harness(outline);
    let area = diagram_area(&h);
    for id in [root, leaf, deepest, h.state().outline.len() - 1] {
        let p = at(&h, id);
        assert!(area.contains(p), "node {id} at {p:?} is on screen");
        assert_eq!(hover(&mut h, p), Some(NodeId(id as u32)), "node {id}");
        // A couple of points off the centre is still on it.
        assert_eq!(hover(&mut h, p + vec2(1.5, 1.0)), Some(NodeId(id as u32)));
    }
    // The tooltip names the node last hovered, with its depth from the outline.
    let depth = h.state().outline[h.state().outline.len() - 1].depth;
    let id = h.state().outline.len() - 1;
    let tip = format!("node {id}, depth {depth}\n");
    assert!(
        labels(&h).iter().any(|l| l.starts_with(&tip)),
        "{tip:?} in {:#?}",
        labels(&h)
    );
    // Far from every node (the bottom-right corner, below the deepest level): nothing.
    let corner = area.right_bottom() - vec2(3.0, 3.0);
    assert_eq!(hover(&mut h, corner), None);

    let p = at(&h, leaf);
    h.hover_at(p);
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos: p,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.run();
    assert_eq!(h.state().clicked, Some(NodeId(leaf as u32)));
}

#[test]
fn drag_pans_zoom_keeps_the_anchor_and_fit_restores() {
    let mut h = harness(outline(StructureKind::Quadtree, 150, 1));
    let (a, b) = (0, h.state().outline.len() - 1);
    let (a0, b0) = (at(&h, a), at(&h, b));
    let area = diagram_area(&h);
    let from = area.left_bottom() + vec2(20.0, -20.0);
    drag(&mut h, from, from + vec2(120.0, -40.0));
    let moved = at(&h, a) - a0;
    assert!(
        (moved - vec2(120.0, -40.0)).length() < 1.0,
        "panned by {moved:?}"
    );
    assert!(
        (at(&h, b) - b0 - moved).length() < 1e-3,
        "the whole picture moved"
    );

    // Zoom in at the node nearest the middle: it stays under the pointer, the others spread
    // away from it.
    let middle = area.center();
    let b = (0..h.state().outline.len())
        .min_by(|&i, &j| {
            at(&h, i)
                .distance(middle)
                .total_cmp(&at(&h, j).distance(middle))
        })
        .expect("nodes");
    let anchor = at(&h, b);
    assert!(area.contains(anchor));
    let before = at(&h, a).distance(anchor);
    h.hover_at(anchor);
    h.event(Event::Zoom(1.5));
    h.run();
    assert!(at(&h, b).distance(anchor) < 0.5, "the anchor stays");
    assert!(
        at(&h, a).distance(anchor) > before * 1.2,
        "the rest spreads"
    );

    h.get_by_label("Fit the tree diagram").click();
    h.run();
    assert!(at(&h, a).distance(a0) < 1e-3);
    let last = h.state().outline.len() - 1;
    assert!(at(&h, last).distance(b0) < 1e-3);
}

#[test]
fn the_node_hovered_on_the_canvas_is_brought_into_view() {
    let mut h = harness(outline(StructureKind::KdTree, 300, 1));
    let area = diagram_area(&h);
    let target = h.state().outline.len() / 2;
    // Pan the diagram far to the right, three times across the window.
    for _ in 0..3 {
        let from = area.left_bottom() + vec2(10.0, -10.0);
        drag(&mut h, from, from + vec2(area.width() - 30.0, 0.0));
    }
    assert!(!area.contains(at(&h, target)), "panned out of view");
    h.state_mut().linked = Some(NodeId(target as u32));
    h.run();
    let p = at(&h, target);
    assert!(
        area.contains(p),
        "linked node {target} at {p:?}, area {area:?}"
    );
    assert_eq!(hover(&mut h, p), Some(NodeId(target as u32)));
}

#[test]
fn a_grid_is_shown_as_cells_with_a_caption_and_an_empty_scene_as_words() {
    let mut h = harness(outline(StructureKind::Grid, 200, 2));
    let caption = labels(&h)
        .into_iter()
        .find(|l| l.starts_with("A uniform grid is not a tree"))
        .expect("the caption");
    let cells = h.state().outline.len();
    assert!(caption.contains(&format!("its {cells} cells")), "{caption}");
    for id in [0, cells / 3, cells - 1] {
        let p = at(&h, id);
        assert_eq!(hover(&mut h, p), Some(NodeId(id as u32)));
    }

    let mut h = harness(outline(StructureKind::BruteForce, 200, 2));
    assert!(labels(&h).iter().any(|l| l == EMPTY_MESSAGE));
    assert_eq!(hover(&mut h, pos2(300.0, 200.0)), None);
    let mut h = harness(outline(StructureKind::AabbTree, 0, 2));
    assert!(labels(&h).iter().any(|l| l == EMPTY_MESSAGE));
    assert_eq!(hover(&mut h, pos2(300.0, 200.0)), None);
}

#[test]
fn twenty_thousand_nodes_are_laid_out_and_exported_fitted() {
    let outline = outline(StructureKind::AabbTree, 10_000, 1);
    assert!(outline.len() >= 19_999, "{} nodes", outline.len());
    let root = outline
        .iter()
        .position(|n| n.parent.is_none())
        .expect("root");
    let mut h = harness(outline);
    let area = diagram_area(&h);
    let n = h.state().outline.len();
    for id in 0..n {
        let p = at(&h, id);
        assert!(
            p.x >= area.left() && p.x <= area.right(),
            "node {id} at {p:?}"
        );
    }
    let p = at(&h, root);
    assert_eq!(hover(&mut h, p), Some(NodeId(root as u32)));

    let rect = Rect::from_min_size(pos2(10.0, 10.0), vec2(1200.0, 500.0));
    let ctx = h.ctx.clone();
    let s = h.state_mut();
    let shapes = s
        .widget
        .export_shapes(&s.outline, &TreeHighlight::default(), rect, &ctx);
    assert!(!shapes.is_empty());
    for shape in &shapes {
        assert!(
            rect.expand(1.0).contains_rect(shape.visual_bounding_rect()),
            "fitted"
        );
    }
    // Nodes that fall on the same point in the same colour are drawn once: far fewer
    // shapes than nodes and edges.
    assert!(shapes.len() < n, "{} shapes for {n} nodes", shapes.len());
}

/// Filled dots and squares of `color` among `shapes`.
fn fills(shapes: &[Shape], color: egui::Color32) -> usize {
    shapes
        .iter()
        .filter(|s| match s {
            Shape::Circle(c) => c.fill == color,
            Shape::Rect(r) => r.fill == color,
            _ => false,
        })
        .count()
}

#[test]
fn the_export_colours_exactly_the_nodes_the_query_marked() {
    let prims = random_segments(120, 30.0, 2.0, 4).primitives().segments;
    let built = Built::build(&prims, &BuildSettings::default());
    let ray = Ray2::through(Vec2::new(-2.0, 9.0), Vec2::new(33.0, 17.0)).expect("ray");
    let outcome = RayOutcome::run(&built, &BruteForce::build(&prims), ray);
    let outline = built.outline();
    let marks = NodeMarks::from_events(&outcome.events, outline.len());
    assert!(marks.count(NodeMark::Visited) > 1 && marks.count(NodeMark::Culled) > 0);
    let current = marks
        .nodes
        .iter()
        .position(|m| *m == Some(NodeMark::Visited))
        .map(|i| NodeId(i as u32));

    let mut h = harness(outline);
    let ctx = h.ctx.clone();
    let s = h.state_mut();
    let highlight = TreeHighlight {
        marks: Some(&marks),
        current,
        ..TreeHighlight::default()
    };
    // Wide enough that no two nodes share a point.
    let rect = Rect::from_min_size(Pos2::ZERO, vec2(2000.0, 600.0));
    let shapes = s.widget.export_shapes(&s.outline, &highlight, rect, &ctx);
    for (mark, color) in [
        (NodeMark::Visited, colors::VISITED),
        (NodeMark::Culled, colors::CULLED),
        (NodeMark::Pruned, colors::PRUNED),
    ] {
        assert_eq!(fills(&shapes, color), marks.count(mark), "{mark:?}");
    }
    let untouched = marks.nodes.iter().filter(|m| m.is_none()).count();
    assert_eq!(fills(&shapes, colors::STRUCTURE), untouched);
    let rings = shapes
        .iter()
        .filter(|s| matches!(s, Shape::Circle(c) if c.stroke.color == colors::ANSWER))
        .count();
    assert_eq!(rings, 1, "the current node's ring");

    // Build playback with a depth limit: only nodes built so far and not too deep keep
    // their full colour.
    let existing: Vec<bool> = (0..s.outline.len()).map(|i| i % 3 != 0).collect();
    let highlight = TreeHighlight {
        existing: Some(&existing),
        max_depth: 3,
        ..TreeHighlight::default()
    };
    let shapes = s.widget.export_shapes(&s.outline, &highlight, rect, &ctx);
    let bright = (0..s.outline.len())
        .filter(|&i| existing[i] && s.outline[i].depth <= 3)
        .count();
    assert_eq!(fills(&shapes, colors::STRUCTURE), bright);
    let all = shapes
        .iter()
        .filter(|s| matches!(s, Shape::Circle(_) | Shape::Rect(_)))
        .count();
    assert_eq!(all, s.outline.len(), "the faint ones are drawn too");
}
