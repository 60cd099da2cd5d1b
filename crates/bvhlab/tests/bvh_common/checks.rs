//! Every query of a tree against brute force, and costs against events.

use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh, BvhOptions, NodeVolume, SplitRecord};
use bvhlab::structure::{BruteForce, Event, Hit, RangeShape, Recorder};
use bvhlab::{Aabb, Ray, Sphere};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::{plausible_hit, points_for, random_vector, rays_for, scene_box};

/// How many queries a scene gets.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    pub rays: usize,
    pub points: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            rays: 60,
            points: 24,
        }
    }
}

/// Builds `Bvh<B, P>` over `prims`, validates it, and checks every query against brute force
/// on the rays and points of [`rays_for`] and [`points_for`]. Returns the tree.
///
/// The tree must give brute force's answers exactly: all hits, k nearest, range and collision
/// lists are compared with `==`; the first hit too, or else be a tie to 1e-5.
///
/// # Panics
/// On the first disagreement, naming the scene and the query.
pub fn check_scene<B, P>(
    name: &str,
    prims: &[P],
    options: &BvhOptions,
    rng: &mut ChaCha8Rng,
    budget: Budget,
) -> Checked<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let name = format!("{name} ({} tree, {:?})", B::NAME, options.method);
    let mut split_log = Recorder::default();
    let bvh = Bvh::<B, P>::build_observed(prims, options, &mut split_log);
    let log = split_log.splits;
    bvh.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    let stats = bvh.stats();
    assert_eq!(stats.primitives, prims.len(), "{name}: {stats:?}");
    assert_eq!(
        stats.references + bvh.skipped(),
        prims.len(),
        "{name}: {stats:?}"
    );
    let rays_hit = check_tree(&name, &bvh, prims, &log, rng, budget);
    Checked { bvh, rays_hit }
}

/// Checks every query of a built (or refitted) tree over `prims` against brute force on
/// `prims`, as [`check_scene`] does; `log` (may be empty) aims some rays and points at split
/// planes. Returns how many rays hit something.
///
/// # Panics
/// On the first disagreement, naming the tree and the query.
pub fn check_tree<B, P>(
    name: &str,
    bvh: &Bvh<B, P>,
    prims: &[P],
    log: &[SplitRecord],
    rng: &mut ChaCha8Rng,
    budget: Budget,
) -> usize
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let brute = BruteForce::build(prims);
    let mut rays_hit = 0;
    for (i, ray) in rays_for(rng, prims, log, budget.rays).iter().enumerate() {
        let t_max = [f32::INFINITY, rng.random_range(0.0f32..1.5), 0.0][i % 3];
        rays_hit += usize::from(check_ray(name, bvh, &brute, ray, t_max, i % 4 == 0));
    }
    let (_, size) = scene_box(prims);
    for (i, point) in points_for(rng, prims, log, budget.points)
        .into_iter()
        .enumerate()
    {
        // The unobserved closest point takes its own, faster walk.
        assert_eq!(
            bvh.closest_point(point),
            bvh.k_nearest_observed(point, 1, &mut ())
                .answer
                .first()
                .copied(),
            "{name}: the fast closest point differs from the observed one, {point:?}"
        );
        for k in [1, 3, 10] {
            let got = bvh.k_nearest(point, k);
            assert_eq!(
                got,
                brute.k_nearest(point, k),
                "{name}: {k} nearest to {point:?}"
            );
        }
        if i % 4 == 0 {
            let mut recorder = Recorder::default();
            let traced = bvh.k_nearest_observed(point, 3, &mut recorder);
            assert_eq!(
                traced.answer,
                bvh.k_nearest(point, 3),
                "{name}: observing changed it"
            );
            assert_counts(name, &recorder, traced.cost);
        }
        let ball = RangeShape::Ball(Sphere::new(point, rng.random_range(0.0..0.3) * size));
        assert_eq!(
            bvh.range(&ball),
            brute.range(&ball),
            "{name}: range {ball:?}"
        );
        let corner = point + random_vector::<P::Point>(rng, 0.3 * size);
        let boxed = RangeShape::Box(Aabb::new(point.min(corner), point.max(corner)));
        assert_eq!(
            bvh.range(&boxed),
            brute.range(&boxed),
            "{name}: range {boxed:?}"
        );
    }
    let nan = P::Point::splat(f32::NAN);
    assert!(
        bvh.closest_point(nan).is_none(),
        "{name}: a NaN point has no nearest"
    );
    assert!(bvh.k_nearest(P::Point::ZERO, 0).is_empty(), "{name}: k = 0");
    rays_hit
}

