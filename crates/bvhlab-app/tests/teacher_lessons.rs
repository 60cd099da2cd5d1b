//! A teacher's lesson opened while the lab runs (issue 31): dropped on the window, sent by
//! the embedding page (`load-lesson`), named by the address (`lesson-url=`), and saved with
//! the student's state. A bad file says `file:line: why` and changes nothing; markup in its
//! text stays characters.

use crate::common;

use bvhlab_app::embed::{Command, StartParams};
use bvhlab_app::lessons::format::{MAX_TEACHER_BYTES, MAX_TEACHER_STEPS, read_teacher};
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::{Action, Action2d, Lab, LessonAction, LessonProgress, PlaybackAction};
use bvhlab_app::persist::{SavedState, from_file, from_fragment, link_fragment, to_file};

use crate::common::tick_lab as tick;

/// A teacher's lesson: a title with markup, one step to read and one with a goal (the
/// built-in queries lesson's second step, so its solution is known to reach it).
const EXAM: &str = r#"title = "<b>Exam</b> warm-up <script>alert(1)</script>"
section = "Week 3"

[[step]]
title = "Look first"
setup = "preset=random-segments&structure=aabb-tree&task=first-hit"
text = "Look at the boxes. <a href=\"https://example.com\">not a link</a>"

[[step]]
title = "Hit with few tests"
setup = "preset=random-segments&structure=aabb-tree&compare=brute-force&task=first-hit&ray=-2,-2,-1,-0.4"
text = "Drag the ray."
task = "Make the ray hit a segment with at most 6 segments tested."
goal = ["answer = hit", "primitives-tested <= 6"]
solution = "ray=-2,9.5,1,0.15"
"#;

/// A lab with the student's own work in it: a preset and a structure of their choosing.
fn students_lab() -> Lab {
    let mut lab = Lab::default();
    lab.apply(Action2d::LoadPreset(Preset::KdHandful).into())
        .expect("a preset loads");
    tick(&mut lab);
    lab
}

/// Puts the step's solution in place and plays to the end, as the lessons test does.
fn do_the_solution(lab: &mut Lab) {
    let step = lab.lesson().expect("a lesson is open").current().clone();
    let solution = step.solution.expect("the step has a solution");
    assert!(lab.apply_setup(&solution, "the solution").is_empty());
    lab.apply(PlaybackAction::End.into()).expect("to the end");
    tick(lab);
}

