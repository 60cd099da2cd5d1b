//! Saved trees (`bvhlab::saved`, the `serde` feature): every structure, in 2D and 3D, over
//! seeded random data and a real mesh, loads back equal to what was saved and answers every
//! query as the original and as brute force do; and files that are not what they claim (wrong
//! magic, version or kind, cut at every length, single bytes changed) are refused with an
//! error or load into a tree that passes its check and answers as brute force, never a panic.

#![cfg(feature = "serde")]

use std::fmt::Debug;
use std::path::PathBuf;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::saved::{self, LoadError, Saved};
use bvhlab::structure::{BruteForce, Hit, PointOf, RangeShape};
use bvhlab::{Aabb, Bvh, Grid, KdTree, Orthtree, Ray, Sphere};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A point in `[-1, 11)^D`: around the random scenes, which fill `[0, 10]^D`.
fn random_vector<V: Vector>(rng: &mut ChaCha8Rng) -> V {
    let mut v = V::ZERO;
    for axis in 0..V::DIM {
        v.set_coord(axis, rng.random_range(-1.0..11.0));
    }
    v
}

fn random_segments(rng: &mut ChaCha8Rng, n: usize) -> Vec<Segment2> {
    (0..n)
        .map(|_| {
            let a = random_vector::<Vec2>(rng) * 0.9 + Vec2::splat(0.5);
            Segment2::new(a, a + (random_vector::<Vec2>(rng) - Vec2::splat(5.0)) * 0.2)
        })
        .collect()
}

fn random_triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<Triangle3> {
    (0..n)
        .map(|_| {
            let a = random_vector::<Vec3>(rng) * 0.9 + Vec3::splat(0.5);
            let mut corner = || a + (random_vector::<Vec3>(rng) - Vec3::splat(5.0)) * 0.2;
            Triangle3::new(a, corner(), corner())
        })
        .collect()
}

fn random_points<V: Vector>(rng: &mut ChaCha8Rng, n: usize) -> Vec<V> {
    (0..n).map(|_| random_vector(rng)).collect()
}

/// A ray from a random point towards another (aimed at the scene, so most hit something).
fn random_ray<V: Vector>(rng: &mut ChaCha8Rng, scale: f32, center: V) -> Option<Ray<V>> {
    let from = (random_vector::<V>(rng) - V::splat(5.0)) * (scale * 0.4) + center;
    let to = (random_vector::<V>(rng) - V::splat(5.0)) * (scale * 0.05) + center;
    Ray::new(from, to - from).ok()
}

fn random_range<V: Vector>(rng: &mut ChaCha8Rng, scale: f32, center: V) -> RangeShape<V> {
    let c = (random_vector::<V>(rng) - V::splat(5.0)) * (scale * 0.1) + center;
    let r = rng.random_range(0.0..0.2) * scale;
    if rng.random_bool(0.5) {
        RangeShape::Box(Aabb::new(c - V::splat(r), c + V::splat(r)))
    } else {
        RangeShape::Ball(Sphere::new(c, r))
    }
}

/// The scene's centre and size, for queries at its scale.
fn frame<P: Primitive>(prims: &[P]) -> (P::Point, f32) {
    let bounds = prims
        .iter()
        .filter(|p| p.has_finite_coordinates())
        .map(Primitive::bounds)
        .reduce(|a, b| a.merge(&b))
        .expect("a scene with primitives");
    let size = (bounds.max - bounds.min).max_element().max(1e-3);
    ((bounds.min + bounds.max) * 0.5, size)
}

/// Two first hits agree: the same primitive, or a tie at the same `t` (to 1e-5, as the
/// other structure tests allow).
fn same_first_hit(a: Option<Hit>, b: Option<Hit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => a.prim == b.prim || (a.t - b.t).abs() <= 1e-5 * a.t.abs().max(1.0),
        _ => false,
    }
}

