//! Embedding the lab in a course page: the address's parameters choose what it opens with
//! ([`crate::address`], opened by [`StartParams::apply`] here), and the page scripts it with
//! `postMessage` ([`command`], [`Scripting`]).
//!
//! # The scripting API
//! The page posts `{bvhlab: "command", id, command: {type: "set-ray", ...}}` to the lab's
//! window (an `<iframe>`'s `contentWindow`). The lab accepts messages only from its own
//! origin and from the origins its address names with `origin=`; others are ignored. Each
//! command is answered, once the lab has applied it and its structures and recording are
//! ready, with `{bvhlab: "reply", id, ok: true, report}` (the lab's [`Report`]: the scene,
//! structure, answers, counters and playback) or `{bvhlab: "reply", id, ok: false, error}`.
//! Commands are applied in the order they arrive. `web/bvhlab-embed.js` wraps this in
//! promises; `web/embed.html` is a runnable example with two labs side by side.
//!
//! [`Report`]: crate::report::Report

#[cfg(target_arch = "wasm32")]
pub mod browser;
pub mod command;
pub mod size;
pub mod target;

use std::collections::VecDeque;

pub use crate::address::{PARAMETERS, StartParams};
pub use command::Command;

use crate::LabApp;
use crate::model::{Action, Lab, LessonAction};

/// The longest command id echoed, in characters of JSON.
const MAX_ID_CHARS: usize = 256;

/// How long a reply may wait for a build to finish, in seconds, before it is sent as an
/// error ("still building").
pub const REPLY_TIMEOUT: f64 = 60.0;

/// What the page opens with.
pub struct Start {
    /// The lab.
    pub app: LabApp,
    /// What could not be used, for the status line.
    pub message: Option<String>,
    /// The saved state was there but could not be restored (keep it until the student
    /// changes something, so that a newer lab version can still read it).
    pub saved_failed: bool,
}

/// The lab the page opens with.
///
/// In order: a share link's fragment (`#s=...`), then the state saved in this browser under
/// the parameters' [`StartParams::storage_key`] (unless `fresh=1`), then the parameters.
/// Whatever fails says why in the status line; the rest still applies.
pub fn start(fragment: Option<&str>, params: &StartParams, saved: Option<&str>) -> Start {
    let link = fragment.filter(|f| f.trim().trim_start_matches('#').starts_with("s="));
    let saved = saved.filter(|_| !params.fresh);
    let mut problems = params.problems.clone();
    let (mut lab, message) = if link.is_some() || saved.is_some() {
        crate::persist::startup(link, None, saved)
    } else {
        (Lab::default(), None)
    };
    let failed = message.is_some();
    if let Some(m) = message {
        problems.insert(0, m);
    }
    // The parameters choose the starting state only when nothing else did.
    if link.is_none() && (saved.is_none() || failed) {
        let mut fresh = Lab::default();
        problems.extend(params.apply(&mut fresh));
        lab = fresh;
    }
    let message = (!problems.is_empty()).then(|| sentences(&problems));
    if message.is_some() {
        let _ = lab.apply(Action::SetMessage(message.clone()));
    }
    let mut app = LabApp::new(lab);
    if let Some(panels) = params.panels {
        app.ui.panels = panels;
    }
    Start {
        app,
        message,
        saved_failed: failed && link.is_none(),
    }
}

impl StartParams {
    /// Puts what the parameters ask for into `lab` (a fresh one), and returns what could
    /// not be used, one sentence each. (The panels are the UI's: the caller shows them.) A
    /// lesson opens after the rest, at `step=` (1 is its first step).
    pub fn apply(&self, lab: &mut Lab) -> Vec<String> {
        let mut problems = lab.apply_setup(&self.setup(), "the address");
        if let Some(name) = &self.lesson {
            let step = self.step.unwrap_or(1).max(1) - 1;
            match crate::lessons::find(name) {
                Ok(lesson) => {
                    if let Err(e) = lab.apply(Action::Lesson(LessonAction::Open { lesson, step })) {
                        problems.push(format!("the address: {e}"));
                    }
                }
                Err(e) => problems.push(format!("the address's lesson: {e}")),
            }
        }
        problems
    }
}

