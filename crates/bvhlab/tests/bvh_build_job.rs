//! The build in slices ([`BvhBuild`]): whatever the budget of each step, the tree is the one
//! [`Bvh::build_with`] builds, bit for bit (nodes, volumes, leaf order), for every node
//! volume, split method and degenerate scene; and its progress only moves forward and ends
//! exactly at its total.
//!
//! The `#[ignore]`d test at the end measures a million triangles:
//! `cargo test -p bvhlab --test all bvh_build_job -- --ignored --nocapture`.

use crate::bvh_common;

use std::time::{Duration, Instant};

use bvh_common::scenes::{degenerate, random};
use bvh_common::{TestPrim, rng};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::NodeId;
use bvhlab::structure::bvh::{
    BuildPhase, BuildProgress, Bvh, BvhBuild, BvhOptions, NodeVolume, SphereFit, SplitMethod,
};
use bvhlab::{Aabb, Obb, Segment2, Sphere};
use proptest::prelude::*;

/// The bits of a volume's coordinates, to compare volumes exactly (`==` on floats would
/// take `-0` for `0`).
trait VolumeBits {
    fn bits(&self) -> Vec<u32>;
}

fn coords<V: Vector>(v: V) -> impl Iterator<Item = u32> {
    (0..V::DIM).map(move |i| v.coord(i).to_bits())
}

impl<V: Vector> VolumeBits for Aabb<V> {
    fn bits(&self) -> Vec<u32> {
        coords(self.min).chain(coords(self.max)).collect()
    }
}

impl<V: Vector> VolumeBits for Sphere<V> {
    fn bits(&self) -> Vec<u32> {
        coords(self.center).chain([self.radius.to_bits()]).collect()
    }
}

impl<V: Vector> VolumeBits for Obb<V> {
    fn bits(&self) -> Vec<u32> {
        let axes = self.axes.as_ref().iter().flat_map(|&a| coords(a));
        coords(self.center)
            .chain(axes)
            .chain(coords(self.half_extents))
            .collect()
    }
}

/// The input indices in leaf order: the leaves' primitives, leaf by leaf in node order.
fn leaf_order<B, P: Primitive>(bvh: &Bvh<B, P>) -> Vec<u32> {
    (0..bvh.nodes().len())
        .flat_map(|i| bvh.leaf_primitives(NodeId(i as u32)).iter().copied())
        .collect()
}

/// Runs a build in steps of `budget` to the end, checking the progress after each step, and
/// returns the tree and how many steps it took.
fn build_in_steps<B, P>(prims: &[P], options: &BvhOptions, budget: usize) -> (Bvh<B, P>, usize)
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let mut build = BvhBuild::<B, P>::new(prims.to_vec(), *options);
    let mut last = build.progress();
    assert_eq!(last.total, 3 * prims.len(), "three units per primitive");
    assert_eq!(last.done == last.total, build.is_done());
    let mut steps = 0;
    while !build.is_done() {
        let now = build.step(budget);
        steps += 1;
        assert_eq!(now, build.progress());
        check_progress(&last, &now);
        assert_eq!(now.done == now.total, build.is_done(), "{now:?}");
        last = now;
    }
    assert_eq!((last.phase, last.fraction()), (BuildPhase::Done, 1.0));
    (build.finish(), steps)
}

/// `now` follows `before`: nothing goes back, and the phases come in their order
/// (preparing; fitting and splitting, interleaved node by node; ordering; done).
fn check_progress(before: &BuildProgress, now: &BuildProgress) {
    let rank = |phase: BuildPhase| match phase {
        BuildPhase::Preparing => 0,
        BuildPhase::Fitting | BuildPhase::Splitting => 1,
        BuildPhase::Ordering => 2,
        BuildPhase::Done => 3,
    };
    assert_eq!(now.total, before.total);
    assert!(
        now.done >= before.done && now.done <= now.total,
        "{before:?} -> {now:?}"
    );
    assert!((0.0..=1.0).contains(&now.fraction()));
    assert!(now.fraction() >= before.fraction(), "{before:?} -> {now:?}");
    assert!(
        rank(now.phase) >= rank(before.phase),
        "{before:?} -> {now:?}"
    );
    assert_eq!(now.fraction() == 1.0, now.phase == BuildPhase::Done);
}

