//! Queries on hulls against independent answers: dense sampling along rays, the facets' own
//! ray tests, brute-force distances to sampled facets, and overlap from vertices and edges.

use bvhlab::glam::{EulerRot, Quat};
use bvhlab::{Ray, Ray2, Ray3};

use super::*;

/// Hulls of several kinds and dimensions, and the scale of their coordinates.
fn hulls<V: Vector>(seed: u64) -> Vec<ConvexHull<V>> {
    let mut r = rng(seed);
    let centre: V = random_vector(&mut r, 3.0);
    let mut flat: Vec<V> = ball_points(&mut r, 12, centre, 2.0);
    for p in &mut flat {
        p.set_coord(V::DIM - 1, 0.5);
    }
    let dir: V = random_vector(&mut r, 1.0);
    vec![
        ConvexHull::from_points(&ball_points(&mut r, 30, centre, 2.0)),
        ConvexHull::from_points(
            &(0..5)
                .map(|_| random_vector(&mut r, 2.0))
                .collect::<Vec<V>>(),
        ),
        ConvexHull::from_points(&flat),
        ConvexHull::from_points(&[centre, centre + dir * 2.0]),
        ConvexHull::from_points(&[centre]),
    ]
}

/// `ray_interval` against `contains` at 3000 points along the ray, and (for a proper crossing
/// from outside a solid) `t_enter` against the first facet the ray hits.
fn check_ray<V: Vector>(hull: &ConvexHull<V>, ray: &Ray<V>, t_max: f32) {
    let interval = hull.ray_interval(ray);
    let slack = 1e-3 * t_max;
    for k in 0..=3000 {
        let t = t_max * k as f32 / 3000.0;
        let predicted = interval.is_some_and(|(a, b)| a <= t && t <= b);
        let near_end =
            interval.is_some_and(|(a, b)| (t - a).abs() < slack || (t - b).abs() < slack);
        assert!(
            hull.contains(ray.at(t)) == predicted || near_end,
            "{ray:?} at t = {t}: {interval:?}"
        );
    }
    let Some((t_enter, t_exit)) = interval else {
        return;
    };
    assert!(0.0 <= t_enter && t_enter <= t_exit);
    let proper =
        (t_exit - t_enter) * ray.dir().length() > 1e-3 && hull.distance(ray.origin()) > 1e-3;
    if hull.dimension() == Some(V::DIM) && proper {
        let first = hull
            .facets()
            .iter()
            .filter_map(|f| f.ray_hit(ray))
            .fold(f32::INFINITY, f32::min);
        assert!(
            (first - t_enter).abs() < 1e-4 * (1.0 + t_enter),
            "{first} vs {t_enter}"
        );
    }
}

fn random_rays<V: Vector>(seed: u64) {
    let mut r = rng(seed);
    for hull in hulls::<V>(seed) {
        for _ in 0..40 {
            let origin: V = random_vector(&mut r, 6.0);
            // Aim at a vertex, mostly with a little miss, or anywhere.
            let target = hull.vertices()[r.random_range(0..hull.vertices().len())];
            let aim = if r.random_bool(0.7) {
                target + random_vector::<V>(&mut r, 0.5) - origin
            } else {
                random_vector(&mut r, 1.0)
            };
            let Ok(ray) = Ray::new(origin, aim) else {
                continue;
            };
            check_ray(&hull, &ray, 20.0 / aim.length());
        }
    }
}

#[test]
fn ray_interval_matches_sampling_and_facet_hits() {
    for seed in 0..8 {
        random_rays::<Vec2>(seed);
        random_rays::<Vec3>(seed);
    }
}

