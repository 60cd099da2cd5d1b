//! "Write a lesson": the teacher's mode that turns what is on screen into a lesson step. The
//! step's setup and solution are what the lab shows, in the address's words
//! ([`crate::address::words`]); the teacher types the text and the task and picks goals from
//! the quantities the lab knows ([`goals`]); the lab checks the step as the lessons test does
//! ([`check`]) before it lets it be saved; the lesson is exported as a lesson file
//! ([`text`]) and as a share link, and a lesson file opened again is edited.
//!
//! The writer is its own small model beside the lab's, changed only through
//! [`LessonWriter::apply`]: it reads the lab (to describe it) and hands back the lab actions
//! it needs (opening the lesson to try it), which the app applies as any others.

pub mod check;
pub mod goals;
pub mod text;

use std::sync::Arc;

use crate::address::words::{describe, words_added};
use crate::model::{Action, Lab, LessonAction};
pub use text::{DraftStep, LessonDraft};

/// The lesson being written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LessonWriter {
    /// The lesson file's name (`my-lesson.toml`).
    pub file: String,
    /// The lesson, with the steps saved so far.
    pub draft: LessonDraft,
    /// The step being written.
    pub step: DraftStep,
    /// Where it goes among the saved steps (their count: a new step at the end).
    pub at: usize,
    /// The last check of the step as it is now: `Ok(what passed)` or `Err(why not)`; none
    /// after a change.
    pub verdict: Option<Result<String, String>>,
    /// What the lab showed that the setup's words could not hold, at the last capture.
    pub unsaid: Vec<String>,
}

/// A field of the lesson.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LessonField {
    /// The lesson's title.
    Title,
    /// The lecture's section.
    Section,
    /// The file's name.
    File,
}

/// A field of the step being written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepField {
    /// Its title.
    Title,
    /// Its setup, in the address's words.
    Setup,
    /// What it says.
    Text,
    /// Its formula or pseudocode (empty: none).
    Formula,
    /// Its task (empty: none).
    Task,
    /// Why the goal matters (empty: nothing).
    Why,
    /// Its solution, in the address's words (empty: none).
    Solution,
}

/// What the teacher asks of the writer: start it, edit the teacher's lesson open in the lab,
/// close it, or change the lesson being written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WriterCommand {
    /// Starts a new lesson from what the lab shows.
    Start,
    /// Edits the teacher's lesson open in the lab (its file, as opened).
    EditOpen,
    /// Closes the writer (what is not saved as a file is gone).
    Close,
    /// A change of the lesson being written.
    Do(WriterAction),
}

/// A change of the lesson being written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WriterAction {
    /// Sets a field of the lesson.
    SetLesson(LessonField, String),
    /// Sets a field of the step being written.
    SetStep(StepField, String),
    /// The step's setup becomes what the lab shows now.
    CaptureSetup,
    /// The step's solution becomes what the lab shows now (what differs from the setup).
    RecordSolution,
    /// Adds a goal line (`nodes-visited < 14`).
    AddGoal(String),
    /// Removes the goal at this index.
    RemoveGoal(usize),
    /// Checks the step as the lessons test does.
    Check,
    /// Saves the step into the lesson (only once checked) and starts the next.
    SaveStep,
    /// Writes the saved step at this index again (it becomes the step being written; the
    /// lab opens it).
    EditStep(usize),
    /// Removes the saved step at this index.
    RemoveStep(usize),
    /// Opens the lesson as saved so far in the lab, at the step at this index.
    Try(usize),
}

impl LessonWriter {
    /// A new lesson, its first step starting from what the lab shows.
    pub fn new(lab: &Lab) -> Self {
        let mut writer = Self {
            file: "my-lesson.toml".to_owned(),
            draft: LessonDraft::default(),
            step: DraftStep::default(),
            at: 0,
            verdict: None,
            unsaid: Vec::new(),
        };
        writer.capture(lab);
        writer
    }

    /// The lesson file `text` (called `file`) to edit, with a new step at its end.
    ///
    /// # Errors
    /// `file:line: why`, when it is not a lesson file.
    pub fn editing(file: &str, text: &str, lab: &Lab) -> Result<Self, String> {
        let draft = text::from_toml(file, text)?;
        let mut writer = Self::new(lab);
        writer.at = draft.steps.len();
        writer.draft = draft;
        file.rsplit(['/', '\\'])
            .next()
            .unwrap_or(file)
            .clone_into(&mut writer.file);
        Ok(writer)
    }

    /// The lesson file's text, as saved so far.
    pub fn toml(&self) -> String {
        text::to_toml(&self.draft)
    }

    /// The lesson as saved so far, read as the lab reads a teacher's file.
    ///
    /// # Errors
    /// When it has no steps yet, or does not read.
    pub fn lesson(&self) -> Result<Arc<crate::model::Lesson>, String> {
        if self.draft.steps.is_empty() {
            return Err("the lesson has no saved step yet".to_owned());
        }
        super::format::read_teacher(&self.file_name(), self.toml().as_bytes()).map(Arc::new)
    }

