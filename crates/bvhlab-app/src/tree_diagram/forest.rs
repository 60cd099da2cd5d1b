//! The outline's links as one clean rooted tree, the shape the layout algorithm needs.
//!
//! An outline lists each node's children; it is not necessarily in depth-first order, and a
//! uniform grid's cells are all roots. Here every node gets exactly one parent: the outline's
//! roots (nodes no other node lists as a child) hang under one virtual root, one past the last
//! node, so that a forest is laid out like a tree. Malformed links cannot loop or panic the
//! layout: a child id out of range is ignored, a node listed twice keeps its first parent, and
//! a cycle with no root is cut where the sweep first enters it.

use bvhlab::{NodeOutline, Vector};

/// "No node": the virtual root's parent, and an empty thread in the tidy walk.
pub(super) const NONE: usize = usize::MAX;

/// Every node's children (left to right, in the outline's order) and parent.
pub(super) struct Forest {
    /// `children[start[v]..start[v + 1]]` are `v`'s children.
    start: Vec<usize>,
    children: Vec<usize>,
    parent: Vec<usize>,
}

impl Forest {
    /// The outline's links, with a virtual root over its roots.
    pub(super) fn from_outline<V: Vector>(outline: &[NodeOutline<V>]) -> Self {
        let n = outline.len();
        let mut listed = vec![false; n];
        for (v, node) in outline.iter().enumerate() {
            for c in &node.children {
                if c.index() < n && c.index() != v {
                    listed[c.index()] = true;
                }
            }
        }
        // Claim parents depth first from each root; a second sweep over every node picks up
        // what no root reaches (a cycle), as a root of its own.
        let mut parent = vec![NONE; n + 1];
        let mut seen = vec![false; n];
        let mut roots = Vec::new();
        let mut stack = Vec::new();
        for r in (0..n).filter(|&v| !listed[v]).chain(0..n) {
            if seen[r] {
                continue;
            }
            seen[r] = true;
            parent[r] = n;
            roots.push(r);
            stack.push(r);
            while let Some(v) = stack.pop() {
                for c in &outline[v].children {
                    let c = c.index();
                    if c < n && !seen[c] {
                        seen[c] = true;
                        parent[c] = v;
                        stack.push(c);
                    }
                }
            }
        }
        let mut start = Vec::with_capacity(n + 2);
        let mut children = Vec::with_capacity(n);
        let mut placed = vec![false; n];
        for (v, node) in outline.iter().enumerate() {
            start.push(children.len());
            for c in &node.children {
                let c = c.index();
                if c < n && parent[c] == v && !placed[c] {
                    placed[c] = true;
                    children.push(c);
                }
            }
        }
        start.push(children.len());
        children.extend_from_slice(&roots);
        start.push(children.len());
        Self {
            start,
            children,
            parent,
        }
    }

    /// The virtual root (one past the outline's last node).
    pub(super) fn root(&self) -> usize {
        self.parent.len() - 1
    }

    /// How many nodes, the virtual root included.
    pub(super) fn len(&self) -> usize {
        self.parent.len()
    }

    /// `v`'s children, left to right.
    pub(super) fn children(&self, v: usize) -> &[usize] {
        &self.children[self.start[v]..self.start[v + 1]]
    }

    /// `v`'s parent: the virtual root for the outline's roots, [`NONE`] for the virtual root.
    pub(super) fn parent(&self, v: usize) -> usize {
        self.parent[v]
    }

    /// Every node, parents before children, left subtrees before right ones.
    pub(super) fn preorder(&self) -> Vec<usize> {
        self.walk(true)
    }

    /// Every node, children before parents, left subtrees before right ones.
    pub(super) fn postorder(&self) -> Vec<usize> {
        // A preorder that takes children right to left, reversed.
        let mut order = self.walk(false);
        order.reverse();
        order
    }

    /// Each outline node's depth (the outline's roots at 0), from the links.
    pub(super) fn depths(&self) -> Vec<u32> {
        let root = self.root();
        let mut depth = vec![0; self.len()];
        for v in self.preorder() {
            for &c in self.children(v) {
                depth[c] = if v == root { 0 } else { depth[v] + 1 };
            }
        }
        depth.truncate(root);
        depth
    }

    /// A preorder from the virtual root, children left to right or right to left.
    fn walk(&self, left_first: bool) -> Vec<usize> {
        let mut order = Vec::with_capacity(self.len());
        let mut stack = vec![self.root()];
        while let Some(v) = stack.pop() {
            order.push(v);
            // The stack pops the last pushed first.
            if left_first {
                stack.extend(self.children(v).iter().rev());
            } else {
                stack.extend(self.children(v));
            }
        }
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::glam::Vec2;
    use bvhlab::{Aabb2, NodeId, NodeShape};

    fn node(id: u32, children: &[u32]) -> NodeOutline<Vec2> {
        NodeOutline {
            id: NodeId(id),
            parent: None,
            depth: 0,
            shape: NodeShape::Aabb(Aabb2::new(Vec2::ZERO, Vec2::ONE)),
            splits: Vec::new(),
            children: children.iter().map(|&c| NodeId(c)).collect(),
            primitives: Vec::new(),
        }
    }

    #[test]
    fn links_out_of_order_outline_and_cuts_malformed_links() {
        // Node 3 is the root, listed last; 0 and 2 are its children, 1 is 2's child.
        let outline = [node(0, &[]), node(1, &[]), node(2, &[1]), node(3, &[0, 2])];
        let f = Forest::from_outline(&outline);
        assert_eq!(f.children(f.root()), &[3]);
        assert_eq!(f.children(3), &[0, 2]);
        assert_eq!(f.parent(1), 2);
        assert_eq!(f.depths(), vec![1, 2, 1, 0]);
        assert_eq!(f.preorder(), vec![4, 3, 0, 2, 1]);
        assert_eq!(f.postorder(), vec![0, 1, 2, 3, 4]);

        // A cycle 0 -> 1 -> 0, an id out of range, a self-loop and a duplicate child.
        let bad = [node(0, &[1, 9, 0]), node(1, &[0, 2, 2]), node(2, &[])];
        let f = Forest::from_outline(&bad);
        let mut every: Vec<usize> = f.preorder();
        every.sort_unstable();
        assert_eq!(every, vec![0, 1, 2, 3], "each node exactly once");
        assert_eq!(f.children(f.root()), &[0]);
        assert_eq!(f.children(1), &[2]);
    }
}