/// The same tree, to the bit: nodes (volume bits, child or leaf range), leaf order, input
/// and options (through the tree's `Debug`, which also shows the leaf-order copies).
fn assert_same_tree<B, P>(sliced: &Bvh<B, P>, whole: &Bvh<B, P>, context: &str)
where
    B: NodeVolume<Point = P::Point> + VolumeBits,
    P: Primitive,
{
    assert_eq!(sliced.nodes().len(), whole.nodes().len(), "{context}");
    for (i, (a, b)) in sliced.nodes().iter().zip(whole.nodes()).enumerate() {
        assert_eq!(
            (a.start, a.count, a.volume.bits()),
            (b.start, b.count, b.volume.bits()),
            "{context}: node {i}"
        );
    }
    assert_eq!(leaf_order(sliced), leaf_order(whole), "{context}");
    assert_eq!(sliced.skipped(), whole.skipped(), "{context}");
    assert_eq!(format!("{sliced:?}"), format!("{whole:?}"), "{context}");
}

/// Every option the builder branches on: each method, leaves of 1, 4 and 16, no depth limit
/// and a depth limit of 2, 2 and 12 bins, both sphere fits, leaves costed one by one and by
/// blocks of four.
fn option_grid() -> Vec<BvhOptions> {
    let mut grid = Vec::new();
    for method in [
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
        SplitMethod::BinnedSah,
    ] {
        for (leaf_size, max_depth, bins, sphere_fit, leaf_block) in [
            (1, 64, 12, SphereFit::Ritter, 1),
            (4, 64, 2, SphereFit::Ritter, 1),
            (4, 2, 12, SphereFit::Ritter, 1),
            (4, 64, 12, SphereFit::Welzl, 1),
            (16, 64, 16, SphereFit::Ritter, 4),
        ] {
            grid.push(BvhOptions {
                method,
                leaf_size,
                max_depth,
                bins,
                sphere_fit,
                leaf_block,
            });
        }
    }
    grid
}

const BUDGETS: [usize; 4] = [1, 7, 1000, usize::MAX];

/// The degenerate scenes of the other BVH tests, plus primitives with non-finite
/// coordinates among finite ones and coordinates near 1e19 (beyond which the sphere and
/// OBB fits check every vertex).
fn scenes<P: TestPrim>(seed: u64) -> Vec<(&'static str, Vec<P>)> {
    let mut rng = rng(seed);
    let mut scenes = degenerate::<P>(&mut rng);
    let mut non_finite: Vec<P> = random(&mut rng, 60);
    non_finite[3] = non_finite[3].map(|v| v * f32::NAN);
    non_finite[17] = non_finite[17].map(|v| v * f32::INFINITY);
    scenes.push(("with NaN and infinite coordinates", non_finite));
    let huge = random::<P>(&mut rng, 80)
        .iter()
        .map(|p| p.map(|v| v * 2e18))
        .collect();
    scenes.push(("huge (x2e18)", huge));
    scenes.push(("two", random(&mut rng, 2)));
    scenes
}

fn check_scenes<B, P>(seed: u64)
where
    B: NodeVolume<Point = P::Point> + VolumeBits,
    P: TestPrim,
{
    for (name, prims) in scenes::<P>(seed) {
        for options in option_grid() {
            let whole = Bvh::<B, P>::build_with(&prims, &options);
            for budget in BUDGETS {
                let (sliced, _) = build_in_steps::<B, P>(&prims, &options, budget);
                let context = format!("{} tree, {name}, {options:?}, budget {budget}", B::NAME);
                assert_same_tree(&sliced, &whole, &context);
            }
        }
    }
}

