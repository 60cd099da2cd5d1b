//! Building hulls: invariants on random and degenerate point sets, measures against closed
//! forms, and a large real mesh.

use std::f64::consts::PI;

use bvhlab::GeometryError;
use bvhlab::glam::{EulerRot, Quat};
use proptest::prelude::*;

use super::*;

/// Point sets of many kinds, `seed` choosing the randomness.
fn clouds<V: Vector>(seed: u64) -> Vec<Vec<V>> {
    let mut r = rng(seed);
    let far = V::from_dvec3(DVec3::splat(1.0e4));
    let grid: Vec<V> = (0..125)
        .map(|i: i32| {
            let c = |j: i32| f64::from(j % 5);
            V::from_dvec3(DVec3::new(c(i), c(i / 5), c(i / 25)))
        })
        .collect();
    let tenths: Vec<V> = (0..200)
        .map(|_| {
            let mut c = || f64::from(r.random_range(-5i32..=5)) * 0.1;
            V::from_dvec3(DVec3::new(c(), c(), c()))
        })
        .collect();
    let mut sphere: Vec<V> = sphere_points(500);
    sphere.extend(ball_points(&mut r, 100, V::ZERO, 0.99));
    vec![
        (0..300).map(|_| random_vector(&mut r, 1.0)).collect(),
        ball_points(&mut r, 300, V::ZERO, 5.0),
        ball_points(&mut r, 100, far, 1.0),
        ball_points(&mut r, 100, V::ZERO, 1.0e-3),
        (0..7).map(|_| random_vector(&mut r, 1.0)).collect(),
        sphere,
        grid,
        tenths,
    ]
}

#[test]
fn random_clouds_give_valid_hulls() {
    for seed in 0..20 {
        for points in clouds::<Vec2>(seed) {
            let hull = check_2d(&points);
            assert_eq!(hull.dimension(), Some(2));
        }
        for points in clouds::<Vec3>(seed) {
            let hull = check_3d(&points);
            assert_eq!(hull.dimension(), Some(3));
        }
    }
}

#[test]
fn unit_square_and_cube_with_interior_points() {
    let mut r = rng(1);
    let mut square: Vec<Vec2> = (0..4)
        .map(|i| Vec2::new((i & 1) as f32, (i >> 1) as f32))
        .collect();
    square.extend((0..200).map(|_| Vec2::splat(0.5) + random_vector::<Vec2>(&mut r, 0.49)));
    let hull = check_2d(&square);
    assert_eq!(hull.vertices().len(), 4);
    assert!((hull.measure() - 1.0).abs() < 1e-6);
    assert!((hull.boundary_measure() - 4.0).abs() < 1e-6);

    let mut cube: Vec<Vec3> = Aabb3::new(Vec3::ZERO, Vec3::ONE).corners().collect();
    cube.extend((0..500).map(|_| Vec3::splat(0.5) + random_vector::<Vec3>(&mut r, 0.49)));
    let hull = check_3d(&cube);
    assert_eq!((hull.vertices().len(), hull.facets().len()), (8, 12));
    assert!((hull.measure() - 1.0).abs() < 1e-6);
    assert!((hull.boundary_measure() - 6.0).abs() < 1e-5);
}

#[test]
fn grid_drops_points_on_faces_and_edges() {
    let grid = &clouds::<Vec3>(0)[6];
    let hull = check_3d(grid);
    assert_eq!((hull.vertices().len(), hull.facets().len()), (8, 12));
    assert_eq!((hull.measure(), hull.boundary_measure()), (64.0, 96.0));
    let square = check_2d(&clouds::<Vec2>(0)[6]);
    assert_eq!(square.vertices().len(), 4);
}

