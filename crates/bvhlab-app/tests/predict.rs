//! Predict: for every structure's ray and distance queries and for the builds, the lab asks
//! before the steps that decide something; a right answer reveals exactly the step it is
//! about (checked against the state after it, not against the question's own answer); a
//! wrong one gets a hint and a second try; scores count each way a question was settled and
//! come back with a saved state; stepping past a question and playing are refused.

use bvhlab_app::embed::StartParams;
use bvhlab_app::model::outcome::NodeMark;
use bvhlab_app::model::predict::{Choice, PredictAction, PredictQuestion, Verdict};
use bvhlab_app::model::snapshot::Snapshot;
use bvhlab_app::model::{Lab, PlaybackAction};

/// A lab in the state an address describes.
fn lab_at(query: &str) -> Lab {
    let mut lab = Lab::default();
    let problems = StartParams::parse(query).apply(&mut lab);
    assert!(problems.is_empty(), "{query}: {problems:?}");
    lab
}

/// The 2D main lane's snapshot at the step shown.
fn snapshot(lab: &Lab) -> Snapshot {
    lab.two()
        .half
        .lane
        .snapshot
        .clone()
        .expect("a recording is shown")
}

/// Checks that the step revealed by answering `question` is the one it was about: the state
/// after it agrees with the answer (a node chosen is the one entered or pruned; a node kept
/// is neither pruned nor culled; a node pruned is marked so).
fn check_revealed(lab: &Lab, question: &PredictQuestion, context: &str) {
    let after = snapshot(lab);
    assert_eq!(
        after.step,
        question.step + question.reveal,
        "{context}: {question:?}"
    );
    let marks = &after.marks;
    let events = &lab.two().half.lane.recorded().expect("recorded").events;
    let first = events[question.step];
    match question.answer {
        Choice::Node(n) => {
            // The node taken next, or the child visited first: the step names it.
            let named = format!("{first:?}");
            assert!(
                named.contains(&format!("NodeId({n})")),
                "{context}: {n} not in {named}"
            );
        }
        Choice::Missed | Choice::NoNearer | Choice::Beyond => {
            let node = node_of(&first);
            assert!(
                matches!(marks.nodes[node], Some(NodeMark::Culled | NodeMark::Pruned)),
                "{context}: node {node} should be refused after {question:?}"
            );
        }
        Choice::Kept => {
            let node = node_of(&first);
            assert!(
                !matches!(marks.nodes[node], Some(NodeMark::Culled | NodeMark::Pruned)),
                "{context}: node {node} should be kept after {question:?}"
            );
        }
        _ => {}
    }
}

fn node_of(event: &bvhlab::Event<bvhlab::glam::Vec2>) -> usize {
    match *event {
        bvhlab::Event::RayBoundTest { node, .. }
        | bvhlab::Event::DistanceBoundTest { node, .. } => node.index(),
        other => panic!("not a bound test: {other:?}"),
    }
}

/// Walks the whole recording with Predict on, answering each question right; returns the
/// questions asked.
fn walk_right(lab: &mut Lab, context: &str) -> Vec<PredictQuestion> {
    lab.apply(PredictAction::On(true).into())
        .expect("Predict on");
    assert_eq!(
        snapshot(lab).step,
        0,
        "{context}: Predict starts at the start"
    );
    let steps = lab.steps();
    let mut asked = Vec::new();
    while snapshot(lab).step < steps {
        match lab.predict_question() {
            Some(q) => {
                lab.apply(PredictAction::Answer(q.answer).into())
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
                let feedback = lab.predict().feedback.clone().expect("feedback");
                assert_eq!(feedback.verdict, Verdict::Right, "{context}");
                check_revealed(lab, &q, context);
                asked.push(q);
            }
            None => lab
                .apply(PlaybackAction::StepBy(1).into())
                .unwrap_or_else(|e| panic!("{context}: {e}")),
        }
    }
    asked
}

const STRUCTURES: [&str; 7] = [
    "sphere-tree",
    "aabb-tree",
    "obb-tree",
    "grid",
    "bsp",
    "quadtree",
    "kd-tree",
];