#[test]
fn ray_interval_edge_cases() {
    let square = ConvexHull2::from_points(&[Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]);
    let ray = |o: (f32, f32), d: (f32, f32)| {
        Ray2::new(Vec2::new(o.0, o.1), Vec2::new(d.0, d.1)).expect("ray")
    };
    // The ends move out by the tolerance (here 8 · f32::EPSILON · 2 along each axis).
    let near = |got: Option<(f32, f32)>, want: (f32, f32)| {
        got.is_some_and(|(a, b)| (a - want.0).abs() < 1e-5 && (b - want.1).abs() < 1e-5)
    };
    assert!(near(
        square.ray_interval(&ray((0.5, 0.5), (1.0, 0.0))),
        (0.0, 0.5)
    ));
    assert!(near(
        square.ray_interval(&ray((-1.0, 0.5), (2.0, 0.0))),
        (0.5, 1.0)
    ));
    // Along an edge, and through a corner only: touching counts.
    assert!(square.ray_interval(&ray((-1.0, 1.0), (1.0, 0.0))).is_some());
    let (a, b) = square
        .ray_interval(&ray((-1.0, 1.0), (1.0, -1.0)))
        .expect("touches (0, 0)");
    assert!((b - a).abs() < 1e-5);
    assert_eq!(square.ray_interval(&ray((2.0, 0.5), (1.0, 0.0))), None);
    assert_eq!(
        ConvexHull2::EMPTY.ray_interval(&ray((0.0, 0.0), (1.0, 0.0))),
        None
    );
    // A flat polygon in 3D is crossed in one point.
    let flat = ConvexHull3::from_points(&[Vec3::ZERO, Vec3::X, Vec3::Y]);
    let down = Ray3::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z).expect("ray");
    let (a, b) = flat.ray_interval(&down).expect("crosses the triangle");
    assert!((a - 1.0).abs() < 1e-5 && (b - 1.0).abs() < 1e-5);
}

/// Inside a closed boundary, a ray crosses it an odd number of times (once, for a convex one);
/// outside, an even number. Points near the boundary are skipped.
fn check_contains_by_parity<V: Vector>(seed: u64) {
    let mut r = rng(seed);
    for hull in hulls::<V>(seed)
        .into_iter()
        .filter(|h| h.dimension() == Some(V::DIM))
    {
        let samples = boundary_samples(&hull, 40);
        for _ in 0..200 {
            let p: V = random_vector(&mut r, 5.0);
            if samples.iter().all(|&s| (s - p).length() > 0.1) {
                let ray = Ray::new(p, random_vector(&mut r, 1.0)).expect("a random direction");
                let hits = hull
                    .facets()
                    .iter()
                    .filter(|f| f.ray_hit(&ray).is_some())
                    .count();
                assert_eq!(hull.contains(p), hits % 2 == 1, "{p:?}: {hits} crossings");
            }
        }
    }
}

#[test]
fn contains_matches_ray_parity() {
    for seed in 0..6 {
        check_contains_by_parity::<Vec2>(seed);
        check_contains_by_parity::<Vec3>(seed);
    }
}

/// A flat polygon in 3D contains what its plane's 2D hull contains, and nothing off the plane.
#[test]
fn flat_polygon_contains_its_shadow() {
    let mut r = rng(4);
    for _ in 0..10 {
        let shadow: Vec<Vec2> = (0..8).map(|_| random_vector(&mut r, 2.0)).collect();
        let polygon = ConvexHull2::from_points(&shadow);
        let flat =
            ConvexHull3::from_points(&shadow.iter().map(|p| p.extend(0.5)).collect::<Vec<_>>());
        for _ in 0..200 {
            let p: Vec2 = random_vector(&mut r, 3.0);
            let edge = polygon
                .facets()
                .iter()
                .map(|f| f.distance(p))
                .fold(f32::INFINITY, f32::min);
            if edge > 1e-3 {
                assert_eq!(flat.contains(p.extend(0.5)), polygon.contains(p), "{p:?}");
            }
            assert!(!flat.contains(p.extend(0.51)) && !flat.contains(p.extend(0.49)));
        }
    }
}

/// Points on the boundary: a fine grid on every facet (or on the segment, or the point).
fn boundary_samples<V: Vector>(hull: &ConvexHull<V>, k: usize) -> Vec<V> {
    let mut samples = hull.vertices().to_vec();
    let corners: Vec<Vec<V>> = if hull.facets().is_empty() {
        vec![hull.vertices().to_vec()]
    } else {
        hull.facets()
            .iter()
            .map(|f| f.vertices().collect())
            .collect()
    };
    for c in corners {
        for i in 0..=k {
            for j in 0..=(if c.len() == 3 { k - i } else { 0 }) {
                let (s, t) = (i as f32 / k as f32, j as f32 / k as f32);
                let p = match c.as_slice() {
                    [a, b] => *a + (*b - *a) * s,
                    [a, b, c] => *a + (*b - *a) * s + (*c - *a) * t,
                    _ => continue,
                };
                samples.push(p);
            }
        }
    }
    samples
}