/// `loaded` answers `queries` random rays, points and ranges exactly as `original` does, and
/// as brute force over the same primitives does.
fn check_answers<S>(name: &str, original: &S, loaded: &S, rng: &mut ChaCha8Rng, queries: usize)
where
    S: SpatialIndex,
{
    // (Equal primitives are `round_trip`'s to check: here `original` may be `loaded` itself,
    // with a NaN that equals nothing.)
    let prims = loaded.primitives();
    if prims.is_empty() {
        return;
    }
    let brute = BruteForce::build(prims);
    let (center, scale) = frame(prims);
    for q in 0..queries {
        if let Some(ray) = random_ray::<PointOf<S>>(rng, scale, center) {
            let first = loaded.ray_first_hit(&ray, f32::INFINITY);
            assert_eq!(
                first,
                original.ray_first_hit(&ray, f32::INFINITY),
                "{name}: first hit {q}"
            );
            assert!(
                same_first_hit(first, brute.ray_first_hit(&ray, f32::INFINITY)),
                "{name}: first hit {q} against brute force"
            );
            let any = loaded.ray_any_hit(&ray, f32::INFINITY);
            assert_eq!(
                any,
                original.ray_any_hit(&ray, f32::INFINITY),
                "{name}: any hit {q}"
            );
            assert_eq!(
                any.is_some(),
                first.is_some(),
                "{name}: any hit {q} against first hit"
            );
            let all = loaded.ray_all_hits(&ray, f32::INFINITY);
            assert_eq!(
                all,
                original.ray_all_hits(&ray, f32::INFINITY),
                "{name}: all hits {q}"
            );
            assert_eq!(
                all,
                brute.ray_all_hits(&ray, f32::INFINITY),
                "{name}: all hits {q} against brute force"
            );
        }
        let point =
            (random_vector::<PointOf<S>>(rng) - PointOf::<S>::splat(5.0)) * (scale * 0.15) + center;
        let nearest = loaded.k_nearest(point, 3);
        assert_eq!(
            nearest,
            original.k_nearest(point, 3),
            "{name}: 3 nearest {q}"
        );
        assert_eq!(
            nearest,
            brute.k_nearest(point, 3),
            "{name}: 3 nearest {q} against brute force"
        );
        let shape = random_range::<PointOf<S>>(rng, scale, center);
        let found = loaded.range(&shape);
        assert_eq!(found, original.range(&shape), "{name}: range {q}");
        assert_eq!(
            found,
            brute.range(&shape),
            "{name}: range {q} against brute force"
        );
    }
}