/// Six rays across the 20 x 20 scene of random segments, and six query points in it.
fn queries(task: &str) -> Vec<String> {
    (0..6)
        .map(|i| {
            let i = i as f32;
            if task == "nearest" {
                format!("point={},{}", 3.0 + 2.5 * i, 4.0 + 2.0 * i)
            } else {
                format!("ray=0.3,{},1,{}", 2.0 + 3.0 * i, 0.1 * (i - 3.0) + 0.05)
            }
        })
        .collect()
}

#[test]
fn every_structure_asks_about_its_ray_and_distance_queries_and_right_answers_walk_to_the_end() {
    for structure in STRUCTURES {
        for task in ["first-hit", "any-hit", "nearest"] {
            let mut kinds = Vec::new();
            for question in queries(task) {
                let query =
                    format!("?preset=random-segments&structure={structure}&task={task}&{question}");
                let mut lab = lab_at(&query);
                let asked = walk_right(&mut lab, &query);
                let score = lab.predict().score(&lab.exercise());
                assert_eq!(score.first_time as usize, asked.len(), "{query}");
                assert_eq!((score.after_hint, score.shown), (0, 0), "{query}");
                kinds.extend(asked.iter().map(|q| q.answer));
            }
            let context = format!("{structure}, {task}");
            assert!(kinds.len() >= 6, "{context}: {kinds:?}");
            // A tree decides something at its volumes too, not only at primitives.
            if structure != "grid" {
                assert!(
                    kinds.iter().any(|k| !matches!(k, Choice::Yes | Choice::No)),
                    "{context}: only yes/no questions: {kinds:?}"
                );
            }
        }
    }
}

#[test]
fn the_first_hit_asks_which_node_is_next_and_whether_a_node_beyond_the_best_hit_is_pruned() {
    let mut asked = Vec::new();
    for question in queries("first-hit") {
        let query =
            format!("?preset=random-segments&structure=aabb-tree&task=first-hit&{question}");
        let mut lab = lab_at(&query);
        asked.extend(walk_right(&mut lab, &query));
    }
    let has = |c: fn(&Choice) -> bool| asked.iter().any(|q| c(&q.answer));
    assert!(has(|c| matches!(c, Choice::Node(_))), "{asked:#?}");
    assert!(has(|c| *c == Choice::Kept), "{asked:#?}");
    assert!(has(|c| *c == Choice::Beyond), "{asked:#?}");
    assert!(has(|c| *c == Choice::Missed), "{asked:#?}");
    assert!(has(|c| *c == Choice::Yes), "a primitive hit");
}

#[test]
fn the_grid_asks_which_cell_comes_next() {
    let query = "?preset=random-segments&structure=grid&task=first-hit&ray=0.5,0.7,1,0.61";
    let mut lab = lab_at(query);
    let asked = walk_right(&mut lab, query);
    let cells: Vec<&PredictQuestion> = asked
        .iter()
        .filter(|q| matches!(q.answer, Choice::Cell { .. }))
        .collect();
    assert!(cells.len() >= 3, "{asked:#?}");
    // Both directions the ray moves in are offered, and both are right somewhere.
    assert!(cells.iter().all(|q| q.choices.len() == 2));
    let axes: std::collections::HashSet<_> = cells
        .iter()
        .map(|q| match q.answer {
            Choice::Cell { axis, up } => (axis, up),
            _ => unreachable!(),
        })
        .collect();
    assert_eq!(
        axes,
        [(0, true), (1, true)].into_iter().collect(),
        "the ray goes up and right"
    );
}

#[test]
fn builds_ask_leaf_or_split_axis() {
    for structure in ["aabb-tree", "kd-tree", "bsp", "quadtree"] {
        let query = format!("?preset=random-segments&structure={structure}&task=build");
        let mut lab = lab_at(&query);
        let asked = walk_right(&mut lab, &query);
        let leaves = asked.iter().filter(|q| q.answer == Choice::Leaf).count();
        let splits = asked.len() - leaves;
        assert!(
            leaves > 3 && splits > 3,
            "{query}: {leaves} leaves, {splits} splits"
        );
        if matches!(structure, "aabb-tree" | "kd-tree") {
            for axis in [0, 1] {
                assert!(
                    asked.iter().any(|q| q.answer == Choice::SplitAcross(axis)),
                    "{query}: no split across axis {axis}"
                );
            }
        }
    }
}