#[test]
fn regular_polygons_match_closed_forms() {
    for n in [3usize, 7, 100, 1000] {
        let r = 2.0;
        let centre = Vec2::new(3.0, -1.0);
        let points: Vec<Vec2> = sphere_points::<Vec2>(n)
            .iter()
            .map(|&p| centre + p * r)
            .collect();
        let hull = check_2d(&points);
        assert_eq!(hull.vertices().len(), n);
        let (n, r) = (n as f64, f64::from(r));
        let area = n / 2.0 * r * r * (2.0 * PI / n).sin();
        let perimeter = 2.0 * n * r * (PI / n).sin();
        assert!(
            (f64::from(hull.measure()) - area).abs() < 1e-5 * area,
            "{n}-gon area"
        );
        assert!((f64::from(hull.boundary_measure()) - perimeter).abs() < 1e-5 * perimeter);
    }
}

#[test]
fn points_on_a_sphere_approach_its_volume_and_area() {
    let (ball, surface) = (4.0 / 3.0 * PI, 4.0 * PI);
    let mut previous = 0.0;
    for n in [100, 1000, 10_000] {
        let hull = check_3d(&sphere_points::<Vec3>(n));
        assert_eq!(hull.vertices().len(), n);
        let (volume, area) = (
            f64::from(hull.measure()),
            f64::from(hull.boundary_measure()),
        );
        // An inscribed polyhedron: smaller than the ball, short by O(1/n).
        assert!(volume < ball && area < surface && volume > previous);
        assert!(ball - volume < 30.0 / n as f64, "n = {n}: volume {volume}");
        assert!(surface - area < 45.0 / n as f64, "n = {n}: area {area}");
        previous = volume;
    }
}

#[test]
fn empty_and_non_finite_input() {
    let empty = ConvexHull3::from_points(&[]);
    assert!(empty.is_empty() && empty.facets().is_empty());
    assert_eq!(
        (empty.dimension(), empty.measure(), empty.boundary_measure()),
        (None, 0.0, 0.0)
    );
    assert_eq!(empty, ConvexHull3::default());
    assert!(matches!(
        ConvexHull2::try_from_points(&[]),
        Err(GeometryError::Empty { .. })
    ));

    let good = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    let mut bad = good.to_vec();
    bad.insert(2, Vec3::new(f32::NAN, 0.0, 0.0));
    bad.push(Vec3::splat(f32::INFINITY));
    assert_eq!(
        ConvexHull3::from_points(&bad),
        ConvexHull3::from_points(&good)
    );
    assert!(matches!(
        ConvexHull3::try_from_points(&bad),
        Err(GeometryError::NonFinite { .. })
    ));
    assert_eq!(
        ConvexHull3::try_from_points(&good),
        Ok(ConvexHull3::from_points(&good))
    );
    let only_nan = [Vec2::NAN, Vec2::INFINITY];
    assert!(ConvexHull2::from_points(&only_nan).is_empty());
}

/// One point, repeated: a point hull. Collinear points: the segment between the extremes.
fn check_point_and_segment<V: Vector>(seed: u64, hull_of: impl Fn(&[V]) -> ConvexHull<V>) {
    // Multiples of 1/8, so that the points below are exactly collinear in f32.
    let mut r = rng(seed);
    let mut eighths = |extent: f64| {
        V::from_dvec3((random_vector::<V>(&mut r, extent).to_dvec3() * 8.0).round() / 8.0)
    };
    let p: V = eighths(10.0);
    let dir: V = eighths(1.0) + V::unit_axis(0) * 1.125;
    for points in [vec![p], vec![p; 6]] {
        let hull = hull_of(&points);
        assert_eq!(
            (hull.dimension(), hull.vertices()),
            (Some(0), [p].as_slice())
        );
        assert!(hull.facets().is_empty() && hull.measure() == 0.0);
        assert!(!hull.contains(p + dir * 1e-3));
        assert_eq!(hull.closest_point(p + dir).map(|n| n.point), Some(p));
    }
    // Repeats, out of order, with the extremes at steps 0 and 4.
    let line: Vec<V> = (0..15)
        .map(|i| p + dir * ((i * 7 % 5) as f32 * 0.75))
        .collect();
    let hull = hull_of(&line);
    assert_eq!(hull.dimension(), Some(1));
    let ends = [p, p + dir * 3.0];
    assert!(hull.vertices().len() == 2 && ends.iter().all(|e| hull.vertices().contains(e)));
    let length = dir.length() * 3.0;
    let boundary = hull.boundary_measure();
    assert!(boundary == 0.0 || (boundary - 2.0 * length).abs() < 1e-5 * length);
    assert_eq!(hull.measure(), 0.0);
    assert!(hull.contains(p + dir * 1.3) && !hull.contains(p + dir * 3.1));
    assert!(!hull.contains(p - dir * 0.1));
}

