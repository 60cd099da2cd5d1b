//! The layout checked on every structure the lab builds, and on random trees whose ids are
//! not in depth-first order: every property is recomputed here by brute force from the
//! positions and the outline, not read back from the layout's own bookkeeping.

use bvhlab::glam::Vec2;
use bvhlab::{Aabb2, NodeId, NodeOutline, NodeShape};

use super::layout::{Arrangement, Layout, LayoutKey};
use super::tidy::SEPARATION;
use crate::model::presets::random_segments;
use crate::model::structures::{BuildSettings, Built, StructureKind};

const EPS: f32 = 1e-3;

fn outline_of(kind: StructureKind, n: usize, seed: u64) -> Vec<NodeOutline<Vec2>> {
    let prims = random_segments(n, 30.0, 2.0, seed).primitives().segments;
    let settings = BuildSettings {
        kind,
        leaf_size: 1,
        ..BuildSettings::default()
    };
    Built::build(&prims, &settings).outline()
}

/// Every tree property the diagram promises, by brute force.
fn check_tree(outline: &[NodeOutline<Vec2>], what: &str) {
    let layout = Layout::new(outline);
    let Arrangement::Tree { levels } = layout.arrangement else {
        panic!("{what}: laid out as a grid");
    };
    assert_eq!(layout.pos.len(), outline.len(), "{what}: every node placed");
    for (id, node) in outline.iter().enumerate() {
        let [x, y] = layout.pos[id];
        assert!(
            x.is_finite() && x >= -EPS && x <= layout.x_max + EPS,
            "{what}: x of {id}"
        );
        // The outline's depths come from the core, not from the layout's own walk.
        assert_eq!(y, node.depth as f32, "{what}: node {id} at its depth");
        assert!((node.depth as usize) < levels, "{what}");
        let xs: Vec<f32> = node
            .children
            .iter()
            .map(|c| layout.pos[c.index()][0])
            .collect();
        if let (Some(&first), Some(&last)) = (xs.first(), xs.last()) {
            assert!(
                (x - 0.5 * (first + last)).abs() < EPS,
                "{what}: {id} at {x} is centred over its children {xs:?}"
            );
            assert!(
                xs.windows(2).all(|w| w[1] - w[0] >= SEPARATION - EPS),
                "{what}: children of {id} in order and apart: {xs:?}"
            );
        }
    }
    // Same depth: sorted, no two closer than the separation, and the parents above them in
    // the same order (no crossing edges, which the edge culling relies on).
    let mut by_depth: Vec<Vec<(f32, usize)>> = vec![Vec::new(); levels];
    for (id, p) in layout.pos.iter().enumerate() {
        by_depth[p[1] as usize].push((p[0], id));
    }
    for row in &mut by_depth {
        row.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in row.windows(2) {
            assert!(
                w[1].0 - w[0].0 >= SEPARATION - EPS,
                "{what}: nodes {} and {} overlap",
                w[0].1,
                w[1].1
            );
        }
        let parent_x: Vec<f32> = row
            .iter()
            .filter_map(|&(_, id)| outline[id].parent)
            .map(|p| layout.pos[p.index()][0])
            .collect();
        assert!(
            parent_x.windows(2).all(|w| w[0] <= w[1] + EPS),
            "{what}: edges cross"
        );
    }
    check_culling(&layout, outline, what);
}