/// A tree that passed [`check_scene`], and how many of its rays hit something (so that a
/// test can tell its rays were not all trivial misses).
pub struct Checked<B, P: Primitive> {
    pub bvh: Bvh<B, P>,
    pub rays_hit: usize,
}

/// Checks one ray's three queries against brute force; with `observe`, also that the
/// observed query gives the same answer and that its cost matches its events. Returns
/// whether brute force found a hit.
pub fn check_ray<B, P>(
    name: &str,
    bvh: &Bvh<B, P>,
    brute: &BruteForce<P>,
    ray: &Ray<P::Point>,
    t_max: f32,
    observe: bool,
) -> bool
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let prims = brute.primitives();
    let all = bvh.ray_all_hits(ray, t_max);
    let all_want = brute.ray_all_hits(ray, t_max);
    let plausible = |h: &Hit| plausible_hit(&prims[h.prim], ray, h.t);
    if all_want.iter().all(plausible) {
        assert_eq!(all, all_want, "{name}: all hits, {ray:?}, t_max {t_max}");
    } else {
        // Brute force reports a hit off its primitive (see `plausible_hit`): compare the rest.
        let keep = |hits: &[Hit]| hits.iter().copied().filter(plausible).collect::<Vec<_>>();
        assert_eq!(
            keep(&all),
            keep(&all_want),
            "{name}: all hits, {ray:?}, t_max {t_max}"
        );
    }
    let want = brute.ray_first_hit(ray, t_max);
    let got = bvh.ray_first_hit(ray, t_max);
    // The unobserved query takes its own, faster walk: it must give the observed answer bit
    // for bit.
    assert_eq!(
        got,
        bvh.ray_first_hit_observed(ray, t_max, &mut ()).answer,
        "{name}: the fast first hit differs from the observed one, {ray:?}, t_max {t_max}"
    );
    if got != want && want.as_ref().is_none_or(plausible) {
        let tie = match (got, want) {
            (Some(g), Some(w)) => {
                (g.t - w.t).abs() <= 1e-5 * w.t.abs() && prims[g.prim].ray_hit(ray) == Some(g.t)
            }
            _ => false,
        };
        assert!(
            tie,
            "{name}: first hit {got:?}, brute force {want:?}, {ray:?}, t_max {t_max}"
        );
    }
    if let Some(g) = got {
        assert_eq!(
            prims[g.prim].ray_hit(ray),
            Some(g.t),
            "{name}: first hit {g:?} is no hit"
        );
    }
    let any = bvh.ray_any_hit(ray, t_max);
    // The unobserved any hit takes the fast walk: it must stop where the observed one does.
    assert_eq!(
        any,
        bvh.ray_any_hit_observed(ray, t_max, &mut ()).answer,
        "{name}: the fast any hit differs from the observed one, {ray:?}, t_max {t_max}"
    );
    if all_want.iter().any(plausible) {
        assert!(
            any.is_some(),
            "{name}: no any hit, brute force {want:?} {ray:?}"
        );
    }
    assert_eq!(
        any.is_some(),
        got.is_some(),
        "{name}: any hit {any:?} vs first {got:?} {ray:?}"
    );
    if let Some(h) = any {
        assert!(
            prims[h.prim].ray_hit(ray) == Some(h.t) && h.t <= t_max,
            "{name}: any hit {h:?}"
        );
    }
    if observe {
        let mut recorder = Recorder::default();
        let traced = bvh.ray_first_hit_observed(ray, t_max, &mut recorder);
        assert_eq!(traced.answer, got, "{name}: observing changed the answer");
        assert_counts(name, &recorder, traced.cost);
        let mut recorder = Recorder::default();
        let traced = bvh.ray_all_hits_observed(ray, t_max, &mut recorder);
        assert_eq!(traced.answer, all, "{name}: observing changed the answer");
        assert_counts(name, &recorder, traced.cost);
    }
    want.is_some()
}

