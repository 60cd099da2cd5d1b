//! The question asked before a step of playback: what happens next?
//!
//! A question is read from the recording itself: the event about to be shown (and, where the
//! answer takes more than one event, those after it) and the state before it ([`Snapshot`]:
//! the nodes waiting, the best so far, the cells entered). Only steps where something is
//! decided get a question: which node is taken next when two or more wait (`walk.rs`);
//! whether the ray meets a volume, and whether a node is kept or pruned against the best so
//! far; which child is visited first; whether the ray hits a primitive, or a primitive
//! becomes the nearest (`leaf.rs`); which cell the ray enters next (`cell.rs`); whether a node
//! being built becomes a leaf, or across which axis it is split (`build.rs`). The other steps
//! (entering a node just chosen, a new best the question before gave away) are shown without
//! one.
//!
//! Every answer is read from the events, never from a second computation: a question whose
//! answer the recording does not settle (a cell two axes away, a node taken that is not the
//! frontier's first) is not asked.

use bvhlab::structure::{NodeId, PruneAt};
use bvhlab::{Event, Vector};

use super::{build, cell, leaf, walk};
use crate::model::recording::Recording;
use crate::model::snapshot::Snapshot;
use crate::model::structures::StructureKind;

/// An answer a student can give.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Choice {
    /// Yes.
    Yes,
    /// No.
    No,
    /// This node (or grid cell).
    Node(u32),
    /// The node is kept (queued or entered).
    Kept,
    /// The ray misses the node's volume: it is pruned.
    Missed,
    /// The ray meets the volume only after the best hit so far: it is pruned.
    Beyond,
    /// The volume is no nearer than the best distance so far: it is pruned.
    NoNearer,
    /// The next cell along `axis`, one up (`true`) or one down.
    Cell {
        /// 0 for x, 1 for y, 2 for z.
        axis: u8,
        /// Towards larger coordinates.
        up: bool,
    },
    /// The node becomes a leaf.
    Leaf,
    /// The node is split across this axis (its plane's normal).
    SplitAcross(u8),
    /// The node is split (by a plane that is not axis-aligned, or into four or eight).
    Split,
}

/// What decides a question, lit in the views while it is asked (the canvas or 3D view and
/// the tree diagram): a question is asked only when the picture shows what decides it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct About {
    /// The nodes (or cells) it names or chooses among.
    pub nodes: Vec<NodeId>,
    /// The primitives it names.
    pub prims: Vec<u32>,
}

impl About {
    /// About these nodes.
    pub fn nodes(nodes: impl IntoIterator<Item = NodeId>) -> Self {
        Self {
            nodes: nodes.into_iter().collect(),
            prims: Vec::new(),
        }
    }

    /// About this primitive.
    pub fn prim(prim: u32) -> Self {
        Self {
            nodes: Vec::new(),
            prims: vec![prim],
        }
    }

    /// Whether it names nothing.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty() && self.prims.is_empty()
    }
}

/// What is asked before a step.
#[derive(Clone, Debug, PartialEq)]
pub struct PredictQuestion {
    /// The playback step it is asked at: before event `step` is shown.
    pub step: usize,
    /// The question, in a sentence.
    pub prompt: String,
    /// The answers offered, each with its label, in a fixed order that gives nothing away.
    pub choices: Vec<(Choice, String)>,
    /// The right one.
    pub answer: Choice,
    /// How many events answering shows (the step and what settles it).
    pub reveal: usize,
    /// Why the answer is right, in the event's own numbers.
    pub why: String,
    /// A hint after a wrong answer: where to look, not the answer.
    pub hint: String,
    /// What decides it, lit in the views while it is asked.
    pub about: About,
}

impl PredictQuestion {
    /// The label of `choice`, if offered.
    pub fn label(&self, choice: Choice) -> Option<&str> {
        self.choices
            .iter()
            .find(|(c, _)| *c == choice)
            .map(|(_, l)| l.as_str())
    }
}

/// What a question is read from: the recording, the state before the step, and the
/// structure's kind.
pub(super) struct At<'a, V: Vector> {
    /// The recording.
    pub recording: &'a Recording<V>,
    /// The state before the step.
    pub snapshot: &'a Snapshot<V>,
    /// The structure.
    pub kind: StructureKind,
}

