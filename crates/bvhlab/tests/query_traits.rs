//! One query API (issue 20): `RayCast` and `PointQuery` are answered alike by volumes,
//! primitives and every structure, `Bvh4` included, with one name and one return type each.
//! Code written once against the traits gets brute force's answers from each of them.

use std::path::PathBuf;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::BvhOptions;
use bvhlab::structure::{BruteForce, BspOptions, GridOptions, KdTreeOptions, OrthtreeOptions};
use bvhlab::{
    BspTree, Bvh4, Grid, Hit, KdTree, Nearest, Orthtree, PointQuery, RayCast, Recorder, Vector,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_vec3(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
    )
}

fn random_triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<Triangle3> {
    (0..n)
        .map(|_| {
            let a = random_vec3(rng, 10.0);
            Triangle3::new(a, a + random_vec3(rng, 1.5), a + random_vec3(rng, 1.5))
        })
        .collect()
}

/// The bunny when the shared mesh folder is there (it is in CI), else random triangles.
fn scene(rng: &mut ChaCha8Rng) -> (String, Vec<Triangle3>) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes/stanford-bunny.obj");
    match std::fs::read(&path) {
        Ok(bytes) => {
            let mesh = Mesh::from_obj(&bytes).expect("the bunny parses");
            ("the bunny".into(), mesh.triangles().to_vec())
        }
        Err(_) => ("random triangles".into(), random_triangles(rng, 3000)),
    }
}

/// What the two traits answer: first hits, `intersects_ray`, closest points, distances.
type Answers = (
    Vec<Option<Hit>>,
    Vec<bool>,
    Vec<Option<Nearest<Vec3>>>,
    Vec<f32>,
);

/// Everything the two traits answer for the queries, written once for any implementor.
fn answers<Q: RayCast<Vec3> + PointQuery<Vec3>>(
    thing: &Q,
    rays: &[Ray3],
    points: &[Vec3],
) -> Answers {
    (
        rays.iter()
            .map(|r| thing.ray_first_hit(r, f32::INFINITY))
            .collect(),
        rays.iter().map(|r| thing.intersects_ray(r, 30.0)).collect(),
        points.iter().map(|&p| thing.closest_point(p)).collect(),
        points.iter().map(|&p| thing.distance(p)).collect(),
    )
}

#[test]
fn every_structure_answers_the_query_traits_as_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(20);
    let (name, tris) = scene(&mut rng);
    let bounds = tris.iter().fold(Aabb3::EMPTY, |b, t| b.merge(&t.bounds()));
    let (centre, reach) = (bounds.center(), bounds.size().length());
    let rays: Vec<Ray3> = (0..300)
        .map(|_| {
            let from = centre + random_vec3(&mut rng, 1.0).normalize_or(Vec3::X) * reach;
            let to = centre + random_vec3(&mut rng, reach * 0.3);
            Ray3::through(from, to).expect("distinct points")
        })
        .collect();
    let points: Vec<Vec3> = (0..200)
        .map(|_| centre + random_vec3(&mut rng, reach * 0.6))
        .collect();
    let expected = answers(&BruteForce::build(&tris), &rays, &points);
    assert!(
        expected.0.iter().filter(|h| h.is_some()).count() > 50,
        "{name}: too few rays hit to test anything"
    );
    let check = |what: &str, got: Answers| {
        assert_eq!(got.0, expected.0, "{name}: {what}'s first hits");
        assert_eq!(got.1, expected.1, "{name}: {what}'s intersects_ray");
        assert_eq!(got.2, expected.2, "{name}: {what}'s closest points");
        assert_eq!(got.3, expected.3, "{name}: {what}'s distances");
    };
    check("Bvh4", answers(&Bvh4::build(&tris), &rays, &points));
    check(
        "AabbTree3",
        answers(&AabbTree3::build(&tris), &rays, &points),
    );
    check(
        "SphereTree3",
        answers(&SphereTree3::build(&tris), &rays, &points),
    );
    check("ObbTree3", answers(&ObbTree3::build(&tris), &rays, &points));
    check("KdTree", answers(&KdTree::build(&tris), &rays, &points));
    check("Grid", answers(&Grid::build(&tris), &rays, &points));
    check("Octree", answers(&Orthtree::build(&tris), &rays, &points));
    if tris.len() <= 5000 {
        // The BSP tree's autopartition is slow on the full bunny in a debug build.
        check("BspTree", answers(&BspTree::build(&tris), &rays, &points));
    }
}