#[test]
fn a_lesson_file_dropped_on_the_lab_opens_as_the_teachers_and_its_goal_is_checked() {
    let dir = std::env::temp_dir().join(format!("bvhlab-teacher-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let path = dir.join("week-3 exam.toml");
    std::fs::write(&path, EXAM).expect("the lesson file is written");
    let mut h = common::lab();
    common::drop_file(&mut h, &path);
    common::settle(&mut h);
    let lab = h.state().lab();
    let progress = lab.lesson().expect("the dropped lesson is open");
    assert_eq!(progress.step, 0);
    assert_eq!(progress.lesson.name, "week-3-exam");
    assert!(progress.lesson.teacher.is_some(), "marked as the teacher's");
    // Markup is kept as characters: nothing is parsed out of the teacher's text.
    assert_eq!(
        progress.lesson.title,
        "<b>Exam</b> warm-up <script>alert(1)</script>"
    );
    let said = lab.message().unwrap_or_default().to_owned();
    assert!(said.contains("Opened the teacher's lesson"), "{said}");
    assert!(
        common::shows(&h, "A teacher's lesson, from"),
        "the panel says whose lesson it is"
    );
    assert!(
        common::shows(&h, "<script>alert(1)</script>"),
        "shown as text"
    );

    // Its checked goal: not reached where the step starts, reached by its solution.
    let lesson = h.state().lab().lesson().expect("open").lesson.clone();
    let mut lab = Lab::default();
    lab.apply(Action::Lesson(LessonAction::Open { lesson, step: 1 }))
        .expect("step 2 opens");
    tick(&mut lab);
    assert!(!lab.lesson().is_some_and(LessonProgress::reached_here));
    do_the_solution(&mut lab);
    assert!(lab.lesson().is_some_and(LessonProgress::reached_here));
    std::fs::remove_dir_all(&dir).ok();
}

/// What dropping a file holding `text` (called `name`) on `lab` does: the status line, and
/// whether the student's state is as it was.
fn drop_text(name: &str, text: &[u8]) -> (String, bool) {
    let dir = std::env::temp_dir().join(format!("bvhlab-bad-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("written");
    let mut h = common::lab();
    let lesson = bvhlab_app::lessons::find("slab-test").expect("built in");
    common::act(
        &mut h,
        Action::Lesson(LessonAction::Open { lesson, step: 1 }),
    );
    let before = SavedState::capture(h.state().lab());
    common::drop_file(&mut h, &path);
    common::settle(&mut h);
    let after = SavedState::capture(h.state().lab());
    std::fs::remove_dir_all(&dir).ok();
    let said = h.state().lab().message().unwrap_or_default().to_owned();
    (said, before == after)
}

#[test]
fn a_broken_lesson_file_says_its_line_and_loses_nothing() {
    // Line 7: a step without its text.
    let broken = EXAM.replacen(
        "text = \"Look at the boxes.",
        "txt = \"Look at the boxes.",
        1,
    );
    let (said, kept) = drop_text("broken.toml", broken.as_bytes());
    assert!(said.starts_with("broken.toml:7:"), "{said}");
    assert!(said.contains("nothing else changed"), "{said}");
    assert!(kept, "the student's lesson and state are as they were");

    let big = format!("{EXAM}\n# {}\n", "x".repeat(MAX_TEACHER_BYTES));
    let (said, kept) = drop_text("big.toml", big.as_bytes());
    assert!(said.contains("at most 256 KiB"), "{said}");
    assert!(kept);

    let step = "\n[[step]]\ntitle = \"S\"\nsetup = \"preset=kd-tree\"\ntext = \"t\"\n";
    let long = format!(
        "title = \"T\"\nsection = \"S\"\n{}",
        step.repeat(MAX_TEACHER_STEPS + 1)
    );
    let (said, kept) = drop_text("long.toml", long.as_bytes());
    assert!(said.contains("at most 200"), "{said}");
    assert!(kept);

    let (said, kept) = drop_text("latin1.toml", b"title = \"caf\xe9\"\n");
    assert!(
        said.starts_with("latin1.toml:1: the file is not UTF-8"),
        "{said}"
    );
    assert!(kept);

    // A setup that names where a page starts is refused, as in the built-in lessons.
    let page = EXAM.replacen("task=first-hit\"", "task=first-hit&lesson-url=x.toml\"", 1);
    let (said, kept) = drop_text("page.toml", page.as_bytes());
    assert!(said.starts_with("page.toml:6:"), "{said}");
    assert!(kept);
}

#[test]
fn a_teachers_lesson_comes_back_with_the_saved_state_and_the_share_link() {
    let mut lab = students_lab();
    let lesson = read_teacher("exam.toml", EXAM.as_bytes()).expect("reads");
    lab.apply(Action::Lesson(LessonAction::Open {
        lesson: lesson.into(),
        step: 1,
    }))
    .expect("opens");
    tick(&mut lab);
    do_the_solution(&mut lab);
    let before = lab.lesson().expect("open").clone();
    assert!(before.reached_here());

    let saved = from_file(&to_file(&lab)).expect("the file reads back");
    let link = from_fragment(&link_fragment(&SavedState::capture(&lab)).expect("fits in a link"))
        .expect("the link reads back");
    for (how, state) in [("file", saved), ("link", link)] {
        let mut back = Lab::default();
        back.apply(state.apply().expect("restores"))
            .expect("applies");
        let progress = back.lesson().expect("the teacher's lesson came back");
        assert_eq!(*progress, before, "via the {how}");
        assert_eq!(
            progress.lesson.teacher.as_ref().map(|t| t.file.as_str()),
            Some("exam.toml")
        );
    }
}

#[test]
fn the_embedding_page_opens_a_teachers_lesson_and_moves_in_it_by_name() {
    let mut lab = students_lab();
    let json =
        serde_json::json!({"type": "load-lesson", "text": EXAM, "file": "exam.toml", "step": 2});
    let (actions, _) = Command::parse(&json.to_string())
        .expect("a command")
        .actions(&lab, false)
        .expect("accepted");
    for action in actions {
        lab.apply(action).expect("applies");
    }
    tick(&mut lab);
    let progress = lab.lesson().expect("open");
    assert_eq!((progress.lesson.name.as_str(), progress.step), ("exam", 1));

    let back = serde_json::json!({"type": "go-to-lesson", "lesson": "exam", "step": 1});
    let (actions, _) = Command::parse(&back.to_string())
        .expect("a command")
        .actions(&lab, false)
        .expect("the open teacher's lesson is found by its name");
    for action in actions {
        lab.apply(action).expect("applies");
    }
    assert_eq!(lab.lesson().expect("open").step, 0);

    let broken = serde_json::json!({"type": "load-lesson", "text": "title = \n", "file": "x.toml"});
    let refused = Command::parse(&broken.to_string())
        .expect("a command")
        .actions(&lab, false)
        .expect_err("a broken lesson is refused");
    assert!(refused.starts_with("x.toml:1:"), "{refused}");
}

#[test]
fn the_address_names_a_lesson_file_on_the_web_or_on_this_server_only() {
    for good in [
        "lesson-url=lessons/week-3.toml",
        "lesson-url=https%3A%2F%2Fcourse.example.edu%2Fexam.toml",
        "lesson-url=HTTP://course.example.edu/exam.toml",
    ] {
        let params = StartParams::parse(good);
        assert!(params.problems.is_empty(), "{good}: {:?}", params.problems);
        assert!(params.lesson_url.is_some(), "{good}");
        assert!(
            params.storage_key().contains("lesson-url="),
            "its own saved state"
        );
    }
    for bad in [
        "lesson-url=javascript:alert(1)",
        "lesson-url=data:text/plain,title",
        "lesson-url=file:///etc/passwd",
        "lesson-url=",
    ] {
        let params = StartParams::parse(bad);
        assert!(params.lesson_url.is_none(), "{bad}");
        assert!(
            params.problems.iter().any(|p| p.contains("lesson-url")),
            "{bad}: {:?}",
            params.problems
        );
    }
}

/// What an LMS kept for a student (the SCORM launch page's `suspend_data`) comes back on
/// another computer: `go-to-lesson` with `reached` opens the step with those goals reached,
/// and refuses steps the lesson does not have, changing nothing.
#[test]
fn going_to_a_lesson_with_the_steps_reached_before_resumes_the_student() {
    let mut lab = Lab::default();
    let lesson = bvhlab_app::lessons::find("slab-test").expect("the slab test lesson");
    let steps = lesson.steps.len();
    let json = serde_json::json!({
        "type": "go-to-lesson", "lesson": "slab-test", "step": 2, "reached": [1]
    });
    let (actions, _) = Command::parse(&json.to_string())
        .and_then(|c| c.actions(&lab, false))
        .expect("accepted");
    lab.apply_all(actions).expect("applies");
    let progress = lab.lesson().expect("open");
    assert_eq!(progress.step, 1);
    let mut expected = vec![false; steps];
    expected[0] = true;
    assert_eq!(progress.reached, expected);
    let report = bvhlab_app::lessons::report::LessonReport::of(&lab).expect("open");
    assert_eq!(report.goals_reached, 1, "{report:?}");

    let before = lab.lesson().cloned();
    let beyond = serde_json::json!({
        "type": "go-to-lesson", "lesson": "slab-test", "step": 1, "reached": [steps + 1]
    });
    let refused = Command::parse(&beyond.to_string())
        .and_then(|c| c.actions(&lab, false))
        .expect_err("a step the lesson lacks");
    assert!(refused.contains(&format!("1 to {steps}")), "{refused}");
    assert!(
        lab.apply(Action::Lesson(LessonAction::MarkReached(vec![steps])))
            .is_err()
    );
    assert_eq!(lab.lesson(), before.as_ref());
    lab.apply(Action::Lesson(LessonAction::Close))
        .expect("closes");
    assert!(
        lab.apply(Action::Lesson(LessonAction::MarkReached(vec![0])))
            .is_err(),
        "no lesson open"
    );
}
