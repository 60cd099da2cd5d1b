//! Construction: the build events, the SAH cost curves, the options, the stats, and the node
//! layout.

use crate::bvh_common;

use bvh_common::rng;
use bvh_common::scenes::random;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{
    AabbTree, Bvh, BvhNode, BvhOptions, MAX_DEPTH, NodeVolume, ObbTree, SphereTree, SplitMethod,
    SplitRecord,
};
use bvhlab::structure::{Event, NodeId, Recorder};
use bvhlab::{Aabb, Obb, Sphere};

#[test]
fn the_3d_box_node_is_32_bytes() {
    assert_eq!(size_of::<BvhNode<Aabb3>>(), 32);
    assert_eq!(size_of::<BvhNode<Sphere3>>(), 24);
    assert_eq!(size_of::<BvhNode<Aabb2>>(), 24);
}

/// The input indices below a node, ascending.
fn prims_below<B, P: Primitive>(bvh: &Bvh<B, P>, node: NodeId) -> Vec<usize> {
    let mut out = Vec::new();
    let mut stack = vec![node];
    while let Some(n) = stack.pop() {
        match bvh.children(n) {
            Some((a, b)) => stack.extend([a, b]),
            None => out.extend(bvh.leaf_primitives(n).iter().map(|&i| i as usize)),
        }
    }
    out.sort_unstable();
    out
}

fn half_area(b: &Aabb3) -> f64 {
    let s = b.size().as_dvec3();
    s.x * s.y + s.y * s.z + s.z * s.x
}

/// Build events come depth-first, first child first: `BuildNode` with the node's index, its
/// parent, depth and size, then at once its `BuildSplit` (sizes adding up) or `BuildLeaf`.
fn check_build_events<B: NodeVolume<Point = Vec3>>(prims: &[Triangle3], options: &BvhOptions) {
    let mut recorder = Recorder::default();
    let bvh = Bvh::<B, Triangle3>::build_observed(prims, options, &mut recorder);
    let mut parents = vec![None; bvh.nodes().len()];
    let mut depths = vec![0u32; bvh.nodes().len()];
    for i in 0..bvh.nodes().len() {
        if let Some((a, b)) = bvh.children(NodeId(i as u32)) {
            for c in [a, b] {
                parents[c.index()] = Some(NodeId(i as u32));
                depths[c.index()] = depths[i] + 1;
            }
        }
    }
    let mut events = recorder.events.iter();
    for i in 0..bvh.nodes().len() {
        let below = prims_below(&bvh, NodeId(i as u32)).len() as u32;
        let id = NodeId(i as u32);
        assert_eq!(
            events.next(),
            Some(&Event::BuildNode {
                node: id,
                parent: parents[i],
                depth: depths[i],
                prims: below
            })
        );
        match events.next() {
            Some(&Event::BuildLeaf { node, prims }) => {
                assert!(node == id && prims == below && node.index() == i);
                assert_eq!(node_count(&bvh, i), prims);
            }
            Some(&Event::BuildSplit {
                node,
                normal,
                left,
                right,
                ..
            }) => {
                assert_eq!(node, id);
                assert_eq!(left + right, below);
                let (a, _) = bvh.children(id).expect("a split node has children");
                assert_eq!(prims_below(&bvh, a).len() as u32, left);
                assert_eq!(normal.length(), 1.0);
            }
            other => panic!("node {i}: expected its split or leaf, got {other:?}"),
        }
    }
    assert_eq!(events.next(), None);
}

fn node_count<B, P: Primitive>(bvh: &Bvh<B, P>, i: usize) -> u32 {
    bvh.nodes()[i].count
}

#[test]
fn build_events_follow_the_tree() {
    let mut rng = rng(41);
    let prims: Vec<Triangle3> = random(&mut rng, 300);
    for method in [
        SplitMethod::BinnedSah,
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
    ] {
        let options = BvhOptions::with_method(method);
        check_build_events::<Aabb3>(&prims, &options);
        check_build_events::<Sphere3>(&prims, &options);
        check_build_events::<Obb3>(&prims, &options);
    }
    check_build_events::<Aabb3>(&[], &BvhOptions::default());
    check_build_events::<Aabb3>(&prims[..1], &BvhOptions::default());
}

