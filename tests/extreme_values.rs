//! Every structure the lab offers, with every build option it offers, built over extreme but
//! finite input and asked every query: coordinates from 1e-30 to 1e30 of both signs and mixed
//! scales, all-equal points, zero-length segments, collinear and zero-area triangles, rays
//! with zero, tiny or huge direction components, query points far away (property tests).
//!
//! Each case must end (it runs on a watchdog thread: over [`TIME_LIMIT`] fails it) and must
//! not panic. Within the range where the core promises brute force's answers (every
//! coordinate at most [`EXACT_LIMIT`] in magnitude: beyond it `f32` squares of distances
//! overflow, as the core's `HUGE` and the lab's `MAX_COORD` say; and no coordinate but zero
//! more than [`EXACT_SPREAD`] below the largest) each answer must equal brute force's; beyond
//! it an answer must still name real primitives, with a `t` or distance that is not NaN and
//! within the query's bounds.
//!
//! 256 cases per test by default (about 2 s for the file in the test profile);
//! `PROPTEST_CASES=2000 cargo test -p bvhlab-tests --test all extreme_values` searches longer.

use std::fmt::Debug;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::thread;
use std::time::Duration;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{NodeVolume, SphereFit};
use bvhlab::structure::kdtree::AxisRule;
use bvhlab::structure::{
    BspOptions, BvhOptions, GridOptions, KdTreeOptions, OrthtreeOptions, PointOf, RangeShape,
    Recorder, SplitMethod,
};
use bvhlab::{
    Aabb, BruteForce, BspTree, Bvh, Grid, Hit, KdTree, NodeShape, Obb, Orthtree, Ray, Sphere,
    Vector,
};
use proptest::prelude::*;
use proptest::test_runner::Config;

/// The longest a case may take before it counts as a loop that does not end.
const TIME_LIMIT: Duration = Duration::from_secs(5);

/// The largest coordinate magnitude at which answers must equal brute force's.
const EXACT_LIMIT: f32 = 1e15;

/// How far below the case's largest coordinate the others may lie for answers to equal brute
/// force's. A primitive's own tests are only as exact as its coordinates (a few `f32` units in
/// the last place, about 1e-7 of them); where a scene mixes scales further apart than this,
/// a primitive with huge coordinates can report a hit or a distance, within its own rounding,
/// across a plane or cell boundary near tiny ones, and the structures' tolerances, relative to
/// the query's coordinates, need not follow it there.
const EXACT_SPREAD: f32 = 1e-5;

/// A primitive made of pool points (so that primitives share, repeat and line up vertices).
trait FromCorners: Primitive {
    /// How many points make one.
    const CORNERS: usize;
    /// The primitive with these corners (`corners.len() == CORNERS`).
    fn from_corners(corners: &[Self::Point]) -> Self;
}

impl FromCorners for Segment2 {
    const CORNERS: usize = 2;
    fn from_corners(c: &[Vec2]) -> Self {
        Segment2::new(c[0], c[1])
    }
}

impl FromCorners for Triangle3 {
    const CORNERS: usize = 3;
    fn from_corners(c: &[Vec3]) -> Self {
        Triangle3::new(c[0], c[1], c[2])
    }
}

impl FromCorners for Vec2 {
    const CORNERS: usize = 1;
    fn from_corners(c: &[Vec2]) -> Self {
        c[0]
    }
}

impl FromCorners for Vec3 {
    const CORNERS: usize = 1;
    fn from_corners(c: &[Vec3]) -> Self {
        c[0]
    }
}

// ---- input ----

/// A magnitude from 1e-30 to below `10^(top + 1)`, any sign.
fn extreme(top: i32) -> impl Strategy<Value = f32> {
    (-30i32..=top, 1.0f32..10.0, any::<bool>()).prop_map(|(exponent, mantissa, negative)| {
        let v = mantissa * 10f32.powi(exponent);
        if negative { -v } else { v }
    })
}

/// A coordinate: zero, or an extreme magnitude.
fn coordinate(top: i32) -> impl Strategy<Value = f32> {
    prop_oneof![1 => Just(0.0f32), 4 => extreme(top)]
}

fn vector<V: Vector>(top: i32) -> impl Strategy<Value = V> {
    prop::collection::vec(coordinate(top), V::DIM).prop_map(|c| from_coords(&c))
}

fn from_coords<V: Vector>(coords: &[f32]) -> V {
    let mut v = V::ZERO;
    for (i, &c) in coords.iter().enumerate() {
        v.set_coord(i, c);
    }
    v
}