impl<V: Vector> At<'_, V> {
    /// The step asked about (the event about to be shown).
    pub fn step(&self) -> usize {
        self.snapshot.step
    }

    /// The event after the step's, if any.
    pub fn next(&self) -> Option<Event<V>> {
        self.recording.events.get(self.step() + 1).copied()
    }

    /// Whether the event after the step's prunes `node`.
    pub fn prune_follows(&self, node: NodeId) -> bool {
        matches!(self.next(), Some(Event::Prune { node: n, .. }) if n == node)
    }

    /// The k-th best distance so far, once k are found: the nearest query's bound.
    pub fn kth_best(&self) -> Option<f32> {
        let k = self.recording.question.k.max(1);
        self.snapshot.best.get(k - 1).map(|b| b.1)
    }

    /// A question at this step about what `about` names.
    #[allow(clippy::too_many_arguments)] // a question's parts, each named by its field
    pub fn ask(
        &self,
        prompt: String,
        choices: Vec<(Choice, String)>,
        answer: Choice,
        reveal: usize,
        why: String,
        hint: &str,
        about: About,
    ) -> PredictQuestion {
        PredictQuestion {
            step: self.step(),
            prompt,
            choices,
            answer,
            reveal,
            why,
            hint: hint.to_owned(),
            about,
        }
    }
}

/// Two numbers as the questions show them (three decimals): a comparison is asked only when
/// they differ as shown, so that the numbers on screen decide it.
pub(super) fn shown_apart(a: f32, b: f32) -> bool {
    format!("{a:.3}") != format!("{b:.3}")
}

/// How far apart, as a share of the distance along the ray, two points of a ray must be for
/// the picture to tell which comes first (about 4 points in 400): nearer than this, a
/// question that hangs on their order and cannot show both numbers is not asked.
pub const DISTINCT_ALONG_RAY: f32 = 0.01;

/// The names of the axes.
pub(super) const AXES: [&str; 3] = ["x", "y", "z"];

/// The question before event `snapshot.step` of `recording` (over a structure of `kind`), or
/// `None` where nothing is decided or the recording is at its end.
pub fn question_at<V: Vector>(
    recording: &Recording<V>,
    snapshot: &Snapshot<V>,
    kind: StructureKind,
) -> Option<PredictQuestion> {
    let at = At {
        recording,
        snapshot,
        kind,
    };
    match *recording.events.get(snapshot.step)? {
        Event::EnterNode { node, .. }
        | Event::Prune {
            node,
            at: PruneAt::Pop,
            ..
        } => walk::next_node(&at, node),
        Event::RayBoundTest { node, interval } => Some(walk::ray_bound(&at, node, interval)),
        Event::DistanceBoundTest { node, distance } => walk::distance_bound(&at, node, distance),
        Event::ChildQueued {
            parent,
            child,
            rank: 0,
            ..
        } => walk::child_order(&at, parent, child),
        Event::PrimitiveTest { prim, result } => leaf::primitive(&at, prim, result),
        Event::CellEnter { coords, .. } => cell::next_cell(&at, coords),
        Event::BuildSplit { node, .. } | Event::BuildLeaf { node, .. } => {
            build::build_step(&at, node)
        }
        _ => None,
    }
}

/// The word for a node's volume in `kind`.
pub(super) fn volume_word(kind: StructureKind) -> &'static str {
    match kind {
        StructureKind::SphereTree => "circle",
        StructureKind::ObbTree => "oriented box",
        StructureKind::Quadtree | StructureKind::Grid => "cell",
        StructureKind::KdTree | StructureKind::Bsp => "region",
        _ => "box",
    }
}

/// Yes and no, in that order.
pub(super) fn yes_no() -> Vec<(Choice, String)> {
    vec![
        (Choice::Yes, "yes".to_owned()),
        (Choice::No, "no".to_owned()),
    ]
}

/// Choices sorted by node number, so that their order gives nothing away.
pub(super) fn by_node(mut choices: Vec<(Choice, String)>) -> Vec<(Choice, String)> {
    choices.sort_by_key(|(c, _)| match c {
        Choice::Node(n) => *n,
        _ => 0,
    });
    choices
}
