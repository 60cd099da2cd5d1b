//! Tidy tree drawing: each node's horizontal position, with depth down the page.
//!
//! Reingold and Tilford, "Tidier Drawings of Trees" (IEEE TSE, 1981): lay out each subtree,
//! then push sibling subtrees together until their facing contours are one unit apart, and
//! centre each parent over its first and last child. Walker ("A Node-positioning Algorithm for
//! General Trees", 1990) extended it to any number of children, spacing the small subtrees
//! between two big ones evenly; Buchheim, Jünger and Leipert ("Improving Walker's Algorithm to
//! Run in Linear Time", Graph Drawing 2002) made that linear. This file follows the last
//! paper's `FirstWalk`, `Apportion`, `MoveSubtree`, `ExecuteShifts` and `SecondWalk`, run
//! without recursion (deep trees must not overflow the stack, on the web least of all).
//!
//! The drawing keeps the order of children, never lets two nodes of one level come closer
//! than [`SEPARATION`], and draws a subtree the same wherever it occurs.

use super::forest::{Forest, NONE};

/// The least horizontal distance between two nodes of one level, in layout units.
pub(super) const SEPARATION: f32 = 1.0;

/// The per-node state of the walk (the paper's names in the comments).
struct Walk {
    /// `prelim`: the position relative to the parent's subtree, before the second walk.
    prelim: Vec<f32>,
    /// `mod`: how far the whole subtree below the node moves.
    modifier: Vec<f32>,
    /// `thread`: the next node on a contour, for nodes that end one.
    thread: Vec<usize>,
    /// `ancestor`: the sibling subtree a contour node belongs to, for `MoveSubtree`.
    ancestor: Vec<usize>,
    /// `shift` and `change`: moves of whole subtrees, spread over siblings in
    /// `ExecuteShifts`.
    shift: Vec<f32>,
    change: Vec<f32>,
    /// `number`: the node's place among its siblings.
    number: Vec<usize>,
    /// `defaultAncestor`, per parent.
    default_ancestor: Vec<usize>,
}

/// The x of every outline node (not of the virtual root), with the leftmost at 0.
pub(super) fn tidy_x(forest: &Forest) -> Vec<f32> {
    let len = forest.len();
    let mut number = vec![0; len];
    for v in 0..len {
        for (i, &c) in forest.children(v).iter().enumerate() {
            number[c] = i;
        }
    }
    let default_ancestor = (0..len)
        .map(|v| forest.children(v).first().copied().unwrap_or(NONE))
        .collect();
    let mut walk = Walk {
        prelim: vec![0.0; len],
        modifier: vec![0.0; len],
        thread: vec![NONE; len],
        ancestor: (0..len).collect(),
        shift: vec![0.0; len],
        change: vec![0.0; len],
        number,
        default_ancestor,
    };
    let root = forest.root();
    for v in forest.postorder() {
        if v == root {
            // The outline's roots are siblings under the virtual root: spread them too.
            walk.execute_shifts(forest, root);
        } else {
            walk.first_walk(forest, v);
        }
    }
    // Second walk: a node's x is its prelim plus the modifiers of its proper ancestors.
    let mut x = vec![0.0; len];
    let mut sum = vec![0.0; len];
    for v in forest.preorder() {
        let p = forest.parent(v);
        if p != NONE {
            x[v] = walk.prelim[v] + sum[p];
            sum[v] = sum[p] + walk.modifier[v];
        }
    }
    x.truncate(root);
    let left = x.iter().copied().fold(f32::INFINITY, f32::min);
    if left.is_finite() {
        for xi in &mut x {
            *xi -= left;
        }
    }
    x
}

impl Walk {
    /// `FirstWalk` for `v`, whose children are all done: centre it over them, place it
    /// right of its left sibling, and push its subtree clear of the siblings' on its left.
    fn first_walk(&mut self, forest: &Forest, v: usize) {
        let parent = forest.parent(v);
        let siblings = forest.children(parent);
        let left = self.number[v].checked_sub(1).map(|i| siblings[i]);
        let kids = forest.children(v);
        if let (Some(&first), Some(&last)) = (kids.first(), kids.last()) {
            self.execute_shifts(forest, v);
            let midpoint = 0.5 * (self.prelim[first] + self.prelim[last]);
            if let Some(w) = left {
                self.prelim[v] = self.prelim[w] + SEPARATION;
                self.modifier[v] = self.prelim[v] - midpoint;
            } else {
                self.prelim[v] = midpoint;
            }
        } else if let Some(w) = left {
            self.prelim[v] = self.prelim[w] + SEPARATION;
        }
        if let Some(w) = left {
            let default = self.default_ancestor[parent];
            self.default_ancestor[parent] = self.apportion(forest, v, w, siblings[0], default);
        }
    }