/// The points primitives are made of: independent extreme points (mixed scales), small
/// integers times one power of ten (aligned, touching, on split planes), one point repeated,
/// or points on one line.
fn pool<V: Vector>(top: i32) -> impl Strategy<Value = Vec<V>> {
    prop_oneof![
        prop::collection::vec(vector::<V>(top), 1..8),
        (
            -30i32..=top,
            prop::collection::vec(prop::collection::vec(-3i8..=3, V::DIM), 1..8)
        )
            .prop_map(|(exponent, points)| {
                let scale = 10f32.powi(exponent);
                points
                    .iter()
                    .map(|p| {
                        let c: Vec<f32> = p.iter().map(|&i| f32::from(i) * scale).collect();
                        from_coords(&c)
                    })
                    .collect()
            }),
        (vector::<V>(top), 1..8usize).prop_map(|(p, n)| vec![p; n]),
        (
            vector::<V>(top),
            vector::<V>(top),
            prop::collection::vec(-3i8..=3, 1..8)
        )
            .prop_map(|(p, d, steps)| steps.iter().map(|&k| p + d * f32::from(k)).collect()),
    ]
}

/// Primitives over a pool: up to 10 of them, corners picked (with repeats) from the pool.
fn primitives<P: FromCorners>(pool: Vec<P::Point>) -> impl Strategy<Value = Vec<P>> {
    let n = pool.len();
    prop::collection::vec(prop::collection::vec(0..n, P::CORNERS), 0..10).prop_map(move |picks| {
        picks
            .iter()
            .map(|corners| {
                let c: Vec<P::Point> = corners.iter().map(|&i| pool[i]).collect();
                P::from_corners(&c)
            })
            .collect()
    })
}

/// A direction component: zero, tiny, huge or ordinary, any sign.
fn component(top: i32) -> impl Strategy<Value = f32> {
    prop_oneof![Just(0.0f32), extreme(top), -2.0f32..2.0]
}

/// Rays: from pool points or anywhere, along odd directions or at pool points. Directions
/// that `Ray::new` refuses (zero) are dropped.
fn rays<V: Vector>(pool: Vec<V>, top: i32) -> impl Strategy<Value = Vec<Ray<V>>> {
    let n = pool.len();
    let origin = prop_oneof![(0..n).prop_map(move |i| pool[i]), vector::<V>(top)];
    let pool2 = origin.clone();
    prop::collection::vec(
        (
            origin,
            prop::collection::vec(component(top), V::DIM),
            pool2,
            any::<bool>(),
        ),
        1..5,
    )
    .prop_map(|choices| {
        choices
            .into_iter()
            .filter_map(|(origin, dir, target, aimed)| {
                if aimed {
                    Ray::new(origin, target - origin).ok()
                } else {
                    Ray::new(origin, from_coords(&dir)).ok()
                }
            })
            .collect()
    })
}

/// Query points: pool points, anywhere, or far away (`10^top`).
fn points<V: Vector>(pool: Vec<V>, top: i32) -> impl Strategy<Value = Vec<V>> {
    let n = pool.len();
    let far = 10f32.powi(top);
    let far = prop::collection::vec(prop_oneof![Just(far), Just(-far)], V::DIM)
        .prop_map(|c| from_coords::<V>(&c));
    prop::collection::vec(
        prop_oneof![(0..n).prop_map(move |i| pool[i]), vector::<V>(top), far],
        1..4,
    )
}

/// One case: the primitives, a second set to collide with, rays, query points, and a
/// magnitude for `t_max`, radii and box sizes.
#[derive(Clone, Debug)]
struct Case<P: Primitive> {
    prims: Vec<P>,
    other: Vec<P>,
    rays: Vec<Ray<P::Point>>,
    points: Vec<P::Point>,
    size: f32,
}

/// Half the cases stay within [`EXACT_LIMIT`] (coordinates below 1e15), where answers are
/// compared with brute force's; the others reach 1e30.
fn case<P: FromCorners>() -> impl Strategy<Value = Case<P>> {
    prop_oneof![Just(14), Just(29)]
        .prop_flat_map(|top| (pool::<P::Point>(top), Just(top)))
        .prop_flat_map(|(pool, top)| {
            (
                primitives::<P>(pool.clone()),
                primitives::<P>(pool.clone()),
                rays(pool.clone(), top),
                points(pool, top),
                extreme(top),
            )
                .prop_map(|(prims, other, rays, points, size)| Case {
                    prims,
                    other,
                    rays,
                    points,
                    size: size.abs(),
                })
        })
}

