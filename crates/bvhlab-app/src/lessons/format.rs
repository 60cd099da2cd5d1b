//! Reads a lesson file (TOML; the format is in `crates/bvhlab-app/lessons/README.md`) into
//! a [`Lesson`], or says which line of which file is wrong and why.

use serde::Deserialize;
use toml::Spanned;

use super::goal_text;
use crate::address::StartParams;
use crate::model::{Lesson, LessonStep, TeacherFile};

/// The largest lesson file a teacher may give the lab at run time, in bytes.
pub const MAX_TEACHER_BYTES: usize = 256 * 1024;

/// The most steps a teacher's lesson may have.
pub const MAX_TEACHER_STEPS: usize = 200;

/// A lesson file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LessonFile {
    title: String,
    section: String,
    #[serde(rename = "step")]
    steps: Vec<StepFile>,
}

/// A step as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StepFile {
    title: String,
    setup: Spanned<String>,
    text: String,
    formula: Option<String>,
    task: Option<String>,
    #[serde(default)]
    goal: Vec<Spanned<String>>,
    why: Option<String>,
    solution: Option<Spanned<String>>,
}

/// The lesson in `text`, read from the file `file` (`03-slab-test.toml`: the lesson's name
/// is `slab-test`).
///
/// # Errors
/// `file:line: what is wrong`.
pub fn read(file: &str, text: &str) -> Result<Lesson, String> {
    let name = lesson_name(file);
    let parsed: LessonFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map_or(0, |s| line_of(text, s.start));
        format!("{file}:{line}: {}", e.message())
    })?;
    if parsed.steps.is_empty() {
        return Err(format!("{file}:1: the lesson has no [[step]]"));
    }
    let mut steps = Vec::with_capacity(parsed.steps.len());
    for step in parsed.steps {
        let at = |span: std::ops::Range<usize>| format!("{file}:{}", line_of(text, span.start));
        let params = StartParams::parse(step.setup.get_ref());
        if let Some(problem) = params.problems.first() {
            return Err(format!("{}: the setup: {problem}", at(step.setup.span())));
        }
        if params.lesson.is_some()
            || params.lesson_url.is_some()
            || !params.origins.is_empty()
            || params.lab.is_some()
        {
            return Err(format!(
                "{}: the setup says where the lab starts: lesson, lesson-url, lab and origin \
                 belong to a page",
                at(step.setup.span())
            ));
        }
        let goals = step
            .goal
            .iter()
            .map(|g| goal_text::parse(g.get_ref()).map_err(|e| format!("{}: {e}", at(g.span()))))
            .collect::<Result<Vec<_>, String>>()?;
        let solution = match &step.solution {
            Some(text) => {
                let params = StartParams::parse(text.get_ref());
                if let Some(problem) = params.problems.first() {
                    return Err(format!("{}: the solution: {problem}", at(text.span())));
                }
                Some(params.setup())
            }
            None => None,
        };
        if solution.is_some() == goals.is_empty() {
            return Err(format!(
                "{}: a step with a goal has a solution that reaches it (and only then: the \
                 step \"{}\")",
                at(step.setup.span()),
                step.title
            ));
        }
        if step.task.is_some() == goals.is_empty() {
            return Err(format!(
                "{}: a step with a task has a goal to check it, and a goal has a task saying \
                 what to do (the step \"{}\")",
                at(step.setup.span()),
                step.title
            ));
        }
        steps.push(LessonStep {
            title: step.title,
            setup: params.setup(),
            text: reflow(&step.text),
            formula: step.formula.map(|f| f.trim_end().to_owned()),
            task: step.task.as_deref().map(reflow),
            goals,
            why: step.why.as_deref().map(reflow),
            solution,
        });
    }
    Ok(Lesson {
        name,
        title: parsed.title,
        section: parsed.section,
        steps,
        teacher: None,
    })
}

/// A lesson file a teacher gives the lab while it runs (`file`: its name or address), read
/// as [`read`] reads the built-in ones, within the limits a file from outside gets: at most
/// [`MAX_TEACHER_BYTES`] of UTF-8 and [`MAX_TEACHER_STEPS`] steps (its setups already keep to
/// the address's limits). Its text is shown as plain text: the panel draws no markup and
/// follows no links, so `<script>` in a title is only characters.
///
/// # Errors
/// `file:line: what is wrong`, like the built-in check.
pub fn read_teacher(file: &str, bytes: &[u8]) -> Result<Lesson, String> {
    if bytes.len() > MAX_TEACHER_BYTES {
        // Worded as a file picked or dropped is refused before it is read.
        return Err(format!(
            "{file} could not be read ({})",
            crate::persist::too_large(bytes.len() as u64, MAX_TEACHER_BYTES)
        ));
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = line_of(&String::from_utf8_lossy(bytes), e.valid_up_to());
        format!("{file}:{line}: the file is not UTF-8 text")
    })?;
    let short = file.rsplit(['/', '\\']).next().unwrap_or(file);
    let short = short.split(['?', '#']).next().unwrap_or(short);
    let mut lesson = read(file, text)?;
    if lesson.steps.len() > MAX_TEACHER_STEPS {
        return Err(format!(
            "{file}:1: the lesson has {} steps; a lesson may have at most {MAX_TEACHER_STEPS}",
            lesson.steps.len()
        ));
    }
    lesson.name = lesson_name(short)
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    if lesson.name.trim_matches('-').is_empty() {
        "teachers-lesson".clone_into(&mut lesson.name);
    }
    lesson.teacher = Some(TeacherFile {
        file: file.to_owned(),
        text: text.into(),
    });
    Ok(lesson)
}

/// `slab-test` for `03-slab-test.toml`: the file's name without its order number and
/// extension.
pub fn lesson_name(file: &str) -> String {
    let stem = file.strip_suffix(".toml").unwrap_or(file);
    let unnumbered = stem
        .split_once('-')
        .filter(|(number, _)| !number.is_empty() && number.chars().all(|c| c.is_ascii_digit()))
        .map_or(stem, |(_, rest)| rest);
    unnumbered.to_owned()
}

/// Prose as the panel wraps it: the lines of a paragraph joined by spaces (a file's line
/// breaks are only where its author's editor wrapped), paragraphs kept apart by a blank line.
fn reflow(text: &str) -> String {
    text.trim()
        .split("\n\n")
        .map(|paragraph| paragraph.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|paragraph| !paragraph.is_empty())
        .collect::<Vec<_>>()
        .join("\n\n")
}

/// The line (from 1) of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text.get(..offset)
        .map_or(0, |before| before.matches('\n').count())
        + 1
}