/// Builds `S` over `prims`, saves it, loads it back, and checks the copy: equal to the
/// original, the same statistics, a valid tree, the same answers. Returns the file's size.
fn round_trip<S>(name: &str, prims: &[S::Prim], rng: &mut ChaCha8Rng, queries: usize) -> usize
where
    S: SpatialIndex + Saved + Debug,
{
    let original = S::build(prims);
    let bytes = saved::save(&original).expect("saves");
    let loaded: S = saved::load(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    // Saved again, the same bytes: equal bit for bit (`==` would refuse a NaN coordinate).
    assert!(
        saved::save(&loaded).expect("saves") == bytes,
        "{name}: the loaded tree differs from the saved one"
    );
    // Memory counts capacity, which a build and a load each leave as their vectors grew.
    let (stats, saved_stats) = (loaded.stats(), original.stats());
    let same_memory = |s: bvhlab::Stats| bvhlab::Stats {
        memory_bytes: 0,
        ..s
    };
    assert_eq!(
        same_memory(stats),
        same_memory(saved_stats),
        "{name}: stats"
    );
    loaded.validate().expect("a loaded tree is valid");
    check_answers(name, &original, &loaded, rng, queries);
    bytes.len()
}

/// [`round_trip`] for the 4-wide tree, which has its own query methods.
fn round_trip_bvh4<P>(name: &str, prims: &[P], rng: &mut ChaCha8Rng, queries: usize) -> usize
where
    P: saved::SavedPrimitive + Debug,
{
    let original = Bvh4::build(prims);
    let bytes = saved::save(&original).expect("saves");
    let loaded: Bvh4<P> = saved::load(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        saved::save(&loaded).expect("saves") == bytes,
        "{name}: the loaded tree differs from the saved one"
    );
    loaded.validate().expect("a loaded tree is valid");
    if prims.is_empty() {
        return bytes.len();
    }
    let brute = BruteForce::build(prims);
    let (center, scale) = frame(prims);
    for q in 0..queries {
        if let Some(ray) = random_ray::<P::Point>(rng, scale, center) {
            let first = loaded.ray_first_hit(&ray, f32::INFINITY);
            assert_eq!(
                first,
                original.ray_first_hit(&ray, f32::INFINITY),
                "{name}: first hit {q}"
            );
            assert!(
                same_first_hit(first, brute.ray_first_hit(&ray, f32::INFINITY)),
                "{name}: first hit {q} against brute force"
            );
            let any = loaded.ray_any_hit(&ray, f32::INFINITY);
            assert_eq!(
                any,
                original.ray_any_hit(&ray, f32::INFINITY),
                "{name}: any hit {q}"
            );
            assert_eq!(
                loaded.ray_all_hits(&ray, f32::INFINITY),
                brute.ray_all_hits(&ray, f32::INFINITY),
                "{name}: all hits {q}"
            );
        }
        let point =
            (random_vector::<P::Point>(rng) - P::Point::splat(5.0)) * (scale * 0.15) + center;
        assert_eq!(
            loaded.k_nearest(point, 3),
            brute.k_nearest(point, 3),
            "{name}: 3 nearest {q}"
        );
        assert_eq!(
            loaded.closest_point(point),
            original.closest_point(point),
            "{name}: closest {q}"
        );
        let shape = random_range::<P::Point>(rng, scale, center);
        assert_eq!(
            loaded.range(&shape),
            brute.range(&shape),
            "{name}: range {q}"
        );
    }
    bytes.len()
}

/// Every structure over one set of primitives (and its 4-wide tree when `wide`).
macro_rules! every_structure {
    ($prim:ty, $prims:expr, $rng:expr, $queries:expr, $label:expr) => {{
        let (prims, rng, queries, label): (&[$prim], &mut ChaCha8Rng, usize, &str) =
            ($prims, $rng, $queries, $label);
        round_trip::<Bvh<Aabb<<$prim as Primitive>::Point>, $prim>>(
            &format!("{label} AABB tree"),
            prims,
            rng,
            queries,
        );
        round_trip::<Bvh<Sphere<<$prim as Primitive>::Point>, $prim>>(
            &format!("{label} sphere tree"),
            prims,
            rng,
            queries,
        );
        round_trip::<Bvh<bvhlab::Obb<<$prim as Primitive>::Point>, $prim>>(
            &format!("{label} OBB tree"),
            prims,
            rng,
            queries,
        );
        round_trip_bvh4::<$prim>(&format!("{label} Bvh4"), prims, rng, queries);
        round_trip::<KdTree<$prim>>(&format!("{label} k-d tree"), prims, rng, queries);
        round_trip::<bvhlab::BspTree<$prim>>(&format!("{label} BSP tree"), prims, rng, queries);
        round_trip::<Grid<$prim>>(&format!("{label} grid"), prims, rng, queries);
        round_trip::<Orthtree<$prim>>(&format!("{label} orthtree"), prims, rng, queries);
        round_trip::<BruteForce<$prim>>(&format!("{label} brute force"), prims, rng, queries);
    }};
}

#[test]
fn every_structure_over_random_segments_loads_and_answers_as_saved() {
    for (seed, n) in [(1, 1), (2, 40), (3, 300)] {
        let mut rng = rng(seed);
        let prims = random_segments(&mut rng, n);
        every_structure!(Segment2, &prims, &mut rng, 30, &format!("{n} segments"));
    }
}

#[test]
fn every_structure_over_random_triangles_loads_and_answers_as_saved() {
    for (seed, n) in [(11, 1), (12, 40), (13, 300)] {
        let mut rng = rng(seed);
        let prims = random_triangles(&mut rng, n);
        every_structure!(Triangle3, &prims, &mut rng, 30, &format!("{n} triangles"));
    }
}

#[test]
fn every_structure_over_random_points_loads_and_answers_as_saved() {
    let mut rng = rng(21);
    let points2: Vec<Vec2> = random_points(&mut rng, 300);
    every_structure!(Vec2, &points2, &mut rng, 30, "300 2D points");
    let points3: Vec<Vec3> = random_points(&mut rng, 300);
    every_structure!(Vec3, &points3, &mut rng, 30, "300 3D points");
}

#[test]
fn empty_structures_load() {
    let mut rng = rng(31);
    every_structure!(Segment2, &[], &mut rng, 0, "no segments");
}

/// A primitive with a NaN or infinite coordinate is never an answer, in a tree built or
/// loaded, and not from brute force either (issue 28: a loaded k-d tree over a point at
/// `z = -inf` answered nothing where brute force answered that point at distance `inf`).
#[test]
fn non_finite_primitives_load_and_are_never_answered() {
    let mut rng = rng(32);
    let mut triangles = random_triangles(&mut rng, 40);
    triangles[3].b.x = f32::NAN;
    triangles[7].c.z = f32::INFINITY;
    triangles[11].a.y = f32::NEG_INFINITY;
    every_structure!(
        Triangle3,
        &triangles,
        &mut rng,
        30,
        "40 triangles, 3 not finite"
    );
    let mut segments = random_segments(&mut rng, 40);
    segments[0].a = Vec2::splat(f32::INFINITY);
    segments[5].b.y = f32::NAN;
    every_structure!(
        Segment2,
        &segments,
        &mut rng,
        30,
        "40 segments, 2 not finite"
    );
    let mut points: Vec<Vec3> = random_points(&mut rng, 60);
    points[0] = Vec3::new(-0.0, 1.000_007_6, f32::NEG_INFINITY);
    points[9].x = f32::NAN;
    every_structure!(Vec3, &points, &mut rng, 30, "60 3D points, 2 not finite");
    let mut points: Vec<Vec2> = random_points(&mut rng, 60);
    points[59] = Vec2::new(f32::INFINITY, f32::NEG_INFINITY);
    every_structure!(Vec2, &points, &mut rng, 30, "60 2D points, 1 not finite");

    let file = saved::save(&KdTree::build(&points3_at_infinity())).expect("saves");
    let tree = saved::load::<KdTree<Vec3>>(&file).expect("loads");
    let brute = BruteForce::build(tree.primitives());
    for k in [1, 2, 5] {
        assert_eq!(
            tree.k_nearest(Vec3::ZERO, k),
            brute.k_nearest(Vec3::ZERO, k)
        );
        assert!(
            brute.k_nearest(Vec3::ZERO, k).is_empty(),
            "brute force answers a point at infinity"
        );
    }
}

/// Only points that are not finite: nothing to answer with.
fn points3_at_infinity() -> Vec<Vec3> {
    vec![
        Vec3::new(-0.0, 1.000_007_6, f32::NEG_INFINITY),
        Vec3::splat(f32::INFINITY),
        Vec3::new(f32::NAN, 0.0, 0.0),
    ]
}

fn mesh(name: &str) -> Option<Vec<Triangle3>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes");
    if !dir.is_dir() {
        eprintln!("skipping {name}: the shared mesh folder is absent");
        return None;
    }
    let bytes = std::fs::read(dir.join(name)).expect("a readable mesh");
    Some(
        Mesh::from_obj(&bytes)
            .expect("a valid OBJ file")
            .triangles()
            .to_vec(),
    )
}

