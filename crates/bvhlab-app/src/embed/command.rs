//! The scripting API's commands: what a course page may ask of an embedded lab through
//! `postMessage`, read from JSON and applied to the lab. Each command either changes the lab
//! or is refused with a message that says why; a refused command changes nothing.

use bvhlab::Ray3;
use bvhlab::glam::{Vec2, Vec3};
use serde::Deserialize;

use crate::model::lab2d::RayHandles;
use crate::model::mesh::MeshSource;
use crate::model::predict::PredictAction;
use crate::model::presets::Preset;
use crate::model::{
    Action, Action2d, Action3d, Dimension, HalfAction, Lab, LessonAction, PlaybackAction,
};
use crate::persist::{MAX_FILE_BYTES, SavedState, StructureName, TaskName};

/// A command, as the page sends it: `{"type": "set-ray", "origin": [0, 0], "direction": [1, 0]}`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Command {
    /// Replaces the whole state with a scene file's content (the JSON that "Export scene"
    /// writes, as an object); the same checks as a dropped file.
    LoadScene {
        /// The scene file's JSON.
        scene: serde_json::Value,
    },
    /// Opens a 2D preset (`kd-tree`, `quadtree`, ...) and shows the 2D half.
    LoadPreset {
        /// The preset's slug.
        preset: String,
    },
    /// Opens a built-in mesh (`bunny`, `torus`, ...) and shows the 3D half.
    LoadMesh {
        /// The mesh's slug.
        mesh: String,
    },
    /// Shows the 2D or the 3D half.
    Show {
        /// `"2d"` or `"3d"`.
        view: String,
    },
    /// Sets the structure of the half shown.
    SetStructure {
        /// The structure's name (`kd-tree`, `aabb-tree`, ...).
        structure: StructureName,
    },
    /// Sets what is stepped through.
    SetTask {
        /// The task's name (`first-hit`, `nearest`, ...).
        task: TaskName,
    },
    /// Sets the ray of the half shown: 2 numbers each in 2D, 3 in 3D.
    SetRay {
        /// Where it starts.
        origin: Vec<f64>,
        /// Its direction (any non-zero length).
        direction: Vec<f64>,
    },
    /// Sets the query point of the half shown.
    SetPoint {
        /// Its coordinates.
        point: Vec<f64>,
    },
    /// Moves playback by `by` steps (negative: back).
    Step {
        /// How many steps.
        by: i64,
    },
    /// Moves playback to step `step` (0: the start; past the end: the end).
    GoToStep {
        /// The step.
        step: usize,
    },
    /// Starts or stops playback.
    Play {
        /// Whether to play.
        playing: bool,
    },
    /// Opens a lesson at a step (1 is its first), as `?lesson=NAME&step=N` does.
    GoToLesson {
        /// The lesson's name (`slab-test`).
        lesson: String,
        /// The step, from 1.
        #[serde(default = "first_step")]
        step: usize,
        /// Steps (from 1) whose goals the student reached in an earlier session, marked
        /// reached again: what an LMS kept for the student (the SCORM launch page sends it).
        #[serde(default)]
        reached: Vec<usize>,
    },
    /// Opens a teacher's lesson file (its TOML text) at a step, as dropping the file on the
    /// lab does; the same checks and limits.
    LoadLesson {
        /// The lesson file's text.
        text: String,
        /// The file's name, for messages and the lesson's name (`my-lesson.toml`).
        #[serde(default = "lesson_file_name")]
        file: String,
        /// The step, from 1.
        #[serde(default = "first_step")]
        step: usize,
    },
    /// Switches Predict on or off (on: playback goes to the start when at the end).
    Predict {
        /// Whether the lab asks before each step.
        on: bool,
    },
    /// Answers the question Predict asks: `choice` counts the answers offered from 1 (the
    /// report's `predict.question.choices`, in order), as the keys 1 to 9 do.
    Answer {
        /// The answer's number, from 1.
        choice: usize,
    },
    /// Shows the answer of the question Predict asks (it counts as shown).
    ShowAnswer,
    /// Changes nothing: the reply carries the report.
    Report,
    /// Replies with the lab's state as a scene file's JSON, in `scene`.
    ExportScene,
    /// Panics (only when the page's address has `debug=panic`): the browser test of what a
    /// crash shows.
    PanicForTest,
}

