//! The uniform grid against brute force, in 2D and 3D, on random, degenerate and scaled
//! scenes, with rays that start on, run along and cross cell boundaries; and the grid's own
//! promises: exact cell lists, mailboxing, the hit-inside-the-cell rule, the resolution rule.

use crate::grid_support;

use bvhlab::RayCast;
use bvhlab::SpatialQuery;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::grid::{Grid, GridOptions};
use bvhlab::structure::{PrimitiveResult, PruneReason, Recorder};
use bvhlab::{Event, Primitive, Ray, Segment2, SpatialIndex, Triangle3};
use grid_support::{Map, check_queries, load_mesh, points_for, rays_for, rng, scenes};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Corners of random cells: rays through them start on and run along cell boundaries.
fn corners<P: Primitive>(grid: &Grid<P>, rng: &mut ChaCha8Rng, count: usize) -> Vec<P::Point> {
    if grid.cell_count() == 0 {
        return Vec::new();
    }
    (0..count)
        .map(|_| {
            let cell = grid.cell_box(grid.cell_coords(rng.random_range(0..grid.cell_count())));
            if rng.random_bool(0.5) {
                cell.min
            } else {
                cell.max
            }
        })
        .collect()
}

fn options() -> [(&'static str, GridOptions); 3] {
    let coarse = GridOptions {
        resolution: Some([2, 3, 2]),
        ..GridOptions::default()
    };
    let fine = GridOptions {
        density: 20.0,
        ..GridOptions::default()
    };
    [
        ("default", GridOptions::default()),
        ("coarse", coarse),
        ("fine", fine),
    ]
}

fn conformance<P: Map>(seed: u64) {
    let mut rng = rng(seed);
    let scenes = scenes::<P>(&mut rng);
    let other = Grid::build(&scenes[3].1);
    for (name, prims) in &scenes {
        for (label, options) in options() {
            let grid = Grid::build_with(prims, &options);
            let corners = corners(&grid, &mut rng, 10);
            let rays = rays_for(&mut rng, prims, &corners, 40);
            let points = points_for(&mut rng, prims, &corners, 10);
            let name = format!("{name} ({label}, {:?} cells)", grid.resolution());
            check_queries(&name, &grid, Some(&other), &rays, &points, &mut rng);
        }
    }
}

#[test]
fn segments_agree_with_brute_force() {
    conformance::<Segment2>(1);
}

#[test]
fn triangles_agree_with_brute_force() {
    conformance::<Triangle3>(2);
}

#[test]
fn points_2d_agree_with_brute_force() {
    conformance::<Vec2>(3);
}

#[test]
fn points_3d_agree_with_brute_force() {
    conformance::<Vec3>(4);
}

/// A 10 x 10 grid over `[0, 10]^2` (integer boundaries, exactly) with the given segments.
fn unit_grid(mut segments: Vec<Segment2>) -> (Grid<Segment2>, Vec<Segment2>) {
    segments.push(Segment2::new(Vec2::ZERO, Vec2::ZERO));
    segments.push(Segment2::new(Vec2::splat(10.0), Vec2::splat(10.0)));
    let options = GridOptions {
        resolution: Some([10, 10, 1]),
        ..GridOptions::default()
    };
    (Grid::build_with(&segments, &options), segments)
}

#[test]
fn a_long_primitive_is_listed_in_exactly_the_cells_it_touches() {
    let diagonal = Segment2::new(Vec2::ZERO, Vec2::splat(10.0));
    let (grid, _) = unit_grid(vec![diagonal]);
    assert_eq!(grid.resolution(), [10, 10, 1]);
    grid.validate().expect("valid grid");
    let touched = (0..grid.cell_count())
        .filter(|&c| diagonal.intersects_aabb(&grid.cell_box(grid.cell_coords(c))))
        .count();
    let listed = (0..grid.cell_count())
        .filter(|&c| grid.cell_primitives(c).contains(&0))
        .count();
    assert_eq!(listed, touched);
    // The diagonal runs through the cells (k, k) and touches their neighbours' corners.
    assert!((10..=28).contains(&listed), "{listed}");
    let stats = grid.stats();
    assert_eq!(
        stats.references,
        stats.primitives + stats.duplicated_references()
    );
    assert!(stats.duplicated_references() >= 9);
    assert_eq!(stats.sah_cost, None);
}

#[test]
fn a_duplicated_primitive_is_tested_once_per_ray() {
    let wall = Segment2::new(Vec2::new(0.0, 5.5), Vec2::new(10.0, 5.5));
    let (grid, _) = unit_grid(vec![wall]);
    let ray = Ray::new(Vec2::new(-1.0, 5.0), Vec2::new(1.0, 0.05)).expect("ray");
    let mut recorder = Recorder::default();
    let traced = grid.ray_all_hits_observed(&ray, f32::INFINITY, &mut recorder);
    assert_eq!(traced.answer.len(), 1);
    let tests_of_wall = |result: fn(&PrimitiveResult) -> bool| {
        recorder
            .events
            .iter()
            .filter(|e| matches!(e, Event::PrimitiveTest { prim: 0, result: r } if result(r)))
            .count()
    };
    assert_eq!(tests_of_wall(|r| *r != PrimitiveResult::AlreadyTested), 1);
    assert!(tests_of_wall(|r| *r == PrimitiveResult::AlreadyTested) >= 5);
    assert_eq!(traced.cost.prim_tests, 1);
}

#[test]
fn a_hit_beyond_the_cell_does_not_end_the_walk() {
    // The slanted segment is listed in the ray's first cell but hit only at x = 5; the
    // vertical one at x = 3 is nearer.
    let slanted = Segment2::new(Vec2::new(0.5, 5.2), Vec2::new(9.5, 5.8));
    let vertical = Segment2::new(Vec2::new(3.0, 5.1), Vec2::new(3.0, 5.9));
    let (grid, _) = unit_grid(vec![slanted, vertical]);
    let ray = Ray::new(Vec2::new(0.0, 5.5), Vec2::X).expect("ray");
    let mut recorder = Recorder::default();
    let hit = grid
        .ray_first_hit_observed(&ray, f32::INFINITY, &mut recorder)
        .answer;
    assert_eq!(hit.map(|h| h.prim), Some(1));
    assert!(
        recorder
            .events
            .iter()
            .any(|e| matches!(e, Event::HitBeyondRegion { prim: 0, .. }))
    );
    // The walk stops at the first cell beyond the hit, and says why.
    let last = recorder.events.last().expect("events");
    assert!(
        matches!(
            last,
            Event::Prune {
                reason: PruneReason::BeyondBestHit { .. },
                ..
            }
        ),
        "{last:?}"
    );
    let entered: Vec<[u32; 3]> = recorder
        .events
        .iter()
        .filter_map(|e| match e {
            Event::CellEnter { coords, .. } => Some(*coords),
            _ => None,
        })
        .collect();
    assert_eq!(entered, [[0, 5, 0], [1, 5, 0], [2, 5, 0], [3, 5, 0]]);
}

#[test]
fn cells_are_walked_in_order_with_contiguous_intervals() {
    let mut rng = rng(7);
    let prims = Triangle3::random(&mut rng, 400, 1.0);
    let grid = Grid::build(&prims);
    for _ in 0..50 {
        let origin: Vec3 = grid_support::random_vector(&mut rng, 15.0);
        let ray = Ray::new(origin, grid_support::random_vector(&mut rng, 1.0)).expect("ray");
        let mut recorder = Recorder::default();
        grid.ray_all_hits_observed(&ray, f32::INFINITY, &mut recorder);
        let mut last_exit = f32::NEG_INFINITY;
        for event in &recorder.events {
            if let Event::CellEnter {
                t_enter,
                t_exit,
                cell,
                coords,
            } = *event
            {
                assert!(t_enter <= t_exit, "{event:?}");
                assert!(
                    t_enter >= last_exit - 1e-4 * last_exit.abs().max(1.0),
                    "{event:?} after {last_exit}"
                );
                assert_eq!(grid.cell_index(coords), cell.index());
                last_exit = last_exit.max(t_exit);
            }
        }
    }
}

#[test]
fn rays_on_cell_boundaries_with_signed_zero_directions() {
    let mut rng = rng(8);
    let mut segments: Vec<Segment2> = (0..80)
        .map(|_| {
            let a = Vec2::new(
                rng.random_range(0..=10) as f32,
                rng.random_range(0..=10) as f32,
            );
            let b = Vec2::new(
                rng.random_range(0..=10) as f32,
                rng.random_range(0..=10) as f32,
            );
            Segment2::new(a, b)
        })
        .collect();
    segments.push(Segment2::new(Vec2::new(4.0, 3.0), Vec2::new(6.0, 3.0)));
    let (grid, segments) = unit_grid(segments);
    let brute = bvhlab::BruteForce::build(&segments);
    for k in 0..=10 {
        for (origin, dir) in [
            (Vec2::new(-1.0, k as f32), Vec2::new(1.0, 0.0)),
            (Vec2::new(-1.0, k as f32), Vec2::new(1.0, -0.0)),
            (Vec2::new(11.0, k as f32), Vec2::new(-1.0, -0.0)),
            (Vec2::new(k as f32, 11.0), Vec2::new(0.0, -1.0)),
            (Vec2::new(k as f32, -1.0), Vec2::new(-0.0, 1.0)),
            (Vec2::new(k as f32, 2.0), Vec2::new(0.0, 1.0)),
            (Vec2::new(0.0, k as f32), Vec2::new(1.0, 1.0)),
            (Vec2::new(k as f32, 0.0), Vec2::new(-1.0, 1.0)),
        ] {
            let ray = Ray::new(origin, dir).expect("ray");
            assert_eq!(
                grid.ray_first_hit(&ray, f32::INFINITY),
                brute.ray_first_hit(&ray, f32::INFINITY),
                "{ray:?}"
            );
            assert_eq!(
                grid.ray_all_hits(&ray, f32::INFINITY),
                brute.ray_all_hits(&ray, f32::INFINITY),
                "{ray:?}"
            );
        }
    }
}

#[test]
fn non_finite_primitives_are_left_out_and_never_answered() {
    let mut rng = rng(9);
    let mut prims = Triangle3::random(&mut rng, 100, 1.5);
    prims[3].a.x = f32::NAN;
    prims[50].b = Vec3::splat(f32::INFINITY);
    prims[77].c.y = f32::NEG_INFINITY;
    let grid = Grid::build(&prims);
    assert!(grid.unplaced().is_empty(), "{:?}", grid.unplaced());
    assert_eq!(grid.stats().primitives, 100);
    let listed: Vec<u32> = (0..grid.cell_count())
        .flat_map(|c| grid.cell_primitives(c).iter().copied())
        .collect();
    for left_out in [3, 50, 77] {
        assert!(!listed.contains(&left_out), "{left_out} is listed");
    }
    // Rays and points aimed at the left-out triangles' finite vertices too: whatever the
    // geometry says, neither the grid nor brute force answers with them.
    let rays = rays_for(&mut rng, &prims[..80], &[], 120);
    let points = points_for(&mut rng, &prims[..80], &[], 20);
    check_queries("non-finite", &grid, Some(&grid), &rays, &points, &mut rng);
    for ray in &rays {
        for hit in grid.ray_all_hits(ray, f32::INFINITY) {
            assert!(![3, 50, 77].contains(&hit.prim), "{hit:?}");
        }
    }
}

#[test]
fn coordinates_near_the_float_limit() {
    let mut rng = rng(10);
    let prims: Vec<Segment2> = Segment2::random(&mut rng, 60, 3.0)
        .iter()
        .map(|s| s.map(|v| v * 3e37))
        .collect();
    let grid = Grid::build(&prims);
    let rays = rays_for(&mut rng, &prims, &[], 60);
    let points = points_for(&mut rng, &prims, &[], 10);
    check_queries(
        "near f32::MAX",
        &grid,
        Some(&grid),
        &rays,
        &points,
        &mut rng,
    );
}

#[test]
fn resolution_follows_the_options() {
    let mut rng = rng(11);
    let prims = Triangle3::random(&mut rng, 1000, 1.0);
    let grid = Grid::build(&prims);
    let cells = grid.cell_count();
    assert!(
        (1000..=6000).contains(&cells),
        "about 3 cells per triangle: {cells}"
    );
    let capped = Grid::build_with(
        &prims,
        &GridOptions {
            max_cells: 100,
            ..GridOptions::default()
        },
    );
    assert!(
        capped.cell_count() <= 100 && capped.cell_count() >= 20,
        "{:?}",
        capped.resolution()
    );
    let fixed = Grid::build_with(
        &prims,
        &GridOptions {
            resolution: Some([4, 5, 6]),
            ..GridOptions::default()
        },
    );
    assert_eq!(fixed.resolution(), [4, 5, 6]);
    // A flat scene gets one cell across its flat axis.
    let flat: Vec<Triangle3> = prims
        .iter()
        .map(|t| {
            t.map(|mut v| {
                v.z = 2.0;
                v
            })
        })
        .collect();
    assert_eq!(Grid::build(&flat).resolution()[2], 1);
    // Points in 2D: the unused third axis has one cell.
    assert_eq!(Grid::build(&[Vec2::ZERO, Vec2::ONE]).resolution()[2], 1);
    let empty = Grid::<Triangle3>::build(&[]);
    assert_eq!(empty.cell_count(), 0);
    assert_eq!(empty.stats().nodes, 0);
    empty.validate().expect("empty grid is valid");
}

#[test]
fn identical_primitives_and_a_single_point() {
    let same = vec![Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y); 50];
    let grid = Grid::build(&same);
    grid.validate().expect("valid");
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z).expect("ray");
    assert_eq!(
        grid.ray_first_hit(&ray, f32::INFINITY).map(|h| h.prim),
        Some(0)
    );
    assert_eq!(grid.ray_all_hits(&ray, f32::INFINITY).len(), 50);
    let point = Grid::build(&[Vec3::splat(2.0)]);
    assert_eq!(point.cell_count(), 1);
    assert_eq!(point.k_nearest(Vec3::ZERO, 3).len(), 1);
}