#[test]
fn every_structure_over_a_real_mesh_loads_and_answers_as_saved() {
    let Some(prims) = mesh("spot.obj") else {
        return;
    };
    let mut rng = rng(41);
    every_structure!(Triangle3, &prims, &mut rng, 40, "spot");
}

/// The bunny's AABB tree and 4-wide tree, with their file sizes per triangle (printed with
/// `--nocapture`): a saved tree holds the input, the leaf-order copy and the nodes.
#[test]
fn the_bunny_saves_and_loads() {
    let Some(prims) = mesh("stanford-bunny.obj") else {
        return;
    };
    let mut rng = rng(51);
    let binary = round_trip::<AabbTree3>("bunny AABB tree", &prims, &mut rng, 40);
    let wide = round_trip_bvh4("bunny Bvh4", &prims, &mut rng, 40);
    let per = |bytes: usize| bytes as f64 / prims.len() as f64;
    eprintln!(
        "bunny, {} triangles: AABB tree {binary} bytes ({:.1} per triangle), Bvh4 {wide} bytes ({:.1} per triangle)",
        prims.len(),
        per(binary),
        per(wide)
    );
    // Triangles are 36 bytes; the tree must not cost more than a few times its input.
    assert!(per(binary) < 4.0 * 36.0 && per(wide) < 4.0 * 36.0);
}

