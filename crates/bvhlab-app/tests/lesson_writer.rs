//! "Write a lesson" (issue 31): a step's setup and solution taken from what the lab shows,
//! goals offered with their values now, the step checked as the lessons test checks the
//! lab's own (its goal not met where it starts, met by its solution) before it can be saved,
//! and the lesson file it writes opened again: to study, and to edit.

use crate::common;

use egui_kittest::kittest::Queryable as _;

use bvhlab::glam::Vec2;
use bvhlab_app::LabApp;
use bvhlab_app::embed::StartParams;
use bvhlab_app::lessons::format::read_teacher;
use bvhlab_app::lessons::writer::text::from_toml;
use bvhlab_app::lessons::writer::{LessonField, StepField, WriterAction, WriterCommand, goals};
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::{Action, Action2d, Lab, LessonProgress, PlaybackAction};

/// The lab on 200 segments, an AABB tree beside brute force, a ray that misses them all.
fn lab_on_segments() -> LabApp {
    let mut lab = Lab::default();
    let params = StartParams::parse(
        "preset=random-segments&structure=aabb-tree&compare=brute-force&task=first-hit&ray=-2,-2,-1,-0.4",
    );
    assert!(params.apply(&mut lab).is_empty());
    common::tick_lab(&mut lab);
    LabApp::new(lab)
}

/// Three frames' ticks of `app`'s lab.
fn tick(app: &mut LabApp) {
    for _ in 0..3 {
        app.apply(Action::Tick {
            seconds: 0.0,
            build_ms: 1e6,
        })
        .expect("a tick");
    }
}

/// Does `action` in the writer.
fn write(app: &mut LabApp, action: WriterAction) {
    let said = format!("{action:?}");
    app.write(WriterCommand::Do(action))
        .unwrap_or_else(|e| panic!("{said} was refused: {e}"));
}

/// Writes the step of the queries lesson: a ray that hits with few segments tested.
fn write_hit_step(app: &mut LabApp) {
    write(
        app,
        WriterAction::SetStep(StepField::Title, "Hit cheaply".into()),
    );
    write(
        app,
        WriterAction::SetStep(StepField::Text, "Drag the ray.".into()),
    );
    write(
        app,
        WriterAction::SetStep(StepField::Task, "Hit a segment, 6 tests at most.".into()),
    );
    write(app, WriterAction::AddGoal("answer = hit".into()));
    write(app, WriterAction::AddGoal("primitives-tested <= 6".into()));
}

/// The ray the queries lesson's solution names, set by hand.
fn aim_at_a_segment(app: &mut LabApp) {
    let origin = Vec2::new(-2.0, 9.5);
    app.apply(Action2d::SetRay(Some(RayHandles {
        origin,
        target: origin + Vec2::new(1.0, 0.15),
    })))
    .expect("the ray moves");
    tick(app);
}

#[test]
fn a_step_written_from_the_screen_is_checked_before_it_is_saved_and_its_file_reads() {
    let mut app = lab_on_segments();
    app.write(WriterCommand::Start).expect("the writer opens");
    let setup = app.writer().expect("open").step.setup.clone();
    for word in [
        "preset=random-segments",
        "structure=aabb-tree",
        "compare=brute-force",
        "task=first-hit",
        "ray=-2,-2,-1,-0.4",
    ] {
        assert!(setup.split('&').any(|w| w == word), "{word} in {setup}");
    }
    write_hit_step(&mut app);
    // Not checked yet: refused; checked without a solution: refused with the reason.
    assert!(
        app.write(WriterCommand::Do(WriterAction::SaveStep))
            .is_err()
    );
    write(&mut app, WriterAction::Check);
    let verdict = app.writer().expect("open").verdict.clone();
    assert!(
        matches!(&verdict, Some(Err(why)) if why.contains("solution")),
        "{verdict:?}"
    );
    assert!(
        app.write(WriterCommand::Do(WriterAction::SaveStep))
            .is_err()
    );

    aim_at_a_segment(&mut app);
    write(&mut app, WriterAction::RecordSolution);
    let solution = app.writer().expect("open").step.solution.clone();
    assert_eq!(
        solution.as_deref(),
        Some("ray=-2,9.5,1,0.15"),
        "only what changed"
    );
    write(&mut app, WriterAction::Check);
    let verdict = app.writer().expect("open").verdict.clone();
    assert!(matches!(verdict, Some(Ok(_))), "{verdict:?}");
    write(&mut app, WriterAction::SaveStep);
    let writer = app.writer().expect("open");
    assert_eq!(writer.draft.steps.len(), 1);
    assert_eq!(writer.verdict, None, "the next step is not checked yet");

    // The file it writes reads as the lab reads a teacher's lesson, and back into the same
    // draft.
    let text = writer.toml();
    let lesson = read_teacher("my-lesson.toml", text.as_bytes()).expect("reads");
    assert_eq!(lesson.steps[0].goals.len(), 2);
    assert_eq!(
        from_toml("my-lesson.toml", &text).expect("reads"),
        writer.draft
    );
}

