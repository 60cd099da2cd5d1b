//! Inserting, removing and moving primitives in an AABB tree (issue 20, "Moving geometry"):
//! after every step of seeded random sequences, in 2D and 3D, the tree validates, holds
//! exactly the primitives a plain `Vec` holds after the same steps (swap-remove indices),
//! and answers every query as brute force on them. Also: a mesh losing and regaining a
//! third of its triangles, the depth limit, errors, and the reinsertion pass that must
//! never raise the SAH cost.

use crate::bvh_common;

use bvh_common::{Budget, TestPrim, check_tree, random_vector, rng, shared_mesh};
use bvhlab::Vector;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh, BvhOptions, SplitMethod};
use bvhlab::structure::{Removed, UpdateError};
use bvhlab::volume::Aabb;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

type Tree<P> = Bvh<Aabb<<P as Primitive>::Point>, P>;

/// A tree beside the `Vec` it must mirror, and the queries that check it.
struct Mirror<P: TestPrim> {
    name: String,
    max_depth: usize,
    tree: Tree<P>,
    prims: Vec<P>,
    steps: usize,
    rays_hit: usize,
}

impl<P: TestPrim> Mirror<P> {
    fn new(name: &str, prims: Vec<P>, options: &BvhOptions) -> Self {
        Self {
            name: format!("{name}, {options:?}"),
            max_depth: options.max_depth,
            tree: Tree::<P>::build_with(&prims, options),
            prims,
            steps: 0,
            rays_hit: 0,
        }
    }

    fn insert(&mut self, prim: P) {
        let index = self.tree.insert(prim);
        assert_eq!(index, self.prims.len(), "{}: insert's index", self.name);
        self.prims.push(prim);
    }

    fn remove(&mut self, index: usize) {
        let removed = self.tree.remove(index).expect("in range");
        let last = self.prims.len() - 1;
        let want = Removed {
            prim: self.prims.swap_remove(index),
            moved_from: (index != last).then_some(last),
        };
        // Compared as text: a NaN primitive is not equal to itself.
        assert_eq!(format!("{removed:?}"), format!("{want:?}"), "{}", self.name);
    }

    fn replace(&mut self, index: usize, prim: P) {
        let old = self.tree.replace(index, prim).expect("in range");
        let want = std::mem::replace(&mut self.prims[index], prim);
        assert_eq!(format!("{old:?}"), format!("{want:?}"), "{}", self.name);
    }

    /// Validates, compares the primitives, and checks every query against brute force
    /// (a few queries after each step, more every `thorough` steps).
    fn check(&mut self, rng: &mut ChaCha8Rng, what: &str, thorough: bool) {
        self.steps += 1;
        let name = format!("{} after step {} ({what})", self.name, self.steps);
        self.tree
            .validate()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            format!("{:?}", self.tree.primitives()),
            format!("{:?}", self.prims),
            "{name}: the primitives"
        );
        let depth = self.tree.stats().max_depth;
        assert!(depth <= self.max_depth, "{name}: depth {depth}");
        let finite = self.prims.iter().filter(|p| is_finite(*p)).count();
        assert_eq!(self.tree.skipped(), self.prims.len() - finite, "{name}");
        let budget = if thorough {
            Budget {
                rays: 30,
                points: 10,
            }
        } else {
            Budget { rays: 6, points: 2 }
        };
        self.rays_hit += check_tree(&name, &self.tree, &self.prims, &[], rng, budget);
    }
}

fn is_finite<P: Primitive>(p: &P) -> bool {
    p.vertices().all(Vector::is_finite)
}

/// A random primitive, now and then one with a NaN vertex (kept, but left out of the tree).
fn random_prim<P: TestPrim>(rng: &mut ChaCha8Rng, extent: f32) -> P {
    let prim = P::random(rng, extent);
    if rng.random_range(0..25) == 0 {
        prim.map(|v| v * f32::NAN)
    } else {
        prim
    }
}