#[test]
fn box_trees_built_in_steps_equal_the_one_shot_build() {
    check_scenes::<Aabb<Vec3>, Triangle3>(1);
    check_scenes::<Aabb<Vec2>, Segment2>(2);
    check_scenes::<Aabb<Vec3>, Vec3>(3);
}

#[test]
fn sphere_trees_built_in_steps_equal_the_one_shot_build() {
    check_scenes::<Sphere<Vec3>, Triangle3>(4);
    check_scenes::<Sphere<Vec2>, Segment2>(5);
    check_scenes::<Sphere<Vec2>, Vec2>(6);
}

#[test]
fn obb_trees_built_in_steps_equal_the_one_shot_build() {
    check_scenes::<Obb<Vec3>, Triangle3>(7);
    check_scenes::<Obb<Vec2>, Segment2>(8);
    check_scenes::<Obb<Vec3>, Vec3>(9);
}

/// A larger scene, deep enough that every stage is cut many times, with the default
/// options and budgets that do not divide the node sizes.
#[test]
fn a_deep_tree_built_in_odd_steps_equals_the_one_shot_build() {
    let prims: Vec<Triangle3> = random(&mut rng(10), 5000);
    for method in [SplitMethod::BinnedSah, SplitMethod::SpatialMedian] {
        let options = BvhOptions::with_method(method);
        for budget in [13, 997] {
            let (a, _) = build_in_steps::<Obb<Vec3>, _>(&prims, &options, budget);
            assert_same_tree(&a, &Bvh::build_with(&prims, &options), "OBB");
            let (s, _) = build_in_steps::<Sphere<Vec3>, _>(&prims, &options, budget);
            assert_same_tree(&s, &Bvh::build_with(&prims, &options), "sphere");
        }
    }
}

#[test]
fn an_empty_build_is_done_from_the_start() {
    let build = BvhBuild::<Aabb<Vec3>, Triangle3>::new(Vec::new(), BvhOptions::default());
    let progress = build.progress();
    assert!(build.is_done() && progress.is_done());
    assert_eq!(
        (progress.done, progress.total, progress.fraction()),
        (0, 0, 1.0)
    );
    let tree = build.finish();
    assert_eq!(tree, Bvh::build_with(&[], &BvhOptions::default()));
    assert!(tree.root().is_none());
}

/// The first steps compute primitive boxes, one unit each: a step of `k` prepares exactly
/// `k` primitives, a step of 0 does nothing, and an unfinished build finishes in `finish`.
#[test]
fn steps_spend_their_budget_on_primitives() {
    let prims: Vec<Triangle3> = random(&mut rng(11), 100);
    let mut build = BvhBuild::<Sphere<Vec3>, Triangle3>::new(prims.clone(), BvhOptions::default());
    assert_eq!(build.step(0).done, 0);
    let after = build.step(30);
    assert_eq!((after.done, after.phase), (30, BuildPhase::Preparing));
    assert_eq!(build.step(1).done, 31);
    assert!(!build.is_done());
    assert_same_tree(
        &build.finish(),
        &Bvh::build_with(&prims, &BvhOptions::default()),
        "finished early",
    );
}

/// A primitive left out (non-finite) counts all three of its units when it is scanned.
#[test]
fn left_out_primitives_count_as_built_once_scanned() {
    let mut prims: Vec<Triangle3> = random(&mut rng(12), 10);
    prims[0] = prims[0].map(|v| v * f32::NAN);
    let mut build = BvhBuild::<Aabb<Vec3>, Triangle3>::new(prims, BvhOptions::default());
    assert_eq!(build.step(1).done, 3);
    assert_eq!(build.step(1).done, 4);
}