/// The culling queries return exactly the nodes and edges a full scan finds.
fn check_culling(layout: &Layout, outline: &[NodeOutline<Vec2>], what: &str) {
    let windows = [
        (-1.0, 1e9),
        (0.5, 3.5),
        (layout.x_max * 0.3, layout.x_max * 0.6),
        (7.0, 7.0),
    ];
    for r in 0..layout.row_count() {
        for &(lo, hi) in &windows {
            let mut got: Vec<usize> = layout
                .nodes_between(r, lo, hi)
                .iter()
                .map(|&i| i as usize)
                .collect();
            got.sort_unstable();
            let want: Vec<usize> = (0..outline.len())
                .filter(|&id| layout.pos[id][1] as usize == r)
                .filter(|&id| (lo..=hi).contains(&layout.pos[id][0]))
                .collect();
            assert_eq!(got, want, "{what}: nodes of row {r} in [{lo}, {hi}]");
            let mut got: Vec<usize> = layout
                .edges_between(r, lo, hi)
                .iter()
                .map(|&i| i as usize)
                .collect();
            got.sort_unstable();
            let want: Vec<usize> = (0..outline.len())
                .filter(|&id| layout.pos[id][1] as usize == r)
                .filter(|&id| {
                    let x = layout.pos[id][0];
                    let px = outline[id].parent.map_or(x, |p| layout.pos[p.index()][0]);
                    x.max(px) >= lo && x.min(px) <= hi
                })
                .collect();
            assert_eq!(got, want, "{what}: edges of row {r} in [{lo}, {hi}]");
        }
    }
}

#[test]
fn every_structure_is_laid_out_tidily() {
    for kind in StructureKind::ALL {
        for (n, seed) in [(1, 5), (2, 6), (40, 7), (300, 8)] {
            let outline = outline_of(kind, n, seed);
            let what = format!("{kind:?} on {n} segments");
            match kind {
                StructureKind::BruteForce => assert!(outline.is_empty()),
                StructureKind::Grid if outline.len() > 1 => check_grid(&outline, &what),
                _ => check_tree(&outline, &what),
            }
        }
    }
}

#[test]
fn an_empty_scene_is_laid_out_without_panicking() {
    let layout = Layout::new::<Vec2>(&[]);
    assert_eq!(layout.row_count(), 0);
    assert!(layout.pos.is_empty());
    assert!(layout.nodes_between(0, 0.0, 1.0).is_empty());
    for kind in StructureKind::ALL {
        let settings = BuildSettings {
            kind,
            ..BuildSettings::default()
        };
        let outline = Built::<bvhlab::Segment2>::build(&[], &settings).outline();
        let layout = Layout::new(&outline);
        assert_eq!(layout.pos.len(), outline.len(), "{kind:?}");
        assert_eq!(
            layout.row_count(),
            usize::from(!outline.is_empty()),
            "{kind:?}"
        );
    }
}

/// Grid cells: one per place, in the places their boxes are (left to right by x, top to
/// bottom by decreasing y).
fn check_grid(outline: &[NodeOutline<Vec2>], what: &str) {
    let layout = Layout::new(outline);
    let Arrangement::Grid { cols, rows } = layout.arrangement else {
        panic!("{what}: a grid's cells are not a tree");
    };
    assert_eq!(cols * rows, outline.len(), "{what}");
    let mut seen = vec![false; outline.len()];
    for p in &layout.pos {
        let (c, r) = (p[0] as usize, p[1] as usize);
        assert!(
            c < cols && r < rows && p[0] == c as f32 && p[1] == r as f32,
            "{what}"
        );
        assert!(
            !std::mem::replace(&mut seen[r * cols + c], true),
            "{what}: shared place"
        );
    }
    for a in 0..outline.len() {
        for b in 0..outline.len() {
            let (ca, cb) = (
                outline[a].shape.aabb().center(),
                outline[b].shape.aabb().center(),
            );
            if ca.x < cb.x - EPS {
                assert!(
                    layout.pos[a][0] < layout.pos[b][0],
                    "{what}: columns follow x"
                );
            }
            if ca.y < cb.y - EPS {
                assert!(
                    layout.pos[a][1] > layout.pos[b][1],
                    "{what}: rows follow y, top first"
                );
            }
        }
    }
    check_culling(&layout, outline, what);
}

/// A small deterministic generator for random trees.
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 33) % n as u64) as usize
    }
}