    /// `Apportion`: walks down the right contour of the subtrees left of `v` and the left
    /// contour of `v`'s, moving `v`'s right wherever they come too close, then threads the
    /// shorter contour onto the longer. Returns the new default ancestor.
    fn apportion(
        &mut self,
        forest: &Forest,
        v: usize,
        left_sibling: usize,
        leftmost_sibling: usize,
        default: usize,
    ) -> usize {
        // Inside and outside contours, right (v's subtree) and left (its left siblings'),
        // and the sums of modifiers along each.
        let (mut in_right, mut out_right) = (v, v);
        let (mut in_left, mut out_left) = (left_sibling, leftmost_sibling);
        let m = &self.modifier;
        let (mut s_in_right, mut s_out_right) = (m[in_right], m[out_right]);
        let (mut s_in_left, mut s_out_left) = (m[in_left], m[out_left]);
        loop {
            let (next_in_left, next_in_right) = (
                self.next_right(forest, in_left),
                self.next_left(forest, in_right),
            );
            let (next_out_left, next_out_right) = (
                self.next_left(forest, out_left),
                self.next_right(forest, out_right),
            );
            // Both outside contours are as deep as the inside ones; checked all the same.
            if [next_in_left, next_in_right, next_out_left, next_out_right].contains(&NONE) {
                break;
            }
            (in_left, in_right) = (next_in_left, next_in_right);
            (out_left, out_right) = (next_out_left, next_out_right);
            self.ancestor[out_right] = v;
            let shift = (self.prelim[in_left] + s_in_left) - (self.prelim[in_right] + s_in_right)
                + SEPARATION;
            if shift > 0.0 {
                let a = self.ancestor[in_left];
                let from = if forest.parent(a) == forest.parent(v) {
                    a
                } else {
                    default
                };
                self.move_subtree(from, v, shift);
                s_in_right += shift;
                s_out_right += shift;
            }
            s_in_left += self.modifier[in_left];
            s_in_right += self.modifier[in_right];
            s_out_left += self.modifier[out_left];
            s_out_right += self.modifier[out_right];
        }
        let next_in_left = self.next_right(forest, in_left);
        if next_in_left != NONE && self.next_right(forest, out_right) == NONE {
            self.thread[out_right] = next_in_left;
            self.modifier[out_right] += s_in_left - s_out_right;
        }
        let next_in_right = self.next_left(forest, in_right);
        if next_in_right != NONE && self.next_left(forest, out_left) == NONE {
            self.thread[out_left] = next_in_right;
            self.modifier[out_left] += s_in_right - s_out_left;
            return v;
        }
        default
    }

    /// `MoveSubtree`: moves the subtree of `right` by `shift`, and records that the
    /// siblings strictly between `left` and `right` move by shares of it.
    fn move_subtree(&mut self, left: usize, right: usize, shift: f32) {
        let subtrees = self.number[right].saturating_sub(self.number[left]).max(1) as f32;
        self.change[right] -= shift / subtrees;
        self.shift[right] += shift;
        self.change[left] += shift / subtrees;
        self.prelim[right] += shift;
        self.modifier[right] += shift;
    }

    /// `ExecuteShifts`: applies the moves `move_subtree` recorded to `v`'s children, right
    /// to left, in one pass.
    fn execute_shifts(&mut self, forest: &Forest, v: usize) {
        let (mut shift, mut change) = (0.0, 0.0);
        for &w in forest.children(v).iter().rev() {
            self.prelim[w] += shift;
            self.modifier[w] += shift;
            change += self.change[w];
            shift += self.shift[w] + change;
        }
    }

    /// The next node on a left contour: the first child, or the thread.
    fn next_left(&self, forest: &Forest, v: usize) -> usize {
        forest
            .children(v)
            .first()
            .copied()
            .unwrap_or(self.thread[v])
    }

    /// The next node on a right contour: the last child, or the thread.
    fn next_right(&self, forest: &Forest, v: usize) -> usize {
        forest.children(v).last().copied().unwrap_or(self.thread[v])
    }
}
