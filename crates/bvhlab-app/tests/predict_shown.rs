//! Issue 29: Predict asks only what the picture shows. On every lesson's ray and point steps,
//! each question the lab asks lights what decides it, read from what the views paint: the
//! nodes it names or chooses among (on the canvas and in the tree diagram, each with its
//! number and a question mark) and the primitive it names; a comparison of two numbers shows
//! both, and they differ as shown. What decides a question is read here from the recording's
//! event, not from the question.

use bvhlab::structure::PrimitiveResult;
use bvhlab::{Event, NodeId};
use bvhlab_app::LabApp;
use bvhlab_app::lessons;
use bvhlab_app::model::dimension::Dimension;
use bvhlab_app::model::lesson::Lesson;
use bvhlab_app::model::predict::{Choice, DISTINCT_ALONG_RAY, PredictAction, PredictQuestion};
use bvhlab_app::model::question::Task;
use bvhlab_app::model::{Action, Lab, LessonAction, PlaybackAction};
use bvhlab_app::paint::colors;
use egui::epaint::{ColorMode, Shape};
use egui::{Pos2, Rect};
use egui_kittest::Harness;

use crate::common;

/// The nodes and primitive that decide `q`, read from the event it is asked before and the
/// state before it: the node tested, the nodes chosen among, the cell the ray is in, the
/// primitive tested.
fn deciding<V: bvhlab::Vector>(
    q: &PredictQuestion,
    event: Event<V>,
    cell: Option<NodeId>,
) -> (Vec<NodeId>, Option<u32>) {
    let mut nodes: Vec<NodeId> = q
        .choices
        .iter()
        .filter_map(|(c, _)| match c {
            Choice::Node(n) => Some(NodeId(*n)),
            _ => None,
        })
        .collect();
    let mut prim = None;
    match event {
        Event::RayBoundTest { node, .. }
        | Event::DistanceBoundTest { node, .. }
        | Event::BuildSplit { node, .. }
        | Event::BuildLeaf { node, .. } => nodes.push(node),
        Event::CellEnter { .. } => nodes.extend(cell),
        Event::PrimitiveTest { prim: p, .. } => prim = Some(p),
        _ => {}
    }
    nodes.sort_unstable();
    nodes.dedup();
    (nodes, prim)
}

/// Every shape painted in the last frame, flattened.
fn shapes(h: &Harness<'_, LabApp>) -> Vec<Shape> {
    fn flat(shape: &Shape, out: &mut Vec<Shape>) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| flat(s, out)),
            s => out.push(s.clone()),
        }
    }
    let mut out = Vec::new();
    for c in &h.output().shapes {
        flat(&c.shape, &mut out);
    }
    out
}

/// Whether `shape` is stroked in the asked colour.
fn asked_stroke(shape: &Shape) -> bool {
    match shape {
        Shape::LineSegment { stroke, .. } => stroke.color == colors::ASKED,
        Shape::Path(p) => p.stroke.color == ColorMode::Solid(colors::ASKED),
        Shape::Rect(r) => r.stroke.color == colors::ASKED,
        Shape::Circle(c) => c.stroke.color == colors::ASKED,
        _ => false,
    }
}

/// Whether two rectangles agree within `slack` points on every side.
fn near(a: Rect, b: Rect, slack: f32) -> bool {
    (a.min - b.min).length() <= slack && (a.max - b.max).length() <= slack
}