    /// The lesson file's name as saved: the name typed, ending in `.toml`.
    pub fn file_name(&self) -> String {
        let name = self.file.trim();
        let name = if name.is_empty() { "my-lesson" } else { name };
        if name.to_ascii_lowercase().ends_with(".toml") {
            name.to_owned()
        } else {
            format!("{name}.toml")
        }
    }

    /// Carries out `action`, reading `lab`; returns the lab actions it asks for.
    ///
    /// # Errors
    /// Why it was refused (a step saved unchecked, an index out of range, a goal that does
    /// not read); the writer is then unchanged.
    pub fn apply(&mut self, action: WriterAction, lab: &Lab) -> Result<Vec<Action>, String> {
        let mut asks = Vec::new();
        let changes_step = !matches!(
            action,
            WriterAction::Check | WriterAction::Try(_) | WriterAction::SetLesson(..)
        );
        match action {
            WriterAction::SetLesson(field, value) => match field {
                LessonField::Title => self.draft.title = value,
                LessonField::Section => self.draft.section = value,
                LessonField::File => {
                    if value.contains(['/', '\\']) {
                        return Err(format!(
                            "\"{value}\" is not a file name: a name like week-3.toml, without \
                             folders"
                        ));
                    }
                    self.file = value;
                }
            },
            WriterAction::SetStep(field, value) => self.set_step(field, value),
            WriterAction::CaptureSetup => self.capture(lab),
            WriterAction::RecordSolution => {
                let now = describe(lab).words;
                self.step.solution = Some(words_added(&self.step.setup, &now));
            }
            WriterAction::AddGoal(goal) => {
                super::goal_text::parse(&goal)?;
                if !self.step.goal.contains(&goal) {
                    self.step.goal.push(goal);
                }
            }
            WriterAction::RemoveGoal(i) => {
                check_index(i, self.step.goal.len(), "goal")?;
                self.step.goal.remove(i);
            }
            WriterAction::Check => {
                let file = self.file_name();
                self.verdict = Some(check::check_step(&file, &self.draft, &self.step));
            }
            WriterAction::SaveStep => {
                match &self.verdict {
                    Some(Ok(_)) => {}
                    Some(Err(why)) => return Err(format!("the step is not saved: {why}")),
                    None => return Err("check the step before saving it".to_owned()),
                }
                let at = self.at.min(self.draft.steps.len());
                if at < self.draft.steps.len() {
                    self.draft.steps[at] = self.step.clone();
                } else {
                    self.draft.steps.push(self.step.clone());
                }
                self.at = self.draft.steps.len();
                // The next step starts where this one's solution left the lab.
                self.step = DraftStep::default();
                self.capture(lab);
            }
            WriterAction::EditStep(i) => {
                check_index(i, self.draft.steps.len(), "step")?;
                asks.push(self.open(i)?);
                self.step = self.draft.steps[i].clone();
                self.at = i;
                self.unsaid.clear();
            }
            WriterAction::RemoveStep(i) => {
                check_index(i, self.draft.steps.len(), "step")?;
                self.draft.steps.remove(i);
                if self.at > i {
                    self.at -= 1;
                }
                self.at = self.at.min(self.draft.steps.len());
            }
            WriterAction::Try(i) => {
                check_index(i, self.draft.steps.len(), "step")?;
                asks.push(self.open(i)?);
            }
        }
        if changes_step {
            self.verdict = None;
        }
        Ok(asks)
    }

    /// Sets one field of the step being written (an empty optional field is none).
    fn set_step(&mut self, field: StepField, value: String) {
        let optional = (!value.trim().is_empty()).then(|| value.clone());
        match field {
            StepField::Title => self.step.title = value,
            StepField::Setup => self.step.setup = value,
            StepField::Text => self.step.text = value,
            StepField::Formula => self.step.formula = optional,
            StepField::Task => self.step.task = optional,
            StepField::Why => self.step.why = optional,
            StepField::Solution => self.step.solution = optional,
        }
    }

    /// The step's setup becomes what the lab shows.
    fn capture(&mut self, lab: &Lab) {
        let described = describe(lab);
        self.step.setup = described.words;
        self.unsaid = described.unsaid;
    }

    /// The lab action that opens the lesson saved so far at step `i`.
    fn open(&self, i: usize) -> Result<Action, String> {
        Ok(Action::Lesson(LessonAction::Open {
            lesson: self.lesson()?,
            step: i,
        }))
    }
}

/// Refuses index `i` of a list of `len` `what`s when there is none.
fn check_index(i: usize, len: usize, what: &str) -> Result<(), String> {
    if i < len {
        Ok(())
    } else {
        Err(format!("there is no {what} {} (there are {len})", i + 1))
    }
}