fn check_distances<V: Vector>(seed: u64) {
    let mut r = rng(seed);
    for hull in hulls::<V>(seed) {
        let k = 40;
        let samples = boundary_samples(&hull, k);
        let longest = hull
            .facets()
            .iter()
            .map(|f| f.bounds().size().length())
            .fold(0.0, f32::max)
            .max(hull.aabb().size().length());
        for _ in 0..60 {
            let p: V = random_vector(&mut r, 7.0);
            let q = hull.closest_point(p).expect("not empty").point;
            let distance = hull.distance(p);
            assert!(hull.contains(q), "closest point {q:?} is outside");
            assert!(((q - p).length() - distance).abs() < 1e-5);
            let brute = if hull.contains(p) {
                0.0
            } else {
                samples
                    .iter()
                    .map(|&s| (s - p).length())
                    .fold(f32::INFINITY, f32::min)
            };
            assert!(distance <= brute + 1e-4, "{distance} > brute force {brute}");
            assert!(
                distance >= brute - longest / k as f32,
                "{distance} < brute force {brute}"
            );
            // q is nearest iff the whole hull is behind the plane through q normal to p − q.
            for &v in hull.vertices() {
                assert!(
                    (p - q).dot(v - q) <= 1e-4 * (1.0 + distance),
                    "{v:?} is nearer than {q:?}"
                );
            }
        }
    }
}

#[test]
fn distances_match_brute_force() {
    for seed in 0..6 {
        check_distances::<Vec2>(seed);
        check_distances::<Vec3>(seed);
    }
    assert_eq!(ConvexHull3::EMPTY.closest_point(Vec3::ZERO), None);
    assert_eq!(ConvexHull3::EMPTY.distance(Vec3::ZERO), f32::INFINITY);
}

/// Overlap decided without separating axes: a vertex of one inside the other, or an edge of
/// one crossing a facet of the other (a watertight ray test limited to the edge).
fn touches<V: Vector>(a: &ConvexHull<V>, b: &ConvexHull<V>) -> bool {
    let vertex_inside =
        |a: &ConvexHull<V>, b: &ConvexHull<V>| a.vertices().iter().any(|&v| b.contains(v));
    let edge_crosses = |a: &ConvexHull<V>, b: &ConvexHull<V>| {
        a.facets().iter().any(|f| {
            let c: Vec<V> = f.vertices().collect();
            (0..c.len()).any(|i| {
                let (p, q) = (c[i], c[(i + 1) % c.len()]);
                Ray::through(p, q).is_ok_and(|ray| {
                    b.facets()
                        .iter()
                        .any(|g| g.ray_hit(&ray).is_some_and(|t| t <= 1.0))
                })
            })
        })
    };
    vertex_inside(a, b) || vertex_inside(b, a) || edge_crosses(a, b) || edge_crosses(b, a)
}

/// The hull of `points` scaled by `s` about their centroid.
fn scaled<V: Vector>(points: &[V], s: f32) -> ConvexHull<V> {
    let c = points.iter().fold(V::ZERO, |m, &p| m + p) / points.len() as f32;
    ConvexHull::from_points(&points.iter().map(|&p| c + (p - c) * s).collect::<Vec<V>>())
}

fn random_pairs<V: Vector>(seed: u64) -> [usize; 2] {
    let mut r = rng(seed);
    let mut decided = [0, 0];
    for _ in 0..300 {
        let cloud = |r: &mut ChaCha8Rng, centre: V| -> Vec<V> {
            let n = r.random_range(4..10);
            (0..n)
                .map(|_| centre + random_vector::<V>(r, 1.0))
                .collect()
        };
        let offset = random_vector(&mut r, 1.6);
        let (pa, pb) = (cloud(&mut r, V::ZERO), cloud(&mut r, offset));
        let (a, b) = (ConvexHull::from_points(&pa), ConvexHull::from_points(&pb));
        // Near-touching pairs, where shrinking or growing by 2% changes the answer, are skipped.
        let truth = touches(&scaled(&pa, 0.98), &scaled(&pb, 0.98));
        if a.dimension() != Some(V::DIM) || truth != touches(&scaled(&pa, 1.02), &scaled(&pb, 1.02))
        {
            continue;
        }
        assert_eq!(a.overlaps(&b), truth, "{pa:?} vs {pb:?}");
        assert_eq!(b.overlaps(&a), truth);
        decided[usize::from(truth)] += 1;
    }
    decided
}

#[test]
fn overlaps_matches_vertex_and_edge_tests() {
    for seed in 0..4 {
        let [apart, overlapping] = random_pairs::<Vec2>(seed);
        assert!(
            apart > 30 && overlapping > 30,
            "2D: {apart} apart, {overlapping} overlapping"
        );
        let [apart, overlapping] = random_pairs::<Vec3>(seed);
        assert!(
            apart > 30 && overlapping > 30,
            "3D: {apart} apart, {overlapping} overlapping"
        );
    }
}