impl Command {
    /// Reads a command from its JSON text.
    ///
    /// # Errors
    /// Not JSON, an unknown `type`, a missing or unknown field, a wrong type.
    pub fn parse(json: &str) -> Result<Self, String> {
        if json.len() > MAX_FILE_BYTES {
            return Err(format!(
                "the command is {} bytes; at most {MAX_FILE_BYTES}",
                json.len()
            ));
        }
        serde_json::from_str(json).map_err(|e| format!("not a command the lab knows: {e}"))
    }

    /// Whether the command needs the lab's structures and recording ready (playback needs
    /// to know how many steps there are).
    pub fn needs_idle(&self) -> bool {
        matches!(
            self,
            Self::Step { .. }
                | Self::GoToStep { .. }
                | Self::Play { .. }
                | Self::Predict { .. }
                | Self::Answer { .. }
                | Self::ShowAnswer
        )
    }

    /// What the command asks of `lab`, as actions; and the extra reply as JSON text
    /// (`ExportScene`'s scene).
    ///
    /// # Errors
    /// Why it was refused (before anything is applied).
    ///
    /// # Panics
    /// On [`Command::PanicForTest`] when `debug_panic` is set: that is its purpose.
    pub fn actions(
        self,
        lab: &Lab,
        debug_panic: bool,
    ) -> Result<(Vec<Action>, Option<String>), String> {
        let three = lab.dimension() == Dimension::Three;
        let one = |a: Action| Ok((vec![a], None));
        match self {
            Self::LoadScene { scene } => {
                let text = serde_json::to_vec(&scene).map_err(|e| e.to_string())?;
                one(crate::persist::from_file(&text)?.apply()?)
            }
            Self::LoadPreset { preset } => {
                let p = Preset::from_slug(&preset)
                    .ok_or_else(|| format!("the lab has no preset \"{preset}\""))?;
                one(Action2d::LoadPreset(p).into())
            }
            Self::LoadMesh { mesh } => one(Action3d::OpenMesh(MeshSource::Builtin(mesh)).into()),
            Self::Show { view } => one(Action::Show(match view.as_str() {
                "2d" => Dimension::Two,
                "3d" => Dimension::Three,
                _ => return Err(format!("view is \"{view}\"; it must be \"2d\" or \"3d\"")),
            })),
            Self::SetStructure { structure } => {
                let mut settings = if three {
                    lab.three().half.lane.settings
                } else {
                    lab.two().half.lane.settings
                };
                settings.kind = structure.into();
                one(HalfAction::SetStructure(settings).into())
            }
            Self::SetTask { task } => one(HalfAction::SetTask(task.into()).into()),
            Self::SetRay { origin, direction } => one(set_ray(three, &origin, &direction)?),
            Self::SetPoint { point } => one(set_point(three, &point)?),
            Self::Step { by } => {
                let by =
                    isize::try_from(by).unwrap_or(if by < 0 { isize::MIN } else { isize::MAX });
                one(PlaybackAction::StepBy(by).into())
            }
            Self::GoToStep { step } => one(PlaybackAction::GoTo(step).into()),
            Self::Play { playing } => one(PlaybackAction::Play(playing).into()),
            Self::GoToLesson {
                lesson,
                step,
                reached,
            } => Ok((go_to_lesson(lab, &lesson, step, &reached)?, None)),
            Self::LoadLesson { text, file, step } => {
                let lesson = crate::lessons::format::read_teacher(&file, text.as_bytes())?;
                one(open_at(std::sync::Arc::new(lesson), step)?)
            }
            Self::Predict { on } => one(PredictAction::On(on).into()),
            Self::Answer { choice } => {
                let question = lab.predict_question().ok_or_else(|| {
                    "there is no question to answer: Predict is off, or this step decides \
                     nothing"
                        .to_owned()
                })?;
                let (answer, _) = choice
                    .checked_sub(1)
                    .and_then(|i| question.choices.get(i))
                    .ok_or_else(|| {
                        format!(
                            "choice is {choice}; the question has answers 1 to {}",
                            question.choices.len()
                        )
                    })?;
                one(PredictAction::Answer(*answer).into())
            }
            Self::ShowAnswer => one(PredictAction::Show.into()),
            Self::Report => Ok((Vec::new(), None)),
            Self::ExportScene => {
                let scene = serde_json::to_string(&SavedState::capture_full(lab))
                    .map_err(|e| e.to_string())?;
                Ok((Vec::new(), Some(scene)))
            }
            Self::PanicForTest => {
                if !debug_panic {
                    return Err(
                        "panic-for-test works only when the page's address has debug=panic"
                            .to_owned(),
                    );
                }
                #[expect(clippy::panic, reason = "what the browser test of a crash asks for")]
                {
                    panic!("panic-for-test: the page asked the lab to crash");
                }
            }
        }
    }
}