#[test]
fn points_and_segments() {
    for seed in 0..10 {
        check_point_and_segment::<Vec2>(seed, check_2d);
        check_point_and_segment::<Vec3>(seed, check_3d);
    }
    let collinear_2d = check_2d(&[Vec2::ZERO, Vec2::ONE, Vec2::splat(0.5)]);
    assert_eq!(collinear_2d.boundary_measure(), 2.0 * 2f32.sqrt());
    assert_eq!(collinear_2d.facets().len(), 2);
}

#[test]
fn coplanar_points_give_a_flat_polygon_covered_on_both_sides() {
    for seed in 0..10 {
        let mut r = rng(seed);
        let xy: Vec<Vec2> = (0..40).map(|_| random_vector(&mut r, 3.0)).collect();
        let polygon = check_2d(&xy);
        // The plane z = 1.5 and the tilted plane z = x + 2y, both exact in f32 for these points.
        let level: Vec<Vec3> = xy.iter().map(|p| p.extend(1.5)).collect();
        let grid: Vec<Vec2> = xy.iter().map(|p| (*p * 8.0).round()).collect();
        let tilted: Vec<Vec3> = grid.iter().map(|p| p.extend(p.x + 2.0 * p.y)).collect();
        let cases = [
            (level, polygon.measure(), 1.0),
            (tilted, check_2d(&grid).measure(), 1.0 / 6f32.sqrt()),
        ];
        for (points, area, slope) in cases {
            let hull = check_3d(&points);
            assert_eq!(hull.dimension(), Some(2));
            assert_eq!(hull.measure(), 0.0);
            let shadow = hull.boundary_measure() / 2.0 * slope;
            assert!(
                (shadow - area).abs() < 1e-4 * area,
                "both sides: {shadow} vs {area}"
            );
            assert_eq!(hull.facets().len(), 2 * (hull.vertices().len() - 2));
        }
    }
}

/// Point sets that are degenerate up to rounding, turned and moved so that nothing lines up
/// with the axes: the surface of a cube, a grid, a thin slab, a needle, clusters of
/// near-duplicates, at scales from 1e-3 to 1e4. (A tolerance band in which points count as
/// inside the hull loses points around the rim of a thin slab; exact tests do not.)
#[test]
fn nearly_degenerate_sets_in_any_orientation() {
    for seed in 0..60 {
        let mut r = rng(seed);
        let turn = Quat::from_euler(
            EulerRot::XYZ,
            r.random_range(0.0..6.3),
            r.random_range(0.0..6.3),
            r.random_range(0.0..6.3),
        );
        let scale = 10f32.powi(r.random_range(-3..5));
        let offset: Vec3 =
            random_vector::<Vec3>(&mut r, 1.0) * scale * r.random_range(0.0..100.0f32);
        let place = |p: Vec3| offset + turn * p * scale;
        let n = r.random_range(4..300);
        let mut jitter = |e: f64| random_vector::<Vec3>(&mut r, e);
        let mut sets: [Vec<Vec3>; 5] = Default::default();
        for i in 0..n {
            let mut on_cube = jitter(1.0);
            on_cube[i % 3] = if i % 2 == 0 { 1.0 } else { -1.0 };
            let grid = (jitter(3.5) * 0.3).round();
            let slab = jitter(1.0) * Vec3::new(1.0, 1.0, 1e-6);
            let needle = jitter(1.0) * Vec3::new(1.0, 1e-6, 1e-6);
            let corner = Vec3::new((i % 4) as f32, (i / 4 % 3) as f32, (i / 12 % 2) as f32);
            let cluster = corner + jitter(1e-6);
            for (set, p) in sets.iter_mut().zip([on_cube, grid, slab, needle, cluster]) {
                set.push(place(p));
            }
        }
        for points in &sets {
            check_3d(points);
        }
    }
}

