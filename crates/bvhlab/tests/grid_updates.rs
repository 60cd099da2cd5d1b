//! Inserting, removing and moving primitives in a uniform grid (issue 20, "Moving
//! geometry"): after every step of seeded random sequences, in 2D and 3D, the grid validates
//! (every primitive listed exactly in the cells it touches, or unplaced when it left the
//! box), holds what a plain `Vec` holds after the same steps, answers every query as brute
//! force, and has edited no cell but those the primitive covered or now covers.

use crate::grid_support;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::{Removed, UpdateError};
use bvhlab::{Grid, Primitive, Segment2, SpatialIndex, Triangle3};
use grid_support::{Map, check_queries, load_mesh, points_for, random_vector, rays_for, rng};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Every cell's list, to compare before and after an update.
fn lists<P: Primitive>(grid: &Grid<P>) -> Vec<Vec<u32>> {
    (0..grid.cell_count())
        .map(|c| grid.cell_primitives(c).to_vec())
        .collect()
}

/// The cells that list any of `ids`.
fn cells_listing(lists: &[Vec<u32>], ids: &[u32]) -> Vec<usize> {
    (0..lists.len())
        .filter(|&c| ids.iter().any(|id| lists[c].contains(id)))
        .collect()
}

/// Checks that only cells listing `ids` before or after changed.
fn only_touched(name: &str, before: &[Vec<u32>], after: &[Vec<u32>], ids: &[u32]) {
    let mut touched = cells_listing(before, ids);
    touched.extend(cells_listing(after, ids));
    for c in 0..before.len() {
        if !touched.contains(&c) {
            assert_eq!(before[c], after[c], "{name}: cell {c} changed, untouched");
        }
    }
}

/// A random primitive: mostly inside the build's box (`[-10, 10]`), sometimes beyond it,
/// rarely with a NaN vertex.
fn random_prim<P: Map>(rng: &mut ChaCha8Rng) -> P {
    let prim = P::random(rng, 1, 1.5)[0];
    match rng.random_range(0..20) {
        0 => prim.map(|v| v * f32::NAN),
        1..=3 => prim.map(|v| v * 1.4),
        _ => prim,
    }
}

fn check<P: Map>(name: &str, grid: &Grid<P>, want: &[P], other: &Grid<P>, rng: &mut ChaCha8Rng) {
    assert_eq!(
        format!("{:?}", grid.primitives()),
        format!("{want:?}"),
        "{name}: the primitives"
    );
    let rays = rays_for(rng, want, &[], 8);
    let points = points_for(rng, want, &[], 3);
    check_queries(name, grid, Some(other), &rays, &points, rng);
}

/// `steps` random inserts, removes and moves, checking after each; then down to nothing
/// and back.
fn random_sequence<P: Map>(name: &str, seed: u64, steps: usize) {
    let mut rng = rng(seed);
    let mut want: Vec<P> = P::random(&mut rng, 60, 1.5);
    let mut grid = Grid::build(&want);
    let other = Grid::build(&P::random(&mut rng, 30, 2.0));
    let mut unplaced_seen = 0;
    for step in 0..steps {
        let n = want.len();
        let before = lists(&grid);
        let (what, ids) = match rng.random_range(0..4) {
            0 => {
                let prim = random_prim(&mut rng);
                assert_eq!(grid.insert(prim), n, "{name}: insert's index");
                want.push(prim);
                ("insert", vec![n as u32])
            }
            1 if n > 0 => {
                let i = rng.random_range(0..n);
                let removed = grid.remove(i).expect("in range");
                let want_removed = Removed {
                    prim: want.swap_remove(i),
                    moved_from: (i != n - 1).then_some(n - 1),
                };
                assert_eq!(
                    format!("{removed:?}"),
                    format!("{want_removed:?}"),
                    "{name}"
                );
                ("remove", vec![i as u32, (n - 1) as u32])
            }
            _ if n > 0 => {
                let i = rng.random_range(0..n);
                let prim = if rng.random_bool(0.7) {
                    let shift = random_vector::<P::Point>(&mut rng, 3.0);
                    want[i].map(|v| v + shift)
                } else {
                    random_prim(&mut rng)
                };
                let old = grid.replace(i, prim).expect("in range");
                assert_eq!(format!("{old:?}"), format!("{:?}", want[i]), "{name}");
                want[i] = prim;
                ("replace", vec![i as u32])
            }
            _ => continue,
        };
        let name = format!("{name}, step {step} ({what})");
        only_touched(&name, &before, &lists(&grid), &ids);
        unplaced_seen += grid.unplaced().len();
        check(&name, &grid, &want, &other, &mut rng);
    }
    assert!(unplaced_seen > 0, "{name}: no primitive ever left the box");
    while !want.is_empty() {
        let i = rng.random_range(0..want.len());
        grid.remove(i).expect("in range");
        want.swap_remove(i);
        check(&format!("{name}, emptying"), &grid, &want, &other, &mut rng);
    }
    assert_eq!(
        grid.stats().references,
        0,
        "{name}: an empty grid lists nothing"
    );
    for _ in 0..10 {
        let prim = random_prim(&mut rng);
        grid.insert(prim);
        want.push(prim);
        check(
            &format!("{name}, refilling"),
            &grid,
            &want,
            &other,
            &mut rng,
        );
    }
}