/// Smaller budgets take more steps: the budget bounds the work of a step.
#[test]
fn smaller_budgets_take_more_steps() {
    let prims: Vec<Triangle3> = random(&mut rng(13), 2000);
    let options = BvhOptions::default();
    let steps: Vec<usize> = [100, 1000, 10_000, usize::MAX]
        .into_iter()
        .map(|budget| build_in_steps::<Obb<Vec3>, _>(&prims, &options, budget).1)
        .collect();
    assert!(steps.windows(2).all(|w| w[0] > w[1]), "{steps:?}");
    assert_eq!(steps[3], 1);
    // Every primitive is read at least three times (box, node box, leaf order).
    assert!(steps[0] >= 3 * prims.len() / 100, "{steps:?}");
}

fn coordinate() -> impl Strategy<Value = f32> {
    // Few distinct values, so that duplicates and coincident centres are common.
    prop_oneof![
        4 => -4.0f32..4.0,
        2 => prop::sample::select(vec![0.0, -0.0, 1.0, 1e-30, 1e19, -2.5]),
    ]
}

fn triangle() -> impl Strategy<Value = Triangle3> {
    prop::array::uniform9(coordinate()).prop_map(|c| {
        Triangle3::new(
            Vec3::new(c[0], c[1], c[2]),
            Vec3::new(c[3], c[4], c[5]),
            Vec3::new(c[6], c[7], c[8]),
        )
    })
}

fn segment() -> impl Strategy<Value = Segment2> {
    prop::array::uniform4(coordinate())
        .prop_map(|c| Segment2::new(Vec2::new(c[0], c[1]), Vec2::new(c[2], c[3])))
}

fn options() -> impl Strategy<Value = BvhOptions> {
    (
        prop::sample::select(vec![
            SplitMethod::SpatialMedian,
            SplitMethod::ObjectMedian,
            SplitMethod::BinnedSah,
        ]),
        1usize..6,
        1usize..10,
        2usize..20,
        prop::bool::ANY,
        1usize..5,
    )
        .prop_map(
            |(method, leaf_size, max_depth, bins, welzl, leaf_block)| BvhOptions {
                method,
                leaf_size,
                max_depth,
                bins,
                leaf_block,
                sphere_fit: if welzl {
                    SphereFit::Welzl
                } else {
                    SphereFit::Ritter
                },
            },
        )
}

fn check_all_volumes<P: Primitive>(prims: &[P], options: &BvhOptions, budget: usize) {
    let context = format!("{options:?}, budget {budget}");
    let (a, _) = build_in_steps::<Aabb<P::Point>, P>(prims, options, budget);
    assert_same_tree(&a, &Bvh::build_with(prims, options), &context);
    let (s, _) = build_in_steps::<Sphere<P::Point>, P>(prims, options, budget);
    assert_same_tree(&s, &Bvh::build_with(prims, options), &context);
    let (o, _) = build_in_steps::<Obb<P::Point>, P>(prims, options, budget);
    assert_same_tree(&o, &Bvh::build_with(prims, options), &context);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn any_triangles_any_budget_give_the_one_shot_tree(
        prims in prop::collection::vec(triangle(), 0..60),
        options in options(),
        budget in prop_oneof![1usize..40, Just(usize::MAX)],
    ) {
        check_all_volumes(&prims, &options, budget);
    }

    #[test]
    fn any_segments_any_budget_give_the_one_shot_tree(
        prims in prop::collection::vec(segment(), 0..60),
        options in options(),
        budget in prop_oneof![1usize..40, Just(usize::MAX)],
    ) {
        check_all_volumes(&prims, &options, budget);
    }
}

/// `n` small triangles (about 0.02 across) with centres uniform in `[-10, 10]^3`.
fn small_triangles(n: usize, seed: u64) -> Vec<Triangle3> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| {
            let c: Vec3 = bvh_common::random_vector(&mut rng, 10.0);
            let mut corner = || c + bvh_common::random_vector::<Vec3>(&mut rng, 0.01);
            Triangle3::new(corner(), corner(), corner())
        })
        .collect()
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort_unstable();
    times[times.len() / 2]
}

