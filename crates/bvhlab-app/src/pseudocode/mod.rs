//! The pseudocode panel's data: each algorithm's text, and which line each observer event
//! happens at.
//!
//! The lab steps through a query's or a build's [`Event`]s and shows, beside the canvas, the
//! algorithm's pseudocode with the current line highlighted. The text uses the lecture's
//! names and notation (`bvNode`, `ray`, `t`, `currentMin`, `intersect`, `minDistance`), so
//! the slides and the lab read alike. The [`Variant::Full`] listings describe what the core
//! really runs, event for event; the [`Variant::Lecture`] listings are the slides' own
//! pseudocode, with only the lines the slides leave implicit added and marked.
//!
//! Files: `listing` (a line's step, and how a classifier reads an event), one file per family
//! of algorithms (`brute`, `bvh`, `lecture`, `plane` for k-d and BSP trees, `quadtree`,
//! `grid`), `build` for the builders, and `sentence` (each event in words).

mod brute;
mod build;
mod bvh;
mod grid;
mod lecture;
mod listing;
mod plane;
mod quadtree;
mod sentence;

use bvhlab::glam::Vec2;
use bvhlab::{Event, Vector};

pub use self::sentence::describe;
pub use crate::model::question::{Task, Variant};

use self::listing::{Classify, Listing};
use crate::model::structures::StructureKind;

/// One algorithm's pseudocode.
#[derive(Debug, PartialEq, Eq)]
pub struct Pseudocode {
    /// What it is, for the panel's heading.
    pub title: &'static str,
    /// The lines, indented with spaces, for a monospace font.
    pub lines: &'static [&'static str],
    /// A sentence or two: where it comes from (lecture section, paper) and what the slides
    /// leave out.
    pub note: &'static str,
}

/// An algorithm: its listing, and how it reads its own events.
struct Algorithm<V: Vector> {
    listing: &'static Listing,
    classify: Classify<V>,
}

/// The algorithm `kind` runs for `task`, in `variant`.
fn algorithm<V: Vector>(kind: StructureKind, task: Task, variant: Variant) -> Option<Algorithm<V>> {
    if task == Task::Build {
        return (variant == Variant::Full).then(|| build::algorithm(kind));
    }
    if variant != Variant::Full {
        return if kind.is_bvh() {
            lecture::algorithm(task, variant)
        } else {
            None
        };
    }
    match kind {
        StructureKind::BruteForce => brute::algorithm(task),
        StructureKind::SphereTree | StructureKind::AabbTree | StructureKind::ObbTree => {
            bvh::algorithm(task)
        }
        StructureKind::Bsp | StructureKind::KdTree => plane::algorithm(task),
        StructureKind::Quadtree => quadtree::algorithm(task),
        StructureKind::Grid => grid::algorithm(task),
    }
}

/// The pseudocode for a structure, task and variant; `None` when that variant does not exist
/// for it ([`Variant::Lecture`] and [`Variant::LecturePruned`] exist only for BVH first hit
/// and nearest; [`Variant::Full`] exists for every structure and task).
pub fn pseudocode(
    kind: StructureKind,
    task: Task,
    variant: Variant,
) -> Option<&'static Pseudocode> {
    algorithm::<Vec2>(kind, task, variant).map(|a| &a.listing.code)
}

/// The variants that exist for `kind` and `task` ([`Variant::Full`] first).
pub fn variants(kind: StructureKind, task: Task) -> Vec<Variant> {
    [Variant::Full, Variant::Lecture, Variant::LecturePruned]
        .into_iter()
        .filter(|&v| algorithm::<Vec2>(kind, task, v).is_some())
        .collect()
}

/// The line (an index into [`Pseudocode::lines`]) that `events[step]` happens at, read from
/// that event alone (it says what it is: a prune says where in the walk it happened, a bound
/// test names its node). `None` only for an event the algorithm does not emit (or a `step`
/// past the end, or a variant that does not exist).
pub fn line_of<V: Vector>(
    kind: StructureKind,
    task: Task,
    variant: Variant,
    events: &[Event<V>],
    step: usize,
) -> Option<usize> {
    let algorithm = algorithm(kind, task, variant)?;
    let event = events.get(step)?;
    algorithm.listing.line((algorithm.classify)(event)?)
}

#[cfg(test)]
mod tests;
