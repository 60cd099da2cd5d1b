//! Every query of the 4-wide tree answers as brute force and as the binary AABB tree it is
//! collapsed from: first hit, any hit, all hits, k nearest and range (box and ball), on
//! seeded random and degenerate scenes of 2D segments and 3D triangles (empty, one
//! primitive, duplicates, flat, integer coordinates, far clusters, tiny and huge scales) and
//! on the shared real meshes, with rays that start inside boxes, run parallel to axes and
//! split planes, and with `t_max` of 0, a random one and infinity; k from 1 to more than the
//! count.
//!
//! All hits, the k nearest and ranges must equal the binary tree's bit for bit (and brute
//! force's, up to the hits brute force reports off their primitive: see `plausible_hit`).
//! The any hit must be found exactly when the binary tree finds one, and be a true hit within
//! `t_max`; which primitive it is may differ (the binary walk visits nearer boxes first).

use crate::bvh_common;

use bvh_common::scenes::degenerate;
use bvh_common::{TestPrim, plausible_hit, points_for, random_vector, rays_for, rng, scene_box};
use bvh_common::{scenes::random, shared_mesh};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh4, BvhOptions, SplitMethod};
use bvhlab::structure::{BruteForce, RangeShape};
use bvhlab::{Aabb, Bvh, Hit, Ray, Sphere};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// How many rays and points a scene gets.
#[derive(Clone, Copy)]
struct Budget {
    rays: usize,
    points: usize,
}

/// What one scene's checks met, so that a test can tell its queries were not all trivial.
#[derive(Default)]
struct Seen {
    rays_hit: usize,
    multi_hits: usize,
    ranges_found: usize,
}

/// The binary tree, the wide tree collapsed from it and the wide tree built directly must
/// agree; the two wide trees are checked query by query.
fn check_scene<P: TestPrim>(
    name: &str,
    prims: &[P],
    options: &BvhOptions,
    rng: &mut ChaCha8Rng,
    budget: Budget,
) -> Seen {
    let mut split_log = bvhlab::Recorder::default();
    let binary = Bvh::<Aabb<P::Point>, P>::build_observed(prims, options, &mut split_log);
    let log = split_log.splits;
    let collapsed = Bvh4::from_bvh(&binary);
    let direct = Bvh4::build_with(prims, options);
    collapsed
        .validate()
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        collapsed, direct,
        "{name}: the direct build differs from the collapse"
    );
    let brute = BruteForce::build(prims);
    let mut seen = Seen::default();
    let mut rays = rays_for(rng, prims, &log, budget.rays);
    rays.extend(inside_rays(rng, prims, budget.rays / 4));
    for (i, ray) in rays.iter().enumerate() {
        let t_max = [f32::INFINITY, rng.random_range(0.0f32..1.5), 0.0][i % 3];
        check_ray(name, &direct, &binary, &brute, ray, t_max, &mut seen);
    }
    let (_, size) = scene_box(prims);
    for point in points_for(rng, prims, &log, budget.points) {
        check_point(name, &direct, &binary, &brute, point, size, rng, &mut seen);
    }
    seen
}

/// Rays from inside primitives' boxes (their centroids, so inside every box up to the root),
/// half of them along an axis.
fn inside_rays<P: Primitive>(rng: &mut ChaCha8Rng, prims: &[P], n: usize) -> Vec<Ray<P::Point>> {
    let (_, size) = scene_box(prims);
    (0..n)
        .filter(|_| !prims.is_empty())
        .filter_map(|i| {
            let origin = prims[rng.random_range(0..prims.len())].centroid();
            let dir = if i % 2 == 0 {
                random_vector::<P::Point>(rng, size)
            } else {
                P::Point::unit_axis(rng.random_range(0..P::Point::DIM))
            };
            Ray::new(origin, dir).ok()
        })
        .collect()
}

/// Checks one ray's first, any and all hits.
fn check_ray<P: Primitive>(
    name: &str,
    wide: &Bvh4<P>,
    binary: &Bvh<Aabb<P::Point>, P>,
    brute: &BruteForce<P>,
    ray: &Ray<P::Point>,
    t_max: f32,
    seen: &mut Seen,
) {
    let prims = brute.primitives();
    let what = || format!("{name}: {ray:?}, t_max {t_max}");
    assert_eq!(
        wide.ray_first_hit(ray, t_max),
        binary.ray_first_hit(ray, t_max),
        "{}: first hit",
        what()
    );
    let all = wide.ray_all_hits(ray, t_max);
    assert_eq!(all, binary.ray_all_hits(ray, t_max), "{}: all hits", what());
    let plausible = |h: &Hit| plausible_hit(&prims[h.prim], ray, h.t);
    let keep = |hits: &[Hit]| hits.iter().copied().filter(plausible).collect::<Vec<_>>();
    let want = brute.ray_all_hits(ray, t_max);
    assert_eq!(
        keep(&all),
        keep(&want),
        "{}: all hits vs brute force",
        what()
    );
    let any = wide.ray_any_hit(ray, t_max);
    assert_eq!(
        any.is_some(),
        binary.ray_any_hit(ray, t_max).is_some(),
        "{}: any hit {any:?}",
        what()
    );
    if let Some(h) = any {
        assert!(
            all.contains(&h),
            "{}: any hit {h:?} is not among all hits {all:?}",
            what()
        );
    }
    seen.rays_hit += usize::from(any.is_some());
    seen.multi_hits += usize::from(all.len() > 1);
}