/// A small 2D AABB tree's file, for the refusal tests.
fn small_file() -> (Vec<Segment2>, Vec<u8>) {
    let prims = random_segments(&mut rng(61), 12);
    let bytes = saved::save(&AabbTree2::build(&prims)).expect("saves");
    (prims, bytes)
}

#[test]
fn a_file_that_is_not_a_tree_file_is_refused() {
    let (_, bytes) = small_file();
    for garbage in [
        &b""[..],
        b"v 0 0 0\nv 1 0 0\n",
        b"{\"nodes\": []}",
        &[0; 64],
    ] {
        assert_eq!(
            saved::load::<AabbTree2>(garbage),
            Err(LoadError::NotATreeFile)
        );
    }
    let mut wrong = bytes.clone();
    wrong[0] ^= 0x20;
    let err = saved::load::<AabbTree2>(&wrong).expect_err("a wrong magic");
    assert_eq!(err.to_string(), "not a bvhlab tree file");
}

#[test]
fn a_file_of_another_version_is_refused_with_both_versions() {
    let (_, mut bytes) = small_file();
    // The version before this library's: a file saved before a format change.
    let older = saved::FORMAT_VERSION - 1;
    bytes[8..12].copy_from_slice(&older.to_le_bytes());
    let err = saved::load::<AabbTree2>(&bytes).expect_err("another version");
    assert_eq!(err, LoadError::Version { found: older });
    assert_eq!(
        err.to_string(),
        format!(
            "saved by format version {older}, this library reads version {}",
            saved::FORMAT_VERSION
        )
    );
}

#[test]
fn a_file_loaded_as_another_kind_says_what_it_holds() {
    let (_, bytes) = small_file();
    let holds = "the file holds a Bvh with Aabb nodes over Segment2";
    let cases = [
        (
            saved::load::<KdTree2>(&bytes).map(drop),
            "not a KdTree over Segment2",
        ),
        (
            saved::load::<AabbTree3>(&bytes).map(drop),
            "not a Bvh with Aabb nodes over Triangle3",
        ),
        (
            saved::load::<SphereTree2>(&bytes).map(drop),
            "not a Bvh with Sphere nodes over Segment2",
        ),
        (
            saved::load::<Bvh4<Segment2>>(&bytes).map(drop),
            "not a Bvh4 over Segment2",
        ),
        (
            saved::load::<Grid<Vec2>>(&bytes).map(drop),
            "not a Grid over Vec2",
        ),
    ];
    for (result, wanted) in cases {
        let err = result.expect_err("another kind");
        assert!(matches!(err, LoadError::WrongKind { .. }));
        assert_eq!(err.to_string(), format!("{holds}, {wanted}"));
    }
    assert_eq!(
        saved::kind_of(&bytes).map(|k| k.to_string()),
        Ok("Bvh with Aabb nodes over Segment2".to_owned())
    );
}

#[test]
fn a_file_cut_at_any_length_is_refused() {
    let (_, bytes) = small_file();
    for len in 0..bytes.len() {
        let err = saved::load::<AabbTree2>(&bytes[..len]).expect_err("cut short");
        if len >= 12 {
            assert!(
                matches!(err, LoadError::Truncated { .. }),
                "cut at {len}: {err}"
            );
            assert!(
                err.to_string().starts_with("truncated"),
                "cut at {len}: {err}"
            );
        }
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(
        saved::load::<AabbTree2>(&longer),
        Err(LoadError::Corrupt { .. })
    ));
    assert!(saved::load::<AabbTree2>(&bytes).is_ok());
}

