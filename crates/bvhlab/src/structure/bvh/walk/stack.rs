//! The traversal stack: a fixed array, so that a query allocates nothing.
//!
//! Each traversal visits a node's nearer child next and leaves at most one sibling per level
//! on the stack, and trees are at most [`MAX_DEPTH`] deep, so `MAX_DEPTH + 2` entries always
//! suffice.

use crate::structure::bvh::MAX_DEPTH;

/// Capacity: one waiting sibling per level, plus the node about to be popped.
const CAPACITY: usize = MAX_DEPTH + 2;

/// A node waiting to be visited, with the key it was queued by (entry `t` or distance).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(in crate::structure::bvh) struct Entry {
    pub node: u32,
    pub depth: u32,
    pub key: f32,
}

/// A last-in, first-out stack of [`Entry`]s.
pub(in crate::structure::bvh) struct Stack {
    items: [Entry; CAPACITY],
    len: usize,
}

impl Stack {
    #[inline]
    pub fn new() -> Self {
        Self {
            items: [Entry::default(); CAPACITY],
            len: 0,
        }
    }

    /// Pushes an entry. The depth bound of the tree guarantees room (checked by
    /// [`Bvh::validate`](crate::structure::SpatialIndex::validate)).
    #[inline]
    pub fn push(&mut self, entry: Entry) {
        self.items[self.len] = entry;
        self.len += 1;
    }

    #[inline]
    pub fn pop(&mut self) -> Option<Entry> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }

    /// Pushes the children that survived their tests, the later-visited first, so that the
    /// nearer (smaller key) is popped next; ties keep the first child first. Returns them in
    /// visiting order. The first-hit walk's order is mirrored in the app's heat map shader
    /// (`trace.wgsl`, in `trace`): a change here must be made there too.
    #[inline]
    pub fn push_pair(&mut self, a: Option<Entry>, b: Option<Entry>) -> [Option<Entry>; 2] {
        let order = match (a, b) {
            (Some(x), Some(y)) if y.key < x.key => [b, a],
            (None, _) => [b, None],
            _ => [a, b],
        };
        for entry in order.iter().rev().flatten() {
            self.push(*entry);
        }
        order
    }
}