/// What is wrong with how the 2D canvas and the tree diagram show `q`, if anything.
fn check_2d(h: &Harness<'_, LabApp>, q: &PredictQuestion) -> Vec<String> {
    let lab = h.state().lab();
    let lane = &lab.two().half.lane;
    let snapshot = lane.snapshot.as_ref().expect("a snapshot");
    let recording = lane.recorded().expect("a recording");
    let event = recording.events[q.step];
    let cell = snapshot.cells.last().map(|c| c.cell);
    let (nodes, prim) = deciding(q, event, cell);
    let painted = shapes(h);
    let screen = h.state().canvas_screen();
    // The canvas's own labels (the question itself is in the panel).
    let texts: Vec<String> = common::painted(h)
        .into_iter()
        .filter(|p| screen.rect.contains_rect(p.rect))
        .map(|p| p.text)
        .collect();
    let mut wrong = Vec::new();
    let structure = lane.current(lab.two().scene.revision()).expect("built");
    let outline = structure.outline.as_deref().expect("an outline");
    let grid = structure.settings.kind == bvhlab_app::model::structures::StructureKind::Grid;
    for node in &nodes {
        let b = outline[node.index()].shape.aabb();
        let r = Rect::from_two_pos(screen.to_screen(b.min), screen.to_screen(b.max));
        let lit = painted
            .iter()
            .any(|s| asked_stroke(s) && near(s.visual_bounding_rect(), r, 3.5));
        if !lit {
            wrong.push(format!("node {} is not lit on the canvas", node.0));
        }
        let unit = if grid { "cell" } else { "node" };
        if !texts
            .iter()
            .any(|t| t.contains(&format!("{unit} {}?", node.0)))
        {
            wrong.push(format!("node {} is not labelled on the canvas", node.0));
        }
        let at = h.state().ui.trees.two[0].node_screen_pos(*node);
        let ringed = at.is_some_and(|at| {
            painted
                .iter()
                .any(|s| asked_stroke(s) && (s.visual_bounding_rect().center() - at).length() < 1.0)
        });
        if !ringed {
            wrong.push(format!("node {} is not lit in the tree diagram", node.0));
        }
    }
    if let Some(p) = prim {
        let s = lab.two().prims().segments[p as usize];
        let (a, b) = (screen.to_screen(s.a), screen.to_screen(s.b));
        let lit = painted.iter().any(|shape| match shape {
            Shape::LineSegment { points, stroke } => {
                stroke.color == colors::ASKED
                    && ((points[0] - a).length() < 1.0 && (points[1] - b).length() < 1.0)
            }
            Shape::Circle(c) => c.fill == colors::ASKED && (c.center - a).length() < 1.0,
            _ => false,
        });
        if !lit {
            wrong.push(format!("primitive {p} is not marked on the canvas"));
        }
        if !texts.iter().any(|t| t.contains(&format!("primitive {p}?"))) {
            wrong.push(format!("primitive {p} is not labelled on the canvas"));
        }
    }
    wrong.extend(check_numbers(
        q,
        event,
        snapshot.best.as_slice(),
        lab.two().half.k,
    ));
    wrong
}

/// What is wrong with how the 3D view and the tree diagram show `q`, if anything.
fn check_3d(h: &Harness<'_, LabApp>, q: &PredictQuestion) -> Vec<String> {
    let lab = h.state().lab();
    let three = lab.three();
    let lane = &three.half.lane;
    let snapshot = lane.snapshot.as_ref().expect("a snapshot");
    let event = lane.recorded().expect("a recording").events[q.step];
    let (nodes, prim) = deciding(q, event, snapshot.cells.last().map(|c| c.cell));
    let rect = Rect::from_min_size(Pos2::ZERO, egui::vec2(800.0, 600.0));
    let drawn = bvhlab_app::lab3d::draw::draw(
        three,
        0,
        rect,
        false,
        bvhlab_app::lab3d::draw::Lit::default(),
        &lab.predict_about(),
    );
    let asked = bvhlab_app::lab3d::draw::rgba(colors::ASKED, 1.0);
    let structure = lane.current(three.revision()).expect("built");
    let mut wrong = Vec::new();
    for node in &nodes {
        let b = structure.node(*node).expect("a node").shape.aabb();
        let inside =
            |p: bvhlab::glam::Vec3| p.cmpge(b.min - 1e-3).all() && p.cmple(b.max + 1e-3).all();
        let lit = drawn
            .overlay
            .iter()
            .filter(|s| s.color == asked)
            .filter(|s| inside(s.a) && inside(s.b))
            .count();
        if lit < 4 {
            wrong.push(format!("node {} is not lit in the 3D view", node.0));
        }
        // The diagram is drawn when the tree is small enough to list.
        if structure.outline.is_some() && h.state().ui.panels.tree3d {
            let at = h.state().ui.trees.three[0].node_screen_pos(*node);
            let painted = shapes(h);
            let ringed = at.is_some_and(|at| {
                painted.iter().any(|s| {
                    asked_stroke(s) && (s.visual_bounding_rect().center() - at).length() < 1.0
                })
            });
            if !ringed {
                wrong.push(format!("node {} is not lit in the tree diagram", node.0));
            }
        }
    }
    if let Some(p) = prim
        && !drawn.highlights.contains(&(p, asked))
    {
        wrong.push(format!("triangle {p} is not marked in the 3D view"));
    }
    wrong.extend(check_numbers(
        q,
        event,
        snapshot.best.as_slice(),
        three.half.k,
    ));
    wrong
}