#[test]
fn real_meshes() {
    let mut rng = rng(12);
    for (name, rays) in [
        ("spot.obj", 150),
        ("teapot.obj", 150),
        ("fandisk.obj", 150),
        ("stanford-bunny.obj", 40),
    ] {
        let Some(mesh) = load_mesh(name) else { return };
        let grid = Grid::build(&mesh);
        let corners = corners(&grid, &mut rng, 5);
        let rays: Vec<Ray<Vec3>> = rays_for(&mut rng, &mesh, &corners, rays);
        let points = points_for(&mut rng, &mesh, &[], 6);
        let other = Grid::build(&mesh[..20]);
        let other = (mesh.len() < 20_000).then_some(&other);
        check_queries(name, &grid, other, &rays, &points, &mut rng);
    }
}

/// Regression (found by `tests/extreme_values.rs`): a ray from a million units away, aimed
/// exactly at a point on the grid's far corner, missed it. The rounding tolerance (relative
/// to the origin's magnitude) was wider than a cell, so the crossing of the last row "tied"
/// with the column crossings several cells earlier, and stepping both at once left the grid
/// before the cells between were visited.
#[test]
fn a_ray_from_far_away_visits_every_cell_to_the_far_corner() {
    let points = [Vec2::new(-1.0, 2.0), Vec2::new(-3.0, -2.0)];
    let ray = Ray::new(Vec2::new(-1e6, 0.0), Vec2::new(999_999.0, 2.0)).expect("ray");
    let brute = bvhlab::BruteForce::build(&points);
    let want = brute.ray_first_hit(&ray, f32::INFINITY);
    assert_eq!(want.map(|h| h.prim), Some(0), "the ray is aimed at point 0");
    for n in [2, 7, 30] {
        let grid = Grid::build_with(
            &points,
            &GridOptions {
                resolution: Some([n, n, 1]),
                ..GridOptions::default()
            },
        );
        assert_eq!(
            grid.ray_first_hit(&ray, f32::INFINITY),
            want,
            "{n} x {n} cells"
        );
        assert_eq!(
            grid.ray_all_hits(&ray, f32::INFINITY),
            brute.ray_all_hits(&ray, f32::INFINITY)
        );
        assert!(
            grid.ray_any_hit(&ray, f32::INFINITY).is_some(),
            "{n} x {n} cells"
        );
    }
}

