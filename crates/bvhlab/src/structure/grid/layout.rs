//! The grid's memory layout: its box, the cell planes per axis, and the cell lists in one
//! index array (each cell's start, length and room, so that updates edit a list in place).

use crate::volume::Aabb;
use crate::{BoundingVolume, Primitive, Vector};

/// Options of a grid build. [`GridOptions::default`] picks the resolution from the primitive
/// count with `density = 3` and at most 2^22 cells.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridOptions {
    /// Cells per primitive, λ in Cleary and Wyvill's rule (see
    /// [`Grid::build_with`]): about `density · n` cells in all. pbrt-v1 uses 3.
    pub density: f32,
    /// Cells per axis, overriding the automatic choice (entries beyond the dimension are
    /// ignored; 0 counts as 1). Axes along which the scene is flat always get one cell.
    pub resolution: Option<[u32; 3]>,
    /// The most cells the grid may have (a memory cap: each cell costs 12 bytes, where its
    /// list lies and how much room it has).
    /// The resolution is scaled down uniformly to fit.
    pub max_cells: usize,
}

impl Default for GridOptions {
    fn default() -> Self {
        Self {
            density: 3.0,
            resolution: None,
            max_cells: 1 << 22,
        }
    }
}

/// A uniform grid over primitives (lecture §3, "Uniform spatial subdivision"): the scene's
/// bounding box cut into equal cells, each listing every primitive that shares a point with
/// it. A primitive that spans several cells is listed in each (the lecture's "duplicate
/// triangle"); queries test it once each (mailboxing).
///
/// One implementation for 2D (segments, points) and 3D (triangles, points). Build with
/// [`Grid::build`] or [`Grid::build_with`]; query through
/// [`SpatialIndex`](crate::SpatialIndex).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "P: serde::Serialize, P::Point: serde::Serialize",
        deserialize = "P: serde::Deserialize<'de>, P::Point: serde::Deserialize<'de>"
    ))
)]
pub struct Grid<P: Primitive> {
    pub(super) prims: Vec<P>,
    /// The box the cells tile: the bounds of the placeable primitives (empty when none).
    pub(super) bounds: Aabb<P::Point>,
    /// Cells per axis; 1 on axes beyond the dimension, all 0 for an empty grid.
    pub(super) dims: [u32; 3],
    /// Per axis, the `dims[i] + 1` cell boundaries from `bounds.min` to `bounds.max`
    /// (exactly those values at the ends), non-decreasing. Cell `k` spans
    /// `[planes[i][k], planes[i][k + 1]]`. Build and queries read the same values, so a
    /// primitive listed in a cell touches exactly the box the queries see.
    pub(super) planes: [Vec<f32>; 3],
    /// Where each cell's list lies in `cell_prims`, in linear cell order.
    pub(super) cell_lists: Vec<CellList>,
    /// The cell lists, each ascending by primitive index, with the room updates left
    /// (`update.rs`); a build packs them in cell order, with no room to spare.
    pub(super) cell_prims: Vec<u32>,
    /// Entries of `cell_prims` that hold no list entry: the room left in lists, and whole
    /// rooms left behind by lists that moved (`update.rs`, which packs the lists again when
    /// these outnumber the entries and cells).
    pub(super) spare: usize,
    /// Primitives in no cell, ascending, tested by every query: those that an update moved
    /// (or inserted) so that they stick out of the grid's box. Primitives with a NaN or
    /// infinite coordinate are in no cell and not here either: no query answers with them.
    pub(super) unplaced: Vec<u32>,
    pub(super) options: GridOptions,
}

/// Where one cell's list lies: `cell_prims[start..start + len]`, with room for updates up
/// to `start + room` (12 bytes a cell: the price of updates that touch only their cells,
/// where compressed sparse rows would move every list after the change).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct CellList {
    pub(super) start: u32,
    pub(super) len: u32,
    pub(super) room: u32,
}

impl CellList {
    /// The entries of `cell_prims` it holds.
    pub(super) fn range(self) -> std::ops::Range<usize> {
        self.start as usize..(self.start + self.len) as usize
    }
}

/// Integer cell coordinates; unused axes are 0.
pub type CellCoords = [u32; 3];

impl<P: Primitive> Grid<P> {
    /// The box the cells tile (empty when no primitive could be placed).
    pub fn bounds(&self) -> Aabb<P::Point> {
        self.bounds
    }

    /// Cells per axis (1 on axes beyond the dimension; all 0 for an empty grid).
    pub fn resolution(&self) -> [u32; 3] {
        self.dims
    }

    /// The options the grid was built with.
    pub fn options(&self) -> &GridOptions {
        &self.options
    }

    /// The number of cells.
    pub fn cell_count(&self) -> usize {
        self.dims.iter().map(|&n| n as usize).product()
    }

    /// The linear index of a cell: `x + nx · (y + ny · z)`.
    pub fn cell_index(&self, c: CellCoords) -> usize {
        let [nx, ny, _] = self.dims.map(|n| n as usize);
        c[0] as usize + nx * (c[1] as usize + ny * c[2] as usize)
    }

    /// The coordinates of the cell with a linear index.
    pub fn cell_coords(&self, index: usize) -> CellCoords {
        let [nx, ny, _] = self.dims.map(|n| n.max(1) as usize);
        [
            (index % nx) as u32,
            (index / nx % ny) as u32,
            (index / (nx * ny)) as u32,
        ]
    }

    /// The closed box of a cell.
    pub fn cell_box(&self, c: CellCoords) -> Aabb<P::Point> {
        let mut b = Aabb::new(P::Point::ZERO, P::Point::ZERO);
        for (i, &k) in c.iter().enumerate().take(P::Point::DIM) {
            b.min.set_coord(i, self.planes[i][k as usize]);
            b.max.set_coord(i, self.planes[i][k as usize + 1]);
        }
        b
    }

