//! [`Lab::apply`]: every change of the lab, one arm per action, with the rules that go with
//! it. The halves' own rules are in [`Lab2d`](super::Lab2d)'s and
//! [`Lab3d`](super::Lab3d)'s `apply`; the structures, question and playback, which both
//! halves have, are changed here for the half shown.

use bvhlab::structure::bvh::NodeVolume;
use bvhlab::{Aabb, Bvh, Obb, SpatialIndex, Sphere};

use super::action::{Action, Action2d, Action3d, HalfAction, PlaybackAction};
use super::dimension::{Dimension, LabPrimitive};
use super::half::{Half, MAX_K};
use super::lane::{BuildBudget, Lane};
use super::question::Variant;
use super::{Lab, Note};
use crate::pseudocode::variants;

impl Lab {
    /// Carries out `action` with the rules that go with it, then brings what is derived from
    /// the state (structures, recordings, the snapshot at the playback step) up to date.
    ///
    /// # Errors
    /// Why the action cannot apply, in a sentence for the status line; the lab is then
    /// unchanged.
    pub fn apply(&mut self, action: Action) -> Result<(), String> {
        // The half whose question the action changes, if it asks a new one.
        let asks = action.asks_new_question().then_some(match &action {
            Action::Three(_) => Dimension::Three,
            Action::Half(_) => self.dimension,
            _ => Dimension::Two,
        });
        let note = match action {
            Action::Show(dimension) => {
                if dimension == self.dimension {
                    Note::Keep
                } else {
                    self.dimension = dimension;
                    Note::Clear
                }
            }
            Action::SetMessage(message) => {
                self.message = message;
                Note::Keep
            }
            Action::Two(action) => {
                let shows = matches!(action, Action2d::LoadPreset(_));
                let note = self.two.apply(action)?;
                if shows {
                    self.dimension = Dimension::Two;
                }
                note
            }
            Action::Three(action) => {
                let shows = matches!(action, Action3d::OpenMesh(_));
                let note = self.three.apply(action)?;
                if shows {
                    self.dimension = Dimension::Three;
                }
                note
            }
            Action::Half(action) => self.apply_half(action)?,
            Action::Lesson(action) => self.apply_lesson(action)?,
            Action::Predict(action) => self.apply_predict(action)?,
            Action::Restore(state) => {
                let state = *state;
                state.two.write(&mut self.two);
                if let Some(three) = state.three {
                    three.write(&mut self.three);
                }
                self.dimension = state.shown;
                // The lesson comes back as it was (its step's state is the one restored),
                // and Predict with its scores (a file from before Predict leaves it as is).
                self.lesson = state.lesson;
                if let Some(predict) = state.predict {
                    self.predict = predict;
                }
                state.note.map_or(Note::Keep, Note::Say)
            }
            Action::Tick { seconds, build_ms } => {
                if !self.tick(seconds, build_ms) {
                    // A 3D structure can be made and built within one tick, which counts as
                    // no change; its answer may still reach the lesson's goal.
                    self.check_goal();
                    return Ok(());
                }
                Note::Keep
            }
        };
        // A new question shows its answer (the rule is in `super::playback`); with Predict
        // on, it starts from the beginning, to be predicted.
        let predicting = self.predict.on;
        let playback = match asks {
            Some(Dimension::Two) => Some(&mut self.two.half.playback),
            Some(Dimension::Three) => Some(&mut self.three.half.playback),
            None => None,
        };
        if let Some(playback) = playback {
            playback.new_question();
            if predicting {
                playback.at_end = false;
                playback.step = 0;
            }
        }
        match note {
            Note::Keep => {}
            Note::Clear => self.message = None,
            Note::Say(m) => self.message = Some(m),
        }
        self.changes += 1;
        self.refresh();
        self.check_goal();
        Ok(())
    }

    /// Brings what is derived from both halves up to date (3D builds advance only on
    /// [`Action::Tick`]).
    pub(super) fn refresh(&mut self) {
        self.two.refresh();
        self.three.refresh(BuildBudget::None);
    }

    /// A frame: playback advances, and the 3D half (when shown) loads and builds. Whether
    /// anything that is saved changed (the playback step, the mesh).
    fn tick(&mut self, seconds: f64, build_ms: f64) -> bool {
        match self.dimension {
            Dimension::Two => {
                // The drifting preset's shapes move, and the lanes refit or rebuild. Not
                // counted as a change: the motion is not saved frame by frame.
                if self.two.animate(seconds) {
                    self.two.refresh();
                }
                let len = self.two.half.steps();
                let moved = self.two.half.playback.advance(seconds, len);
                if moved {
                    self.two.refresh();
                }
                moved
            }
            Dimension::Three => {
                let loading = self.three.pending.is_some();
                let building = |lab: &Self| lab.three.half.lanes().any(|l| l.job.is_some());
                let was_building = building(self);
                self.three.tick(seconds, build_ms);
                let len = self.three.half.steps();
                let moved = self.three.half.playback.advance(seconds, len);
                if moved {
                    self.three.refresh(BuildBudget::None);
                }
                // A finished build changes no saved state but is news: count it too, so that
                // a reply waiting for it goes out and a lesson's goal that its answer reaches
                // is checked (a build that ends in this tick counts: it was building).
                loading || moved || was_building || building(self)
            }
        }
    }