#[test]
fn a_goal_met_where_the_step_starts_or_a_change_after_the_check_keeps_the_step_unsaved() {
    let mut app = lab_on_segments();
    app.write(WriterCommand::Start).expect("opens");
    write(
        &mut app,
        WriterAction::SetStep(StepField::Title, "Miss".into()),
    );
    write(&mut app, WriterAction::SetStep(StepField::Text, "t".into()));
    write(
        &mut app,
        WriterAction::SetStep(StepField::Task, "Miss.".into()),
    );
    write(&mut app, WriterAction::AddGoal("answer = miss".into()));
    write(
        &mut app,
        WriterAction::SetStep(StepField::Solution, "ray=-2,-2,-1,-0.5".into()),
    );
    write(&mut app, WriterAction::Check);
    let verdict = app.writer().expect("open").verdict.clone();
    assert!(
        matches!(&verdict, Some(Err(why)) if why.contains("met where the step starts")),
        "{verdict:?}"
    );

    // A goal that does not read is refused with what was expected.
    let refused = app
        .write(WriterCommand::Do(WriterAction::AddGoal(
            "nodes-vistied < 3".into(),
        )))
        .expect_err("refused");
    assert!(refused.contains("nodes-visited"), "{refused}");

    // Passed, then changed: saving needs a new check.
    let mut app = lab_on_segments();
    app.write(WriterCommand::Start).expect("opens");
    write_hit_step(&mut app);
    write(
        &mut app,
        WriterAction::SetStep(StepField::Solution, "ray=-2,9.5,1,0.15".into()),
    );
    write(&mut app, WriterAction::Check);
    assert!(matches!(app.writer().expect("open").verdict, Some(Ok(_))));
    write(
        &mut app,
        WriterAction::SetStep(StepField::Task, "Changed.".into()),
    );
    assert!(
        app.write(WriterCommand::Do(WriterAction::SaveStep))
            .is_err()
    );
}

#[test]
fn the_goals_offered_are_the_quantities_with_a_value_now_and_each_reads() {
    let app = lab_on_segments();
    let offers = goals::offers(app.lab());
    let nodes = offers
        .iter()
        .find(|o| o.quantity == "nodes-visited")
        .expect("nodes visited is offered");
    let goal = bvhlab_app::lessons::goal_text::parse(&format!("nodes-visited = {}", nodes.now))
        .expect("reads");
    assert!(goal.holds(app.lab()), "the value shown is the value now");
    assert!(
        nodes
            .goals
            .contains(&format!("nodes-visited < {}", nodes.now))
    );
    assert!(nodes.goals.contains(&"nodes-visited < compare".to_owned()));
    let answer = offers
        .iter()
        .find(|o| o.quantity == "answer")
        .expect("answer");
    assert_eq!(answer.now, "miss");
    for offer in &offers {
        for goal in &offer.goals {
            assert!(
                bvhlab_app::lessons::goal_text::parse(goal).is_ok(),
                "{goal}"
            );
        }
    }
}

#[test]
fn a_written_lesson_opened_from_disk_runs_its_goal_and_opens_again_in_the_writer() {
    let mut app = lab_on_segments();
    app.write(WriterCommand::Start).expect("opens");
    write(
        &mut app,
        WriterAction::SetLesson(LessonField::Title, "Week 3".into()),
    );
    write(
        &mut app,
        WriterAction::SetLesson(LessonField::File, "week-3".into()),
    );
    write_hit_step(&mut app);
    write(
        &mut app,
        WriterAction::SetStep(StepField::Solution, "ray=-2,9.5,1,0.15".into()),
    );
    write(&mut app, WriterAction::Check);
    write(&mut app, WriterAction::SaveStep);
    let writer = app.writer().expect("open").clone();
    assert_eq!(writer.file_name(), "week-3.toml");

    // Saved to disk, dropped on a fresh lab: it opens, and its goal is checked.
    let dir = std::env::temp_dir().join(format!("bvhlab-writer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a folder");
    let path = dir.join(writer.file_name());
    std::fs::write(&path, writer.toml()).expect("written");
    let mut h = common::lab();
    common::drop_file(&mut h, &path);
    common::settle(&mut h);
    std::fs::remove_dir_all(&dir).ok();
    let progress = h.state().lab().lesson().expect("the lesson opened").clone();
    assert_eq!(progress.lesson.title, "Week 3");
    assert!(!progress.reached_here());
    let mut lab = Lab::default();
    lab.apply(Action::Lesson(bvhlab_app::model::LessonAction::Open {
        lesson: progress.lesson.clone(),
        step: 0,
    }))
    .expect("opens");
    let solution = progress.lesson.steps[0]
        .solution
        .clone()
        .expect("a solution");
    assert!(lab.apply_setup(&solution, "the solution").is_empty());
    lab.apply(PlaybackAction::End.into()).expect("end");
    common::tick_lab(&mut lab);
    assert!(lab.lesson().is_some_and(LessonProgress::reached_here));

    // Opened again in the writer: the same lesson, its step editable.
    let mut app = LabApp::new(lab);
    app.write(WriterCommand::EditOpen)
        .expect("the open lesson is edited");
    assert_eq!(app.writer().expect("open").draft, writer.draft);
    write(&mut app, WriterAction::EditStep(0));
    assert_eq!(app.writer().expect("open").at, 0);
    write(
        &mut app,
        WriterAction::SetStep(StepField::Title, "Renamed".into()),
    );
    write(&mut app, WriterAction::Check);
    write(&mut app, WriterAction::SaveStep);
    let draft = &app.writer().expect("open").draft;
    assert_eq!(draft.steps.len(), 1, "replaced, not added");
    assert_eq!(draft.steps[0].title, "Renamed");
}

#[test]
fn the_writer_opens_from_the_lessons_pane_with_named_fields() {
    let mut h = common::lab();
    common::click(&mut h, "Write a lesson");
    assert!(h.state().writer().is_some(), "the button opens the writer");
    for name in [
        "Lesson title",
        "Step title",
        "Text",
        "Check the step",
        "Save the step",
    ] {
        let _ = h.get_by_label(name);
    }
    common::click(&mut h, "Close the writer");
    assert!(h.state().writer().is_none());
}