/// Every SAH decision is logged with its cost curve; the chosen plane is the cheapest; its
/// cost is the heuristic recomputed from the two children's primitives; and it is the cost
/// the `BuildSplit` event reports.
#[test]
fn sah_records_are_the_heuristic() {
    let mut rng = rng(42);
    let prims: Vec<Triangle3> = random(&mut rng, 500);
    let options = BvhOptions {
        bins: 12,
        ..BvhOptions::default()
    };
    let mut recorder = Recorder::default();
    let bvh = AabbTree::<Triangle3>::build_observed(&prims, &options, &mut recorder);
    let log = recorder.splits.clone();
    let split_costs: Vec<(NodeId, Option<f32>)> = recorder
        .events
        .iter()
        .filter_map(|e| match e {
            Event::BuildSplit { node, cost, .. } => Some((*node, *cost)),
            _ => None,
        })
        .collect();
    let splits: Vec<&SplitRecord> = log.iter().filter(|r| !r.made_leaf).collect();
    assert_eq!(splits.len(), split_costs.len());
    assert_eq!(
        splits.len(),
        bvh.nodes().iter().filter(|n| !n.is_leaf()).count()
    );
    for (record, (node, cost)) in splits.iter().zip(&split_costs) {
        assert_eq!(record.node, *node);
        assert_eq!(record.method, SplitMethod::BinnedSah);
        assert_eq!(record.bin_costs.len(), 11);
        assert_eq!(record.planes.len(), 11);
        assert!(record.planes.windows(2).all(|w| w[0] <= w[1]));
        let chosen = record.chosen_bin.expect("a SAH split names its bin");
        let min = record
            .bin_costs
            .iter()
            .copied()
            .fold(f32::INFINITY, f32::min);
        assert_eq!(record.bin_costs[chosen], min);
        assert_eq!(*cost, Some(min));
        assert_eq!(record.position, record.planes[chosen]);
        assert!(record.bin_costs.iter().all(|&c| c >= 1.0));

        // Recompute C = 1 + (A_L N_L + A_R N_R) / A from the children's primitives.
        let (a, b) = bvh.children(*node).expect("inner node");
        let bounds = |ids: &[usize]| {
            ids.iter()
                .fold(Aabb::EMPTY, |acc, &i| acc.merge(&prims[i].bounds()))
        };
        let (left, right) = (prims_below(&bvh, a), prims_below(&bvh, b));
        let all: Vec<usize> = left.iter().chain(&right).copied().collect();
        assert_eq!(
            (record.left, record.right),
            (left.len() as u32, right.len() as u32)
        );
        let expected = 1.0
            + (half_area(&bounds(&left)) * left.len() as f64
                + half_area(&bounds(&right)) * right.len() as f64)
                / half_area(&bounds(&all));
        assert!(
            (f64::from(min) - expected).abs() < 1e-4 * expected,
            "{min} vs {expected}"
        );
        assert_eq!(record.leaf_cost, all.len() as f32);
    }
    // Leaves the SAH chose over a split: splitting would have cost at least the leaf.
    for record in log.iter().filter(|r| r.made_leaf) {
        let chosen = record.chosen_bin.expect("evaluated");
        assert!(record.bin_costs[chosen] >= record.leaf_cost);
        assert!(bvh.node(record.node).is_leaf());
    }
}

/// When every centre coincides the SAH has nothing to bin and splits at the object median.
#[test]
fn coinciding_centres_fall_back_to_the_median() {
    let t = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let prims = vec![t; 37];
    let mut split_log = Recorder::default();
    let bvh = AabbTree::<Triangle3>::build_observed(&prims, &BvhOptions::default(), &mut split_log);
    let log = split_log.splits;
    bvh.validate().expect("well formed");
    assert!(!log.is_empty());
    assert!(log.iter().all(|r| r.method == SplitMethod::ObjectMedian));
    assert!(bvh.stats().leaf_sizes.len() <= 5, "leaves of at most 4");
}

#[test]
fn options_shape_the_tree() {
    let mut rng = rng(43);
    let prims: Vec<Segment2> = random(&mut rng, 1000);
    for leaf in [1, 3, 8] {
        for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
            let options = BvhOptions {
                leaf_size: leaf,
                ..BvhOptions::with_method(method)
            };
            let bvh = AabbTree::<Segment2>::build_with(&prims, &options);
            let stats = bvh.stats();
            assert!(stats.leaf_sizes.len() <= leaf + 1, "{method:?} {stats:?}");
            if method == SplitMethod::ObjectMedian {
                // Balanced: depth ceil(log2(n / leaf)).
                let depth = (prims.len() as f64 / leaf as f64).log2().ceil() as usize;
                assert_eq!(stats.max_depth, depth, "{stats:?}");
            }
        }
    }
    for max_depth in [0, 2, 5, 1000] {
        let options = BvhOptions {
            max_depth,
            ..BvhOptions::default()
        };
        let bvh = SphereTree::<Segment2>::build_with(&prims, &options);
        bvh.validate().expect("well formed");
        assert!(bvh.stats().max_depth <= max_depth.min(MAX_DEPTH));
    }
    let one = AabbTree::<Segment2>::build_with(
        &prims,
        &BvhOptions {
            max_depth: 0,
            ..BvhOptions::default()
        },
    );
    assert_eq!(one.nodes().len(), 1);
    assert_eq!(one.leaf_primitives(NodeId(0)).len(), prims.len());
}

