//! Sphere fits and sphere queries, in 2D and 3D, against brute force and dense sampling.

use bvhlab::glam::{DVec2, DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::{Sphere, Vector};
use bvhlab_tests::{
    assert_interval_matches_sampling, degenerate_sets, random_cloud, random_ray, random_vector, rng,
};
use rand::RngExt;

fn fits<V: Vector>(points: &[V]) -> [(&'static str, Sphere<V>); 3] {
    [
        ("centroid", Sphere::centroid_fit(points)),
        ("ritter", Sphere::ritter_fit(points)),
        ("welzl", Sphere::welzl_fit(points)),
    ]
}

fn assert_fits_contain_and_welzl_is_smallest<V: Vector>(points: &[V]) {
    let fits = fits(points);
    for (name, s) in &fits {
        for p in points {
            assert!(s.contains(*p), "{name} fit {s:?} misses {p:?}");
        }
    }
    let welzl = fits[2].1.radius;
    for (name, s) in &fits[..2] {
        // "Never larger" up to the last bit of f32 rounding of the two centres.
        assert!(
            welzl <= s.radius * (1.0 + 1e-6) + 1e-30,
            "welzl {welzl} > {name} {}",
            s.radius
        );
    }
}

#[test]
fn every_fit_contains_its_points_and_welzl_is_smallest_on_random_and_degenerate_sets() {
    let mut rng = rng(10);
    for _ in 0..200 {
        let n = rng.random_range(1..200);
        assert_fits_contain_and_welzl_is_smallest(&random_cloud::<Vec2>(&mut rng, n, 5.0));
        assert_fits_contain_and_welzl_is_smallest(&random_cloud::<Vec3>(&mut rng, n, 5.0));
    }
    for set in degenerate_sets::<Vec2>(&mut rng) {
        assert_fits_contain_and_welzl_is_smallest(&set);
    }
    for set in degenerate_sets::<Vec3>(&mut rng) {
        assert_fits_contain_and_welzl_is_smallest(&set);
    }
}

/// The minimal circle by brute force: every circle through 2 or 3 of the points (closed-form
/// circumcentre), the smallest that contains them all.
fn brute_force_min_circle(points: &[Vec2]) -> f64 {
    let p: Vec<DVec2> = points.iter().map(|v| v.as_dvec2()).collect();
    let mut candidates = vec![(p[0], 0.0)];
    for i in 0..p.len() {
        for j in i + 1..p.len() {
            candidates.push(((p[i] + p[j]) / 2.0, p[i].distance(p[j]) / 2.0));
            for k in j + 1..p.len() {
                let (a, b, c) = (p[i], p[j], p[k]);
                let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
                if d.abs() < 1e-12 {
                    continue;
                }
                let (a2, b2, c2) = (a.length_squared(), b.length_squared(), c.length_squared());
                let ux = (a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d;
                let uy = (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d;
                let centre = DVec2::new(ux, uy);
                candidates.push((centre, centre.distance(a)));
            }
        }
    }
    smallest_enclosing(&candidates, &p, DVec2::distance)
}

/// The minimal 3D sphere by brute force: spheres on 2 points (diameter), circumcircles of 3,
/// circumspheres of 4 (Cramer's rule).
fn brute_force_min_sphere(points: &[Vec3]) -> f64 {
    let p: Vec<DVec3> = points.iter().map(|v| v.as_dvec3()).collect();
    let n = p.len();
    let mut candidates = vec![(p[0], 0.0)];
    for i in 0..n {
        for j in i + 1..n {
            candidates.push(((p[i] + p[j]) / 2.0, p[i].distance(p[j]) / 2.0));
            for k in j + 1..n {
                let (ab, ac) = (p[j] - p[i], p[k] - p[i]);
                let nrm = ab.cross(ac);
                if nrm.length_squared() > 1e-12 {
                    let offset = (nrm.cross(ab) * ac.length_squared()
                        + ac.cross(nrm) * ab.length_squared())
                        / (2.0 * nrm.length_squared());
                    candidates.push((p[i] + offset, offset.length()));
                }
                for l in k + 1..n {
                    let (u, v, w) = (p[j] - p[i], p[k] - p[i], p[l] - p[i]);
                    let det = u.dot(v.cross(w));
                    if det.abs() < 1e-12 {
                        continue;
                    }
                    let offset = (v.cross(w) * u.length_squared()
                        + w.cross(u) * v.length_squared()
                        + u.cross(v) * w.length_squared())
                        / (2.0 * det);
                    candidates.push((p[i] + offset, offset.length()));
                }
            }
        }
    }
    smallest_enclosing(&candidates, &p, DVec3::distance)
}

fn smallest_enclosing<P: Copy>(
    candidates: &[(P, f64)],
    points: &[P],
    dist: impl Fn(P, P) -> f64,
) -> f64 {
    candidates
        .iter()
        .filter(|&&(c, r)| {
            points
                .iter()
                .all(|&p| dist(p, c) <= r * (1.0 + 1e-9) + 1e-12)
        })
        .map(|&(_, r)| r)
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn welzl_matches_the_brute_force_minimum_on_small_sets() {
    let mut rng = rng(11);
    for _ in 0..300 {
        let n = rng.random_range(1..9);
        let pts2: Vec<Vec2> = random_cloud(&mut rng, n, 3.0);
        let want = brute_force_min_circle(&pts2);
        let got = f64::from(Sphere::welzl_fit(&pts2).radius);
        assert!(
            (got - want).abs() <= 1e-5 * want.max(1.0),
            "2D {pts2:?}: welzl {got} vs brute {want}"
        );

        let pts3: Vec<Vec3> = random_cloud(&mut rng, n, 3.0);
        let want = brute_force_min_sphere(&pts3);
        let got = f64::from(Sphere::welzl_fit(&pts3).radius);
        assert!(
            (got - want).abs() <= 1e-5 * want.max(1.0),
            "3D {pts3:?}: welzl {got} vs brute {want}"
        );
    }
}

fn check_queries<V: Vector>(seed: u64) {
    let mut rng = rng(seed);
    for _ in 0..300 {
        let s = Sphere::new(
            random_vector::<V>(&mut rng, 3.0),
            rng.random_range(0.1f32..3.0),
        );
        let ray = random_ray::<V>(&mut rng, 6.0);
        let interval = s.ray_interval(&ray);
        let t_max = 12.0 / ray.dir().length();
        assert_interval_matches_sampling(&ray, interval, |p| s.contains(p), t_max, 1e-3 * t_max);

        // Closest point: on the boundary (or the point itself) and never beaten by a sample of
        // boundary points.
        let p: V = random_vector(&mut rng, 6.0);
        let q = s.closest_point(p).expect("non-empty").point;
        let d = s.distance(p);
        assert!(((q - p).length() - d).abs() <= 1e-4);
        for _ in 0..400 {
            let dir = bvhlab_tests::random_direction::<V>(&mut rng);
            let boundary = s.center + dir * s.radius;
            assert!(d <= (boundary - p).length() + 1e-4);
        }
        assert_eq!(d == 0.0, s.contains(p));

        // Merge contains both; overlap iff some point of one lies in the other.
        let t = Sphere::new(
            random_vector::<V>(&mut rng, 3.0),
            rng.random_range(0.1f32..3.0),
        );
        let m = s.merge(&t);
        for _ in 0..50 {
            let dir = bvhlab_tests::random_direction::<V>(&mut rng);
            assert!(
                m.contains(s.center + dir * s.radius)
                    || m.distance(s.center + dir * s.radius) < 1e-5
            );
            assert!(
                m.contains(t.center + dir * t.radius)
                    || m.distance(t.center + dir * t.radius) < 1e-5
            );
        }
        let witness = t.closest_point(s.center).expect("non-empty").point;
        let gap = (s.center - t.center).length() - s.radius - t.radius;
        if gap.abs() > 1e-4 {
            assert_eq!(s.overlaps(&t), s.contains(witness), "{s:?} {t:?}");
        }
    }
}

#[test]
fn ray_interval_distance_merge_and_overlap_agree_with_sampling_2d() {
    check_queries::<Vec2>(12);
}

#[test]
fn ray_interval_distance_merge_and_overlap_agree_with_sampling_3d() {
    check_queries::<Vec3>(13);
}

#[test]
fn ray_quadratic_is_the_lecture_s_and_stays_accurate_far_away() {
    // Lecture: a = (s-e)ᵀ(s-e), b = 2 eᵀ(s-e), c = eᵀe - r², sphere at the origin.
    let s = Sphere3::new(Vec3::ZERO, 2.0);
    let ray = Ray3::through(Vec3::new(-4.0, 0.0, 0.0), Vec3::new(-3.0, 0.0, 0.0)).expect("ray");
    let q = s.ray_quadratic(&ray);
    assert_eq!((q.a, q.b, q.c), (1.0, -8.0, 12.0));
    assert_eq!(s.ray_interval(&ray), Some((2.0, 6.0)));
    // A tiny sphere far away: the naive formula loses the near root entirely.
    let far = Sphere3::new(Vec3::new(1.0e6, 0.0, 0.0), 1.0e-2);
    let ray = Ray3::new(Vec3::ZERO, Vec3::X).expect("ray");
    let (t0, t1) = far.ray_interval(&ray).expect("hit");
    assert!((t0 - (1.0e6 - 1.0e-2)).abs() < 0.07 && (t1 - (1.0e6 + 1.0e-2)).abs() < 0.07);
    // Inside: t_enter = 0; behind: miss; tangent: touching counts.
    assert_eq!(
        s.ray_interval(&Ray3::new(Vec3::ZERO, Vec3::Y).expect("ray")),
        Some((0.0, 2.0))
    );
    assert_eq!(
        s.ray_interval(&Ray3::new(Vec3::new(3.0, 0.0, 0.0), Vec3::X).expect("ray")),
        None
    );
    let tangent = Ray3::new(Vec3::new(-5.0, 2.0, 0.0), Vec3::X).expect("ray");
    assert_eq!(s.ray_interval(&tangent), Some((5.0, 5.0)));
}

#[test]
fn empty_input_gives_the_empty_sphere_and_try_fits_explain_bad_input() {
    let empty = Sphere3::welzl_fit(&[]);
    assert!(empty.is_empty() && !empty.contains(Vec3::ZERO));
    assert_eq!(empty.distance(Vec3::ZERO), f32::INFINITY);
    assert_eq!(
        empty.ray_interval(&Ray3::new(Vec3::ZERO, Vec3::X).expect("ray")),
        None
    );
    let one = Sphere3::new(Vec3::ONE, 1.0);
    assert_eq!(empty.merge(&one), one);

    let err = Sphere3::try_welzl_fit(&[]).expect_err("empty");
    assert!(err.to_string().contains("empty"), "{err}");
    let err = Sphere2::try_ritter_fit(&[Vec2::ZERO, Vec2::new(1.0, f32::NAN)]).expect_err("NaN");
    assert!(err.to_string().contains("point 1"), "{err}");
    // The lenient fits skip the bad point instead.
    assert_eq!(
        Sphere2::centroid_fit(&[Vec2::ZERO, Vec2::INFINITY]),
        Sphere2::new(Vec2::ZERO, 0.0)
    );
}
