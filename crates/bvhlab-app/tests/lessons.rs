//! The lessons: every file in `crates/bvhlab-app/lessons/` reads; each step opens without a
//! problem, its goal is not reached where the step starts (the student has something to
//! do) and is reached by the step's solution; a bad lesson file is refused with its line;
//! and a lesson opens from the page's address and in the Lessons panel.

use crate::common;

use bvhlab_app::embed::StartParams;
use bvhlab_app::lessons::{self, format};
use bvhlab_app::model::goal::Quantity;
use bvhlab_app::model::{Action, Lab, LessonAction, LessonProgress, PlaybackAction};

use crate::common::tick_lab as tick;

/// Each goal of the step shown with its value now, for a failure's message.
fn goals_now(lab: &Lab) -> String {
    let Some(progress) = lab.lesson() else {
        return "no lesson open".to_owned();
    };
    progress
        .current()
        .goals
        .iter()
        .map(|g| {
            let now = g
                .now(lab)
                .map_or("unknown".to_owned(), lessons::goal_text::value_text);
            format!("`{}` (now {now}, holds: {})", g.text, g.holds(lab))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Switches Predict on and answers every question of the recording right.
fn predict_all(lab: &mut Lab) {
    use bvhlab_app::model::predict::PredictAction;
    lab.apply(PredictAction::On(true).into())
        .expect("Predict on");
    let steps = lab.steps();
    for _ in 0..=steps {
        match lab.predict_question() {
            Some(q) => lab.apply(PredictAction::Answer(q.answer).into()),
            None => lab.apply(PlaybackAction::StepBy(1).into()),
        }
        .expect("an answer or a step applies");
    }
}

#[test]
fn every_lesson_file_reads() {
    assert!(
        lessons::files().len() >= 6,
        "the lessons: {:?}",
        lessons::files()
    );
    for (file, lesson) in lessons::files().iter().zip(lessons::catalog()) {
        let lesson = lesson.as_ref().unwrap_or_else(|e| panic!("{e}"));
        assert!(!lesson.steps.is_empty(), "{}", file.0);
        // Prose is reflowed for the panel: a file's line breaks inside a paragraph are gone.
        for step in &lesson.steps {
            for prose in [Some(&step.text), step.task.as_ref(), step.why.as_ref()]
                .into_iter()
                .flatten()
            {
                let single_breaks = prose.replace("\n\n", "").contains('\n');
                assert!(!single_breaks, "{}: {prose:?}", file.0);
            }
        }
        assert_eq!(lesson.name, format::lesson_name(file.0));
    }
    let names: Vec<&str> = lessons::lessons().map(|l| l.name.as_str()).collect();
    let mut unique = names.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(
        unique.len(),
        names.len(),
        "two lessons share a name: {names:?}"
    );
    // The README's table of address parameters names every lesson.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md"))
        .expect("the README");
    let row = readme
        .lines()
        .find(|l| l.starts_with("| `lesson` |"))
        .expect("the README's lesson parameter");
    for name in names {
        assert!(
            row.contains(&format!("`{name}`")),
            "the README's row lacks {name}: {row}"
        );
    }
}

#[test]
fn each_step_opens_cleanly_starts_unreached_and_its_solution_reaches_it() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for lesson in lessons::lessons() {
        for (index, step) in lesson.steps.iter().enumerate() {
            let at = format!("{} step {} ({})", lesson.name, index + 1, step.title);
            let mut lab = Lab::default();
            lab.apply(Action::Lesson(LessonAction::Open {
                lesson: lesson.clone(),
                step: index,
            }))
            .unwrap_or_else(|e| panic!("{at}: {e}"));
            tick(&mut lab);
            assert_eq!(lab.message(), None, "{at} opened with a problem");
            let progress = lab.lesson().expect("the lesson is open");
            assert_eq!(progress.step, index, "{at}");
            let Some(solution) = &step.solution else {
                assert!(step.goals.is_empty(), "{at}");
                continue;
            };
            if progress.reached_here() {
                failures.push(format!(
                    "{at}: the goal is reached before the student does anything: {}",
                    goals_now(&lab)
                ));
            }
            let problems = lab.apply_setup(solution, "the solution");
            assert!(problems.is_empty(), "{at}: {problems:?}");
            if step.goals.iter().any(|g| g.quantity == Quantity::Predicted) {
                // Reached by answering: Predict on, every question answered right.
                predict_all(&mut lab);
            }
            lab.apply(PlaybackAction::End.into()).expect("to the end");
            tick(&mut lab);
            if !lab.lesson().is_some_and(LessonProgress::reached_here) {
                failures.push(format!(
                    "{at}: the solution does not reach the goal: {}",
                    goals_now(&lab)
                ));
            }
            checked += 1;
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(checked >= 10, "only {checked} steps have goals");
}

#[test]
fn a_reached_goal_stays_reached_and_moving_on_does_not_reach_the_next() {
    let lesson = lessons::lessons()
        .find(|l| l.steps.len() >= 2 && l.steps[0].solution.is_some())
        .expect("a lesson of two steps or more whose first has a goal")
        .clone();
    let mut lab = Lab::default();
    let open = |step| {
        Action::Lesson(LessonAction::Open {
            lesson: lesson.clone(),
            step,
        })
    };
    lab.apply(open(0)).expect("opens");
    let solution = lesson.steps[0].solution.clone().expect("a solution");
    lab.apply_setup(&solution, "the solution");
    lab.apply(PlaybackAction::End.into()).expect("to the end");
    assert!(
        lab.lesson().expect("open").reached_here(),
        "{}",
        goals_now(&lab)
    );
    lab.apply(open(1)).expect("the next step");
    let progress = lab.lesson().expect("open");
    assert_eq!(progress.reached, {
        let mut r = vec![false; lesson.steps.len()];
        r[0] = true;
        r
    });
    // Back to the first step: it starts afresh, and stays marked.
    lab.apply(open(0)).expect("back");
    assert!(lab.lesson().expect("open").reached_here());
    lab.apply(Action::Lesson(LessonAction::Close))
        .expect("closes");
    assert!(lab.lesson().is_none());
    let past = lesson.steps.len();
    let refused = lab.apply(open(past)).expect_err("no such step");
    assert!(refused.contains("has"), "{refused}");
}

/// What reading `text` as `03-test.toml` says.
fn refusal(text: &str) -> String {
    format::read("03-test.toml", text).expect_err("a bad lesson is refused")
}

#[test]
fn a_bad_lesson_file_is_refused_with_its_line() {
    let good_step = "[[step]]\ntitle = \"A\"\nsetup = \"preset=kd-tree\"\ntext = \"t\"\n";
    let head = "title = \"T\"\nsection = \"§3\"\n";
    assert!(format::read("03-test.toml", &format!("{head}{good_step}")).is_ok());
    let cases = [
        // A key the format does not have (a typo), on line 4.
        (
            format!("{head}{good_step}txet = \"x\"\n"),
            "03-test.toml:",
            "txet",
        ),
        // A setup the address would not read.
        (
            format!("{head}[[step]]\ntitle = \"A\"\nsetup = \"preset=kdtree\"\ntext = \"t\"\n"),
            "03-test.toml:5:",
            "kd-tree",
        ),
        // A goal with an unknown quantity.
        (
            format!(
                "{head}{good_step}task = \"x\"\nsolution = \"ray=0,0,1,0\"\ngoal = [\n  \"nodes-vistied < 3\",\n]\n"
            ),
            "03-test.toml:10:",
            "nodes-visited",
        ),
        // A goal without a task to say what to do.
        (
            format!("{head}{good_step}solution = \"ray=0,0,1,0\"\ngoal = [\"answer = hit\"]\n"),
            "03-test.toml:5:",
            "task",
        ),
        // A task without a solution.
        (
            format!("{head}{good_step}task = \"x\"\ngoal = [\"answer = hit\"]\n"),
            "03-test.toml:5:",
            "solution",
        ),
        // A word compared as a number.
        (
            format!(
                "{head}{good_step}task = \"x\"\nsolution = \"ray=0,0,1,0\"\ngoal = [\"answer < hit\"]\n"
            ),
            "03-test.toml:9:",
            "= or !=",
        ),
        (head.to_owned(), "03-test.toml:", "step"),
        (
            "title = \"T\"\nsection = \n".to_owned(),
            "03-test.toml:2:",
            "",
        ),
    ];
    for (text, place, word) in cases {
        let said = refusal(&text);
        assert!(
            said.starts_with(place),
            "{said:?} should start with {place:?}\n{text}"
        );
        assert!(said.contains(word), "{said:?} should name {word:?}");
    }
}

#[test]
fn the_address_opens_a_lesson_at_its_step() {
    let lesson = lessons::lessons()
        .find(|l| l.steps.len() >= 2)
        .expect("a lesson of two steps");
    let params = StartParams::parse(&format!("?lesson={}&step=2", lesson.name));
    assert!(params.problems.is_empty(), "{:?}", params.problems);
    let mut lab = Lab::default();
    let problems = params.apply(&mut lab);
    assert!(problems.is_empty(), "{problems:?}");
    let progress = lab.lesson().expect("the lesson is open");
    assert_eq!(
        (progress.lesson.name.as_str(), progress.step),
        (lesson.name.as_str(), 1)
    );

    let mut lab = Lab::default();
    let problems = StartParams::parse("?lesson=slab-tset").apply(&mut lab);
    assert!(lab.lesson().is_none());
    assert!(
        problems
            .iter()
            .any(|p| p.contains("no lesson named") && p.contains("slab-test")),
        "{problems:?}"
    );
}

#[test]
fn the_lessons_panel_starts_a_lesson_and_moves_through_it() {
    let mut h = common::lab();
    let first = lessons::lessons().next().expect("a lesson").clone();
    assert!(common::shows(&h, "A lesson walks the lecture"));
    common::click(&mut h, &format!("1. {} {}", first.section, first.title));
    let count = first.steps.len();
    assert!(common::shows(
        &h,
        &format!("Step 1 of {count}: {}", first.steps[0].title)
    ));
    assert!(common::shows(&h, "Your task:"), "{:?}", common::labels(&h));
    common::click(&mut h, "Next");
    assert!(common::shows(&h, &format!("Step 2 of {count}")));
    assert_eq!(h.state().lab().lesson().map(|p| p.step), Some(1));
    common::click(&mut h, "Back");
    assert_eq!(h.state().lab().lesson().map(|p| p.step), Some(0));
    common::click(&mut h, "Close");
    assert!(h.state().lab().lesson().is_none());
    assert!(common::shows(&h, "A lesson walks the lecture"));
}

#[test]
fn every_lesson_step_draws_in_the_panel() {
    // Every glyph of every text and formula must be in the lab's fonts (egui refuses to draw
    // one that is not), and each step's title shows.
    let mut h = common::lab();
    for lesson in lessons::lessons() {
        for (index, step) in lesson.steps.iter().enumerate() {
            common::act(
                &mut h,
                Action::Lesson(LessonAction::Open {
                    lesson: lesson.clone(),
                    step: index,
                }),
            );
            let title = format!(
                "Step {} of {}: {}",
                index + 1,
                lesson.steps.len(),
                step.title
            );
            assert!(
                common::shows(&h, &title),
                "{title}: {:?}",
                common::labels(&h)
            );
        }
    }
}

#[test]
fn the_page_opens_a_lesson_by_command_and_the_report_follows_the_progress() {
    use bvhlab_app::embed::command::Command;
    use bvhlab_app::lessons::report::LessonReport;
    let command = |lab: &Lab, json: &str| {
        Command::parse(json)
            .and_then(|c| c.actions(lab, false))
            .map(|(actions, _)| actions)
    };
    let mut lab = Lab::default();
    let actions = command(&lab, r#"{"type": "go-to-lesson", "lesson": "slab-test"}"#)
        .expect("a lesson by name opens at its first step");
    lab.apply_all(actions).expect("applies");
    let report = LessonReport::of(&lab).expect("a lesson is open");
    let lesson = lessons::find("slab-test").expect("the slab test lesson");
    let steps = lesson.steps.len();
    let with_goals = lesson.steps.iter().filter(|s| !s.goals.is_empty()).count();
    assert_eq!(
        (report.lesson.as_str(), report.step, report.steps),
        ("slab-test", 1, steps)
    );
    assert!(!report.goal_reached && report.goals_reached == 0 && report.goals == with_goals);
    assert!(
        report.text().contains(&format!("step 1 of {steps}"))
            && report.text().contains("Not done yet")
    );
    let message: serde_json::Value =
        serde_json::from_str(&report.progress_message()).expect("JSON");
    assert_eq!(message["bvhlab"], "progress");
    assert_eq!(message["step"], 1);

    // The step's solution, as the student would do it: the report says it is done.
    let solution = lab
        .lesson()
        .expect("open")
        .current()
        .solution
        .clone()
        .expect("a solution");
    lab.apply_setup(&solution, "the student");
    let report = LessonReport::of(&lab).expect("open");
    assert!(
        report.goal_reached && report.goals_reached == 1,
        "{report:?}"
    );
    assert!(report.text().ends_with("Done."), "{}", report.text());

    let past = format!(
        r#"{{"type": "go-to-lesson", "lesson": "slab-test", "step": {}}}"#,
        steps + 1
    );
    let range = format!("1 to {steps}");
    for (json, word) in [
        (past.as_str(), range.as_str()),
        (
            r#"{"type": "go-to-lesson", "lesson": "slab-test", "step": 0}"#,
            range.as_str(),
        ),
        (
            r#"{"type": "go-to-lesson", "lesson": "slab-tset"}"#,
            "slab-test",
        ),
    ] {
        let refused = command(&lab, json).expect_err("refused");
        assert!(refused.contains(word), "{json}: {refused}");
    }
}

#[test]
fn a_saved_state_keeps_the_lesson_and_its_goals_reached() {
    use bvhlab_app::persist::{from_file, to_file};
    let lesson = lessons::find("slab-test").expect("the slab test lesson");
    let mut lab = Lab::default();
    let open = |step| {
        Action::Lesson(LessonAction::Open {
            lesson: lesson.clone(),
            step,
        })
    };
    lab.apply(open(0)).expect("opens");
    let solution = lesson.steps[0].solution.clone().expect("a solution");
    lab.apply_setup(&solution, "the student");
    lab.apply(open(1)).expect("step 2");
    let file = String::from_utf8(to_file(&lab)).expect("UTF-8");

    let mut back = Lab::default();
    back.apply(
        from_file(file.as_bytes())
            .expect("reads")
            .apply()
            .expect("applies"),
    )
    .expect("restores");
    let progress = back.lesson().expect("the lesson came back");
    assert_eq!(progress.lesson.name, "slab-test");
    assert_eq!(progress.step, 1);
    let mut reached = vec![false; lesson.steps.len()];
    reached[0] = true;
    assert_eq!(progress.reached, reached);

    // A lesson this lab does not have: the rest comes back, and the status line says why the
    // lesson closed.
    let renamed = file.replace("\"slab-test\"", "\"slab-tests\"");
    assert_ne!(renamed, file, "the file names the lesson: {file}");
    let mut other = Lab::default();
    other
        .apply(
            from_file(renamed.as_bytes())
                .expect("reads")
                .apply()
                .expect("applies"),
        )
        .expect("restores");
    assert!(other.lesson().is_none());
    assert_eq!(other.two().ray, back.two().ray, "the ray came back");
    let said = other.message().unwrap_or_default();
    assert!(
        said.contains("saved lesson") && said.contains("slab-test"),
        "{said}"
    );
}
