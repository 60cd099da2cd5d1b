//! Running the student's queries on the chosen structure and on brute force, and reading the
//! observer's events back as "what happened to each node".
//!
//! Everything the lab shows about a query comes from the core: the answer, its
//! [`QueryCost`], and the [`Event`]s a [`Recorder`] collected. [`NodeMarks::from_events`]
//! folds any prefix of those events, so step-by-step playback can show the state after
//! event `k` with the same code.

use bvhlab::glam::Vec2;
use bvhlab::structure::bvh::NodeVolume;
use bvhlab::structure::{PrimitiveResult, PruneReason};
use bvhlab::{
    Aabb, BruteForce, Event, Hit, Nearest, Obb, Primitive, QueryCost, Ray, Recorder, SpatialIndex,
    Sphere, Vector,
};

use super::structures::Built;

/// What happened to a node during a query.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum NodeMark {
    /// Its bounding volume (or cell) was tested and the query did not go in.
    Culled,
    /// It was skipped by branch and bound: it cannot hold anything better than the best so
    /// far.
    Pruned,
    /// The query went in.
    Visited,
}

/// What happened to each node and primitive, after some prefix of a query's events.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeMarks {
    /// Indexed by node id; `None` for nodes the query never looked at.
    pub nodes: Vec<Option<NodeMark>>,
    /// Primitives whose exact test ran, with the result.
    pub tested: Vec<(u32, PrimitiveResult)>,
    /// Tests skipped because the primitive was already tested in another cell (mailboxing).
    pub mailbox_skips: usize,
}

impl NodeMarks {
    /// Folds `events` over a structure of `node_count` nodes. A node the query entered is
    /// [`NodeMark::Visited`] whatever else was said about it.
    pub fn from_events<V: Vector>(events: &[Event<V>], node_count: usize) -> Self {
        let mut marks = Self {
            nodes: vec![None; node_count],
            ..Self::default()
        };
        let mut set = |node: bvhlab::NodeId, mark: NodeMark| {
            if let Some(slot) = marks.nodes.get_mut(node.index()) {
                *slot = Some(slot.map_or(mark, |old| old.max(mark)));
            }
        };
        let mut tested = Vec::new();
        let mut mailbox_skips = 0;
        for event in events {
            match *event {
                Event::EnterNode { node, .. } | Event::CellEnter { cell: node, .. } => {
                    set(node, NodeMark::Visited);
                }
                Event::RayBoundTest {
                    node,
                    interval: None,
                } => set(node, NodeMark::Culled),
                Event::Prune { node, reason, .. } => set(
                    node,
                    match reason {
                        PruneReason::RayMissed | PruneReason::NoOverlap => NodeMark::Culled,
                        _ => NodeMark::Pruned,
                    },
                ),
                Event::PrimitiveTest {
                    result: PrimitiveResult::AlreadyTested,
                    ..
                } => mailbox_skips += 1,
                Event::PrimitiveTest { prim, result } => tested.push((prim, result)),
                _ => {}
            }
        }
        marks.tested = tested;
        marks.mailbox_skips = mailbox_skips;
        marks
    }

    /// How many nodes carry `mark`.
    pub fn count(&self, mark: NodeMark) -> usize {
        self.nodes.iter().filter(|m| **m == Some(mark)).count()
    }
}

/// A ray query's outcome on the structure and on brute force (in 2D by default).
#[derive(Clone, Debug)]
pub struct RayOutcome<V: Vector = Vec2> {
    /// The ray.
    pub ray: Ray<V>,
    /// The structure's first hit.
    pub hit: Option<Hit>,
    /// What it cost.
    pub cost: QueryCost,
    /// Brute force's first hit.
    pub brute_hit: Option<Hit>,
    /// What brute force cost.
    pub brute_cost: QueryCost,
    /// Everything the structure reported, in order.
    pub events: Vec<Event<V>>,
}

impl<V: Vector> RayOutcome<V> {
    /// Casts `ray` through `built` and through brute force over the same primitives.
    pub fn run<P>(built: &Built<P>, brute: &BruteForce<P>, ray: Ray<V>) -> Self
    where
        P: Primitive<Point = V>,
        Sphere<V>: NodeVolume<Point = V>,
        Aabb<V>: NodeVolume<Point = V>,
        Obb<V>: NodeVolume<Point = V>,
    {
        let mut recorder = Recorder::default();
        let traced = built.ray_first_hit(&ray, &mut recorder);
        let reference = brute.ray_first_hit_observed(&ray, f32::INFINITY, &mut ());
        Self {
            ray,
            hit: traced.answer,
            cost: traced.cost,
            brute_hit: reference.answer,
            brute_cost: reference.cost,
            events: recorder.events,
        }
    }

