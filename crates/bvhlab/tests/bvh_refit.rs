//! Refit (issue 20, "Moving geometry"): after the primitives move (seeded jitter, rigid
//! translations and rotations, a sequence of both), every BVH and `Bvh4` refitted to them
//! validates (children inside parents, every primitive inside its leaf) and answers every
//! query as brute force on the moved primitives; the SAH cost is reported, and
//! `needs_rebuild` tells a scrambled tree from a translated one.

use crate::bvh_common;

use std::cell::RefCell;

use bvh_common::{Budget, TestPrim, check_tree, random_vector, rng, shared_mesh};
use bvhlab::glam::{DMat3, DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{Bvh, BvhOptions, NodeVolume, RefitError, SplitMethod};
use bvhlab::{Aabb, Obb, Sphere, Vector};
use rand_chacha::ChaCha8Rng;

/// A move of the whole scene, vertex by vertex.
type Move<V> = Box<dyn Fn(V) -> V>;

/// Seeded jitter: every vertex moved by up to `amount` on each axis.
fn jitter<P: TestPrim>(prims: &[P], seed: u64, amount: f32) -> Vec<P> {
    let rng = RefCell::new(rng(seed));
    prims
        .iter()
        .map(|p| p.map(|v| v + random_vector::<P::Point>(&mut rng.borrow_mut(), amount)))
        .collect()
}

/// A rigid motion: a rotation by `angle` about an axis (the z axis in 2D, a tilted one in
/// 3D) around the origin, then a translation.
fn rigid<V: Vector>(angle: f64, shift: V) -> Move<V> {
    let axis = if V::DIM == 2 {
        DVec3::Z
    } else {
        DVec3::new(1.0, 2.0, -0.5).normalize()
    };
    let rotation = DMat3::from_axis_angle(axis, angle);
    Box::new(move |v: V| V::from_dvec3(rotation * v.to_dvec3()) + shift)
}

fn moved<P: TestPrim>(prims: &[P], motion: &Move<P::Point>) -> Vec<P> {
    prims.iter().map(|p| p.map(motion)).collect()
}

/// Refits `bvh` to `prims`, validates it and checks every query against brute force on
/// `prims`; returns the SAH cost after the refit.
fn refit_and_check<B, P>(
    name: &str,
    bvh: &mut Bvh<B, P>,
    prims: &[P],
    rng: &mut ChaCha8Rng,
) -> Option<f32>
where
    B: NodeVolume<Point = P::Point>,
    P: TestPrim,
{
    let name = format!("{name} ({} tree)", B::NAME);
    let report = bvh
        .refit(prims)
        .unwrap_or_else(|e| panic!("{name}: refit refused: {e}"));
    assert_eq!(
        report.sah_cost,
        bvh.stats().sah_cost,
        "{name}: reported cost"
    );
    assert_eq!(report.build_sah_cost, bvh.build_sah_cost(), "{name}");
    bvh.validate()
        .unwrap_or_else(|e| panic!("{name}: after refit: {e}"));
    assert_eq!(
        bvh.primitives(),
        prims,
        "{name}: the tree holds the moved primitives"
    );
    let budget = Budget {
        rays: 40,
        points: 16,
    };
    let hit = check_tree(&name, bvh, prims, &[], rng, budget);
    assert!(
        hit > 0,
        "{name}: no ray hit anything, the check proved little"
    );
    // Collision of two refitted trees: the moved scene against itself shifted a little.
    let shift = random_vector::<P::Point>(rng, 0.5);
    let other_prims: Vec<P> = prims.iter().map(|p| p.map(|v| v + shift)).collect();
    let mut other = Bvh::<B, P>::build(prims);
    other.refit(&other_prims).expect("same primitives");
    assert_eq!(
        bvh.collide(&other),
        BruteForce::build(prims).collide(&BruteForce::build(&other_prims)),
        "{name}: collision after refit"
    );
    report.sah_cost
}

/// A `Bvh4` refitted along with the binary tree: valid, and the same first hits and closest
/// points as brute force on the moved primitives.
fn refit_and_check_wide<P: TestPrim>(
    name: &str,
    wide: &mut Bvh4<P>,
    prims: &[P],
    rng: &mut ChaCha8Rng,
) {
    let report = wide
        .refit(prims)
        .unwrap_or_else(|e| panic!("{name}: Bvh4 refit refused: {e}"));
    assert_eq!(report.sah_cost, wide.sah_cost(), "{name}");
    wide.validate()
        .unwrap_or_else(|e| panic!("{name}: Bvh4 after refit: {e}"));
    let brute = BruteForce::build(prims);
    let rays = bvh_common::rays_for(rng, prims, &[], 60);
    let mut hits = 0;
    for ray in &rays {
        for t_max in [f32::INFINITY, 0.5] {
            let want = brute.ray_first_hit(ray, t_max);
            let got = wide.ray_first_hit(ray, t_max);
            if got != want {
                // A tie at equal t may go either way only if both are real hits at that t.
                let tie = matches!((got, want), (Some(g), Some(w)) if g.t == w.t
                    && prims[g.prim].ray_hit(ray) == Some(g.t));
                assert!(
                    tie,
                    "{name}: Bvh4 first hit {got:?}, brute force {want:?}, {ray:?}"
                );
            }
            hits += usize::from(want.is_some());
        }
    }
    assert!(hits > 0, "{name}: no ray hit anything");
    for point in bvh_common::points_for(rng, prims, &[], 30) {
        assert_eq!(
            wide.closest_point(point),
            brute.closest_point(point),
            "{name}: Bvh4 closest point to {point:?}"
        );
    }
}

/// Builds every tree over `prims`, then moves them through `steps` (each a full scene),
/// refitting and checking after every step.
fn check_moves<P: TestPrim>(name: &str, prims: &[P], steps: &[(&str, Vec<P>)], seed: u64) {
    let mut rng = rng(seed);
    for method in [SplitMethod::BinnedSah, SplitMethod::SpatialMedian] {
        let options = BvhOptions::with_method(method);
        let mut aabb = Bvh::<Aabb<P::Point>, P>::build_with(prims, &options);
        let mut sphere = Bvh::<Sphere<P::Point>, P>::build_with(prims, &options);
        let mut obb = Bvh::<Obb<P::Point>, P>::build_with(prims, &options);
        let mut wide = Bvh4::build_with(prims, &options);
        assert!(
            !aabb.needs_rebuild(1.0) && !wide.needs_rebuild(1.0),
            "{name}: fresh trees"
        );
        for (step, moved) in steps {
            let name = format!("{name}, {method:?}, after {step}");
            refit_and_check(&name, &mut aabb, moved, &mut rng);
            refit_and_check(&name, &mut sphere, moved, &mut rng);
            refit_and_check(&name, &mut obb, moved, &mut rng);
            refit_and_check_wide(&name, &mut wide, moved, &mut rng);
        }
    }
}

/// The moves every scene goes through, one after another: jitter, a rigid rotation and
/// translation, jitter again on top, and back to the start.
fn moves_of<P: TestPrim>(prims: &[P], extent: f32, seed: u64) -> Vec<(&'static str, Vec<P>)> {
    let jittered = jitter(prims, seed, 0.05 * extent);
    let shift = P::Point::splat(0.3 * extent);
    let turned = moved(&jittered, &rigid(0.7, shift));
    let jittered_again = jitter(&turned, seed + 1, 0.1 * extent);
    vec![
        ("jitter", jittered),
        ("a rotation and translation", turned),
        ("more jitter", jittered_again),
        ("moving back", prims.to_vec()),
    ]
}

fn random_scene<P: TestPrim>(seed: u64, n: usize, extent: f32) -> Vec<P> {
    let mut rng = rng(seed);
    (0..n).map(|_| P::random(&mut rng, extent)).collect()
}

#[test]
fn refitted_segment_trees_answer_as_brute_force_on_the_moved_segments() {
    let prims: Vec<Segment2> = random_scene(1, 300, 10.0);
    check_moves("segments", &prims, &moves_of(&prims, 10.0, 2), 3);
}

#[test]
fn refitted_triangle_trees_answer_as_brute_force_on_the_moved_triangles() {
    let prims: Vec<Triangle3> = random_scene(4, 300, 10.0);
    check_moves("triangles", &prims, &moves_of(&prims, 10.0, 5), 6);
}

#[test]
fn refitted_point_trees_answer_as_brute_force_on_the_moved_points() {
    let points2: Vec<Vec2> = random_scene(7, 300, 10.0);
    check_moves("2D points", &points2, &moves_of(&points2, 10.0, 8), 9);
    let points3: Vec<Vec3> = random_scene(10, 300, 10.0);
    check_moves("3D points", &points3, &moves_of(&points3, 10.0, 11), 12);
}

#[test]
fn a_refitted_mesh_answers_as_brute_force_after_it_moves() {
    let Some(mesh) = shared_mesh("suzanne.obj") else {
        return;
    };
    let (bounds, extent) = bvh_common::scene_box(&mesh);
    assert!(mesh.len() > 500, "suzanne has {} triangles", mesh.len());
    let center = bounds.center();
    // A twist about the vertical axis through the mesh's centre, growing with height: a
    // deformation, not a rigid motion.
    let twisted: Vec<Triangle3> = mesh
        .iter()
        .map(|t| {
            t.map(|v| {
                let p = (v - center).as_dvec3();
                let turn = DMat3::from_rotation_y(p.y / f64::from(extent) * 1.5);
                (turn * p).as_vec3() + center
            })
        })
        .collect();
    let mut steps = moves_of(&mesh, extent, 13);
    steps.insert(2, ("a twist", twisted));
    check_moves("suzanne", &mesh, &steps, 14);
}

#[test]
fn refit_reports_the_sah_cost_and_needs_rebuild_tells_translation_from_scrambling() {
    let prims: Vec<Triangle3> = random_scene(15, 2000, 10.0);
    let mut tree = AabbTree3::build(&prims);
    let mut wide = Bvh4::build(&prims);
    let built = tree.build_sah_cost().expect("a cost");
    assert_eq!(Some(built), tree.stats().sah_cost);
    // A pure translation keeps every box's shape: the cost stays (up to rounding).
    let shifted = moved(&prims, &rigid(0.0, Vec3::new(3.0, -2.0, 5.0)));
    let report = tree.refit(&shifted).expect("refit");
    let ratio = report.cost_ratio().expect("both costs");
    assert!(
        (ratio - 1.0).abs() < 1e-3,
        "translation changed the cost by {ratio}"
    );
    assert!(!report.needs_rebuild(1.2) && !tree.needs_rebuild(1.2));
    wide.refit(&shifted).expect("refit");
    assert!(!wide.needs_rebuild(1.2), "{:?}", wide.refit_report());
    // Scrambling: every triangle moves to another's place, so the topology groups
    // primitives that are now far apart.
    let mut rng = rng(16);
    let scrambled: Vec<Triangle3> = shifted
        .iter()
        .map(|t| {
            let to = random_vector::<Vec3>(&mut rng, 10.0);
            t.map(|v| v - t.a + to)
        })
        .collect();
    let report = tree.refit(&scrambled).expect("refit");
    tree.validate().expect("valid after scrambling");
    assert!(
        report.cost_ratio().expect("both costs") > 2.0 && tree.needs_rebuild(1.5),
        "{report:?}"
    );
    let rebuilt = AabbTree3::build(&scrambled);
    assert!(
        rebuilt.stats().sah_cost.expect("cost") < report.sah_cost.expect("cost"),
        "a rebuild must pay when needs_rebuild says so"
    );
    wide.refit(&scrambled).expect("refit");
    wide.validate().expect("valid");
    assert!(wide.needs_rebuild(1.5), "{:?}", wide.refit_report());
}

#[test]
fn refit_refuses_a_different_set_of_primitives_and_leaves_the_tree_unchanged() {
    let mut prims: Vec<Triangle3> = random_scene(17, 50, 10.0);
    prims[7].b = Vec3::NAN; // left out of the tree
    let mut tree = SphereTree3::build(&prims);
    let mut wide = Bvh4::build(&prims);
    let (tree_before, wide_before) = (tree.clone(), wide.clone());

    let fewer = &prims[..49];
    assert_eq!(
        tree.refit(fewer),
        Err(RefitError::LengthChanged {
            built: 50,
            given: 49
        })
    );
    assert!(matches!(
        wide.refit(fewer),
        Err(RefitError::LengthChanged { .. })
    ));

    let mut now_finite = prims.clone();
    now_finite[7].b = Vec3::ONE;
    let expected = RefitError::IndexableChanged {
        prim: 7,
        finite_now: true,
    };
    assert_eq!(tree.refit(&now_finite), Err(expected.clone()));
    assert_eq!(wide.refit(&now_finite), Err(expected));

    let mut now_nan = prims.clone();
    now_nan[3].c = Vec3::new(0.0, f32::INFINITY, 0.0);
    let err = tree
        .refit(&now_nan)
        .expect_err("a primitive became infinite");
    assert!(
        err.to_string().contains("primitive 3") && err.to_string().contains("rebuild"),
        "{err}"
    );
    assert!(wide.refit(&now_nan).is_err());

    // Compared as text: primitive 7's NaN is not equal to itself.
    let same =
        |a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| format!("{a:?}") == format!("{b:?}");
    assert!(
        same(&tree, &tree_before),
        "a refused refit changed the tree"
    );
    assert!(
        same(&wide, &wide_before),
        "a refused refit changed the Bvh4"
    );
    // The same primitives refit fine, and the left-out one stays out.
    let report = tree.refit(&prims).expect("the same set");
    assert_eq!(tree.skipped(), 1);
    assert!(report.sah_cost.is_some());
    wide.refit(&prims).expect("the same set");
    wide.validate().expect("valid");
}