/// Regression (found by `tests/extreme_values.rs`): a flat grid (two points on `y = 3`) and
/// a ray along it whose `y` direction is tiny (-8e-27) but not zero. In exact arithmetic the
/// ray leaves the grid's single row at once, so the walk stopped there; but `ray.at(t)`
/// rounds back onto `y = 3` all the way, and brute force hits both points.
#[test]
fn a_ray_with_a_tiny_component_along_a_flat_grid_walks_all_of_it() {
    let points = [Vec2::new(-1.0, 3.0), Vec2::new(0.0, 3.0)];
    let ray = Ray::new(Vec2::new(0.0, 3.0), Vec2::new(-8.5e13, -8e-27)).expect("ray");
    let brute = bvhlab::BruteForce::build(&points);
    let want = brute.ray_all_hits(&ray, f32::INFINITY);
    assert_eq!(want.len(), 2, "brute force hits both points: {want:?}");
    for resolution in [None, Some([6, 1, 1]), Some([6, 3, 1])] {
        let grid = Grid::build_with(
            &points,
            &GridOptions {
                resolution,
                ..GridOptions::default()
            },
        );
        assert_eq!(
            grid.ray_all_hits(&ray, f32::INFINITY),
            want,
            "{resolution:?}"
        );
    }
}

/// Regression (found by `tests/extreme_values.rs`): a segment from 6.5e5 down to 2.4e-12 and a
/// ball of radius 1e-13 around the origin. The segment's `f32` distance, only as exact as its
/// 6.5e5 coordinates, puts it inside the ball, so brute force reports it; the grid grew the
/// ball only by the rounding of the ball's own (zero) coordinates, found no cell, and
/// reported nothing. The grid and the 2^D tree now grow it by their scene's magnitude too.
#[test]
fn a_ball_range_allows_for_the_rounding_of_huge_primitives() {
    let segments = [Segment2::new(
        Vec2::new(645_727.56, -7.153_794_6e-22),
        Vec2::new(2.351_865_2e-12, -6.857_922e-26),
    )];
    let ball = bvhlab::RangeShape::Ball(bvhlab::Sphere::new(Vec2::ZERO, 1e-13));
    let want = bvhlab::BruteForce::build(&segments).range(&ball);
    assert_eq!(want, [0], "brute force, within the segment's rounding");
    assert_eq!(Grid::build(&segments).range(&ball), want, "grid");
    assert_eq!(
        bvhlab::Quadtree2::build(&segments).range(&ball),
        want,
        "quadtree"
    );
}