/// The spatial median needs no more than the depth limit even when every split cuts off one
/// primitive (centres spaced exponentially), and the tree stays valid.
#[test]
fn exponential_spacing_stays_within_the_depth_limit() {
    let prims: Vec<Vec2> = (0..200)
        .map(|i| Vec2::new(2.0f32.powi(-(i % 120)), 0.0))
        .collect();
    let options = BvhOptions {
        leaf_size: 1,
        ..BvhOptions::with_method(SplitMethod::SpatialMedian)
    };
    let bvh = AabbTree::<Vec2>::build_with(&prims, &options);
    bvh.validate().expect("well formed");
    assert_eq!(bvh.stats().max_depth, MAX_DEPTH, "the limit is reached");
    let brute = bvhlab::BruteForce::build(&prims);
    for p in [Vec2::ZERO, Vec2::new(0.3, 0.1), Vec2::new(-1.0, 2.0)] {
        assert_eq!(bvh.k_nearest(p, 5), brute.k_nearest(p, 5));
    }
}

#[test]
fn stats_count_the_tree() {
    let mut rng = rng(44);
    let prims: Vec<Triangle3> = random(&mut rng, 700);
    let aabb = AabbTree::<Triangle3>::build(&prims);
    let sphere = SphereTree::<Triangle3>::build(&prims);
    let obb = ObbTree::<Triangle3>::build(&prims);
    for (stats, node_size) in [
        (aabb.stats(), size_of::<BvhNode<Aabb3>>()),
        (sphere.stats(), size_of::<BvhNode<Sphere3>>()),
        (obb.stats(), size_of::<BvhNode<Obb3>>()),
    ] {
        assert_eq!(stats.nodes, 2 * stats.leaves - 1);
        assert_eq!(stats.references, prims.len());
        assert_eq!(stats.primitives, prims.len());
        assert_eq!(stats.duplicated_references(), 0);
        assert_eq!(stats.leaf_sizes.iter().sum::<usize>(), stats.leaves);
        assert_eq!(
            stats
                .leaf_sizes
                .iter()
                .enumerate()
                .map(|(n, c)| n * c)
                .sum::<usize>(),
            prims.len()
        );
        assert!(stats.memory_bytes >= stats.nodes * node_size + 2 * prims.len() * 36);
        let sah = stats.sah_cost.expect("a SAH cost");
        assert!(sah > 1.0 && sah < prims.len() as f32, "{stats:?}");
        assert!(stats.max_depth >= 8);
    }
    // Boxes are tighter than spheres around thin triangles: the AABB tree's SAH is lower.
    assert!(aabb.stats().sah_cost < sphere.stats().sah_cost);
}

/// On clustered input the SAH finds a cheaper tree than the lecture's spatial median.
#[test]
fn sah_beats_the_spatial_median_on_clusters() {
    let mut rng = rng(45);
    let mut prims: Vec<Triangle3> = random(&mut rng, 600);
    for (i, t) in prims.iter_mut().enumerate() {
        let shift = if i % 10 == 0 {
            Vec3::splat(40.0)
        } else {
            Vec3::ZERO
        };
        *t = Triangle3::new(t.a * 0.2 + shift, t.b * 0.2 + shift, t.c * 0.2 + shift);
    }
    let cost = |method| {
        AabbTree::<Triangle3>::build_with(&prims, &BvhOptions::with_method(method))
            .stats()
            .sah_cost
            .expect("a cost")
    };
    assert!(cost(SplitMethod::BinnedSah) < cost(SplitMethod::SpatialMedian));
}

#[test]
fn builds_are_deterministic() {
    let mut rng = rng(46);
    let prims: Vec<Triangle3> = random(&mut rng, 400);
    assert_eq!(
        ObbTree::<Triangle3>::build(&prims),
        ObbTree::<Triangle3>::build(&prims)
    );
    assert_eq!(
        SphereTree::<Triangle3>::build(&prims),
        SphereTree::<Triangle3>::build(&prims)
    );
}

fn check_volumes_hold<B: NodeVolume<Point = Vec2>>(prims: &[Segment2]) {
    let bvh = Bvh::<B, Segment2>::build(prims);
    for (i, node) in bvh.nodes().iter().enumerate() {
        for p in prims_below(&bvh, NodeId(i as u32)) {
            assert!(node.volume.contains_primitive(&prims[p]));
            assert!(prims[p].vertices().all(|v| node.volume.contains(v)));
        }
    }
}

/// Node volumes hold their primitives; sphere and OBB nodes are fitted to their own
/// vertices, so they may be smaller than their children's union, while boxes nest.
#[test]
fn node_volumes_hold_their_primitives() {
    let mut rng = rng(47);
    let prims: Vec<Segment2> = random(&mut rng, 300);
    check_volumes_hold::<Aabb<Vec2>>(&prims);
    check_volumes_hold::<Sphere<Vec2>>(&prims);
    check_volumes_hold::<Obb<Vec2>>(&prims);
}