#[test]
fn segment_grids_stay_exact_through_random_inserts_removes_and_moves() {
    random_sequence::<Segment2>("segments", 1, 200);
}

#[test]
fn triangle_grids_stay_exact_through_random_inserts_removes_and_moves() {
    random_sequence::<Triangle3>("triangles", 2, 200);
}

#[test]
fn point_grids_stay_exact_through_random_inserts_removes_and_moves() {
    random_sequence::<Vec2>("2D points", 3, 150);
    random_sequence::<Vec3>("3D points", 4, 150);
}

#[test]
fn a_grid_built_over_nothing_keeps_every_insert_unplaced() {
    let mut rng = rng(5);
    let mut grid = Grid::<Segment2>::build(&[]);
    let want: Vec<Segment2> = Segment2::random(&mut rng, 20, 1.5);
    for (i, &prim) in want.iter().enumerate() {
        assert_eq!(grid.insert(prim), i);
    }
    assert_eq!(grid.cell_count(), 0);
    assert_eq!(grid.unplaced().len(), want.len());
    check("built over nothing", &grid, &want, &grid.clone(), &mut rng);
}

#[test]
fn many_inserts_into_the_same_cells_move_and_compact_the_lists() {
    // Lists outgrow their room again and again, and the entries left behind reach half
    // the array: the lists are packed again, and all stays exact.
    let mut rng = rng(6);
    let mut want: Vec<Triangle3> = Triangle3::random(&mut rng, 50, 1.5);
    let mut grid = Grid::build(&want);
    let memory_built = grid.stats().memory_bytes;
    for _ in 0..4000 {
        let prim = Triangle3::random(&mut rng, 1, 1.5)[0].map(|v| v * 0.2);
        grid.insert(prim);
        want.push(prim);
    }
    grid.validate().expect("valid");
    let other = Grid::build(&want[..10]);
    check("crowded", &grid, &want, &other, &mut rng);
    // Then most go again, so lists shrink within their rooms.
    while want.len() > 100 {
        let i = rng.random_range(0..want.len());
        grid.remove(i).expect("in range");
        want.swap_remove(i);
    }
    check("thinned", &grid, &want, &other, &mut rng);
    assert!(grid.stats().memory_bytes > memory_built);
}

#[test]
fn updates_of_missing_primitives_are_refused_and_change_nothing() {
    let mut rng = rng(7);
    let prims = Segment2::random(&mut rng, 10, 1.5);
    let mut grid = Grid::build(&prims);
    let before = grid.clone();
    assert_eq!(
        grid.remove(10),
        Err(UpdateError::NoSuchPrimitive { index: 10, len: 10 })
    );
    assert!(grid.replace(11, prims[0]).is_err());
    assert_eq!(grid, before);
}

#[test]
fn a_mesh_grid_loses_and_regains_a_third_of_its_triangles() {
    let Some(mesh) = load_mesh("suzanne.obj") else {
        return;
    };
    let mut rng = rng(8);
    let mut grid = Grid::build(&mesh);
    let mut want = mesh.clone();
    let other = Grid::build(&mesh[..50]);
    let mut taken = Vec::new();
    for _ in 0..mesh.len() / 3 {
        let i = rng.random_range(0..want.len());
        grid.remove(i).expect("in range");
        taken.push(want.swap_remove(i));
    }
    let rays = rays_for(&mut rng, &want, &[], 60);
    let points = points_for(&mut rng, &want, &[], 20);
    check_queries(
        "suzanne, a third removed",
        &grid,
        Some(&other),
        &rays,
        &points,
        &mut rng,
    );
    for prim in taken {
        grid.insert(prim);
        want.push(prim);
    }
    assert!(
        grid.unplaced().is_empty(),
        "every triangle is back inside the box"
    );
    assert_eq!(grid.primitives(), &want[..]);
    let rays = rays_for(&mut rng, &want, &[], 60);
    let points = points_for(&mut rng, &want, &[], 20);
    check_queries(
        "suzanne, all back",
        &grid,
        Some(&other),
        &rays,
        &points,
        &mut rng,
    );
    // The same cells list the same triangles (under their new indices) as a fresh build.
    let fresh = Grid::build(&want);
    assert_eq!(fresh.resolution(), grid.resolution());
    assert_eq!(lists(&fresh), lists(&grid), "the lists equal a rebuild's");
}
