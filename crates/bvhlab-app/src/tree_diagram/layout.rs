//! Where each node sits in the diagram, computed once per outline.
//!
//! A tree (or forest) gets a tidy drawing (see `tidy.rs`): x from the tidy walk, y the depth,
//! root on top. A uniform grid's cells are all roots with no links: a row of 20,000 siblings
//! would say nothing, so they are shown where they are, as a grid of squares in their cells'
//! places (from the cells' boxes), and the widget says that a grid is not a tree.
//!
//! Positions are in layout units (one unit between neighbours, one per level or grid row); the
//! widget's camera maps them to the screen. Nodes are also kept by row, sorted by x, so that
//! drawing and hovering find the visible nodes by binary search instead of visiting all of
//! them every frame.

use std::ops::Range;

use bvhlab::{NodeOutline, Vector};

use super::forest::{Forest, NONE};
use super::tidy::tidy_x;

/// What a layout was computed from: equal keys mean an equal layout.
///
/// The layout reads only the children lists (and, for a grid, the cells' corners), so the key
/// hashes exactly those: dragging a shape that does not change the structure's topology keeps
/// the layout, the camera and the student's pan and zoom. Hashing 20,000 nodes costs a few
/// tens of microseconds a frame, and saves the caller from passing a generation counter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct LayoutKey(u64);

impl LayoutKey {
    /// The key of `outline`'s layout.
    pub(super) fn of<V: Vector>(outline: &[NodeOutline<V>]) -> Self {
        // The word-at-a-time mix of rustc's FxHasher: fast, and enough to notice a change.
        let mix = |h: u64, word: u64| (h.rotate_left(5) ^ word).wrapping_mul(0x517c_c1b7_2722_0a95);
        let mut h = mix(0, outline.len() as u64);
        let mut linked = false;
        for node in outline {
            h = mix(h, node.children.len() as u64);
            for c in &node.children {
                h = mix(h, u64::from(c.0));
            }
            linked |= !node.children.is_empty();
        }
        if !linked {
            for node in outline {
                let corner = node.shape.aabb().min;
                for axis in 0..V::DIM {
                    h = mix(h, u64::from(corner.coord(axis).to_bits()));
                }
            }
        }
        Self(h)
    }
}

/// How the nodes are arranged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Arrangement {
    /// A tidy tree; rows are depths, `levels` of them.
    Tree {
        /// How many depths (the deepest node's depth plus one).
        levels: usize,
    },
    /// Cells without links (a uniform grid), in `cols` by `rows` places.
    Grid {
        /// Columns.
        cols: usize,
        /// Rows.
        rows: usize,
    },
}

/// Every node's place, and the nodes by row for culling and hovering.
pub(super) struct Layout {
    /// What it was computed from.
    pub(super) key: LayoutKey,
    /// Tree or grid.
    pub(super) arrangement: Arrangement,
    /// Per node id: x, and the row (the depth in a tree).
    pub(super) pos: Vec<[f32; 2]>,
    /// Per node id: the parent the edge goes to, or [`NONE`] for a root.
    pub(super) parent: Vec<usize>,
    /// The rightmost x (the leftmost is 0).
    pub(super) x_max: f32,
    /// How many nodes have no children.
    pub(super) leaves: usize,
    rows: Rows,
}

/// The nodes row by row, each row sorted by x.
struct Rows {
    /// Row `r` is `ids[start[r]..start[r + 1]]`.
    start: Vec<usize>,
    ids: Vec<u32>,
    x: Vec<f32>,
    /// The horizontal extent of the edge from each node up to its parent: both bounds are
    /// sorted along a row too, since a tidy drawing keeps the order of the level above.
    edge_lo: Vec<f32>,
    edge_hi: Vec<f32>,
}

impl Layout {
    /// The layout of `outline` (no rows when it is empty).
    pub(super) fn new<V: Vector>(outline: &[NodeOutline<V>]) -> Self {
        let key = LayoutKey::of(outline);
        let leaves = outline.iter().filter(|n| n.is_leaf()).count();
        let forest = Forest::from_outline(outline);
        let lone_cells = outline.len() > 1 && leaves == outline.len();
        let (arrangement, pos, parent) = if lone_cells {
            let (cols, rows, pos) = grid_places(outline);
            (
                Arrangement::Grid { cols, rows },
                pos,
                vec![NONE; outline.len()],
            )
        } else {
            let depth = forest.depths();
            let x = tidy_x(&forest);
            let levels = depth.iter().max().map_or(1, |&d| d as usize + 1);
            let pos = x.iter().zip(&depth).map(|(&x, &d)| [x, d as f32]).collect();
            let root = forest.root();
            let parent = (0..outline.len())
                .map(|v| {
                    Some(forest.parent(v))
                        .filter(|&p| p != root)
                        .unwrap_or(NONE)
                })
                .collect();
            (Arrangement::Tree { levels }, pos, parent)
        };
        let x_max = pos.iter().map(|p: &[f32; 2]| p[0]).fold(0.0, f32::max);
        let rows = Rows::new(&pos, &parent);
        Self {
            key,
            arrangement,
            pos,
            parent,
            x_max,
            leaves,
            rows,
        }
    }

    /// How many rows (levels, or grid rows).
    pub(super) fn row_count(&self) -> usize {
        self.rows.start.len() - 1
    }

    /// The node's depth in the tree (0 for every grid cell).
    pub(super) fn depth(&self, id: usize) -> u32 {
        match self.arrangement {
            Arrangement::Tree { .. } => self.pos[id][1] as u32,
            Arrangement::Grid { .. } => 0,
        }
    }