/// Flat hulls in one plane of 3D (points, segments, polygons) overlap exactly when their
/// shadows on that plane do, which the 2D vertex-and-edge test decides.
#[test]
fn coplanar_flat_hulls_overlap_like_their_shadows() {
    let mut r = rng(9);
    let mut decided = [0, 0];
    for _ in 0..400 {
        let mut cloud = |centre: Vec2| -> Vec<Vec2> {
            let n = r.random_range(1..6);
            (0..n)
                .map(|_| centre + random_vector::<Vec2>(&mut r, 1.0))
                .collect()
        };
        let (pa, pb) = (cloud(Vec2::ZERO), cloud(Vec2::new(0.6, 0.3)));
        let truth = touches(&scaled(&pa, 0.98), &scaled(&pb, 0.98));
        if truth != touches(&scaled(&pa, 1.02), &scaled(&pb, 1.02)) {
            continue;
        }
        let lift = |p: &[Vec2]| {
            ConvexHull3::from_points(&p.iter().map(|q| q.extend(0.5)).collect::<Vec<_>>())
        };
        let (a, b) = (lift(&pa), lift(&pb));
        assert_eq!(a.overlaps(&b), truth, "{pa:?} vs {pb:?}");
        assert_eq!(b.overlaps(&a), truth);
        decided[usize::from(truth)] += 1;
    }
    assert!(decided[0] > 50 && decided[1] > 50, "{decided:?}");
}

/// Configurations that only an edge-pair axis, or a flat hull's pinned direction crossed
/// with an edge, separates; turned so that no coordinate axis separates them by luck.
#[test]
fn overlaps_needs_edge_axes() {
    let turn = Quat::from_euler(EulerRot::XYZ, 0.3, 0.7, -0.4);
    let hull = |points: &[Vec3]| {
        ConvexHull3::from_points(&points.iter().map(|&p| turn * p).collect::<Vec<_>>())
    };
    // Two wedges, ridge to ridge, crossed at right angles.
    let lower = hull(&[
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, -2.0),
        Vec3::new(0.0, -1.0, -2.0),
    ]);
    for (gap, expected) in [(0.1, false), (0.0, true), (-0.1, true)] {
        let upper = hull(&[
            Vec3::new(0.0, -1.0, gap),
            Vec3::new(0.0, 1.0, gap),
            Vec3::new(1.0, 0.0, 2.0 + gap),
            Vec3::new(-1.0, 0.0, 2.0 + gap),
        ]);
        assert_eq!(lower.overlaps(&upper), expected, "gap {gap}");
    }
    // A triangle pointing at a long segment in its own plane.
    let triangle = hull(&[
        Vec3::new(0.0, 0.1, 0.0),
        Vec3::new(-1.0, 2.0, 0.0),
        Vec3::new(1.0, 2.0, 0.0),
    ]);
    for (y, expected) in [(0.0, false), (0.1, true), (0.2, true)] {
        let segment = hull(&[Vec3::new(-5.0, y, 0.0), Vec3::new(5.0, y, 0.0)]);
        assert_eq!(triangle.overlaps(&segment), expected, "segment at y = {y}");
        assert_eq!(segment.overlaps(&triangle), expected);
    }
    // Points against points and segments.
    let point = hull(&[Vec3::new(0.0, 0.05, 0.0)]);
    assert!(!point.overlaps(&triangle) && point.overlaps(&point.clone()));
    assert!(point.overlaps(&hull(&[Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.1, 0.0)])));
    assert!(!point.overlaps(&hull(&[
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.04, 0.0)
    ])));
    assert!(!ConvexHull3::EMPTY.overlaps(&point));
}

#[test]
fn touching_hulls_overlap() {
    let cube = |x: f32| {
        ConvexHull3::from_points(
            &Aabb3::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0))
                .corners()
                .collect::<Vec<_>>(),
        )
    };
    assert!(cube(0.0).overlaps(&cube(1.0)));
    assert!(!cube(0.0).overlaps(&cube(1.001)));
    let square = |o: Vec2| ConvexHull2::from_points(&[o, o + Vec2::X, o + Vec2::ONE, o + Vec2::Y]);
    assert!(square(Vec2::ZERO).overlaps(&square(Vec2::ONE)));
    assert!(!square(Vec2::ZERO).overlaps(&square(Vec2::new(1.001, 1.0))));
}
