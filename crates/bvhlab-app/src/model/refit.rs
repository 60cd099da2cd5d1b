//! Refit against rebuild: what a lane does when its primitives move.
//!
//! A BVH can follow moving primitives without being rebuilt: a refit keeps every node's
//! children and primitives and fits the volumes again, bottom-up, in time linear in the nodes
//! (Wald, Boulos and Shirley 2007; the core's [`Bvh::refit`](bvhlab::Bvh::refit)). The tree
//! keeps its shape while the primitives drift from where the build grouped them, so its
//! boxes grow, overlap, and its SAH cost rises; a rebuild groups them again. The lane's
//! [`UpdateMode`] chooses, and its [`EditLog`] keeps what each update cost and left behind,
//! for the plot of SAH cost over the edits.
//!
//! The other structures are not refitted: a grid, a quadtree, a k-d or BSP tree partition
//! space, so a moved primitive changes which cells hold it, and they update by rebuilding
//! ([`refit_refused`]; the core's `structure::update` gives the costs).

use std::collections::VecDeque;

use bvhlab::structure::bvh::{NodeVolume, RefitError, RefitReport};
use bvhlab::{Aabb, Obb, Primitive, Sphere};

use super::structures::{Built, StructureKind};

/// What a lane does with its structure when the primitives move.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum UpdateMode {
    /// Build it again: the best tree for where the primitives are now.
    #[default]
    Rebuild,
    /// Refit a BVH in place: the same tree, its volumes fitted to the moved primitives (the
    /// other structures rebuild).
    Refit,
}

impl UpdateMode {
    /// Both, in the panel's order.
    pub const ALL: [Self; 2] = [Self::Rebuild, Self::Refit];

    /// The panel's word for it.
    pub fn label(self) -> &'static str {
        match self {
            Self::Rebuild => "rebuild",
            Self::Refit => "refit",
        }
    }
}

/// How the structure was brought up to date.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EditKind {
    /// Refitted in place.
    Refit,
    /// Built anew.
    Rebuild,
}

/// One update of a lane's structure: how, what it cost and the SAH cost it left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EditEntry {
    /// Refitted or rebuilt.
    pub how: EditKind,
    /// The structure's SAH cost afterwards (`None`: undefined, as for a flat scene, or a
    /// structure without one).
    pub sah_cost: Option<f32>,
    /// Milliseconds the refit or the build took (the core's work only: not the drawing's
    /// outline or the baseline).
    pub millis: f64,
}

/// How many updates an [`EditLog`] keeps.
pub const EDIT_LOG_LEN: usize = 240;

/// The last [`EDIT_LOG_LEN`] updates of a lane's structure, oldest first.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EditLog {
    entries: VecDeque<EditEntry>,
    /// How many updates were ever logged (the first entry kept is update
    /// `total - entries.len()`).
    total: u64,
}

impl EditLog {
    /// Logs an update, forgetting the oldest past [`EDIT_LOG_LEN`].
    pub fn push(&mut self, entry: EditEntry) {
        if self.entries.len() == EDIT_LOG_LEN {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
        self.total += 1;
    }

    /// The updates kept, oldest first.
    pub fn entries(&self) -> impl DoubleEndedIterator<Item = &EditEntry> + ExactSizeIterator {
        self.entries.iter()
    }

    /// The last update.
    pub fn last(&self) -> Option<&EditEntry> {
        self.entries.back()
    }

    /// The last update of this kind.
    pub fn last_of(&self, how: EditKind) -> Option<&EditEntry> {
        self.entries.iter().rev().find(|e| e.how == how)
    }

    /// How many updates are kept.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// How many updates were ever logged.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// How many of the updates kept were of this kind.
    pub fn count(&self, how: EditKind) -> usize {
        self.entries.iter().filter(|e| e.how == how).count()
    }

    /// The mean time of the kept updates of this kind, in milliseconds.
    pub fn mean_millis(&self, how: EditKind) -> Option<f64> {
        let (n, sum) = self
            .entries
            .iter()
            .filter(|e| e.how == how)
            .fold((0u32, 0.0), |(n, sum), e| (n + 1, sum + e.millis));
        (n > 0).then(|| sum / f64::from(n))
    }
}

/// Why a structure of `kind` is not refitted when its primitives move, in the lecture's
/// words; `None` for the BVHs, which are.
pub fn refit_refused(kind: StructureKind) -> Option<&'static str> {
    match kind {
        StructureKind::SphereTree | StructureKind::AabbTree | StructureKind::ObbTree => None,
        StructureKind::BruteForce => {
            Some("brute force has no structure to refit: it tests every primitive")
        }
        StructureKind::Grid => {
            Some("a grid updates by rebuilding its cells: a moved shape lands in other cells")
        }
        StructureKind::Quadtree => Some(
            "a quadtree updates by rebuilding: its cells split space, and a moved shape lands in other cells",
        ),
        StructureKind::KdTree => Some(
            "a k-d tree updates by rebuilding: its planes split space, and a moved shape crosses them",
        ),
        StructureKind::Bsp => {
            Some("a BSP tree updates by rebuilding: its planes are the shapes' own, and they moved")
        }
    }
}

impl<P: Primitive> Built<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    /// Refits a BVH to `prims` (its primitives, moved); `None` for the other structures.
    ///
    /// # Errors
    /// The core's [`RefitError`]: the count changed, or a primitive became (or stopped
    /// being) non-finite; the tree is then unchanged and must be rebuilt.
    pub fn refit(&mut self, prims: &[P]) -> Option<Result<RefitReport, RefitError>> {
        match self {
            Self::SphereTree(t) => Some(t.refit(prims)),
            Self::AabbTree(t) => Some(t.refit(prims)),
            Self::ObbTree(t) => Some(t.refit(prims)),
            _ => None,
        }
    }

    /// A BVH's SAH cost when it was built (`None` for the other structures, or undefined).
    pub fn build_sah_cost(&self) -> Option<f32> {
        match self {
            Self::SphereTree(t) => t.refit_report().build_sah_cost,
            Self::AabbTree(t) => t.refit_report().build_sah_cost,
            Self::ObbTree(t) => t.refit_report().build_sah_cost,
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_log_keeps_the_last_entries() {
        let mut log = EditLog::default();
        for i in 0..EDIT_LOG_LEN + 10 {
            log.push(EditEntry {
                how: if i % 2 == 0 {
                    EditKind::Refit
                } else {
                    EditKind::Rebuild
                },
                sah_cost: Some(i as f32),
                millis: 1.0,
            });
        }
        assert_eq!(log.len(), EDIT_LOG_LEN);
        assert_eq!(log.total(), (EDIT_LOG_LEN + 10) as u64);
        assert_eq!(log.entries().next().and_then(|e| e.sah_cost), Some(10.0));
        assert_eq!(log.mean_millis(EditKind::Refit), Some(1.0));
    }

    #[test]
    fn only_bvhs_are_refitted() {
        for kind in StructureKind::ALL {
            assert_eq!(refit_refused(kind).is_none(), kind.is_bvh(), "{kind:?}");
        }
    }
}
