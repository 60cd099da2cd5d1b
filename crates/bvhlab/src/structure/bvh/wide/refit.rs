//! Refitting a [`Bvh4`] after its primitives moved: every lane's box fitted again,
//! bottom-up, the wide topology kept (Wald, Boulos and Shirley 2007, as the binary tree's
//! `refit.rs`).

use super::layout::{Bvh4, Bvh4Node, WIDTH};
use super::leaves::PADDING;
use crate::Primitive;
use crate::structure::bvh::RefitError;
use crate::structure::bvh::refit::{RefitReport, check_same_primitives};
use crate::structure::stats::sah_cost;
use crate::volume::{Aabb, BoundingVolume};

impl<P: Primitive> Bvh4<P> {
    /// Refits the tree to `prims`, the primitives it was built over after they moved (the
    /// same count, in input order): every lane keeps its child, a leaf lane's box is fitted
    /// to its primitives as the build fits a leaf's, an inner lane's box is the union of its
    /// child node's lanes, children before parents (a node's children have higher indices),
    /// in time linear in the nodes. First hits and closest points then answer as brute force
    /// on the moved primitives, and [`validate`](Self::validate) holds.
    ///
    /// # Errors
    /// [`RefitError`] when the count differs or a primitive became (or stopped being)
    /// non-finite; the tree is then left unchanged.
    pub fn refit(&mut self, prims: &[P]) -> Result<RefitReport, RefitError> {
        let mut indexed = vec![false; self.input_len];
        for (_, id) in self.indexed_slots() {
            indexed[id as usize] = true;
        }
        check_same_primitives(self.input_len, |i| indexed[i], prims)?;
        debug_assert!(
            prims
                .iter()
                .enumerate()
                .all(|(i, p)| indexed[i] == p.has_finite_coordinates())
        );
        for slot in 0..self.leaf_ids.len() {
            let id = self.leaf_ids[slot];
            if id != PADDING {
                self.leaf_prims.set(slot, &prims[id as usize]);
            }
        }
        for i in (0..self.nodes.len()).rev() {
            let mut node = self.nodes[i];
            for lane in 0..WIDTH {
                if node.count[lane] > 0 {
                    let (start, count) = (node.child[lane], node.count[lane]);
                    node.set_lane(lane, &self.leaf_box(start as usize, count as usize));
                } else if node.is_used(lane) {
                    let child = &self.nodes[node.child[lane] as usize];
                    node.set_lane(lane, &node_box::<P>(child));
                }
            }
            self.nodes[i] = node;
        }
        Ok(self.refit_report())
    }

    /// The SAH cost of the wide tree: its root box (the union of the root's lanes), then
    /// every used lane, inner lanes at cost 1 and leaf lanes at their primitive count, over
    /// the root's area ([`Stats::sah_cost`](crate::structure::Stats::sah_cost) for 4-wide
    /// nodes). Lower than the binary tree's, which has more inner nodes.
    pub fn sah_cost(&self) -> Option<f32> {
        let root = self.nodes.first()?;
        let lanes = self.nodes.iter().flat_map(|node| {
            (0..WIDTH).filter(|&lane| node.is_used(lane)).map(|lane| {
                let leaf = node.count[lane] > 0;
                (
                    node.lane_box::<P::Point>(lane),
                    leaf.then_some(node.count[lane] as usize),
                )
            })
        });
        sah_cost(std::iter::once((node_box::<P>(root), None)).chain(lanes))
    }

    /// The SAH cost the tree had when it was built (before any refit).
    pub fn build_sah_cost(&self) -> Option<f32> {
        self.build_sah_cost
    }

    /// The SAH cost now and at build time.
    pub fn refit_report(&self) -> RefitReport {
        RefitReport {
            sah_cost: self.sah_cost(),
            build_sah_cost: self.build_sah_cost,
        }
    }

    /// Whether a rebuild pays: the SAH cost has grown past `max_growth` times what it was
    /// when the tree was built ([`RefitReport::needs_rebuild`]).
    pub fn needs_rebuild(&self, max_growth: f32) -> bool {
        self.refit_report().needs_rebuild(max_growth)
    }

    /// The tree with its build-time SAH cost recorded (the constructors' last step).
    pub(super) fn with_build_cost(mut self) -> Self {
        self.build_sah_cost = self.sah_cost();
        self
    }
}

/// The union of a node's used lanes' boxes: the box its parent's lane holds.
pub(super) fn node_box<P: Primitive>(node: &Bvh4Node) -> Aabb<P::Point> {
    (0..WIDTH)
        .filter(|&lane| node.is_used(lane))
        .fold(Aabb::EMPTY, |b, lane| b.merge(&node.lane_box(lane)))
}
