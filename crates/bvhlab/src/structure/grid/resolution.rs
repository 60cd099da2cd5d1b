//! How many cells a grid gets along each axis, and where their boundaries lie.

use super::layout::GridOptions;
use crate::volume::Aabb;
use crate::{BoundingVolume, Vector};

/// No axis gets more cells than this, whatever the options say.
const MAX_PER_AXIS: f64 = 65_536.0;

/// Cells per axis for `n` primitives in `bounds`.
///
/// Cleary and Wyvill ("Analysis of an algorithm for fast ray tracing using uniform space
/// subdivision", The Visual Computer 4, 1988) show that a grid with a number of cells
/// proportional to the number of objects keeps the expected cost per ray low; pbrt-v1's
/// `GridAccel` takes `3 · n^(1/3)` cells along the longest axis. Here cells are cubes (squares)
/// as far as possible: `n_i = extent_i · s` with `s = (λ n / volume)^(1/D)`, so that there are
/// about `λ n` cells. Axes along which the scene is flat (extent below 1e-9 of the longest),
/// and axes too thin for one cell at that scale, get one cell and drop out of the volume
/// (then `s` is recomputed over the others), so a planar scene in 3D gets a 2D grid and a
/// long thin one a row of cells, still about `λ n` in all. The result is clamped to
/// `1..=65536` per axis and scaled down uniformly to at most `options.max_cells` cells.
pub(super) fn choose_resolution<V: Vector>(
    bounds: &Aabb<V>,
    n: usize,
    options: &GridOptions,
) -> [u32; 3] {
    let mut dims = [1u32; 3];
    if bounds.is_empty() || n == 0 {
        return [0; 3];
    }
    let extent: Vec<f64> = (0..V::DIM)
        .map(|i| f64::from(bounds.max.coord(i)) - f64::from(bounds.min.coord(i)))
        .collect();
    let longest = extent.iter().copied().fold(0.0, f64::max);
    let mut live: Vec<usize> = (0..V::DIM)
        .filter(|&i| extent[i] > 0.0 && extent[i] > 1e-9 * longest)
        .collect();
    if live.is_empty() {
        return dims;
    }
    let max_cells = options.max_cells.clamp(1, u32::MAX as usize) as f64;
    let per_axis: Vec<f64> = if let Some(wanted) = options.resolution {
        live.iter()
            .map(|&i| f64::from(wanted[i].max(1)).min(MAX_PER_AXIS))
            .collect()
    } else {
        // Axes too thin for one cell get one and leave the volume; repeat until every
        // remaining axis gets at least one.
        let density = f64::from(options.density).clamp(1e-6, 1e6);
        let cells = density * n as f64;
        loop {
            let volume: f64 = live.iter().map(|&i| extent[i]).product();
            let s = (cells / volume).powf(1.0 / live.len() as f64);
            let thick: Vec<usize> = live
                .iter()
                .copied()
                .filter(|&i| extent[i] * s >= 1.0)
                .collect();
            if thick.len() == live.len() || thick.is_empty() {
                break live
                    .iter()
                    .map(|&i| (extent[i] * s).round().clamp(1.0, MAX_PER_AXIS))
                    .collect();
            }
            live = thick;
        }
    };
    let fitted = fit_to_cap(&per_axis, max_cells);
    for (&i, &cells) in live.iter().zip(&fitted) {
        dims[i] = cells as u32;
    }
    dims
}

/// Scales cell counts down uniformly until their product is at most `cap`.
fn fit_to_cap(per_axis: &[f64], cap: f64) -> Vec<f64> {
    let mut cells = per_axis.to_vec();
    for _ in 0..64 {
        let total: f64 = cells.iter().product();
        if total <= cap {
            break;
        }
        let shrink = (cap / total).powf(1.0 / cells.len() as f64) * 0.999;
        for c in &mut cells {
            *c = (*c * shrink).floor().max(1.0);
        }
    }
    cells
}

/// The `cells + 1` boundaries along one axis from `lo` to `hi`: `lo + (hi - lo) · k / cells`
/// rounded once from `f64`, so they are non-decreasing, start at `lo` and end at `hi`
/// exactly, and do not overflow for coordinates near `f32::MAX`.
pub(super) fn planes(lo: f32, hi: f32, cells: u32) -> Vec<f32> {
    let (lo64, hi64) = (f64::from(lo), f64::from(hi));
    (0..=cells)
        .map(|k| {
            if k == 0 {
                lo
            } else if k == cells {
                hi
            } else {
                (lo64 + (hi64 - lo64) * f64::from(k) / f64::from(cells)) as f32
            }
        })
        .collect()
}