/// A comparison of two numbers shows both in the question (its prompt or its answers), and
/// they differ as shown; kept or pruned against the best hit, which cannot show where the
/// ray enters without saying that it meets the volume, is asked only when the two are
/// clearly apart along the ray.
fn check_numbers<V: bvhlab::Vector>(
    q: &PredictQuestion,
    event: Event<V>,
    best: &[(u32, f32)],
    k: usize,
) -> Vec<String> {
    let words = format!(
        "{} {}",
        q.prompt,
        q.choices
            .iter()
            .map(|(_, l)| l.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    );
    let kth = best.get(k.max(1) - 1).map(|b| b.1);
    let shows = |a: f32, b: f32| {
        let (a, b) = (format!("{a:.3}"), format!("{b:.3}"));
        if a == b {
            Some(format!("compares {a} with {b}: equal as shown"))
        } else if !words.contains(&a) || !words.contains(&b) {
            Some(format!("compares {a} with {b} but does not show both"))
        } else {
            None
        }
    };
    let mut wrong = Vec::new();
    match event {
        Event::DistanceBoundTest { distance, .. } => {
            wrong.extend(kth.and_then(|best| shows(distance, best)));
        }
        Event::PrimitiveTest {
            result: PrimitiveResult::Distance(d),
            ..
        } => wrong.extend(kth.and_then(|best| shows(d, best))),
        Event::RayBoundTest {
            interval: Some((entry, _)),
            ..
        } if q.choices.iter().any(|(c, _)| *c == Choice::Beyond) => {
            let best = best.first().map_or(f32::NAN, |b| b.1);
            if !words.contains(&format!("{best:.3}")) {
                wrong.push("does not show the best hit".to_owned());
            }
            if (entry - best).abs() < DISTINCT_ALONG_RAY * best.abs() {
                wrong.push(format!(
                    "hangs on entry t {entry:.3} against the best hit {best:.3}: too near to see"
                ));
            }
        }
        _ => {}
    }
    // Nearer first, or a priority queue: the keys compared are the answers'.
    let keyed = q
        .choices
        .iter()
        .any(|(_, l)| l.contains("distance") || l.contains("entry t"));
    if keyed {
        let mut keys: Vec<&str> = q
            .choices
            .iter()
            .filter_map(|(_, l)| l.rsplit(' ').next())
            .collect();
        let count = keys.len();
        keys.sort_unstable();
        keys.dedup();
        if keys.len() != count {
            wrong.push(format!("two answers' keys are equal as shown: {words}"));
        }
    } else if matches!(event, Event::ChildQueued { .. }) && q.why.contains("nearer child") {
        wrong.push("compares the children's keys but does not show them".to_owned());
    }
    wrong
}

/// Opens step `index` of `lesson` with Predict on; whether it asks about a ray or a point.
fn open(h: &mut Harness<'_, LabApp>, lesson: &std::sync::Arc<Lesson>, index: usize) -> bool {
    common::act(
        h,
        Action::Lesson(LessonAction::Open {
            lesson: lesson.clone(),
            step: index,
        }),
    );
    // A 3D mesh loads and builds over a few frames.
    for _ in 0..5 {
        common::act(
            h,
            Action::Tick {
                seconds: 0.0,
                build_ms: 1e6,
            },
        );
    }
    let lab = h.state().lab();
    let task = match lab.dimension() {
        Dimension::Two => lab.two().half.task,
        Dimension::Three => lab.three().half.task,
    };
    task != Task::Build && lab.steps() > 0
}

/// Applies `action`, then draws a frame.
fn apply(h: &mut Harness<'_, LabApp>, action: Action) {
    h.state_mut().apply(action).expect("applies");
    h.step();
}

/// The questions checked per lesson step, from its first: every kind of question a step asks
/// comes within them, and a 3D step's slide version asks hundreds (each a frame drawn).
const QUESTIONS_PER_STEP: usize = 40;

#[test]
fn the_first_40_questions_of_every_lesson_step_light_and_show_what_decides_them() {
    let mut h = common::lab();
    // The tree diagram below the 3D view too (it starts hidden there).
    h.state_mut().ui.panels.tree3d = true;
    common::act(&mut h, PredictAction::On(true));
    let mut asked = 0;
    let mut failures = Vec::new();
    for lesson in lessons::lessons() {
        for index in 0..lesson.steps.len() {
            if !open(&mut h, lesson, index) {
                continue;
            }
            let context = format!("{} step {}", lesson.name, index + 1);
            let steps = h.state().lab().steps();
            let mut asked_here = 0;
            for _ in 0..=steps {
                let lab: &Lab = h.state().lab();
                if lab.shown_step() >= steps || asked_here == QUESTIONS_PER_STEP {
                    break;
                }
                let Some(q) = lab.predict_question() else {
                    apply(&mut h, PlaybackAction::StepBy(1).into());
                    continue;
                };
                let wrong = match lab.dimension() {
                    Dimension::Two => check_2d(&h, &q),
                    Dimension::Three => check_3d(&h, &q),
                };
                if !wrong.is_empty() {
                    failures.push(format!("{context}, {:?}: {wrong:?}", q.prompt));
                }
                asked += 1;
                asked_here += 1;
                apply(&mut h, PredictAction::Answer(q.answer).into());
            }
        }
    }
    let shown: Vec<&String> = failures.iter().take(25).collect();
    assert!(
        failures.is_empty(),
        "{} of {asked} questions: {shown:#?}",
        failures.len()
    );
    assert!(asked > 100, "only {asked} questions asked");
}

/// Item 9: at step 0 with Predict on, a lesson's ray or point step draws the query (the ray's
/// line or the point), the structure, and what the first question is about, if one waits.
#[test]
fn step_zero_with_predict_on_draws_the_query_the_structure_and_what_is_asked() {
    let mut h = common::lab();
    common::act(&mut h, PredictAction::On(true));
    let mut failures = Vec::new();
    let mut checked = 0;
    for lesson in lessons::lessons() {
        for index in 0..lesson.steps.len() {
            if !open(&mut h, lesson, index) {
                continue;
            }
            let context = format!("{} step {}", lesson.name, index + 1);
            let lab = h.state().lab();
            assert_eq!(lab.shown_step(), 0, "{context}: Predict starts at step 0");
            let asks = lab.predict_question().is_some();
            let (query, structure, lit) = match lab.dimension() {
                Dimension::Two => {
                    let painted = shapes(&h);
                    let has = |c: egui::Color32| {
                        painted.iter().any(|s| match s {
                            Shape::LineSegment { stroke, .. } => stroke.color == c,
                            Shape::Circle(ci) => ci.fill == c || ci.stroke.color == c,
                            Shape::Rect(r) => r.stroke.color == c,
                            Shape::Path(p) => p.stroke.color == ColorMode::Solid(c),
                            Shape::Mesh(_) => c == colors::STRUCTURE,
                            _ => false,
                        })
                    };
                    (
                        has(colors::QUERY),
                        has(colors::STRUCTURE),
                        painted.iter().any(asked_stroke),
                    )
                }
                Dimension::Three => {
                    let rect = Rect::from_min_size(Pos2::ZERO, egui::vec2(800.0, 600.0));
                    let three = lab.three();
                    let d = bvhlab_app::lab3d::draw::draw(
                        three,
                        0,
                        rect,
                        false,
                        bvhlab_app::lab3d::draw::Lit::default(),
                        &lab.predict_about(),
                    );
                    let query = bvhlab_app::lab3d::draw::rgba(colors::QUERY, 1.0);
                    let asked = bvhlab_app::lab3d::draw::rgba(colors::ASKED, 1.0);
                    (
                        d.overlay.iter().any(|s| s.color == query)
                            || d.dots.iter().any(|s| s.color == query),
                        !d.lines.is_empty(),
                        // A node asked about is outlined; a triangle (brute force's) is filled.
                        d.overlay.iter().any(|s| s.color == asked)
                            || d.highlights.iter().any(|&(_, c)| c == asked),
                    )
                }
            };
            let brute = lab.exercise().contains("brute force");
            // §2's volumes and boxes in 3D put the trees away on purpose.
            let three = lab.three();
            let section2 = lab.dimension() == Dimension::Three
                && (three.volumes.shown || three.obb_pair.is_some());
            if !query {
                failures.push(format!("{context}: the ray or point is not drawn"));
            }
            if !structure && !brute && !section2 {
                failures.push(format!("{context}: the structure is not drawn"));
            }
            if asks && !lit {
                failures.push(format!(
                    "{context}: what the first question is about is not lit"
                ));
            }
            checked += 1;
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(checked >= 10, "only {checked} steps");
}
