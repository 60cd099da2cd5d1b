//! Opening a teacher's lesson file while the lab runs: dropped on the page, picked in the file
//! dialog, sent by the embedding page (`loadLesson`) or named by the address's `lesson-url=`.
//! All four come here, so each says the same thing about the same file.

use std::sync::Arc;

use super::format::read_teacher;
use crate::model::{Action, LessonAction};

/// Whether a file called `name` is read as a lesson (by its extension).
pub fn is_lesson_file(name: &str) -> bool {
    let path = name.split(['?', '#']).next().unwrap_or(name);
    path.to_ascii_lowercase().ends_with(".toml")
}

/// What opening the lesson file `file` (its bytes, or why they could not be read) does: the
/// lesson opens at its first step and the status line says whose it is; a file that cannot
/// be read, or a lesson that is wrong, changes nothing and says `file:line: why`.
pub fn open_lesson_file(file: &str, bytes: Result<Vec<u8>, String>) -> Vec<Action> {
    let read = bytes
        .map_err(|e| format!("{file} could not be read ({e})"))
        .and_then(|bytes| read_teacher(file, &bytes));
    match read {
        Ok(lesson) => {
            let steps = lesson.steps.len();
            let said = format!(
                "Opened the teacher's lesson \"{}\" from {file} ({steps} step{}).",
                lesson.title,
                crate::model::dimension::plural(steps)
            );
            vec![
                Action::Lesson(LessonAction::Open {
                    lesson: Arc::new(lesson),
                    step: 0,
                }),
                Action::SetMessage(Some(said)),
            ]
        }
        Err(e) => vec![Action::SetMessage(Some(format!(
            "{e}. The lesson was not opened; nothing else changed."
        )))],
    }
}