/// What one build in steps took.
struct StepTimes {
    /// All steps and `finish`.
    total: Duration,
    /// The slowest step, and the phase it started in.
    slowest: (Duration, BuildPhase),
    /// The median step and the 99th percentile.
    median: Duration,
    p99: Duration,
    steps: usize,
}

/// Builds in steps of `budget`, timing each.
fn timed_steps<B: NodeVolume<Point = Vec3>>(
    prims: &[Triangle3],
    options: &BvhOptions,
    budget: usize,
) -> (StepTimes, Bvh<B, Triangle3>) {
    let start = Instant::now();
    let mut build = BvhBuild::<B, Triangle3>::new(prims.to_vec(), *options);
    let mut steps = Vec::new();
    let mut slowest = (Duration::ZERO, BuildPhase::Preparing);
    while !build.is_done() {
        let phase = build.progress().phase;
        let t = Instant::now();
        build.step(budget);
        let took = t.elapsed();
        if took > slowest.0 {
            slowest = (took, phase);
        }
        steps.push(took);
    }
    let tree = build.finish();
    let total = start.elapsed();
    steps.sort_unstable();
    let times = StepTimes {
        total,
        slowest,
        median: steps[steps.len() / 2],
        p99: steps[steps.len() * 99 / 100],
        steps: steps.len(),
    };
    (times, tree)
}

fn measure<B: NodeVolume<Point = Vec3> + VolumeBits>(
    prims: &[Triangle3],
    method: SplitMethod,
    runs: usize,
) {
    let options = BvhOptions::with_method(method);
    let budget = 50_000;
    let mut one_shot = Vec::new();
    let mut runs_in_steps = Vec::new();
    for _ in 0..runs {
        let start = Instant::now();
        let whole = Bvh::<B, Triangle3>::build_with(prims, &options);
        one_shot.push(start.elapsed());
        let (times, tree) = timed_steps::<B>(prims, &options, budget);
        assert_same_tree(&tree, &whole, "a million triangles");
        runs_in_steps.push(times);
    }
    let of = |f: fn(&StepTimes) -> Duration| median(runs_in_steps.iter().map(f).collect());
    let slowest: Vec<_> = runs_in_steps.iter().map(|t| t.slowest).collect();
    eprintln!(
        "{} tree, {method:?}: one shot {:?}; in {} steps of {budget}: {:?}, median step {:?}, \
         p99 {:?}, slowest {:?} (per run, with the phase it started in: {slowest:?})",
        B::NAME,
        median(one_shot),
        runs_in_steps[0].steps,
        of(|t| t.total),
        of(|t| t.median),
        of(|t| t.p99),
        of(|t| t.slowest.0),
    );
}

/// Times a million-triangle build in one go and in steps of 50,000 units for each node
/// volume and split method (medians of three runs), and checks that both give the same tree.
///
/// On a shared 2-core VM (test profile) the steps took as long in total as the one-shot
/// build (AABB/sphere/OBB with SAH: 2.8/3.9/5.8 s in steps, 2.8/4.1/6.6 s at once), the
/// median step 0.2-2.5 ms and the slowest 4-9 ms (the root's object median, about 6 ms,
/// is the largest piece done in one go).
#[test]
#[ignore = "a measurement: several minutes in the test profile"]
fn a_million_triangles_in_steps() {
    let prims = small_triangles(1_000_000, 20);
    for method in [
        SplitMethod::BinnedSah,
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
    ] {
        measure::<Aabb<Vec3>>(&prims, method, 3);
        measure::<Sphere<Vec3>>(&prims, method, 3);
        measure::<Obb<Vec3>>(&prims, method, 3);
    }
}