#[test]
fn merge_contains_both() {
    let mut r = rng(5);
    let a = ConvexHull3::from_points(&ball_points(&mut r, 30, Vec3::ZERO, 1.0));
    let b = ConvexHull3::from_points(&ball_points(&mut r, 30, Vec3::X * 3.0, 1.0));
    let merged = a.merge(&b);
    assert!(
        a.vertices()
            .iter()
            .chain(b.vertices())
            .all(|&v| merged.contains(v))
    );
    assert_eq!(a.merge(&ConvexHull3::EMPTY), a);
    let corners: Vec<Vec3> = a.vertices().to_vec();
    assert_eq!(a.aabb(), Aabb3::from_points(&corners));
}

/// Points of a real scanned mesh, if the shared data folder is there.
fn mesh_vertices(name: &str) -> Option<Vec<Vec3>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    let text = std::fs::read_to_string(path).ok()?;
    let coords = |line: &str| -> Option<Vec3> {
        let mut xyz = line
            .strip_prefix("v ")?
            .split_whitespace()
            .map(str::parse::<f32>);
        Some(Vec3::new(
            xyz.next()?.ok()?,
            xyz.next()?.ok()?,
            xyz.next()?.ok()?,
        ))
    };
    Some(text.lines().filter_map(coords).collect())
}

/// Builds a hull, reporting how long that took (run with `--release --nocapture` to see).
fn timed_hull(what: &str, points: &[Vec3]) -> ConvexHull3 {
    let start = std::time::Instant::now();
    let hull = ConvexHull3::from_points(points);
    let n = hull.vertices().len();
    eprintln!(
        "{what}: {} points, {n} hull vertices, {:?}",
        points.len(),
        start.elapsed()
    );
    hull
}

#[test]
fn large_inputs() {
    let sphere = sphere_points::<Vec3>(100_000);
    let hull = timed_hull("Fibonacci sphere", &sphere);
    assert_eq!(hull.vertices().len(), sphere.len());
    check_closed_mesh(&hull);
    let ball = ball_points(&mut rng(3), 100_000, Vec3::ZERO, 1.0);
    check_closed_mesh(&timed_hull("uniform ball", &ball));
    for name in ["dragon.obj", "stanford-bunny.obj", "fandisk.obj"] {
        let Some(points) = mesh_vertices(name) else {
            eprintln!("skipping {name}: shared mesh folder not found");
            continue;
        };
        let hull = timed_hull(name, &points);
        check_closed_mesh(&hull);
        assert!(points.iter().all(|&p| hull.contains(p)));
    }
}

fn small_grid_points(dim: usize) -> impl Strategy<Value = Vec<DVec3>> {
    let c = -3i32..=3;
    let p = (c.clone(), c.clone(), c).prop_map(move |(x, y, z)| {
        DVec3::new(
            f64::from(x),
            f64::from(y),
            if dim == 3 { f64::from(z) } else { 0.0 },
        )
    });
    prop::collection::vec(p, 0..30)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Tiny integer grids are full of repeated, collinear and coplanar points.
    #[test]
    fn degenerate_grids_give_valid_hulls(p2 in small_grid_points(2), p3 in small_grid_points(3)) {
        check_2d(&p2.iter().map(|&p| Vec2::from_dvec3(p)).collect::<Vec<_>>());
        let tenths: Vec<Vec3> = p3.iter().map(|&p| (p * 0.1).as_vec3()).collect();
        check_3d(&tenths);
        check_3d(&p3.iter().map(|&p| p.as_vec3()).collect::<Vec<_>>());
    }
}