    /// Whether the structure's answer equals brute force's.
    pub fn agrees(&self) -> bool {
        self.hit == self.brute_hit
    }

    /// The hit point, if any.
    pub fn hit_point(&self) -> Option<V> {
        self.hit.map(|h| self.ray.at(h.t))
    }
}

/// A closest-point query's outcome on the structure and on brute force (in 2D by default).
#[derive(Clone, Debug)]
pub struct PointOutcome<V: Vector = Vec2> {
    /// The query point.
    pub point: V,
    /// How many neighbours were asked for.
    pub k: usize,
    /// The structure's `k` nearest, nearest first.
    pub nearest: Vec<Nearest<V>>,
    /// What it cost.
    pub cost: QueryCost,
    /// Brute force's answer.
    pub brute_nearest: Vec<Nearest<V>>,
    /// What brute force cost.
    pub brute_cost: QueryCost,
    /// Everything the structure reported, in order.
    pub events: Vec<Event<V>>,
}

impl<V: Vector> PointOutcome<V> {
    /// Finds the `k` primitives nearest `point` with `built` and with brute force.
    pub fn run<P>(built: &Built<P>, brute: &BruteForce<P>, point: V, k: usize) -> Self
    where
        P: Primitive<Point = V>,
        Sphere<V>: NodeVolume<Point = V>,
        Aabb<V>: NodeVolume<Point = V>,
        Obb<V>: NodeVolume<Point = V>,
    {
        let mut recorder = Recorder::default();
        let traced = built.k_nearest(point, k, &mut recorder);
        let reference = brute.k_nearest_observed(point, k, &mut ());
        Self {
            point,
            k,
            nearest: traced.answer,
            cost: traced.cost,
            brute_nearest: reference.answer,
            brute_cost: reference.cost,
            events: recorder.events,
        }
    }

    /// Whether the structure's answer equals brute force's (same primitives, same distances).
    pub fn agrees(&self) -> bool {
        self.nearest.len() == self.brute_nearest.len()
            && self
                .nearest
                .iter()
                .zip(&self.brute_nearest)
                .all(|(a, b)| a.prim == b.prim && a.distance == b.distance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets::random_segments;
    use crate::model::structures::{BuildSettings, StructureKind};
    use bvhlab::Ray2;

    #[test]
    fn marks_show_visits_and_the_tree_beats_brute_force() {
        let prims = random_segments(500, 50.0, 2.0, 7).primitives().segments;
        let built = Built::build(&prims, &BuildSettings::default());
        let brute = BruteForce::build(&prims);
        let ray = Ray2::through(Vec2::new(-5.0, 20.0), Vec2::new(60.0, 27.0)).expect("ray");
        let outcome = RayOutcome::run(&built, &brute, ray);
        assert!(outcome.agrees());
        assert!(outcome.hit.is_some());
        assert!(outcome.cost.prim_tests < outcome.brute_cost.prim_tests);
        let marks = NodeMarks::from_events(&outcome.events, built.outline().len());
        assert_eq!(
            marks.count(NodeMark::Visited) as u64,
            outcome.cost.nodes_visited
        );
        assert_eq!(marks.tested.len() as u64, outcome.cost.prim_tests);
        // An empty prefix marks nothing: playback starts from a clean picture.
        assert_eq!(NodeMarks::from_events::<Vec2>(&[], 3).nodes, vec![None; 3]);
    }

    #[test]
    fn nearest_agrees_on_every_structure() {
        let prims = random_segments(300, 30.0, 2.0, 8).primitives().segments;
        let brute = BruteForce::build(&prims);
        for kind in StructureKind::ALL {
            let settings = BuildSettings {
                kind,
                ..BuildSettings::default()
            };
            let built = Built::build(&prims, &settings);
            for q in [Vec2::new(15.0, 15.0), Vec2::new(-40.0, 3.0)] {
                let outcome = PointOutcome::run(&built, &brute, q, 3);
                assert!(outcome.agrees(), "{kind:?} at {q}");
            }
        }
    }
}