    /// The nodes of row `r` with `x` in `[lo, hi]`, left to right.
    pub(super) fn nodes_between(&self, r: usize, lo: f32, hi: f32) -> &[u32] {
        let range = self.rows.range(r);
        let xs = &self.rows.x[range.clone()];
        let (a, b) = (
            xs.partition_point(|&x| x < lo),
            xs.partition_point(|&x| x <= hi),
        );
        &self.rows.ids[range.start + a..range.start + b.max(a)]
    }

    /// The nodes of row `r` whose edge up to their parent crosses `[lo, hi]` in x.
    pub(super) fn edges_between(&self, r: usize, lo: f32, hi: f32) -> &[u32] {
        let range = self.rows.range(r);
        let (edge_lo, edge_hi) = (
            &self.rows.edge_lo[range.clone()],
            &self.rows.edge_hi[range.clone()],
        );
        let a = edge_hi.partition_point(|&x| x < lo);
        let b = edge_lo.partition_point(|&x| x <= hi);
        &self.rows.ids[range.start + a..range.start + b.max(a)]
    }

    /// The nodes of row `r` nearest `x`, on either side.
    pub(super) fn nearest_in_row(&self, r: usize, x: f32) -> impl Iterator<Item = usize> {
        let range = self.rows.range(r);
        let k = self.rows.x[range.clone()].partition_point(|&xi| xi < x);
        let around = k.saturating_sub(1)..(k + 1).min(range.len());
        self.rows.ids[range.start + around.start..range.start + around.end]
            .iter()
            .map(|&id| id as usize)
    }
}

impl Rows {
    fn new(pos: &[[f32; 2]], parent: &[usize]) -> Self {
        let count = pos.iter().map(|p| p[1] as usize + 1).max().unwrap_or(0);
        // Counting sort by row, then sort each row by x.
        let mut start = vec![0; count + 1];
        for p in pos {
            start[p[1] as usize + 1] += 1;
        }
        for r in 0..count {
            start[r + 1] += start[r];
        }
        let mut fill = start.clone();
        let mut ids = vec![0; pos.len()];
        for (id, p) in pos.iter().enumerate() {
            let r = p[1] as usize;
            ids[fill[r]] = id as u32;
            fill[r] += 1;
        }
        for r in 0..count {
            ids[start[r]..start[r + 1]]
                .sort_by(|&a, &b| pos[a as usize][0].total_cmp(&pos[b as usize][0]));
        }
        let x: Vec<f32> = ids.iter().map(|&id| pos[id as usize][0]).collect();
        let parent_x = |id: u32| match parent[id as usize] {
            NONE => pos[id as usize][0],
            p => pos[p][0],
        };
        let edge_lo = ids
            .iter()
            .zip(&x)
            .map(|(&id, &x)| x.min(parent_x(id)))
            .collect();
        let edge_hi = ids
            .iter()
            .zip(&x)
            .map(|(&id, &x)| x.max(parent_x(id)))
            .collect();
        Self {
            start,
            ids,
            x,
            edge_lo,
            edge_hi,
        }
    }

    fn range(&self, r: usize) -> Range<usize> {
        match (self.start.get(r), self.start.get(r + 1)) {
            (Some(&a), Some(&b)) => a..b,
            _ => 0..0,
        }
    }
}

/// Cells without links in their places: columns from the distinct left edges of their
/// boxes, rows from the distinct bottom edges (top row first, as y is up in the world). When
/// that does not give one cell per place, they fill a square block in id order instead.
fn grid_places<V: Vector>(outline: &[NodeOutline<V>]) -> (usize, usize, Vec<[f32; 2]>) {
    let corners: Vec<[f32; 2]> = outline
        .iter()
        .map(|n| {
            let min = n.shape.aabb().min;
            [min.coord(0), min.coord(1)]
        })
        .collect();
    let distinct = |axis: usize| -> Vec<f32> {
        let mut v: Vec<f32> = corners
            .iter()
            .map(|c| c[axis])
            .filter(|c| c.is_finite())
            .collect();
        v.sort_by(f32::total_cmp);
        let span = v.last().zip(v.first()).map_or(0.0, |(hi, lo)| hi - lo);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-5 * span);
        v
    };
    let (xs, ys) = (distinct(0), distinct(1));
    let find = |v: &[f32], c: f32| {
        let k = v.partition_point(|&x| x < c);
        // The nearest of the two neighbours, for corners that dedup merged.
        [k.saturating_sub(1), k.min(v.len().saturating_sub(1))]
            .into_iter()
            .min_by(|&a, &b| (v[a] - c).abs().total_cmp(&(v[b] - c).abs()))
            .unwrap_or(0)
    };
    if xs.len() * ys.len() == outline.len() {
        let mut taken = vec![false; outline.len()];
        let places: Vec<[f32; 2]> = corners
            .iter()
            .map(|c| {
                [
                    find(&xs, c[0]) as f32,
                    (ys.len() - 1 - find(&ys, c[1])) as f32,
                ]
            })
            .collect();
        let unique = places.iter().all(|&[col, row]| {
            let slot = &mut taken[row as usize * xs.len() + col as usize];
            !std::mem::replace(slot, true)
        });
        if unique {
            return (xs.len(), ys.len(), places);
        }
    }
    let cols = (outline.len() as f64).sqrt().ceil() as usize;
    let places = (0..outline.len())
        .map(|i| [(i % cols) as f32, (i / cols) as f32])
        .collect();
    (cols, outline.len().div_ceil(cols), places)
}