#[test]
fn any_changed_byte_is_refused_by_the_checksum_or_the_header() {
    let (_, bytes) = small_file();
    let mut rng = rng(71);
    for _ in 0..2000 {
        let mut damaged = bytes.clone();
        let at = rng.random_range(0..damaged.len());
        damaged[at] ^= rng.random_range(1..=255u8);
        assert!(
            saved::load::<AabbTree2>(&damaged).is_err(),
            "byte {at} changed"
        );
    }
}

/// A payload with one byte changed (and the checksum made to match, as a forger or a fuzzer
/// would) either fails to load or loads into a tree that passes its check and answers as
/// brute force over its own primitives.
fn flip_payload_bytes<S>(name: &str, tree: &S, seed: u64, flips: usize) -> (usize, usize)
where
    S: SpatialIndex + Saved,
{
    let bytes = saved::save(tree).expect("saves");
    let mut rng = rng(seed);
    let (mut refused, mut loaded) = (0, 0);
    for _ in 0..flips {
        let mut damaged = bytes.clone();
        let at = rng.random_range(saved::HEADER_LEN..damaged.len());
        damaged[at] ^= rng.random_range(1..=255u8);
        saved::reseal(&mut damaged);
        match saved::load::<S>(&damaged) {
            Err(err) => {
                assert!(!err.to_string().is_empty());
                refused += 1;
            }
            Ok(tree) => {
                tree.validate().expect("a loaded tree is valid");
                check_answers(name, &tree, &tree, &mut rng, 3);
                loaded += 1;
            }
        }
    }
    (refused, loaded)
}

#[test]
fn changed_payload_bytes_never_give_a_panic_or_a_wrong_tree() {
    let mut rng = rng(81);
    let segments = random_segments(&mut rng, 10);
    let triangles = random_triangles(&mut rng, 8);
    let points: Vec<Vec3> = random_points(&mut rng, 12);
    let results = [
        flip_payload_bytes("AABB tree 2D", &AabbTree2::build(&segments), 1, 6000),
        flip_payload_bytes("sphere tree 3D", &SphereTree3::build(&triangles), 2, 4000),
        flip_payload_bytes("OBB tree 3D", &ObbTree3::build(&triangles), 3, 4000),
        flip_payload_bytes("k-d tree 2D", &KdTree2::build(&segments), 4, 4000),
        flip_payload_bytes("k-d tree points", &KdTree::<Vec3>::build(&points), 5, 4000),
        flip_payload_bytes("BSP tree 3D", &Bsp3::build(&triangles), 6, 4000),
        flip_payload_bytes("grid 2D", &Grid2::build(&segments), 7, 4000),
        flip_payload_bytes("octree", &Octree3::build(&triangles), 8, 4000),
        flip_payload_bytes("brute force", &BruteForce::build(&segments), 9, 2000),
    ];
    eprintln!("(refused, loaded) per structure: {results:?}");
    let refused: usize = results.iter().map(|r| r.0).sum();
    assert!(
        refused > 10_000,
        "only {refused} damaged files were refused"
    );
    // Bvh4 has no SpatialIndex: its damaged copies must load valid or be refused.
    let wide = saved::save(&Bvh4::build(&triangles)).expect("saves");
    for _ in 0..4000 {
        let mut damaged = wide.clone();
        let at = rng.random_range(saved::HEADER_LEN..damaged.len());
        damaged[at] ^= rng.random_range(1..=255u8);
        saved::reseal(&mut damaged);
        if let Ok(tree) = saved::load::<Bvh4<Triangle3>>(&damaged) {
            tree.validate().expect("a loaded tree is valid");
            let ray = Ray3::new(Vec3::splat(-1.0), Vec3::ONE).expect("a ray");
            let _ = (
                tree.ray_first_hit(&ray, f32::INFINITY),
                tree.closest_point(Vec3::ONE),
            );
        }
    }
}
