//! The collision query of two trees (the lecture's "collision query", structure against
//! structure): the core's simultaneous descent over two BVHs, recorded event by event so the
//! student steps through it (which node pairs are tested, which are disjoint and cut off,
//! which primitive pairs are tested and which meet), beside brute force over every pair.
//! Generic over the primitive: segments in 2D, triangles in 3D.

use bvhlab::structure::{
    BruteForce, Event, NodeOutline, Outline, QueryCost, Recorder, SpatialIndex,
};
use bvhlab::{AabbTree, ObbTree, Primitive, SphereTree};

/// Which BVH both sides are built as.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CollisionTree {
    /// Spheres (Ritter's fit): the cheapest test, the loosest volume.
    Sphere,
    /// Axis-aligned boxes.
    Aabb,
    /// Oriented boxes under the separating-axis test (the lecture's OBB collision query).
    #[default]
    Obb,
}

impl CollisionTree {
    /// Every kind, in the panel's order.
    pub const ALL: [Self; 3] = [Self::Sphere, Self::Aabb, Self::Obb];

    /// Its name in the panel.
    pub fn label(self) -> &'static str {
        match self {
            Self::Sphere => "sphere trees",
            Self::Aabb => "AABB trees",
            Self::Obb => "OBB trees",
        }
    }
}

/// Brute force runs only up to this many primitive pairs (13 million for the bunny against
/// itself would take seconds a change); past it the panel gives the count it would test.
pub const BRUTE_FORCE_PAIRS_CAP: u64 = 1_000_000;

/// One collision query, recorded.
#[derive(Clone, Debug)]
pub struct CollisionRun<V: bvhlab::Vector> {
    /// The kind of both trees.
    pub tree: CollisionTree,
    /// Tree A's nodes, by the ids its events use.
    pub nodes_a: Vec<NodeOutline<V>>,
    /// Tree B's.
    pub nodes_b: Vec<NodeOutline<V>>,
    /// The walk's events: a `NodePairTest` per pair of nodes taken, a `PairTest` per pair
    /// of primitives in two overlapping leaves.
    pub events: Vec<Event<V>>,
    /// The answer: every pair (primitive of A, primitive of B) that share a point, ascending.
    pub pairs: Vec<(usize, usize)>,
    /// What it cost.
    pub cost: QueryCost,
    /// How many primitive pairs brute force tests: every one.
    pub brute_tests: u64,
    /// Brute force's answer, when it ran (see [`BRUTE_FORCE_PAIRS_CAP`]).
    pub brute: Option<Vec<(usize, usize)>>,
}

/// What the walk has done up to a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CollisionSoFar {
    /// Node pairs tested.
    pub node_pairs: u64,
    /// ... of which disjoint: everything below them is cut off.
    pub disjoint: u64,
    /// Primitive pairs tested.
    pub primitive_pairs: u64,
    /// ... of which meet.
    pub meeting: u64,
}

/// Two trees of kind `S` built over `a` and `b`, and their collision query: both outlines,
/// the answer and the cost.
fn build_and_collide<S, P>(a: &[P], b: &[P], run: &mut Recorder<P::Point>) -> Collided<P::Point>
where
    S: SpatialIndex<Prim = P> + Outline,
    P: Primitive,
{
    let (tree_a, tree_b) = (S::build(a), S::build(b));
    let traced = tree_a.collide_observed(&tree_b, run);
    (
        tree_a.outline(),
        tree_b.outline(),
        traced.answer,
        traced.cost,
    )
}

/// A built pair's outlines, answer and cost.
type Collided<V> = (
    Vec<NodeOutline<V>>,
    Vec<NodeOutline<V>>,
    Vec<(usize, usize)>,
    QueryCost,
);

impl<V: bvhlab::Vector> CollisionRun<V> {
    /// Builds `tree`s over `a` and `b` and records their collision query, with brute force
    /// beside it when `a.len() × b.len()` is at most [`BRUTE_FORCE_PAIRS_CAP`].
    pub fn run<P: Primitive<Point = V>>(a: &[P], b: &[P], tree: CollisionTree) -> Self {
        let mut recorder = Recorder::default();
        let (nodes_a, nodes_b, pairs, cost) = match tree {
            CollisionTree::Sphere => build_and_collide::<SphereTree<P>, P>(a, b, &mut recorder),
            CollisionTree::Aabb => build_and_collide::<AabbTree<P>, P>(a, b, &mut recorder),
            CollisionTree::Obb => build_and_collide::<ObbTree<P>, P>(a, b, &mut recorder),
        };
        let brute_tests = a.len() as u64 * b.len() as u64;
        // The core's brute force: every pair tested with the primitives' own test.
        let brute = (brute_tests <= BRUTE_FORCE_PAIRS_CAP)
            .then(|| BruteForce::build(a).collide(&BruteForce::build(b)));
        Self {
            tree,
            nodes_a,
            nodes_b,
            events: recorder.events,
            pairs,
            cost,
            brute_tests,
            brute,
        }
    }

    /// What the walk did in its first `step` events.
    pub fn so_far(&self, step: usize) -> CollisionSoFar {
        let mut so_far = CollisionSoFar::default();
        for event in self.events.iter().take(step) {
            match *event {
                Event::NodePairTest { overlap, .. } => {
                    so_far.node_pairs += 1;
                    so_far.disjoint += u64::from(!overlap);
                }
                Event::PairTest { overlap, .. } => {
                    so_far.primitive_pairs += 1;
                    so_far.meeting += u64::from(overlap);
                }
                _ => {}
            }
        }
        so_far
    }

    /// The primitive pairs found meeting in the first `step` events.
    pub fn meeting_so_far(&self, step: usize) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.events.iter().take(step).filter_map(|e| match *e {
            Event::PairTest {
                a,
                b,
                overlap: true,
            } => Some((a, b)),
            _ => None,
        })
    }

    /// Whether the tree's answer is brute force's (`None` when brute force did not run).
    pub fn agrees(&self) -> Option<bool> {
        self.brute.as_ref().map(|b| *b == self.pairs)
    }
}