#[test]
fn a_wrong_answer_gets_a_hint_and_a_second_try_then_the_answer_is_shown() {
    let query = "?preset=random-segments&structure=aabb-tree&task=first-hit&ray=0.5,10,1,0.05";
    let mut lab = lab_at(query);
    lab.apply(PredictAction::On(true).into()).expect("present");
    // Step to a question with three answers (kept, missed, beyond).
    let three = loop {
        match lab.predict_question() {
            Some(q) if q.choices.len() >= 3 => break q,
            Some(q) => lab
                .apply(PredictAction::Answer(q.answer).into())
                .expect("present"),
            None => lab
                .apply(PlaybackAction::StepBy(1).into())
                .expect("present"),
        }
    };
    let wrong: Vec<Choice> = three
        .choices
        .iter()
        .map(|c| c.0)
        .filter(|c| *c != three.answer)
        .collect();
    let exercise = lab.exercise();
    let before = lab.predict().score(&exercise);
    // Stepping past it is refused while it waits.
    let refused = lab.apply(PlaybackAction::StepBy(1).into());
    assert!(
        refused
            .expect_err("refused")
            .contains("answer the question")
    );
    assert!(lab.apply(PlaybackAction::Play(true).into()).is_err());

    lab.apply(PredictAction::Answer(wrong[0]).into())
        .expect("present");
    let feedback = lab.predict().feedback.clone().expect("present");
    assert_eq!(feedback.verdict, Verdict::Wrong);
    assert!(feedback.text.contains(&three.hint), "{feedback:?}");
    assert_eq!(snapshot(&lab).step, three.step, "a wrong answer stays");
    assert_eq!(lab.predict().score(&exercise), before);
    // The same wrong answer again is not a second try.
    lab.apply(PredictAction::Answer(wrong[0]).into())
        .expect("present");
    assert_eq!(snapshot(&lab).step, three.step);
    // A second, different wrong answer shows the answer.
    lab.apply(PredictAction::Answer(wrong[1]).into())
        .expect("present");
    let feedback = lab.predict().feedback.clone().expect("present");
    assert_eq!(feedback.verdict, Verdict::Shown);
    assert!(
        feedback
            .text
            .contains(three.label(three.answer).expect("present"))
    );
    check_revealed(&lab, &three, query);
    assert_eq!(lab.predict().score(&exercise).shown, before.shown + 1);

    // Right after a hint.
    let next = loop {
        match lab.predict_question() {
            Some(q) => break q,
            None => lab
                .apply(PlaybackAction::StepBy(1).into())
                .expect("present"),
        }
    };
    let other = next
        .choices
        .iter()
        .map(|c| c.0)
        .find(|c| *c != next.answer)
        .expect("present");
    lab.apply(PredictAction::Answer(other).into())
        .expect("present");
    lab.apply(PredictAction::Answer(next.answer).into())
        .expect("present");
    assert_eq!(
        lab.predict().feedback.as_ref().expect("present").verdict,
        Verdict::RightAfterHint
    );
    assert_eq!(
        lab.predict().score(&exercise).after_hint,
        before.after_hint + 1
    );
    // "Show me" counts as shown.
    let next = loop {
        match lab.predict_question() {
            Some(q) => break q,
            None => lab
                .apply(PlaybackAction::StepBy(1).into())
                .expect("present"),
        }
    };
    lab.apply(PredictAction::Show.into()).expect("present");
    check_revealed(&lab, &next, query);
    assert_eq!(lab.predict().score(&exercise).shown, before.shown + 2);
    // An answer not offered is refused.
    if let Some(q) = lab.predict_question() {
        let not_offered = if q.choices.iter().any(|c| c.0 == Choice::Leaf) {
            Choice::Yes
        } else {
            Choice::Leaf
        };
        assert!(
            lab.apply(PredictAction::Answer(not_offered).into())
                .is_err()
        );
    }
}

