//! The numbers that compare one tree with another: size, depth, leaf sizes, memory, SAH cost.

use crate::Primitive;
use crate::structure::Stats;
use crate::structure::bvh::Bvh;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::stats::sah_cost;

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// The depth of every node (the root is 0), in node order: for drawing the tree one
    /// level at a time.
    pub fn depths(&self) -> Vec<u32> {
        let mut depths = vec![0u32; self.nodes.len()];
        // Children come after their parent in the depth-first array.
        for (i, node) in self.nodes.iter().enumerate() {
            if !node.is_leaf() {
                let child_depth = depths[i] + 1;
                for child in [i + 1, node.start as usize] {
                    if let Some(d) = depths.get_mut(child) {
                        *d = child_depth;
                    }
                }
            }
        }
        depths
    }

    /// Node and leaf counts, depth, leaf sizes, memory and the SAH cost of the node volumes
    /// (their surface areas, perimeters in 2D, relative to the root's: for a sphere tree the
    /// spheres', so the cost also measures how loose the volumes are).
    pub(in crate::structure::bvh) fn stats_impl(&self) -> Stats {
        let leaves = || self.nodes.iter().filter(|n| n.is_leaf());
        let memory_bytes = self.nodes.capacity() * size_of::<super::BvhNode<B>>()
            + (self.prims.capacity() + self.leaf_prims.capacity()) * size_of::<P>()
            + self.leaf_ids.capacity() * size_of::<u32>();
        Stats {
            nodes: self.nodes.len(),
            leaves: leaves().count(),
            max_depth: self.depths().into_iter().max().unwrap_or(0) as usize,
            leaf_sizes: Stats::leaf_size_histogram(leaves().map(|n| n.count as usize)),
            primitives: self.prims.len(),
            references: leaves().map(|n| n.count as usize).sum(),
            memory_bytes,
            sah_cost: self.sah_cost(),
        }
    }

    /// The SAH cost of the node volumes now (after a [`refit`](Bvh::refit), of the refitted
    /// ones): [`Stats::sah_cost`].
    pub fn sah_cost(&self) -> Option<f32> {
        sah_cost(
            self.nodes
                .iter()
                .map(|n| (n.volume, n.is_leaf().then_some(n.count as usize))),
        )
    }

    /// The tree with its build-time SAH cost recorded (the builders' last step).
    pub(in crate::structure::bvh) fn with_build_cost(mut self) -> Self {
        self.build_sah_cost = self.sah_cost();
        self
    }
}
