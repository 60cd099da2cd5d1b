//! The builders: what the core's `build_observed` functions run (`bvh/build/` with
//! `median.rs` and `sah.rs`, `kdtree/build/`, `bsp/build.rs`, `quadtree/build.rs`,
//! `grid/build.rs`).
//!
//! The trees report each node when it is made (`BuildNode`), then how it was split
//! (`BuildSplit`; the quadtree reports one per mid-line) or that it became a leaf
//! (`BuildLeaf`), depth first, first child first. The grid reports only each non-empty
//! cell's finished list.

use bvhlab::Event;
use bvhlab::Vector;

use super::listing::{Listing, Step, listing};
use super::{Algorithm, Pseudocode};
use crate::model::structures::StructureKind;

static BRUTE_FORCE: Listing = listing!(
    "Brute force: no build",
    "Without a structure there is nothing to build: every query tests every primitive.",
    [
        _ "build(primitives)",
        _ "    keep the list as it is       // nothing to build",
    ]
);

static BVH: Listing = listing!(
    "BVH: top-down build",
    "Lecture §3: fit a BV around all primitives, split them in two (the slides: spatially, \
     along the longest axis), recurse until a leaf holds few. The binned SAH (MacDonald and \
     Booth 1990; Wald 2007) costs each plane by the children's surface areas (perimeters in \
     2D). A median that leaves one side empty, or a SAH that cannot bin, falls back to the \
     object median.",
    [
        _          "build(prims, depth)              // top down",
        BuildNode  "    bvNode.bv = fit(prims)       // sphere, AABB or OBB",
        _          "    if (|prims| > 1 && depth < maxDepth)",
        _          "        choose a plane across the centres' box:",
        _          "          spatial median: the middle of its longest axis",
        _          "          object median: the median centre on that axis",
        _          "          binned SAH: the cheapest boundary of B bins per",
        _          "            axis, cost 1 + sum A(child)/A(bvNode) N(child)",
        _          "        if (|prims| > leafSize || the SAH cost < |prims|)",
        BuildSplit "            split prims by their centres: below, above",
        _          "            bvNode.left = build(below, depth + 1)",
        _          "            bvNode.right = build(above, depth + 1)",
        _          "            return bvNode",
        BuildLeaf  "    bvNode is a leaf with prims",
        _          "    return bvNode",
    ]
);

static KD_TREE: Listing = listing!(
    "k-d tree: top-down build",
    "Lecture §3: axis-aligned splitting planes, e.g. at the median (Bentley 1975), one axis \
     per level or the longest first; or the surface area heuristic over the primitives' box \
     edges (pbrt-v3 §4.4.2; Wald and Havran 2006). A primitive straddling the plane is \
     listed on both sides, within a budget of references per primitive.",
    [
        _          "build(prims, cell, depth)        // top down",
        BuildNode  "    node = a new node over prims",
        _          "    if (|prims| > leafSize && depth < maxDepth)",
        _          "        choose an axis-aligned plane strictly inside cell:",
        _          "          median: the median centre, else the cell's middle;",
        _          "            axes in turn or longest first, until one separates",
        _          "          SAH: the cheapest edge of a primitive's box, unless",
        _          "            it costs 4x a leaf (few prims) or 3 bad in a row",
        _          "        if (it separates prims within the reference budget)",
        BuildSplit "            split node at the plane; straddlers go both ways",
        _          "            node.below = build(prims below, cell below, depth + 1)",
        _          "            node.above = build(prims above, cell above, depth + 1)",
        _          "            return node",
        BuildLeaf  "    node is a leaf with prims",
        _          "    return node",
    ]
);

static BSP: Listing = listing!(
    "BSP tree: autopartition, top down",
    "Lecture §3: split by arbitrary planes (lines in 2D). Autopartition (Fuchs, Kedem and \
     Naylor 1980): the splitter is the line of one of the node's own primitives, a few \
     chosen at random (Paterson and Yao 1990) and scored by straddlers and imbalance. A \
     primitive straddling the line is listed on both sides.",
    [
        _          "build(prims, depth)              // autopartition",
        BuildNode  "    node = a new node over prims",
        _          "    if (|prims| > leafSize && depth < maxDepth)",
        _          "        candidates = the lines of a few random prims",
        _          "          (optionally the median line across the centres)",
        _          "        score = straddleWeight * straddlers + |below - above|",
        _          "        take the best that separates prims within the budget",
        _          "          (none: the median line across the centres)",
        _          "        if (there is one)",
        BuildSplit "            split node at that line; straddlers go both ways",
        _          "            node.below = build(prims below, depth + 1)",
        _          "            node.above = build(prims above, depth + 1)",
        _          "            return node",
        BuildLeaf  "    node is a leaf with prims",
        _          "    return node",
    ]
);

static QUADTREE: Listing = listing!(
    "Quadtree: top-down build",
    "Lecture §3: split a square into four until each cell holds few primitives. A primitive \
     is listed in every child it touches; a split that would only copy the primitives, or \
     that the surface area heuristic says costs more than it saves, is not made.",
    [
        _          "build(square, prims, depth)      // top down",
        BuildNode  "    cell = a new cell over prims",
        _          "    if (|prims| > leafSize && depth < maxDepth)",
        _          "        cut square into four at its centre; each child",
        _          "          gets every primitive it touches (some: several)",
        _          "        if (it separates prims && 1 + refs / 2 < |prims|)",
        BuildSplit "            split cell at its two mid-lines",
        _          "            for (c in the four children)",
        _          "                build(c.square, c.prims, depth + 1)",
        _          "            return cell",
        BuildLeaf  "    cell is a leaf with prims",
        _          "    return cell",
    ]
);

static GRID: Listing = listing!(
    "Uniform grid: build",
    "Lecture §3: cut the bounding box into equal cells; each cell lists the primitives that \
     overlap it, so a primitive spanning several cells is listed in each (\"Duplicate \
     Triangle\"). The automatic resolution is Cleary and Wyvill's (1988).",
    [
        _         "build(prims)",
        _         "    box = the bounding box of prims",
        _         "    cells per axis: given, or chosen from |prims| (Cleary, Wyvill)",
        _         "    for (p in prims)",
        _         "        for (c in the cells p's box touches)",
        _         "            if (p shares a point with c)  // exact test",
        _         "                c.primitives.add(p)  // p may be in several",
        _         "    sort the lists into cell order   // a counting sort",
        BuildLeaf "    for (c in the non-empty cells) c's list is done",
    ]
);

/// Every builder's events name their line directly.
fn classify<V: Vector>(event: &Event<V>) -> Option<Step> {
    Some(match event {
        Event::BuildNode { .. } => Step::BuildNode,
        Event::BuildSplit { .. } => Step::BuildSplit,
        Event::BuildLeaf { .. } => Step::BuildLeaf,
        _ => return None,
    })
}

/// The builder of `kind`.
pub(super) fn algorithm<V: Vector>(kind: StructureKind) -> Algorithm<V> {
    let listing = match kind {
        StructureKind::BruteForce => &BRUTE_FORCE,
        StructureKind::SphereTree | StructureKind::AabbTree | StructureKind::ObbTree => &BVH,
        StructureKind::KdTree => &KD_TREE,
        StructureKind::Bsp => &BSP,
        StructureKind::Quadtree => &QUADTREE,
        StructureKind::Grid => &GRID,
    };
    Algorithm { listing, classify }
}