/// Checks the k nearest to one point, and a ball and a box range around it.
#[expect(
    clippy::too_many_arguments,
    reason = "a test helper, each argument named"
)]
fn check_point<P: Primitive>(
    name: &str,
    wide: &Bvh4<P>,
    binary: &Bvh<Aabb<P::Point>, P>,
    brute: &BruteForce<P>,
    point: P::Point,
    size: f32,
    rng: &mut ChaCha8Rng,
    seen: &mut Seen,
) {
    // Up to every primitive and beyond on small scenes only: the k best are kept in a sorted
    // vector, so brute force's k nearest costs up to k per primitive.
    let count = brute.primitives().len();
    let ks: &[usize] = if count <= 400 {
        &[1, 2, 5, count, count + 3]
    } else {
        &[1, 2, 5, 24]
    };
    for &k in ks {
        let got = wide.k_nearest(point, k);
        assert_eq!(
            got,
            binary.k_nearest(point, k),
            "{name}: {k} nearest to {point:?}"
        );
        assert_eq!(
            got,
            brute.k_nearest(point, k),
            "{name}: {k} nearest, brute force"
        );
        assert!(got.len() <= k, "{name}: {k} nearest of {count}");
    }
    assert_eq!(
        wide.k_nearest(point, 1).first().copied(),
        wide.closest_point(point),
        "{name}: one nearest and the closest point"
    );
    let ball = RangeShape::Ball(Sphere::new(point, rng.random_range(0.0..0.3) * size));
    let corner = point + random_vector::<P::Point>(rng, 0.3 * size);
    let boxed = RangeShape::Box(Aabb::new(point.min(corner), point.max(corner)));
    let flat = {
        // A box of no thickness along one axis, through the point.
        let mut hi = point.max(corner);
        let axis = rng.random_range(0..P::Point::DIM);
        hi.set_coord(axis, point.coord(axis));
        RangeShape::Box(Aabb::new(point.min(corner), hi))
    };
    for shape in [ball, boxed, flat] {
        let got = wide.range(&shape);
        assert_eq!(got, binary.range(&shape), "{name}: range {shape:?}");
        assert_eq!(
            got,
            brute.range(&shape),
            "{name}: range {shape:?}, brute force"
        );
        seen.ranges_found += usize::from(!got.is_empty());
    }
}