/// `go-to-lesson`: opens lesson `name` (a built-in one, or the teacher's lesson open by that
/// name) at `step` (from 1), with the steps `reached` (from 1) marked reached.
fn go_to_lesson(
    lab: &Lab,
    name: &str,
    step: usize,
    reached: &[usize],
) -> Result<Vec<Action>, String> {
    let open = lab
        .lesson()
        .map(|p| p.lesson.clone())
        .filter(|l| l.teacher.is_some() && l.name == name);
    let lesson = open.map_or_else(|| crate::lessons::find(name), Ok)?;
    let steps = lesson.steps.len();
    let marked = reached
        .iter()
        .map(|&s| {
            s.checked_sub(1)
                .filter(|&i| i < steps)
                .ok_or_else(|| format!("reached names step {s}; the lesson has steps 1 to {steps}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut actions = vec![open_at(lesson, step)?];
    if !marked.is_empty() {
        actions.push(Action::Lesson(LessonAction::MarkReached(marked)));
    }
    Ok(actions)
}

/// Opens `lesson` at `step` (from 1), or says which steps it has.
fn open_at(lesson: std::sync::Arc<crate::model::Lesson>, step: usize) -> Result<Action, String> {
    if step == 0 || step > lesson.steps.len() {
        return Err(format!(
            "the lesson \"{}\" has steps 1 to {}; step is {step}",
            lesson.name,
            lesson.steps.len()
        ));
    }
    Ok(Action::Lesson(LessonAction::Open {
        lesson,
        step: step - 1,
    }))
}

/// The file name of a lesson sent without one.
fn lesson_file_name() -> String {
    "lesson.toml".to_owned()
}

/// A lesson's first step, when a command names none.
fn first_step() -> usize {
    1
}

/// The ray of the half shown.
fn set_ray(three: bool, origin: &[f64], direction: &[f64]) -> Result<Action, String> {
    if three {
        let ray = Ray3::new(vec3("origin", origin)?, vec3("direction", direction)?)
            .map_err(|e| format!("the ray: {e}"))?;
        Ok(Action3d::SetRay(Some(ray)).into())
    } else {
        let origin = vec2("origin", origin)?;
        let handles = RayHandles {
            origin,
            target: origin + vec2("direction", direction)?,
        };
        handles.ray().map_err(|e| format!("the ray: {e}"))?;
        Ok(Action2d::SetRay(Some(handles)).into())
    }
}

/// The query point of the half shown.
fn set_point(three: bool, point: &[f64]) -> Result<Action, String> {
    Ok(if three {
        Action3d::SetPoint(Some(vec3("point", point)?)).into()
    } else {
        Action2d::SetPoint(Some(vec2("point", point)?)).into()
    })
}

fn vec2(what: &str, n: &[f64]) -> Result<Vec2, String> {
    match checked(what, n)?.as_slice() {
        &[x, y] => Ok(Vec2::new(x, y)),
        other => Err(format!(
            "the {what} has {} numbers; the 2D view takes 2",
            other.len()
        )),
    }
}

fn vec3(what: &str, n: &[f64]) -> Result<Vec3, String> {
    match checked(what, n)?.as_slice() {
        &[x, y, z] => Ok(Vec3::new(x, y, z)),
        other => Err(format!(
            "the {what} has {} numbers; the 3D view takes 3",
            other.len()
        )),
    }
}

/// Finite numbers within the lab's range, as `f32`.
fn checked(what: &str, n: &[f64]) -> Result<Vec<f32>, String> {
    n.iter()
        .map(|&x| crate::address::coordinate(&format!("the {what}"), x))
        .collect()
}