impl<P: Primitive> Case<P> {
    /// Whether the case lies where answers must equal brute force's: every coordinate (of
    /// primitives, query points, ray origins and directions, the size) at most
    /// [`EXACT_LIMIT`], and every one that is not zero within [`EXACT_SPREAD`] of the
    /// largest.
    fn within_exact_range(&self) -> bool {
        let values: Vec<f32> = self
            .prims
            .iter()
            .chain(&self.other)
            .flat_map(Primitive::vertices)
            .chain(self.points.iter().copied())
            .chain(self.rays.iter().flat_map(|r| [r.origin(), r.dir()]))
            .flat_map(|v| (0..P::Point::DIM).map(move |i| v.coord(i).abs()))
            .chain([self.size])
            .collect();
        let largest = values.iter().copied().fold(0.0, f32::max);
        largest <= EXACT_LIMIT
            && values
                .iter()
                .all(|&v| v == 0.0 || v >= largest * EXACT_SPREAD)
    }
}

// ---- running a case ----

/// Runs `check` on a thread and fails when it panics or takes more than [`TIME_LIMIT`].
fn on_watchdog<P: Primitive>(case: Case<P>, check: fn(&Case<P>)) {
    let (done, finished) = mpsc::channel();
    let description = format!("{case:?}");
    let worker = thread::spawn(move || {
        check(&case);
        let _ = done.send(());
    });
    match finished.recv_timeout(TIME_LIMIT) {
        Ok(()) => worker.join().expect("the case ended"),
        Err(RecvTimeoutError::Disconnected) => {
            if let Err(panic) = worker.join() {
                std::panic::resume_unwind(panic);
            }
        }
        Err(RecvTimeoutError::Timeout) => {
            panic!(
                "a case took more than {TIME_LIMIT:?} (a loop that does not end?): {description}"
            )
        }
    }
}

/// Builds every structure the lab offers, with each of its options, and checks each.
fn every_structure<P: Primitive>(case: &Case<P>)
where
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    let (a, b) = (&case.prims, &case.other);
    check(
        case,
        "brute force",
        &BruteForce::build(a),
        &BruteForce::build(b),
    );
    for method in [
        SplitMethod::SpatialMedian,
        SplitMethod::ObjectMedian,
        SplitMethod::BinnedSah,
    ] {
        for leaf_size in [1, 4] {
            let options = BvhOptions {
                method,
                leaf_size,
                ..BvhOptions::default()
            };
            let what = format!("{method:?}, leaves of {leaf_size}");
            bvh::<Aabb<P::Point>, P>(case, &format!("AABB tree, {what}"), &options);
            bvh::<Obb<P::Point>, P>(case, &format!("OBB tree, {what}"), &options);
            for sphere_fit in [SphereFit::Ritter, SphereFit::Welzl] {
                let options = BvhOptions {
                    sphere_fit,
                    ..options
                };
                let name = format!("sphere tree ({sphere_fit:?}), {what}");
                bvh::<Sphere<P::Point>, P>(case, &name, &options);
            }
        }
    }
    let depth = |n: u32| if P::Point::DIM == 3 { n } else { 1 };
    for resolution in [None, Some([1, 1, 1]), Some([7, 7, depth(7)])] {
        let options = GridOptions {
            resolution,
            ..GridOptions::default()
        };
        let what = format!("grid {resolution:?}");
        check(
            case,
            &what,
            &Grid::build_with(a, &options),
            &Grid::build_with(b, &options),
        );
    }
    for leaf_size in [1, 4] {
        let options = BspOptions {
            leaf_size,
            ..BspOptions::default()
        };
        let what = format!("BSP, leaves of {leaf_size}");
        check(
            case,
            &what,
            &BspTree::build_with(a, &options),
            &BspTree::build_with(b, &options),
        );
    }
    for (leaf_size, max_depth) in [(1, 0), (1, 20), (4, 8)] {
        let options = OrthtreeOptions {
            leaf_size,
            max_depth,
        };
        let what = format!("quadtree/octree, leaves of {leaf_size}, depth {max_depth}");
        check(
            case,
            &what,
            &Orthtree::build_with(a, &options),
            &Orthtree::build_with(b, &options),
        );
    }
    for (name, mut options) in [
        (
            "median round robin",
            KdTreeOptions::median(AxisRule::RoundRobin),
        ),
        (
            "median longest axis",
            KdTreeOptions::median(AxisRule::LongestAxis),
        ),
        ("SAH", KdTreeOptions::sah()),
    ] {
        // The lab's SAH k-d tree keeps its own leaf size (1).
        let leaf_sizes: &[usize] = if name == "SAH" { &[1] } else { &[1, 4] };
        for &leaf_size in leaf_sizes {
            options.leaf_size = leaf_size;
            let what = format!("k-d tree, {name}, leaves of {}", options.leaf_size);
            check(
                case,
                &what,
                &KdTree::build_with(a, &options),
                &KdTree::build_with(b, &options),
            );
        }
    }
}