/// The cost a query reports equals the events it emitted: one `EnterNode` per node visited,
/// one bound test event per bound test, one `PrimitiveTest` per primitive tested.
pub fn assert_counts<V: Vector>(name: &str, recorder: &Recorder<V>, cost: bvhlab::QueryCost) {
    let count = |f: fn(&Event<V>) -> bool| recorder.events.iter().filter(|e| f(e)).count() as u64;
    assert_eq!(
        cost.nodes_visited,
        count(|e| matches!(e, Event::EnterNode { .. })),
        "{name}: {cost:?}"
    );
    assert_eq!(
        cost.bound_tests,
        count(|e| matches!(
            e,
            Event::RayBoundTest { .. } | Event::DistanceBoundTest { .. }
        )),
        "{name}: {cost:?}"
    );
    assert_eq!(
        cost.prim_tests,
        count(|e| matches!(e, Event::PrimitiveTest { .. })),
        "{name}: {cost:?}"
    );
}

/// Checks the collision query of two trees against brute force, exactly, and that its cost
/// matches its events (node pair tests, primitive pair tests).
pub fn check_collide<B, P>(name: &str, a: &[P], b: &[P], options: &BvhOptions)
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let (ta, tb) = (
        Bvh::<B, P>::build_with(a, options),
        Bvh::<B, P>::build_with(b, options),
    );
    let want = BruteForce::build(a).collide(&BruteForce::build(b));
    let mut recorder = Recorder::default();
    let traced = ta.collide_observed(&tb, &mut recorder);
    assert_eq!(
        traced.answer,
        want,
        "{name}: collision pairs ({} tree)",
        B::NAME
    );
    assert_eq!(
        ta.collide(&tb),
        want,
        "{name}: observing changed the answer"
    );
    let count =
        |f: fn(&Event<P::Point>) -> bool| recorder.events.iter().filter(|e| f(e)).count() as u64;
    assert_eq!(
        traced.cost.bound_tests,
        count(|e| matches!(e, Event::NodePairTest { .. }))
    );
    assert_eq!(
        traced.cost.prim_tests,
        count(|e| matches!(e, Event::PairTest { .. }))
    );
    let reversed: Vec<(usize, usize)> = {
        let mut r: Vec<_> = tb.collide(&ta).into_iter().map(|(x, y)| (y, x)).collect();
        r.sort_unstable();
        r
    };
    assert_eq!(reversed, want, "{name}: collision is not symmetric");
}

/// A box tree's nodes (corners, start, count) and leaf order, as bits ([`tree_bits`]).
pub type TreeBits = (Vec<Vec<u32>>, Vec<u32>);

/// Everything of a box tree, as bits: `==` on floats would take `-0` for `0`.
pub fn tree_bits<P: Primitive>(tree: &AabbTree<P>) -> TreeBits {
    let nodes = tree
        .nodes()
        .iter()
        .map(|node| {
            let bits = |v: P::Point| (0..P::Point::DIM).map(move |i| v.coord(i).to_bits());
            bits(node.volume.min)
                .chain(bits(node.volume.max))
                .chain([node.start, node.count])
                .collect()
        })
        .collect();
    let leaf_order = (0..tree.nodes().len())
        .flat_map(|i| {
            tree.leaf_primitives(bvhlab::structure::NodeId(i as u32))
                .to_vec()
        })
        .collect();
    (nodes, leaf_order)
}