/// `steps` random inserts, removes and moves (replace; remove then insert; a jitter of every
/// primitive and a refit), checking after each.
fn random_sequence<P: TestPrim>(name: &str, options: &BvhOptions, seed: u64, steps: usize) {
    let mut rng = rng(seed);
    let extent = 10.0;
    let start: Vec<P> = (0..40).map(|_| random_prim(&mut rng, extent)).collect();
    let mut m = Mirror::new(name, start, options);
    m.check(&mut rng, "build", true);
    for step in 0..steps {
        let n = m.prims.len();
        let what = match rng.random_range(0..10) {
            0..=3 => {
                m.insert(random_prim(&mut rng, extent));
                "insert"
            }
            4..=6 if n > 0 => {
                m.remove(rng.random_range(0..n));
                "remove"
            }
            7 if n > 0 => {
                let i = rng.random_range(0..n);
                // Mostly a move; sometimes another primitive, now and then a NaN one (or a
                // NaN one made finite).
                let moved = if rng.random_bool(0.7) {
                    let shift = random_vector::<P::Point>(&mut rng, 0.3 * extent);
                    m.prims[i].map(|v| v + shift)
                } else {
                    random_prim(&mut rng, extent)
                };
                m.replace(i, moved);
                "replace (a move)"
            }
            8 if n > 0 => {
                // A move as a remove and an insert: the primitive gets the last index.
                let i = rng.random_range(0..n);
                let moved = m.prims[i].map(|v| v * 0.5);
                m.remove(i);
                m.insert(moved);
                "remove and insert (a move)"
            }
            _ if n > 0 => {
                let amount = 0.05 * extent;
                let jittered: Vec<P> = m
                    .prims
                    .iter()
                    .map(|p| {
                        let shift = random_vector::<P::Point>(&mut rng, amount);
                        p.map(|v| v + shift)
                    })
                    .collect();
                // Keep the NaN ones NaN: a refit keeps the set of indexed primitives.
                let jittered: Vec<P> = jittered
                    .into_iter()
                    .zip(&m.prims)
                    .map(|(j, p)| if is_finite(p) { j } else { *p })
                    .collect();
                m.tree.refit(&jittered).expect("the same primitives");
                m.prims = jittered;
                "refit (every primitive moves)"
            }
            _ => {
                m.insert(random_prim(&mut rng, extent));
                "insert"
            }
        };
        m.check(&mut rng, what, step % 20 == 0);
    }
    assert!(m.rays_hit > steps / 2, "{name}: too few rays hit anything");
    // Down to nothing, then back up.
    while !m.prims.is_empty() {
        let i = rng.random_range(0..m.prims.len());
        m.remove(i);
        m.check(&mut rng, "emptying", false);
    }
    assert!(
        m.tree.nodes().is_empty(),
        "{name}: an empty tree has no nodes"
    );
    for _ in 0..10 {
        m.insert(random_prim(&mut rng, extent));
        m.check(&mut rng, "refilling", false);
    }
}

fn option_sets() -> Vec<BvhOptions> {
    let median = BvhOptions::with_method(SplitMethod::SpatialMedian);
    vec![
        BvhOptions::default(),
        BvhOptions {
            leaf_size: 1,
            ..median
        },
        BvhOptions {
            leaf_size: 8,
            ..BvhOptions::default()
        },
        // Shallow: inserts must keep within two levels and grow leaves instead.
        BvhOptions {
            max_depth: 2,
            leaf_size: 2,
            ..BvhOptions::default()
        },
    ]
}

#[test]
fn segment_trees_stay_exact_through_random_inserts_removes_and_moves() {
    for (i, options) in option_sets().iter().enumerate() {
        random_sequence::<Segment2>("segments", options, 100 + i as u64, 150);
    }
}

