//! Placeholder until the pseudocode module lands: the task and variant enums the playback uses.

use bvhlab::glam::Vec2;

use crate::structures::StructureKind;

/// What is being stepped through.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Task {
    /// Ray: first hit.
    FirstHit,
    /// Ray: any hit.
    AnyHit,
    /// Ray: all hits.
    AllHits,
    /// Point: k nearest.
    Nearest,
    /// Point: everything within a radius.
    Range,
    /// The structure's construction.
    Build,
}

/// Which version of the algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// What the core runs.
    Full,
    /// The slides' pseudocode.
    Lecture,
    /// The slides' minDistance plus pruning.
    LecturePruned,
}

/// One algorithm's pseudocode.
pub struct Pseudocode {
    /// Title.
    pub title: &'static str,
    /// Lines.
    pub lines: &'static [&'static str],
    /// Note.
    pub note: &'static str,
}

static EMPTY: Pseudocode = Pseudocode {
    title: "",
    lines: &[],
    note: "",
};

/// The pseudocode.
pub fn pseudocode(
    _kind: StructureKind,
    _task: Task,
    _variant: Variant,
) -> Option<&'static Pseudocode> {
    Some(&EMPTY)
}

/// The variants.
pub fn variants(kind: StructureKind, task: Task) -> Vec<Variant> {
    if kind.is_bvh() && task == Task::FirstHit {
        vec![Variant::Full, Variant::Lecture]
    } else if kind.is_bvh() && task == Task::Nearest {
        vec![Variant::Full, Variant::Lecture, Variant::LecturePruned]
    } else {
        vec![Variant::Full]
    }
}

/// The line.
pub fn line_of(
    _kind: StructureKind,
    _task: Task,
    _variant: Variant,
    _events: &[bvhlab::Event<Vec2>],
    _step: usize,
) -> Option<usize> {
    None
}