/// A BVH with node volume `B`: the common checks, and the lecture's recursive `intersect`
/// and `minDistance` the lab runs beside it.
fn bvh<B, P>(case: &Case<P>, what: &str, options: &BvhOptions)
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
    NodeShape<P::Point>: From<B>,
{
    let tree = Bvh::<B, P>::build_with(&case.prims, options);
    check(
        case,
        what,
        &tree,
        &Bvh::<B, P>::build_with(&case.other, options),
    );
    let brute = BruteForce::build(&case.prims);
    let exact = case.within_exact_range();
    for ray in &case.rays {
        let got = tree.lecture_intersect(ray, f32::INFINITY);
        let want = brute.ray_first_hit(ray, f32::INFINITY);
        first_hit_agrees(case, what, ray, got, want, exact, "lecture intersect");
    }
    for &point in &case.points {
        for (variant, got) in [
            ("minDistance", tree.lecture_min_distance(point)),
            (
                "minDistance pruned",
                tree.lecture_min_distance_pruned(point),
            ),
        ] {
            let want = brute.closest_point(point).into_iter().collect::<Vec<_>>();
            nearest_agree(
                case,
                what,
                point,
                &got.into_iter().collect::<Vec<_>>(),
                &want,
                exact,
                variant,
            );
        }
    }
}

// ---- the checks ----

fn close(a: f32, b: f32) -> bool {
    a == b || (a - b).abs() <= 1e-5 * a.abs().max(b.abs())
}

/// Every query of `structure` (built over `case.prims`; `other` over `case.other`).
fn check<S: SpatialIndex + Outline>(case: &Case<S::Prim>, what: &str, structure: &S, other: &S) {
    let n = case.prims.len();
    let exact = case.within_exact_range();
    let brute = BruteForce::build(&case.prims);
    if let Err(e) = structure.validate() {
        panic!("{what}: invalid structure: {e}");
    }
    let stats = structure.stats();
    assert_eq!(stats.primitives, n, "{what}: stats");
    let _ = structure.outline();
    for ray in &case.rays {
        for t_max in [f32::INFINITY, case.size] {
            let got = structure.ray_first_hit(ray, t_max);
            let want = brute.ray_first_hit(ray, t_max);
            first_hit_agrees(case, what, ray, got, want, exact, "first hit");
            let mut recorder = Recorder::default();
            let observed = structure.ray_first_hit_observed(ray, t_max, &mut recorder);
            assert_eq!(observed.answer, got, "{what}: observing changed the answer");

            let any = structure.ray_any_hit(ray, t_max);
            if let Some(hit) = any {
                assert!(
                    hit.prim < n && hit.t >= 0.0 && hit.t <= t_max,
                    "{what}: any hit {hit:?}"
                );
            }
            if exact {
                assert_eq!(
                    any.is_some(),
                    want.is_some(),
                    "{what}: any hit {any:?}, brute {want:?}, {ray:?}"
                );
            }

            let all = structure.ray_all_hits(ray, t_max);
            assert!(
                all.iter().all(|h| h.prim < n && h.t >= 0.0 && h.t <= t_max),
                "{what}: all hits {all:?}"
            );
            assert!(
                all.windows(2).all(|w| w[0].t <= w[1].t),
                "{what}: all hits unsorted {all:?}"
            );
            if exact {
                let mut got: Vec<usize> = all.iter().map(|h| h.prim).collect();
                let mut want: Vec<usize> = brute
                    .ray_all_hits(ray, t_max)
                    .iter()
                    .map(|h| h.prim)
                    .collect();
                got.sort_unstable();
                want.sort_unstable();
                assert_eq!(got, want, "{what}: all hits for {ray:?}, t_max {t_max}");
            }
        }
    }
    for &point in &case.points {
        check_point(case, what, structure, &brute, point, exact);
    }
    let pairs = structure.collide(other);
    let m = case.other.len();
    assert!(
        pairs.iter().all(|&(a, b)| a < n && b < m),
        "{what}: collision pairs {pairs:?}"
    );
    if exact {
        let mut sorted = pairs.clone();
        sorted.sort_unstable();
        let want = brute.collide(&BruteForce::build(&case.other));
        assert_eq!(sorted, want, "{what}: collision pairs");
    }
}