#[test]
fn triangle_trees_stay_exact_through_random_inserts_removes_and_moves() {
    for (i, options) in option_sets().iter().enumerate() {
        random_sequence::<Triangle3>("triangles", options, 200 + i as u64, 150);
    }
}

#[test]
fn point_trees_stay_exact_through_random_inserts_removes_and_moves() {
    random_sequence::<Vec2>("2D points", &BvhOptions::default(), 300, 150);
    random_sequence::<Vec3>("3D points", &BvhOptions::default(), 301, 150);
}

#[test]
fn a_mesh_loses_and_regains_a_third_of_its_triangles() {
    let Some(mesh) = shared_mesh("suzanne.obj") else {
        return;
    };
    let mut rng = rng(400);
    let mut m = Mirror::new("suzanne", mesh.clone(), &BvhOptions::default());
    let built_cost = m.tree.sah_cost().expect("a cost");
    let mut taken = Vec::new();
    for _ in 0..mesh.len() / 3 {
        let i = rng.random_range(0..m.prims.len());
        taken.push(m.prims[i]);
        m.remove(i);
    }
    m.check(&mut rng, "a third removed", true);
    // Every query, on what is left, against brute force: also the rays through the holes.
    for prim in taken {
        m.insert(prim);
    }
    m.check(&mut rng, "all put back", true);
    let sorted = |v: &[Triangle3]| {
        let mut v: Vec<[f32; 9]> = v
            .iter()
            .map(|t| {
                let [a, b, c] = [t.a, t.b, t.c].map(|v| v.to_array());
                [a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]
            })
            .collect();
        v.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
        v
    };
    assert_eq!(
        sorted(m.tree.primitives()),
        sorted(&mesh),
        "the same triangles, in another order"
    );
    let cost = m.tree.sah_cost().expect("a cost");
    // A third of the tree was rebuilt greedily, one triangle at a time: worse than the
    // binned SAH build, but not wildly.
    assert!(
        cost < 2.0 * built_cost,
        "cost {cost} after reinsertion, {built_cost} built"
    );
}

#[test]
fn inserting_one_by_one_makes_a_tree_close_to_a_build() {
    let mut rng = rng(500);
    let prims: Vec<Triangle3> = (0..2000)
        .map(|_| Triangle3::random(&mut rng, 10.0))
        .collect();
    let mut tree = Tree::<Triangle3>::build(&[]);
    for p in &prims {
        tree.insert(*p);
    }
    tree.validate().expect("valid");
    let inserted = tree.sah_cost().expect("a cost");
    let built = Tree::<Triangle3>::build(&prims).sah_cost().expect("a cost");
    let median =
        Tree::<Triangle3>::build_with(&prims, &BvhOptions::with_method(SplitMethod::SpatialMedian));
    assert!(
        inserted < 1.2 * built,
        "inserted one by one: {inserted}, built: {built}, median {:?}",
        median.sah_cost()
    );
    check_tree("inserted", &tree, &prims, &[], &mut rng, Budget::default());
}

#[test]
fn sorted_inserts_keep_the_tree_within_its_depth_limit_and_close_to_a_build() {
    // Points along a line, in order: greedy insertion alone makes a long chain (each point
    // lands beside the root: depth 64, the limit, and 7.6 times the SAH cost of a build);
    // the rotations on the way up keep it as good as a build.
    for options in [
        BvhOptions::default(),
        BvhOptions {
            leaf_size: 1,
            max_depth: 6,
            ..BvhOptions::default()
        },
    ] {
        let mut tree = Tree::<Vec2>::build_with(&[], &options);
        let prims: Vec<Vec2> = (0..3000).map(|i| Vec2::new(i as f32, 0.0)).collect();
        for p in &prims {
            tree.insert(*p);
        }
        tree.validate().expect("valid");
        let stats = tree.stats();
        assert!(
            stats.max_depth <= options.max_depth.min(64),
            "{options:?}: depth {}",
            stats.max_depth
        );
        // Within a depth of 6 the leaves must take what no new leaf can, and the last
        // leaves grow large: that is within the limit, not close to a build.
        if options == BvhOptions::default() {
            let built = Tree::<Vec2>::build_with(&prims, &options);
            let (cost, built_cost) = (tree.sah_cost(), built.sah_cost());
            assert!(
                cost.expect("a cost") < 1.2 * built_cost.expect("a cost"),
                "inserted {cost:?}, built {built_cost:?}"
            );
        }
        let mut rng = rng(600);
        check_tree("a line", &tree, &prims, &[], &mut rng, Budget::default());
    }
}