/// The default options, big leaves costed by blocks of four (what `Bvh4::build` uses over
/// triangles, whose leaves it keeps in blocks; the other primitives one per slot) and the
/// spatial median.
fn option_sets() -> [(&'static str, BvhOptions); 3] {
    [
        ("binned SAH", BvhOptions::default()),
        ("blocks of four", BvhOptions::for_triangle_blocks()),
        (
            "spatial median",
            BvhOptions::with_method(SplitMethod::SpatialMedian),
        ),
    ]
}

fn check_degenerate<P: TestPrim>(seed: u64) {
    let mut r = rng(seed);
    for (scene, prims) in degenerate::<P>(&mut r) {
        for (label, options) in option_sets() {
            let name = format!("{scene} ({label})");
            let seen = check_scene(
                &name,
                &prims,
                &options,
                &mut r,
                Budget {
                    rays: 60,
                    points: 20,
                },
            );
            if prims.len() > 10 && scene == "random" {
                assert!(seen.rays_hit > 0, "{name}: no ray hit anything");
                assert!(seen.ranges_found > 0, "{name}: every range was empty");
            }
        }
    }
}

#[test]
fn segments_2d_answer_as_brute_force_and_the_binary_tree() {
    check_degenerate::<Segment2>(401);
}

#[test]
fn triangles_3d_answer_as_brute_force_and_the_binary_tree() {
    check_degenerate::<Triangle3>(402);
}

/// Denser random scenes (deeper wide trees, full nodes), where rays cross many primitives.
#[test]
fn dense_random_scenes() {
    let mut r = rng(403);
    let segments: Vec<Segment2> = random(&mut r, 3000);
    let seen = check_scene(
        "3000 segments",
        &segments,
        &BvhOptions::default(),
        &mut r,
        Budget {
            rays: 300,
            points: 60,
        },
    );
    assert!(seen.multi_hits > 10, "few rays crossed several segments");
    let triangles: Vec<Triangle3> = random(&mut r, 3000);
    let seen = check_scene(
        "3000 triangles",
        &triangles,
        &BvhOptions::default(),
        &mut r,
        Budget {
            rays: 300,
            points: 60,
        },
    );
    assert!(seen.multi_hits > 10, "few rays crossed several triangles");
}

#[test]
fn real_meshes_answer_as_brute_force_and_the_binary_tree() {
    for (seed, mesh) in [
        (411, "suzanne.obj"),
        (412, "teapot.obj"),
        (413, "fandisk.obj"),
        (414, "spot.obj"),
        (415, "stanford-bunny.obj"),
    ] {
        let Some(tris) = shared_mesh(mesh) else {
            continue;
        };
        let mut r = rng(seed);
        let seen = check_scene(
            mesh,
            &tris,
            &BvhOptions::default(),
            &mut r,
            Budget {
                rays: 90,
                points: 16,
            },
        );
        assert!(seen.rays_hit > 0, "{mesh}: no ray hit the mesh");
        assert!(
            seen.multi_hits > 0,
            "{mesh}: no ray crossed the surface twice"
        );
    }
}

/// An empty tree answers nothing; a NaN `t_max`, a NaN point, `k = 0` and an empty region
/// nothing either.
#[test]
fn empty_trees_and_empty_questions() {
    let empty = Bvh4::<Triangle3>::build(&[]);
    assert!(empty.is_empty());
    let ray = Ray3::new(Vec3::ZERO, Vec3::X).expect("a ray");
    assert_eq!(empty.ray_any_hit(&ray, f32::INFINITY), None);
    assert!(empty.ray_all_hits(&ray, f32::INFINITY).is_empty());
    assert!(empty.k_nearest(Vec3::ZERO, 3).is_empty());
    let everything = RangeShape::Box(Aabb::new(Vec3::splat(-1e30), Vec3::splat(1e30)));
    assert!(empty.range(&everything).is_empty());

    let wall = Triangle3::new(
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(1.0, 1.0, -1.0),
        Vec3::new(1.0, 0.0, 1.0),
    );
    let tree = Bvh4::build(&[wall, wall]);
    assert_eq!(
        tree.ray_any_hit(&ray, f32::INFINITY).map(|h| h.t),
        Some(1.0)
    );
    assert_eq!(tree.ray_all_hits(&ray, f32::INFINITY).len(), 2);
    assert_eq!(tree.ray_any_hit(&ray, f32::NAN), None);
    assert!(tree.ray_all_hits(&ray, f32::NAN).is_empty());
    assert_eq!(
        tree.ray_any_hit(&ray, 0.5),
        None,
        "the wall is beyond t_max"
    );
    assert_eq!(tree.ray_any_hit(&ray, -1.0), None);
    assert!(tree.k_nearest(Vec3::splat(f32::NAN), 1).is_empty());
    assert!(tree.k_nearest(Vec3::ZERO, 0).is_empty());
    let nearest = tree.k_nearest(Vec3::ZERO, 5);
    assert_eq!(
        nearest.iter().map(|n| n.prim).collect::<Vec<_>>(),
        [0, 1],
        "both, the tie by index"
    );
    assert_eq!(tree.range(&everything), [0, 1]);
    let inverted = RangeShape::Box(Aabb::new(Vec3::splat(1.0), Vec3::splat(-1.0)));
    assert!(tree.range(&inverted).is_empty());
    let no_ball = RangeShape::Ball(Sphere::new(Vec3::ZERO, -1.0));
    assert!(tree.range(&no_ball).is_empty());
    let touching = RangeShape::Ball(Sphere::new(Vec3::ZERO, 1.0));
    assert_eq!(
        tree.range(&touching),
        [0, 1],
        "a ball touching the wall holds it"
    );
}

/// A ray that starts on a primitive hits it at `t = 0`, which `t_max = 0` still admits; a
/// ray lying in the plane of a wall of segments, parallel to them, hits none of them but
/// the one it runs along.
#[test]
fn t_max_zero_and_parallel_rays() {
    let walls: Vec<Segment2> = (0..40)
        .map(|i| {
            let x = i as f32;
            Segment2::new(Vec2::new(x, -1.0), Vec2::new(x, 1.0))
        })
        .collect();
    let wide = Bvh4::build(&walls);
    let binary = AabbTree2::build(&walls);
    let on_wall = Ray2::new(Vec2::new(7.0, 0.0), Vec2::X).expect("a ray");
    let at_zero = wide
        .ray_any_hit(&on_wall, 0.0)
        .expect("the wall it starts on");
    assert_eq!((at_zero.prim, at_zero.t), (7, 0.0));
    assert_eq!(
        wide.ray_all_hits(&on_wall, 0.0),
        binary.ray_all_hits(&on_wall, 0.0)
    );
    assert_eq!(wide.ray_all_hits(&on_wall, 0.0).len(), 1);
    assert_eq!(
        wide.ray_all_hits(&on_wall, 2.5).len(),
        3,
        "walls 7, 8 and 9"
    );
    let along = Ray2::new(Vec2::new(12.0, -5.0), Vec2::Y).expect("a ray");
    let hits = wide.ray_all_hits(&along, f32::INFINITY);
    assert_eq!(hits, binary.ray_all_hits(&along, f32::INFINITY));
    assert_eq!(hits.iter().map(|h| h.prim).collect::<Vec<_>>(), [12]);
    let between = Ray2::new(Vec2::new(12.5, -5.0), Vec2::Y).expect("a ray");
    assert_eq!(wide.ray_any_hit(&between, f32::INFINITY), None);
    assert!(wide.ray_all_hits(&between, f32::INFINITY).is_empty());
}