#[test]
fn a_volume_answers_ray_first_hit_and_closest_point_from_its_own_queries() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    for _ in 0..200 {
        let cloud: Vec<Vec3> = (0..8).map(|_| random_vec3(&mut rng, 3.0)).collect();
        let ray = Ray3::through(random_vec3(&mut rng, 8.0), random_vec3(&mut rng, 1.0))
            .expect("distinct points");
        let p = random_vec3(&mut rng, 6.0);
        let t_max = rng.random_range(0.0..12.0);
        check_volume("box", &Aabb3::from_points(&cloud), &ray, p, t_max);
        check_volume("sphere", &Sphere3::ritter_fit(&cloud), &ray, p, t_max);
        check_volume("oriented box", &Obb3::pca_fit(&cloud), &ray, p, t_max);
        check_volume("hull", &ConvexHull3::from_points(&cloud), &ray, p, t_max);
    }
    // The empty volume: no hit, no closest point, infinitely far.
    assert_eq!(
        Aabb3::EMPTY.ray_first_hit(&Ray3::new(Vec3::ZERO, Vec3::X).expect("a valid ray"), 1.0),
        None
    );
    assert_eq!(Aabb3::EMPTY.closest_point(Vec3::ZERO), None);
    assert_eq!(Aabb3::EMPTY.distance(Vec3::ZERO), f32::INFINITY);
}

fn check_volume<B: BoundingVolume<Point = Vec3>>(
    what: &str,
    v: &B,
    ray: &Ray3,
    p: Vec3,
    t_max: f32,
) {
    let interval = v.ray_interval(ray);
    let hit = v.ray_first_hit(ray, t_max);
    assert_eq!(
        hit.map(|h| h.t),
        interval.map(|(t, _)| t).filter(|&t| t <= t_max),
        "{what}: ray_first_hit is where the ray enters, within t_max"
    );
    assert!(
        hit.is_none_or(|h| h.prim == 0),
        "{what}: a volume is primitive 0"
    );
    assert_eq!(v.intersects_ray(ray, t_max), hit.is_some(), "{what}");
    let nearest = v.closest_point(p).expect("not empty");
    assert_eq!(nearest.prim, 0, "{what}");
    assert!(
        (nearest.distance - (nearest.point - p).length()).abs() <= 1e-5,
        "{what}"
    );
    assert!(
        (v.distance(p) - nearest.distance).abs() <= 1e-4,
        "{what}: distance"
    );
    assert_eq!(
        nearest.distance == 0.0,
        v.contains(p) || nearest.point == p,
        "{what}: 0 inside"
    );
    assert_eq!(
        v.checked_closest_point(p).ok().flatten(),
        Some(nearest),
        "{what}"
    );
    assert!(
        v.checked_distance(Vec3::new(f32::NAN, 0.0, 0.0)).is_err(),
        "{what}"
    );
}

#[test]
fn a_primitive_answers_the_query_traits_as_a_one_primitive_structure() {
    let mut rng = ChaCha8Rng::seed_from_u64(22);
    let tris = random_triangles(&mut rng, 300);
    for tri in &tris {
        let alone = BruteForce::build(std::slice::from_ref(tri));
        let ray = Ray3::through(
            random_vec3(&mut rng, 14.0),
            tri.centroid() + random_vec3(&mut rng, 0.3),
        )
        .expect("distinct points");
        let p = random_vec3(&mut rng, 12.0);
        assert_eq!(
            tri.ray_first_hit(&ray, f32::INFINITY),
            alone.ray_first_hit(&ray, f32::INFINITY)
        );
        assert_eq!(
            tri.ray_first_hit(&ray, 1e-3),
            alone.ray_first_hit(&ray, 1e-3)
        );
        assert_eq!(tri.closest_point(p), alone.closest_point(p));
        assert_eq!(tri.distance(p), alone.distance(p));
        assert_eq!(
            tri.closest_point(p).map(|n| n.point),
            Some(tri.project_point(p))
        );
    }
    // Segments and points too, in 2D.
    let s = Segment2::new(Vec2::ZERO, Vec2::new(2.0, 0.0));
    let down = Ray2::new(Vec2::new(0.5, 1.0), -Vec2::Y).expect("a valid ray");
    let hit = s
        .ray_first_hit(&down, f32::INFINITY)
        .expect("the ray crosses the segment");
    assert_eq!((hit.prim, hit.t, hit.u), (0, 1.0, 0.25));
    assert_eq!(s.distance(Vec2::new(3.0, 0.0)), 1.0);
    let point = Vec2::new(1.0, 1.0);
    assert_eq!(
        point.closest_point(Vec2::new(4.0, 5.0)).map(|n| n.distance),
        Some(5.0)
    );
}