#[test]
fn updates_of_missing_primitives_are_refused_and_change_nothing() {
    let mut rng = rng(700);
    let prims: Vec<Triangle3> = (0..30).map(|_| Triangle3::random(&mut rng, 10.0)).collect();
    let mut tree = Tree::<Triangle3>::build(&prims);
    let before = tree.clone();
    assert_eq!(
        tree.remove(30),
        Err(UpdateError::NoSuchPrimitive { index: 30, len: 30 })
    );
    let err = tree.replace(99, prims[0]).expect_err("no primitive 99");
    assert!(err.to_string().contains("99"), "{err}");
    assert_eq!(tree, before);
    // The last primitive's removal moves nothing.
    let removed = tree.remove(29).expect("in range");
    assert_eq!((removed.prim, removed.moved_from), (prims[29], None));
}

/// Reinsertion passes on a tree built with `options`: valid, the same primitives at the
/// same indices, every query as brute force, and the SAH cost never higher; with `gain`,
/// lower by at least that share.
fn check_optimization<P: TestPrim>(
    name: &str,
    prims: &[P],
    options: &BvhOptions,
    gain: Option<f32>,
    seed: u64,
) {
    let name = format!("{name}, {options:?}");
    let mut rng = rng(seed);
    let mut tree = Tree::<P>::build_with(prims, options);
    let before = tree.sah_cost().expect("a cost");
    let report = tree.optimize_by_reinsertion(30);
    tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(report.sah_before, Some(before), "{name}");
    assert_eq!(report.sah_after, tree.sah_cost(), "{name}: {report:?}");
    let after = report.sah_after.expect("a cost");
    assert!(after <= before, "{name}: {report:?}");
    if let Some(gain) = gain {
        assert!(
            after < (1.0 - gain) * before && report.passes > 0 && report.reinserted > 0,
            "{name}: expected {gain} lower: {report:?}"
        );
    }
    assert_eq!(tree.primitives(), prims, "{name}: indices kept");
    check_tree(&name, &tree, prims, &[], &mut rng, Budget::default());
    // Again on the result: still never worse.
    let again = tree.optimize_by_reinsertion(5);
    assert!(again.sah_after <= again.sah_before, "{name}: {again:?}");
    assert_eq!(again.sah_after, tree.sah_cost(), "{name}");
    tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
}

#[test]
fn reinsertion_lowers_the_sah_cost_and_never_raises_it() {
    let mut rng = rng(800);
    let segments: Vec<Segment2> = (0..800).map(|_| Segment2::random(&mut rng, 10.0)).collect();
    let triangles: Vec<Triangle3> = (0..800)
        .map(|_| Triangle3::random(&mut rng, 10.0))
        .collect();
    let mesh = shared_mesh("suzanne.obj");
    // Trees of one primitive per leaf from the median splits leave the most to gain (Bittner
    // et al. report their largest gains on spatial-median trees); with leaves of four, the
    // leaves themselves are kept whole, so less moves. Every tree: never worse.
    for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
        let single = BvhOptions {
            leaf_size: 1,
            ..BvhOptions::with_method(method)
        };
        check_optimization("segments", &segments, &single, Some(0.03), 801);
        check_optimization("triangles", &triangles, &single, Some(0.03), 802);
        if let Some(mesh) = &mesh {
            check_optimization("suzanne", mesh, &single, Some(0.1), 803);
        }
    }
    for options in [
        BvhOptions::default(),
        BvhOptions::with_method(SplitMethod::SpatialMedian),
    ] {
        check_optimization("segments", &segments, &options, None, 804);
        check_optimization("triangles", &triangles, &options, None, 805);
    }
}

