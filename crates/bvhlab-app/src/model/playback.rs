//! The playback transport: where playback is in a recording (a step, or live at its end),
//! whether it plays, and how fast. What the algorithm's state is at that step is
//! [`Snapshot`](super::snapshot::Snapshot)'s job.
//!
//! # Where playback stands after a new question
//!
//! One rule, for both halves and every structure and task: **a new question shows its
//! answer.** A new question is an action that changes what is recorded
//! ([`Action::asks_new_question`](super::Action::asks_new_question)): the scene (a shape
//! added, moved or deleted, the scene cleared, an undo or redo, a preset), the mesh opened,
//! the structure or the one compared with, the task, the variant, k, the radius, the ray or
//! the point. After it, playback stands at the end of the new recording, live (it follows the
//! end while the ray is dragged or a 3D build finishes), with the answer drawn, and it stops
//! if it was playing ([`Playback::new_question`]). `Lab::apply` applies the rule, in one place.
//!
//! Stepping through the new question is one key away: Home goes to step 0, and Play starts
//! from the beginning when at the end. Only playback's own actions move the step; a saved
//! state, and the page's address (`step=`, applied after its question), put it where they
//! say.

/// The transport: where playback is and whether it runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Playback {
    /// How many events are shown (0 to the recording's length).
    pub step: usize,
    /// Stay at the end when the recording changes (live mode while dragging).
    pub at_end: bool,
    /// Whether it advances by itself.
    pub playing: bool,
    /// Events per second while playing.
    pub speed: f32,
    /// Fractional events accumulated between frames.
    carry: f64,
}

impl Default for Playback {
    fn default() -> Self {
        Self {
            step: 0,
            at_end: true,
            playing: false,
            speed: 4.0,
            carry: 0.0,
        }
    }
}

impl Playback {
    /// Keeps the step inside a (new) recording of `len` events: at the end in live mode,
    /// else where it was, as far as the new recording goes.
    pub fn fit(&mut self, len: usize) {
        if self.at_end {
            self.step = len;
        } else {
            self.step = self.step.min(len);
        }
    }

    /// A new question: to the end, live, and not playing (see the module's rule).
    pub fn new_question(&mut self) {
        self.at_end = true;
        self.playing = false;
        self.carry = 0.0;
    }

    /// Goes to `step` (clamped), leaving live mode unless it is the end.
    pub fn go(&mut self, step: usize, len: usize) {
        self.step = step.min(len);
        self.at_end = self.step == len;
        if self.at_end {
            self.playing = false;
        }
    }

    /// Starts playing; from the start when at the end.
    pub fn play(&mut self, len: usize) {
        if self.step >= len {
            self.step = 0;
        }
        self.at_end = false;
        self.playing = true;
        self.carry = 0.0;
    }

    /// The step shown for a recording of `len` events (the end in live mode).
    pub fn shown(&self, len: usize) -> usize {
        if self.at_end { len } else { self.step.min(len) }
    }

    /// Moves `delta` steps from the one shown, and stops playing.
    pub fn step_by(&mut self, delta: isize, len: usize) {
        self.playing = false;
        self.go(self.shown(len).saturating_add_signed(delta), len);
    }

    /// Play or pause.
    pub fn toggle(&mut self, len: usize) {
        if self.playing {
            self.playing = false;
        } else {
            self.play(len);
        }
    }

    /// Advances a playing transport by `seconds`; true when the step changed.
    pub fn advance(&mut self, seconds: f64, len: usize) -> bool {
        if !self.playing {
            return false;
        }
        self.carry += seconds.max(0.0) * f64::from(self.speed.max(0.0));
        let whole = self.carry.floor();
        if whole < 1.0 {
            return false;
        }
        self.carry -= whole;
        let before = self.step;
        let next = self.step.saturating_add(whole as usize);
        self.go(next, len);
        self.step != before
    }
}
