//! Mailboxing: in structures that list a primitive in several cells, each primitive is tested
//! once per query (Amanatides and Woo, "A Fast Voxel Traversal Algorithm", 1987, §4).

/// The primitives already tested during one query.
///
/// A small open-addressing hash set: queries touch few primitives, so it stays in cache and
/// costs nothing to create, unlike a per-primitive stamp array that would have to be cleared or
/// shared between threads.
#[derive(Clone, Debug, Default)]
pub struct Mailbox {
    slots: Vec<u32>,
    len: usize,
}

const EMPTY: u32 = u32::MAX;

use super::{Event, Observer, PrimitiveResult};
use crate::Vector;

impl Mailbox {
    /// An empty mailbox.
    pub fn new() -> Self {
        Self::default()
    }

    /// Marks `prim` as tested; returns `false` when it already was.
    pub fn first_visit(&mut self, prim: usize) -> bool {
        let key = prim as u32;
        if self.slots.is_empty() || (self.len + 1) * 2 > self.slots.len() {
            self.grow();
        }
        let mask = self.slots.len() - 1;
        // Fibonacci hashing (Knuth, TAOCP vol. 3, §6.4).
        let mut i = (key.wrapping_mul(0x9E37_79B9) as usize) & mask;
        loop {
            match self.slots[i] {
                EMPTY => {
                    self.slots[i] = key;
                    self.len += 1;
                    return true;
                }
                k if k == key => return false,
                _ => i = (i + 1) & mask,
            }
        }
    }

    /// [`first_visit`](Self::first_visit) that reports a repeat to the observer as
    /// [`PrimitiveResult::AlreadyTested`]: the one place every mailboxing query does this.
    #[inline]
    pub fn admit<V: Vector, O: Observer<V>>(&mut self, prim: u32, observer: &mut O) -> bool {
        let first = self.first_visit(prim as usize);
        if !first {
            observer.on(Event::PrimitiveTest {
                prim,
                result: PrimitiveResult::AlreadyTested,
            });
        }
        first
    }

    fn grow(&mut self) {
        let capacity = (self.slots.len() * 2).max(32);
        let old = std::mem::replace(&mut self.slots, vec![EMPTY; capacity]);
        self.len = 0;
        for key in old.into_iter().filter(|&k| k != EMPTY) {
            self.first_visit(key as usize);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Mailbox;

    #[test]
    fn each_primitive_is_new_once() {
        let mut mailbox = Mailbox::new();
        for i in 0..1000 {
            assert!(mailbox.first_visit(i * 7));
        }
        for i in 0..1000 {
            assert!(!mailbox.first_visit(i * 7));
        }
        assert!(mailbox.first_visit(3));
    }
}