#[test]
fn scores_and_the_switch_come_back_with_a_saved_state_and_a_new_question_starts_at_the_start() {
    let query = "?preset=random-segments&structure=kd-tree&task=first-hit&ray=1,1.5,1,0.37";
    let mut lab = lab_at(query);
    walk_right(&mut lab, query);
    let score = lab.predict().score(&lab.exercise());
    assert!(score.first_time > 0);
    let file = bvhlab_app::persist::to_file(&lab);
    let state = bvhlab_app::persist::from_file(&file).expect("reads back");
    let mut again = Lab::default();
    again
        .apply(state.apply().expect("restores"))
        .expect("present");
    assert!(again.predict().on);
    assert_eq!(again.predict().score(&again.exercise()), score);
    // A new ray with Predict on starts at step 0, to be predicted.
    let ray = again.two().ray.expect("present");
    let mut moved = ray;
    moved.target.y += 0.5;
    again
        .apply(bvhlab_app::model::Action2d::SetRay(Some(moved)).into())
        .expect("present");
    assert_eq!(snapshot(&again).step, 0);
    assert!(again.predict_question().is_some() || again.steps() > 0);
    // Off: playing works again.
    again
        .apply(PredictAction::On(false).into())
        .expect("present");
    again
        .apply(PlaybackAction::Play(true).into())
        .expect("present");
    assert!(again.playing());
}

#[test]
fn the_page_hears_the_question_answers_by_number_and_receives_the_score() {
    use bvhlab_app::embed::command::Command;
    use bvhlab_app::report::predict::{PredictReport, progress_message};
    let query = "?preset=random-segments&structure=aabb-tree&task=first-hit&ray=0.3,5,1,-0.15";
    let mut lab = lab_at(query);
    assert!(PredictReport::of(&lab).is_none(), "off: nothing to report");
    let run = |lab: &mut Lab, json: &str| {
        let (actions, _) = Command::parse(json)
            .expect("a command")
            .actions(lab, false)
            .expect("accepted");
        lab.apply_all(actions).expect("applies");
    };
    run(&mut lab, r#"{"type": "predict", "on": true}"#);
    let question = lab
        .predict_question()
        .expect("the root's test is asked at step 0");
    let report = PredictReport::of(&lab).expect("on");
    let asked = report.question.as_ref().expect("a question");
    assert_eq!(asked.prompt, question.prompt);
    let text = report.text();
    assert!(text.starts_with("Predict: "), "{text}");
    assert!(text.contains("1 yes; 2 no"), "{text}");
    // Answer 1 is the first offered; a number out of range is refused with the range.
    let wrong = Command::parse(r#"{"type": "answer", "choice": 3}"#)
        .expect("a command")
        .actions(&lab, false)
        .expect_err("refused");
    assert!(wrong.contains("answers 1 to 2"), "{wrong}");
    let right = 1 + question
        .choices
        .iter()
        .position(|c| c.0 == question.answer)
        .expect("offered");
    run(
        &mut lab,
        &format!(r#"{{"type": "answer", "choice": {right}}}"#),
    );
    let report = PredictReport::of(&lab).expect("on");
    let feedback = report.feedback.as_ref().expect("said");
    assert_eq!(feedback.verdict, "right");
    assert!(report.text().starts_with("Right: "), "{}", report.text());
    assert_eq!(report.score.first_time, 1);
    let message = progress_message(None, Some(&report)).expect("a message");
    let json: serde_json::Value = serde_json::from_str(&message).expect("JSON");
    assert_eq!(json["bvhlab"], "progress");
    assert_eq!(json["exercise"], "2D AABB tree: first hit");
    assert_eq!(json["score"]["first_time"], 1);
    assert!(json.get("lesson").is_none());
    // While stepping, the live region says the step in words, and what waits.
    let step = bvhlab_app::report::PlaybackReport::of(&lab.two().half.lane).expect("recorded");
    let words = step.text();
    assert!(
        words.starts_with(&format!(
            " Step {} of {}: ray meets node 0",
            step.step, step.steps
        )),
        "{words}"
    );
    // "show-answer" reveals the next question's step.
    while lab.predict_question().is_none() {
        lab.apply(PlaybackAction::StepBy(1).into()).expect("steps");
    }
    run(&mut lab, r#"{"type": "show-answer"}"#);
    assert_eq!(
        PredictReport::of(&lab).expect("on").score.shown,
        1,
        "shown counts"
    );
}