/// k nearest (1 and 3, plain and observed), and ball and box ranges around `point`.
fn check_point<S: SpatialIndex>(
    case: &Case<S::Prim>,
    what: &str,
    structure: &S,
    brute: &BruteForce<S::Prim>,
    point: PointOf<S>,
    exact: bool,
) {
    let n = case.prims.len();
    for k in [1, 3] {
        let got = structure.k_nearest(point, k);
        let want = brute.k_nearest(point, k);
        nearest_agree(
            case,
            what,
            point,
            &got,
            &want,
            exact,
            &format!("{k} nearest"),
        );
        let mut recorder = Recorder::default();
        let observed = structure.k_nearest_observed(point, k, &mut recorder);
        assert_eq!(observed.answer, got, "{what}: observing changed the answer");
    }
    let corner = point + PointOf::<S>::splat(case.size);
    for shape in [
        RangeShape::Ball(Sphere::new(point, case.size)),
        RangeShape::Box(Aabb::new(point.min(corner), point.max(corner))),
    ] {
        let got = structure.range(&shape);
        assert!(got.iter().all(|&i| i < n), "{what}: range {got:?}");
        assert!(
            got.windows(2).all(|w| w[0] < w[1]),
            "{what}: range {got:?} not ascending"
        );
        if exact {
            assert_eq!(got, brute.range(&shape), "{what}: range {shape:?}");
        }
    }
}

fn first_hit_agrees<P: Primitive>(
    case: &Case<P>,
    what: &str,
    ray: &Ray<P::Point>,
    got: Option<Hit>,
    want: Option<Hit>,
    exact: bool,
    query: &str,
) {
    if let Some(hit) = got {
        assert!(
            hit.prim < case.prims.len() && hit.t >= 0.0,
            "{what}: {query} {hit:?} for {ray:?}"
        );
    }
    if !exact {
        return;
    }
    match (got, want) {
        (None, None) => {}
        (Some(g), Some(w)) => {
            assert!(
                close(g.t, w.t),
                "{what}: {query} {g:?}, brute {w:?}, {ray:?}"
            );
            if g.prim != w.prim {
                let t = case.prims[g.prim].ray_hit(ray);
                assert_eq!(
                    t,
                    Some(w.t),
                    "{what}: {query} {g:?} is no tie with {w:?}, {ray:?}"
                );
            }
        }
        _ => panic!("{what}: {query} {got:?}, brute {want:?}, {ray:?}"),
    }
}

fn nearest_agree<P: Primitive>(
    case: &Case<P>,
    what: &str,
    point: P::Point,
    got: &[bvhlab::Nearest<P::Point>],
    want: &[bvhlab::Nearest<P::Point>],
    exact: bool,
    query: &str,
) {
    for g in got {
        assert!(
            g.prim < case.prims.len() && g.distance >= 0.0,
            "{what}: {query} to {point:?}: {got:?}"
        );
    }
    assert!(
        got.windows(2).all(|w| w[0].distance <= w[1].distance),
        "{what}: {query} unsorted {got:?}"
    );
    if !exact {
        return;
    }
    assert_eq!(
        got.len(),
        want.len(),
        "{what}: {query} to {point:?}: {got:?}, brute {want:?}"
    );
    for (g, w) in got.iter().zip(want) {
        assert!(
            close(g.distance, w.distance),
            "{what}: {query} to {point:?}: {got:?}, brute {want:?}"
        );
    }
}

// ---- the tests ----

fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(256);
    Config {
        cases,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn segments_2d(case in case::<Segment2>()) {
        on_watchdog(case, every_structure);
    }

    #[test]
    fn triangles_3d(case in case::<Triangle3>()) {
        on_watchdog(case, every_structure);
    }

    #[test]
    fn points_2d(case in case::<Vec2>()) {
        on_watchdog(case, every_structure);
    }

    #[test]
    fn points_3d(case in case::<Vec3>()) {
        on_watchdog(case, every_structure);
    }
}