    /// A change of the half shown's structures, question or playback.
    fn apply_half(&mut self, action: HalfAction) -> Result<Note, String> {
        if let HalfAction::Playback(p) = action {
            let forward = matches!(p, PlaybackAction::StepBy(by) if by > 0);
            let plays = matches!(p, PlaybackAction::Play(true))
                || (p == PlaybackAction::Toggle && !self.playing());
            if let Some(why) = self.predict_refuses(forward, plays) {
                return Err(why);
            }
        }
        match self.dimension {
            Dimension::Two => {
                if matches!(action, HalfAction::Playback(_)) {
                    // Playback counts the steps of the recording as it is now.
                    self.two.refresh();
                }
                if matches!(action, HalfAction::SetCompare(_)) {
                    // The canvas halves (or doubles): frame the scene in the new width.
                    self.two.fit_pending = true;
                }
                apply_to_half(&mut self.two.half, action)
            }
            Dimension::Three => {
                if matches!(action, HalfAction::Playback(_)) {
                    self.three.refresh(BuildBudget::None);
                }
                apply_to_half(&mut self.three.half, action)
            }
        }
    }
}

/// A change of `half`'s structures, question or playback.
fn apply_to_half<P: LabPrimitive>(half: &mut Half<P>, action: HalfAction) -> Result<Note, String>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
    Bvh<Sphere<P::Point>, P>: SpatialIndex,
    Bvh<Aabb<P::Point>, P>: SpatialIndex,
    Bvh<Obb<P::Point>, P>: SpatialIndex,
{
    match action {
        HalfAction::SetStructure(settings) => {
            settings.check("the structure")?;
            half.lane.settings = settings;
            if !variants(settings.kind, half.task).contains(&half.variant) {
                half.variant = Variant::Full;
            }
        }
        HalfAction::SetCompare(settings) => match settings {
            Some(settings) => {
                settings.check("the comparison structure")?;
                match &mut half.compare {
                    Some(lane) => lane.settings = settings,
                    None => half.compare = Some(Lane::new(settings)),
                }
            }
            None => half.compare = None,
        },
        HalfAction::SetUpdateMode { lane, mode } => half.set_update_mode(lane, mode)?,
        HalfAction::RebuildNow => half.rebuild_now(),
        HalfAction::SetTask(task) => half.set_task(task),
        HalfAction::SetVariant(variant) => {
            // The panel offers only the task's versions: one of them is always the one shown
            // selected and run.
            let offered = variants(half.lane.settings.kind, half.task);
            if !offered.contains(&variant) {
                let name = |v: Variant| match v {
                    Variant::Full => "the full version",
                    Variant::Lecture => "the slides' version",
                    Variant::LecturePruned => "the slides' version with pruning",
                };
                let has: Vec<&str> = offered.into_iter().map(name).collect();
                return Err(format!(
                    "this task on this structure has no {}; it has {}",
                    name(variant),
                    has.join(" and ")
                ));
            }
            half.variant = variant;
        }
        HalfAction::SetK(k) => {
            if !(1..=MAX_K).contains(&k) {
                return Err(format!("k is {k}; it must be 1 to {MAX_K}"));
            }
            half.k = k;
        }
        HalfAction::SetRadius(radius) => {
            if !(radius.is_finite() && radius >= 0.0) {
                return Err(format!(
                    "the radius is {radius}; it must be a finite number, at least 0"
                ));
            }
            half.radius = radius;
        }
        HalfAction::Playback(action) => {
            let len = half.steps();
            let p = &mut half.playback;
            match action {
                PlaybackAction::GoTo(step) => {
                    p.playing = false;
                    p.go(step, len);
                }
                PlaybackAction::End => p.go(len, len),
                PlaybackAction::Hold(step) => {
                    p.playing = false;
                    p.step = step;
                    p.at_end = false;
                    p.fit(len.max(step));
                }
                PlaybackAction::StepBy(by) => p.step_by(by, len),
                PlaybackAction::Play(on) => {
                    if p.playing != on {
                        p.toggle(len);
                    }
                }
                PlaybackAction::Toggle => p.toggle(len),
                PlaybackAction::SetSpeed(speed) => {
                    if !(speed.is_finite() && speed > 0.0) {
                        return Err(format!("the speed is {speed}; it must be more than 0"));
                    }
                    p.speed = speed;
                }
            }
        }
    }
    Ok(Note::Keep)
}
