//! Unit tests of the grid's internals; the queries are tested against brute force in
//! `tests/grid.rs`.

use glam::{Vec2, Vec3};

use super::layout::{CellCoords, Grid, GridOptions};
use super::resolution::{choose_resolution, planes};
use crate::Segment2;
use crate::volume::Aabb;

#[test]
fn planes_start_and_end_exactly_and_never_decrease() {
    for (lo, hi, n) in [
        (0.0, 10.0, 10),
        (-3e38, 3e38, 7),
        (1e-30, 2e-30, 3),
        (5.0, 5.0, 1),
    ] {
        let p = planes(lo, hi, n);
        assert_eq!(p.len(), n as usize + 1);
        assert_eq!((p[0], p[n as usize]), (lo, hi));
        assert!(p.windows(2).all(|w| w[0] <= w[1]), "{p:?}");
    }
    assert_eq!(planes(0.0, 10.0, 10)[3], 3.0);
}

#[test]
fn resolution_keeps_about_density_times_n_cells_even_for_thin_scenes() {
    let options = GridOptions::default();
    let cube = Aabb::new(Vec3::ZERO, Vec3::splat(1.0));
    let dims = choose_resolution(&cube, 1000, &options);
    assert_eq!(dims, [14, 14, 14]);
    // A long thin box: the thin axes get one cell, the long one about 3n.
    let thin = Aabb::new(Vec3::ZERO, Vec3::new(1e6, 1.0, 1.0));
    assert_eq!(choose_resolution(&thin, 10, &options), [30, 1, 1]);
    let capped = GridOptions {
        max_cells: 64,
        ..options
    };
    let dims = choose_resolution(&cube, 1000, &capped);
    assert!(dims.iter().product::<u32>() <= 64, "{dims:?}");
    assert_eq!(choose_resolution(&Aabb::<Vec2>::EMPTY, 5, &options), [0; 3]);
}

#[test]
fn rings_cover_every_cell_once() {
    // A 10 x 7 grid.
    let all = ([0; 3], [9, 6, 0]);
    for start in [[0, 0, 0], [4, 3, 0], [9, 6, 0]] {
        let mut seen: Vec<CellCoords> = Vec::new();
        for ring in 0..10 {
            Grid::<Segment2>::for_each_in_ring(start, ring, all, |c| seen.push(c));
        }
        seen.sort_unstable();
        let before = seen.len();
        seen.dedup();
        assert_eq!((before, seen.len()), (70, 70), "from {start:?}");
    }
}

#[test]
fn a_diagonal_is_listed_only_where_it_touches() {
    let diagonal = Segment2::new(Vec2::ZERO, Vec2::splat(4.0));
    let grid = Grid::build_with(
        &[diagonal],
        &GridOptions {
            resolution: Some([4, 4, 1]),
            ..GridOptions::default()
        },
    );
    let mut cells = Vec::new();
    grid.cells_of(&diagonal, &mut cells);
    // (k, k) and, through the corners, (k + 1, k) and (k, k + 1).
    assert_eq!(cells, [0, 1, 4, 5, 6, 9, 10, 11, 14, 15]);
}