#[test]
fn reinsertion_of_a_tiny_or_flat_tree_changes_nothing() {
    let one = [Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
    for prims in [&one[..0], &one[..]] {
        let mut tree = Tree::<Triangle3>::build(prims);
        let before = tree.clone();
        let report = tree.optimize_by_reinsertion(3);
        assert_eq!((report.passes, report.reinserted), (0, 0), "{report:?}");
        assert_eq!(tree, before);
    }
    // Points on a line in 3D: every box is flat, so no SAH cost to lower.
    let line: Vec<Vec3> = (0..50).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    let mut tree = Tree::<Vec3>::build(&line);
    let report = tree.optimize_by_reinsertion(3);
    assert!(report.sah_after <= report.sah_before, "{report:?}");
    tree.validate().expect("valid");
}

#[test]
fn degenerate_scenes_stay_exact_when_inserted_one_by_one() {
    let mut rng = rng(900);
    let random: Vec<Triangle3> = (0..300)
        .map(|_| Triangle3::random(&mut rng, 10.0))
        .collect();
    let same = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let scenes: Vec<(&str, Vec<Triangle3>)> = vec![
        // Every box the same: every place costs the same.
        ("identical", vec![same; 300]),
        // Areas overflow f32 to infinity (and their differences to NaN).
        ("huge", random.iter().map(|t| t.map(|v| v * 1e19)).collect()),
        (
            "tiny",
            random.iter().map(|t| t.map(|v| v * 1e-12)).collect(),
        ),
        (
            "flat",
            random
                .iter()
                .map(|t| t.map(|v| Vec3::new(v.x, v.y, 0.5)))
                .collect(),
        ),
    ];
    for (name, prims) in scenes {
        let mut tree = Tree::<Triangle3>::build(&[]);
        for (i, p) in prims.iter().enumerate() {
            tree.insert(*p);
            if i % 60 == 0 {
                tree.validate()
                    .unwrap_or_else(|e| panic!("{name}, {i}: {e}"));
            }
        }
        tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        check_tree(name, &tree, &prims, &[], &mut rng, Budget::default());
        // Half of them out again, and a reinsertion pass.
        let mut left = prims.clone();
        for _ in 0..prims.len() / 2 {
            let i = rng.random_range(0..left.len());
            tree.remove(i).expect("in range");
            left.swap_remove(i);
        }
        let report = tree.optimize_by_reinsertion(3);
        assert!(report.sah_after <= report.sah_before, "{name}: {report:?}");
        tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        check_tree(name, &tree, &left, &[], &mut rng, Budget::default());
    }
}

#[test]
fn a_primitive_replaced_by_a_nan_one_leaves_the_tree_and_comes_back() {
    let mut rng = rng(1000);
    let prims: Vec<Triangle3> = (0..50).map(|_| Triangle3::random(&mut rng, 10.0)).collect();
    let mut m = Mirror::new("nan", prims.clone(), &BvhOptions::default());
    for i in [3, 17, 42] {
        m.replace(i, prims[i].map(|v| v * f32::NAN));
        m.check(&mut rng, "made NaN", true);
    }
    assert_eq!(m.tree.skipped(), 3);
    m.remove(17);
    m.check(&mut rng, "a NaN one removed", true);
    for i in [3, 42] {
        let moved = prims[i].map(|v| v + Vec3::ONE);
        m.replace(i, moved);
        m.check(&mut rng, "made finite again", true);
    }
    assert_eq!(m.tree.skipped(), 0);
    assert!(m.rays_hit > 0, "no ray hit anything");
}
