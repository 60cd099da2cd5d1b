//! How a listing ties its lines to the events that highlight them.
//!
//! Each line of a listing carries the [`Step`] of the algorithm it shows (or none), so the
//! text and the event mapping are written side by side and cannot drift apart: an
//! algorithm's classifier turns an event, on its own, into a step, and the highlighted line
//! is the listing's line for that step. Renumbering or rewording lines never breaks the
//! mapping.

use bvhlab::structure::PrimitiveResult;
use bvhlab::{Event, NodeId};

use super::Pseudocode;

/// The root of every tree (BVH, k-d tree, BSP tree, quadtree): node 0, the first one stored.
pub(super) const ROOT: NodeId = NodeId(0);

/// What a line of pseudocode does, as far as the observer's events can tell.
///
/// Within one listing every step but [`Step::Plain`] labels at most one line, so a step names
/// a line unambiguously.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Step {
    /// No event happens at this line (declarations, braces, loop heads, comments).
    Plain,
    /// The root's bound (or the whole region's box) is tested.
    TestRoot,
    /// The root was missed: the query is over before it began.
    MissRoot,
    /// A node or cell is entered: popped from the stack or queue, or (recursive versions)
    /// a call begins.
    Enter,
    /// A node taken from the stack or queue is skipped without being entered (`at Pop`).
    SkipPopped,
    /// A child's (or a cell's) bound is tested; in the recursive versions, the node's own.
    TestChild,
    /// A child (or cell) is skipped at its test: missed, no overlap, or no nearer.
    SkipChild,
    /// A child is skipped because the ray enters it beyond the best hit (or `tMax`).
    SkipBeyond,
    /// Children are put on the stack or queue.
    Queue,
    /// The ray crosses the node's splitting plane.
    Cross,
    /// A primitive already tested in another cell is skipped (mailboxing).
    Mailbox,
    /// A primitive is tested exactly.
    TestPrim,
    /// The best answer so far improves.
    NewBest,
    /// A hit lies beyond the current region, so it is not final yet.
    HitBeyond,
    /// The answer is final: everything still waiting is skipped (`at Stop`).
    Stop,
    /// The recursive call into the left child.
    CallLeft,
    /// The recursive call into the right child.
    CallRight,
    /// A build creates a node.
    BuildNode,
    /// A build splits a node.
    BuildSplit,
    /// A build makes a node a leaf (for a grid: a cell's list is complete).
    BuildLeaf,
}

/// One algorithm's pseudocode, each line with its [`Step`].
#[derive(Debug)]
pub(super) struct Listing {
    /// What the panel shows.
    pub code: Pseudocode,
    /// `steps[i]` is what `code.lines[i]` does.
    pub steps: &'static [Step],
}

impl Listing {
    /// The line that shows `step`, if the listing has one.
    pub fn line(&self, step: Step) -> Option<usize> {
        if step == Step::Plain {
            return None;
        }
        self.steps.iter().position(|&s| s == step)
    }
}

/// Builds a [`Listing`] from `(step line)` pairs, `_` marking a line no event maps to:
///
/// ```text
/// listing!("title", "note", [
///     _     "intersect(root, ray)",
///     Enter "    (bvNode, tEnter) = stack.pop()",
/// ])
/// ```
macro_rules! listing {
    (@step _) => { Step::Plain };
    (@step $step:ident) => { Step::$step };
    ($title:expr, $note:expr, [$($step:tt $line:literal),* $(,)?]) => {
        Listing {
            code: Pseudocode {
                title: $title,
                lines: &[$($line),*],
                note: $note,
            },
            steps: &[$(listing!(@step $step)),*],
        }
    };
}
pub(super) use listing;

/// An algorithm's reading of its own events: the step `event` is, from the event alone;
/// `None` for an event the algorithm does not emit.
///
/// Events carry what tells their lines apart (a prune says where in the walk it happened, a
/// bound test names its node, so the root's is told from a child's), so a classifier never
/// looks at the events around one.
pub(super) type Classify<V> = fn(&Event<V>) -> Option<Step>;

/// The step of a primitive test: the exact test, or the mailbox's refusal.
pub(super) fn primitive_step(result: PrimitiveResult) -> Step {
    if result == PrimitiveResult::AlreadyTested {
        Step::Mailbox
    } else {
        Step::TestPrim
    }
}