/// Sentences from message parts (each capitalized and ended with a full stop).
fn sentences(parts: &[String]) -> String {
    parts
        .iter()
        .map(|p| {
            let end = if p.ends_with('.') { "" } else { "." };
            format!("{}{end}", crate::persist::capitalized(p))
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A command received, with where its reply goes (`T`: the page's window and origin on the
/// web, anything in tests).
struct Request<T> {
    reply_to: T,
    /// The id as the page wrote it (JSON text), echoed verbatim: read into a number and
    /// written back, an id like `Math.random()` may not come back to the same digits.
    id: String,
    command: Result<Command, String>,
}

/// A command applied (or refused), waiting for the lab to be ready before its reply goes.
struct Waiting<T> {
    reply_to: T,
    id: String,
    outcome: Result<Option<String>, String>,
    since: f64,
}

/// The commands received and the replies owed, frame by frame: [`before_frame`] applies
/// commands in order, [`after_frame`] hands out the replies that are ready.
///
/// [`before_frame`]: Scripting::before_frame
/// [`after_frame`]: Scripting::after_frame
pub struct Scripting<T> {
    queue: VecDeque<Request<T>>,
    waiting: Vec<Waiting<T>>,
    debug_panic: bool,
}

impl<T> Scripting<T> {
    /// No commands yet; `debug_panic` allows [`Command::PanicForTest`].
    pub fn new(debug_panic: bool) -> Self {
        Self {
            queue: VecDeque::new(),
            waiting: Vec::new(),
            debug_panic,
        }
    }

    /// Queues a command's JSON text, with its `id` as JSON text (echoed verbatim in the
    /// reply; anything that is not a short JSON value is echoed as `null`).
    pub fn receive(&mut self, reply_to: T, id: &str, json: &str) {
        let valid =
            id.len() <= MAX_ID_CHARS && serde_json::from_str::<serde::de::IgnoredAny>(id).is_ok();
        self.queue.push_back(Request {
            reply_to,
            id: if valid {
                id.to_owned()
            } else {
                "null".to_owned()
            },
            command: Command::parse(json),
        });
    }

    /// Whether anything waits (the caller keeps repainting).
    pub fn pending(&self) -> bool {
        !self.queue.is_empty() || !self.waiting.is_empty()
    }

    /// Applies the queued commands in order, up to one that needs the lab idle while it is
    /// busy (it waits for a later frame). `now` is the time in seconds.
    pub fn before_frame(&mut self, app: &mut LabApp, now: f64) {
        while let Some(request) = self.queue.front() {
            let ready = request
                .command
                .as_ref()
                .map_or(true, |c| !c.needs_idle() || !app.lab().busy());
            if !ready {
                break;
            }
            let Some(request) = self.queue.pop_front() else {
                break;
            };
            let outcome = request.command.and_then(|command| {
                let (actions, extra) = command.actions(app.lab(), self.debug_panic)?;
                for action in actions {
                    app.apply(action)?;
                }
                Ok(extra)
            });
            self.waiting.push(Waiting {
                reply_to: request.reply_to,
                id: request.id,
                outcome,
                since: now,
            });
        }
    }

    /// The replies that are ready after a frame (the lab's report is then up to date): all
    /// of them when the lab is idle, only refusals while it builds, and anything that waited
    /// longer than [`REPLY_TIMEOUT`]. Each is the reply's JSON text.
    pub fn after_frame(&mut self, app: &LabApp, now: f64) -> Vec<(T, String)> {
        let idle = !app.lab().busy();
        let (ready, waiting): (Vec<_>, Vec<_>) = std::mem::take(&mut self.waiting)
            .into_iter()
            .partition(|w| idle || w.outcome.is_err() || now - w.since > REPLY_TIMEOUT);
        self.waiting = waiting;
        ready
            .into_iter()
            .map(|w| {
                let outcome = if idle {
                    w.outcome
                } else {
                    w.outcome.and(Err(format!(
                        "the lab is still building after {REPLY_TIMEOUT} s; ask for a report later"
                    )))
                };
                (w.reply_to, reply(&w.id, outcome, app))
            })
            .collect()
    }
}

/// A reply's JSON text. The report is written as the page's `data-report` has it (numbers as
/// the shortest decimals of their `f32`s), so both read the same.
fn reply(id: &str, outcome: Result<Option<String>, String>, app: &LabApp) -> String {
    match outcome {
        Ok(extra) => {
            let scene = extra.map_or_else(String::new, |scene| format!(r#","scene":{scene}"#));
            format!(
                r#"{{"bvhlab":"reply","id":{id},"ok":true,"report":{}{scene}}}"#,
                app.report.json()
            )
        }
        Err(error) => format!(
            r#"{{"bvhlab":"reply","id":{id},"ok":false,"error":{}}}"#,
            serde_json::Value::String(error)
        ),
    }
}