#[test]
fn builds_take_build_with_and_leaf_size_alike_everywhere() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let tris = random_triangles(&mut rng, 400);
    let leaf_size = 3;
    // `leaf_sizes[n]` counts the leaves of `n` references: the largest non-empty bucket.
    let max_leaf = |stats: bvhlab::Stats| {
        stats
            .leaf_sizes
            .iter()
            .rposition(|&count| count > 0)
            .unwrap_or(0)
    };
    let bvh = AabbTree3::build_with(
        &tris,
        &BvhOptions {
            leaf_size,
            ..BvhOptions::default()
        },
    );
    assert!(max_leaf(bvh.stats()) <= leaf_size);
    let wide = Bvh4::build_with(
        &tris,
        &BvhOptions {
            leaf_size,
            ..BvhOptions::default()
        },
    );
    assert_eq!(
        wide.ray_first_hit(&Ray3::new(Vec3::ZERO, Vec3::X).expect("a valid ray"), 50.0),
        bvh.ray_first_hit(&Ray3::new(Vec3::ZERO, Vec3::X).expect("a valid ray"), 50.0)
    );
    let mut kd = KdTreeOptions::median(bvhlab::structure::kdtree::AxisRule::LongestAxis);
    kd.leaf_size = leaf_size;
    let kd_tree = KdTree::build_with(&tris, &kd);
    kd_tree.validate().expect("a valid k-d tree");
    // The median builder stops at its depth limit, so a leaf may hold more than `leaf_size`
    // where triangles straddle the planes; most leaves keep to it.
    let kd_stats = kd_tree.stats();
    let small: usize = kd_stats.leaf_sizes.iter().take(leaf_size + 1).sum();
    assert!(small * 2 > kd_stats.leaves, "{kd_stats:?}");
    let bsp = BspOptions {
        leaf_size,
        ..BspOptions::default()
    };
    BspTree::build_with(&tris[..100], &bsp)
        .validate()
        .expect("a valid BSP tree");
    let oct = OrthtreeOptions {
        leaf_size,
        ..OrthtreeOptions::default()
    };
    Orthtree::build_with(&tris, &oct)
        .validate()
        .expect("a valid octree");
    Grid::build_with(&tris, &GridOptions::default())
        .validate()
        .expect("a valid grid");
}

#[test]
fn the_bvh_split_log_reaches_the_observer_and_only_when_asked() {
    let mut rng = ChaCha8Rng::seed_from_u64(24);
    let tris = random_triangles(&mut rng, 500);
    let mut recorder = Recorder::default();
    let tree = AabbTree3::build_observed(&tris, &BvhOptions::default(), &mut recorder);
    let splits = recorder
        .events
        .iter()
        .filter(|e| matches!(e, bvhlab::Event::BuildSplit { .. }))
        .count();
    assert!(splits > 10);
    // One record per split decision, each with its SAH cost curve.
    assert!(
        recorder.splits.len() >= splits,
        "{} records for {splits} splits",
        recorder.splits.len()
    );
    assert!(recorder.splits.iter().any(|r| !r.bin_costs.is_empty()));
    // A closure observer does not ask for them, and the tree is the same.
    let mut events = 0;
    let plain = AabbTree3::build_observed(&tris, &BvhOptions::default(), &mut |_| events += 1);
    assert_eq!(events, recorder.events.len());
    assert_eq!(plain.nodes(), tree.nodes());
}

/// A function written once over the structure's trait gets the query traits with it.
fn first_hits_of_any_index<S: SpatialIndex>(index: &S, rays: &[Ray<PointOf<S>>]) -> usize
where
    PointOf<S>: Vector,
{
    rays.iter()
        .filter(|r| index.ray_first_hit(r, f32::INFINITY).is_some())
        .count()
}

use bvhlab::Ray;
use bvhlab::structure::PointOf;

#[test]
fn spatial_index_brings_the_query_traits_with_it() {
    let mut rng = ChaCha8Rng::seed_from_u64(25);
    let tris = random_triangles(&mut rng, 200);
    let rays: Vec<Ray3> = (0..100)
        .map(|_| {
            Ray3::through(random_vec3(&mut rng, 14.0), random_vec3(&mut rng, 8.0))
                .expect("a valid ray")
        })
        .collect();
    let brute = first_hits_of_any_index(&BruteForce::build(&tris), &rays);
    assert!(brute > 0);
    assert_eq!(
        first_hits_of_any_index(&AabbTree3::build(&tris), &rays),
        brute
    );
    assert_eq!(first_hits_of_any_index(&KdTree::build(&tris), &rays), brute);
}