/// A random tree of `n` nodes: each new node hangs under a random earlier one (a third of
/// the time under the one just made, for long chains), so nodes have any number of children;
/// then the ids are shuffled (so that parents do not come before children), with parents and
/// depths filled in by brute force.
fn random_tree(n: usize, seed: u64) -> Vec<NodeOutline<Vec2>> {
    let mut rng = Lcg(seed);
    let mut kids: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 1..n {
        let parent = if rng.below(3) == 0 {
            i - 1
        } else {
            rng.below(i)
        };
        kids[parent].push(i);
    }
    let mut rename: Vec<usize> = (0..kids.len()).collect();
    for i in (1..rename.len()).rev() {
        rename.swap(i, rng.below(i + 1));
    }
    let shape = NodeShape::Aabb(Aabb2::new(Vec2::ZERO, Vec2::ONE));
    let mut outline: Vec<NodeOutline<Vec2>> = (0..kids.len())
        .map(|i| NodeOutline {
            id: NodeId(i as u32),
            parent: None,
            depth: 0,
            shape,
            splits: Vec::new(),
            children: Vec::new(),
            primitives: Vec::new(),
        })
        .collect();
    let mut depth = vec![0u32; kids.len()];
    for (old, list) in kids.iter().enumerate() {
        for &c in list {
            depth[c] = depth[old] + 1;
            outline[rename[old]].children.push(NodeId(rename[c] as u32));
            outline[rename[c]].parent = Some(NodeId(rename[old] as u32));
        }
    }
    for (old, &d) in depth.iter().enumerate() {
        outline[rename[old]].depth = d;
    }
    outline
}

#[test]
fn random_trees_out_of_order_are_laid_out_tidily() {
    for seed in 0..60 {
        let n = 1 + (seed as usize * 37) % 400;
        check_tree(
            &random_tree(n, seed),
            &format!("random tree {seed} of {n} nodes"),
        );
    }
}

#[test]
fn tidy_is_no_wider_than_one_column_per_leaf() {
    for seed in 0..30 {
        let outline = random_tree(300, seed);
        let layout = Layout::new(&outline);
        let leaves = outline.iter().filter(|n| n.is_leaf()).count();
        assert!(
            layout.x_max <= (leaves - 1) as f32 * SEPARATION + EPS,
            "seed {seed}"
        );
    }
}

#[test]
fn forests_sit_side_by_side() {
    // Two trees: 0 -> {1, 2} and 3 -> {4}; their roots share depth 0.
    let mut outline = random_tree(1, 0);
    outline.truncate(0);
    let mut tree = |children: &[u32]| {
        let mut node = random_tree(1, 0).remove(0);
        node.id = NodeId(outline.len() as u32);
        node.children = children.iter().map(|&c| NodeId(c)).collect();
        outline.push(node);
    };
    tree(&[1, 2]);
    tree(&[]);
    tree(&[]);
    tree(&[4]);
    tree(&[]);
    for (child, parent) in [(1, 0), (2, 0), (4, 3)] {
        outline[child].parent = Some(NodeId(parent));
        outline[child].depth = 1;
    }
    check_tree(&outline, "a forest of two trees");
}

#[test]
fn the_key_follows_topology_not_geometry() {
    let outline = outline_of(StructureKind::AabbTree, 50, 3);
    let mut moved = outline.clone();
    if let NodeShape::Aabb(b) = &mut moved[0].shape {
        b.max.x += 1.0;
    }
    assert_eq!(LayoutKey::of(&outline), LayoutKey::of(&moved));
    let mut relinked = outline.clone();
    let root = relinked[0].children.clone();
    relinked[0].children = root.into_iter().rev().collect();
    assert_ne!(LayoutKey::of(&outline), LayoutKey::of(&relinked));
    // A grid's cells have no links: there, the cells' places are the layout.
    let grid = outline_of(StructureKind::Grid, 50, 3);
    let mut shifted = grid.clone();
    if let NodeShape::Aabb(b) = &mut shifted[0].shape {
        b.min.x -= 100.0;
    }
    assert_ne!(LayoutKey::of(&grid), LayoutKey::of(&shifted));
}