    /// The primitives a cell lists, ascending.
    pub fn cell_primitives(&self, index: usize) -> &[u32] {
        &self.cell_prims[self.cell_lists[index].range()]
    }

    /// The primitives in no cell, ascending, which every query tests: those that an update
    /// moved (or inserted) outside the grid's box, which is fixed at build time. A primitive
    /// with a NaN or infinite coordinate is neither in a cell nor here: it is left out
    /// ([`Primitive::has_finite_coordinates`]).
    pub fn unplaced(&self) -> &[u32] {
        &self.unplaced
    }

    /// Whether a primitive goes into cells: every coordinate finite and its box inside the
    /// grid's box. At build time every finite primitive does (the box is theirs); after
    /// updates, one outside goes to [`unplaced`](Self::unplaced).
    pub(super) fn fits(&self, prim: &P) -> bool {
        let b = prim.bounds();
        self.cell_count() > 0
            && prim.has_finite_coordinates()
            && self.bounds.contains(b.min)
            && self.bounds.contains(b.max)
    }

    /// Whether a primitive belongs in [`unplaced`](Self::unplaced): finite, but not inside
    /// the grid's box.
    pub(super) fn belongs_unplaced(&self, prim: &P) -> bool {
        prim.has_finite_coordinates() && !self.fits(prim)
    }

    /// Cell list entries in all (a primitive counts once per cell that lists it).
    pub(super) fn listed(&self) -> usize {
        self.cell_lists.iter().map(|l| l.len as usize).sum()
    }

    /// Boundary `k` along `axis`, widened to `f64`.
    pub(super) fn plane(&self, axis: usize, k: usize) -> f64 {
        f64::from(self.planes[axis][k])
    }

    /// The cell along `axis` whose closed span holds `x`, clamped to the grid (the upper
    /// cell when `x` lies on a boundary).
    pub(super) fn locate(&self, axis: usize, x: f64) -> u32 {
        let n = self.dims[axis] as usize;
        self.planes[axis][1..n].partition_point(|&p| f64::from(p) <= x) as u32
    }

    /// The first cell along `axis` that a closed interval starting at `x` can touch: the
    /// first whose upper boundary is `>= x`.
    pub(super) fn first_cell_reaching(&self, axis: usize, x: f32) -> u32 {
        let n = self.dims[axis] as usize;
        (self.planes[axis][1..=n].partition_point(|&p| p < x) as u32).min(n as u32 - 1)
    }

    /// The last cell along `axis` that a closed interval ending at `x` can touch: the last
    /// whose lower boundary is `<= x`.
    pub(super) fn last_cell_reaching(&self, axis: usize, x: f32) -> u32 {
        let n = self.dims[axis] as usize;
        (self.planes[axis][..n].partition_point(|&p| p <= x) as u32).saturating_sub(1)
    }

    /// The range of cells, per axis, that a closed box can touch, or `None` when it lies
    /// outside the grid.
    pub(super) fn cell_range(&self, b: &Aabb<P::Point>) -> Option<(CellCoords, CellCoords)> {
        if self.cell_count() == 0 {
            return None;
        }
        let (mut lo, mut hi) = ([0; 3], [0; 3]);
        for i in 0..P::Point::DIM {
            let (b_lo, b_hi) = (b.min.coord(i), b.max.coord(i));
            if !(b_lo <= self.bounds.max.coord(i) && self.bounds.min.coord(i) <= b_hi) {
                return None;
            }
            lo[i] = self.first_cell_reaching(i, b_lo);
            hi[i] = self.last_cell_reaching(i, b_hi);
            if lo[i] > hi[i] {
                return None;
            }
        }
        Some((lo, hi))
    }

    /// The cells a primitive is listed in, ascending: every cell its box touches when that is
    /// one cell, else those of them it shares a point with ([`Primitive::intersects_aabb`]).
    /// Should the exact test refuse all of them (it cannot, for an exact test, as the
    /// primitive lies inside the grid), all are kept, so no primitive is lost. The build and
    /// [`validate`](crate::SpatialIndex::validate) both call this.
    pub(super) fn cells_of(&self, prim: &P, out: &mut Vec<u32>) {
        out.clear();
        let Some(range) = self.cell_range(&prim.bounds()) else {
            return;
        };
        let (lo, hi) = range;
        if lo == hi {
            out.push(self.cell_index(lo) as u32);
            return;
        }
        out.extend(
            cells_in(range)
                .filter(|&c| prim.intersects_aabb(&self.cell_box(c)))
                .map(|c| self.cell_index(c) as u32),
        );
        if out.is_empty() {
            out.extend(cells_in(range).map(|c| self.cell_index(c) as u32));
        }
    }

    /// Heap bytes: the primitives, the planes, the list places and the lists.
    pub(super) fn memory_bytes(&self) -> usize {
        self.prims.len() * size_of::<P>()
            + self.planes.iter().map(Vec::len).sum::<usize>() * 4
            + self.cell_lists.len() * size_of::<CellList>()
            + (self.cell_prims.len() + self.unplaced.len()) * 4
    }
}

/// Every cell in an inclusive coordinate range, in linear-index order.
pub(super) fn cells_in((lo, hi): (CellCoords, CellCoords)) -> impl Iterator<Item = CellCoords> {
    (lo[2]..=hi[2]).flat_map(move |z| {
        (lo[1]..=hi[1]).flat_map(move |y| (lo[0]..=hi[0]).map(move |x| [x, y, z]))
    })
}
