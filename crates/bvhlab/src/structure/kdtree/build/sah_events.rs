//! The sorted edge events of the O(n log n) SAH build (Wald and Havran 2006, §4).
//!
//! Each primitive in a node contributes, per axis, a start and an end event at its bounds
//! (clipped to the node's cell), or one planar event when it is flat on that axis. The events
//! of each axis are kept sorted by position (ends before planars before starts at equal
//! positions). Sorting happens once, at the root; a split keeps the order by distributing the
//! events in order to the children. Only a straddling primitive's clipped bounds change, and
//! only on the split axis, where they end (below) or start (above) exactly at the plane: those
//! new events all share one position, so they are merged in as one block, with no sorting.
//! (Wald and Havran re-create and sort the straddlers' events; with bounds clipped to the cell
//! rather than "perfect" polygon clipping, this is unnecessary.)

use super::{ABOVE, BELOW, STRADDLES};
use crate::Vector;
use crate::volume::Aabb;

/// An end event: the primitive's bounds end here.
pub(crate) const END: u32 = 0;
/// A planar event: the primitive is flat on this axis, here.
pub(crate) const PLANAR: u32 = 1;
/// A start event: the primitive's bounds start here.
pub(crate) const START: u32 = 2;

/// One event: a position and the primitive and kind packed in one word (8 bytes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EdgeEvent {
    /// Where along the axis.
    pub pos: f32,
    /// `prim << 2 | kind`.
    tagged: u32,
}

impl EdgeEvent {
    fn new(pos: f32, prim: u32, kind: u32) -> Self {
        // `+ 0.0` turns -0 into +0, so that equal positions sort together.
        Self {
            pos: pos + 0.0,
            tagged: (prim << 2) | kind,
        }
    }

    /// The primitive.
    pub(crate) fn prim(self) -> u32 {
        self.tagged >> 2
    }

    /// [`END`], [`PLANAR`] or [`START`].
    pub(crate) fn kind(self) -> u32 {
        self.tagged & 3
    }

    /// The sort key: the position's bits made monotone, then the kind.
    fn key(self) -> u64 {
        let bits = self.pos.to_bits();
        let monotone = if bits >> 31 == 1 {
            !bits
        } else {
            bits | 1 << 31
        };
        (u64::from(monotone) << 2) | u64::from(self.kind())
    }
}

/// Calls `push(axis, event)` for the events of primitive `prim` with (clipped) bounds `b`.
fn events_of<V: Vector>(prim: u32, b: &Aabb<V>, mut push: impl FnMut(usize, EdgeEvent)) {
    for axis in 0..V::DIM {
        let (lo, hi) = (b.min.coord(axis), b.max.coord(axis));
        if lo == hi {
            push(axis, EdgeEvent::new(lo, prim, PLANAR));
        } else {
            push(axis, EdgeEvent::new(lo, prim, START));
            push(axis, EdgeEvent::new(hi, prim, END));
        }
    }
}

/// Where one node's events lie in the [`EventArena`]: the sorted events of axis 0, then of
/// axis 1, then of axis 2 (empty in 2D).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Events {
    start: usize,
    /// Where each axis' events end.
    ends: [usize; 3],
}

/// All event lists of a build in one vector, used as a stack: the node being split is on top,
/// its children are written above it (the above child first, so that the below child, which
/// is built first, is on top), and a finished subtree's events are dropped by truncation. No
/// allocation per node.
#[derive(Debug, Default)]
pub(crate) struct EventArena {
    list: Vec<EdgeEvent>,
    /// Scratch: the straddlers' new events at the plane, per side.
    fresh: [Vec<EdgeEvent>; 2],
    /// Scratch: the children's events while they are sorted out.
    below: Vec<EdgeEvent>,
    above: Vec<EdgeEvent>,
}

impl EventArena {
    /// The root's events, sorted.
    pub(crate) fn new<V: Vector>(refs: &[u32], bounds: &[Aabb<V>]) -> (Self, Events) {
        let mut list = Vec::with_capacity(4 * V::DIM * refs.len());
        let mut ends = [0; 3];
        for (axis, end) in ends.iter_mut().enumerate() {
            let start = list.len();
            if axis < V::DIM {
                for &r in refs {
                    events_of(r, &bounds[r as usize], |a, e| {
                        if a == axis {
                            list.push(e);
                        }
                    });
                }
                list[start..].sort_unstable_by_key(|e: &EdgeEvent| e.key());
            }
            *end = list.len();
        }
        let arena = Self {
            list,
            ..Self::default()
        };
        (arena, Events { start: 0, ends })
    }

    /// The sorted events of one axis of a node.
    pub(crate) fn axis(&self, events: &Events, axis: usize) -> &[EdgeEvent] {
        let start = if axis == 0 {
            events.start
        } else {
            events.ends[axis - 1]
        };
        &self.list[start..events.ends[axis]]
    }

    /// The primitives of a node (each has one start or planar event per axis), into `out`.
    pub(crate) fn prims(&self, events: &Events, out: &mut Vec<u32>) {
        out.clear();
        let axis = self.axis(events, 0);
        out.extend(axis.iter().filter(|e| e.kind() != END).map(|e| e.prim()));
    }

    /// Drops every event list from where `events` begins (a finished subtree's).
    pub(crate) fn release(&mut self, events: &Events) {
        self.list.truncate(events.start);
    }

    /// Writes the children's events above the node's (which must be on top), given each
    /// primitive's side flags, and returns `[below, above]`. The order is kept without any
    /// sorting: a primitive on one side keeps its events; a straddler keeps its events on the
    /// other axes (the children's cells equal the parent's there) and, on the split axis, its
    /// start below and its end above, plus a new end (below) or start (above) at the plane,
    /// all of which share one position and so are merged in as one block.
    pub(crate) fn split(
        &mut self,
        events: &Events,
        sides: &[u8],
        refs: &[u32],
        axis: usize,
        pos: f32,
    ) -> [Events; 2] {
        debug_assert_eq!(self.list.len(), events.ends[2]);
        let [new_below, new_above] = &mut self.fresh;
        new_below.clear();
        new_above.clear();
        for &r in refs {
            let flags = sides[r as usize];
            if flags & STRADDLES != 0 {
                if flags & BELOW != 0 {
                    new_below.push(EdgeEvent::new(pos, r, END));
                }
                if flags & ABOVE != 0 {
                    new_above.push(EdgeEvent::new(pos, r, START));
                }
            }
        }
        let room = events.ends[2] - events.start + new_below.len().max(new_above.len()) + 1;
        let filler = EdgeEvent::new(0.0, 0, END);
        let (below, above) = (&mut self.below, &mut self.above);
        below.clear();
        below.resize(room, filler);
        above.clear();
        above.resize(room, filler);
        let (mut nb, mut na) = (0, 0);
        let mut ends = [[0; 3]; 2];
        let mut first = events.start;
        for (a, &end) in events.ends.iter().enumerate() {
            let list = &self.list[first..end];
            first = end;
            if a == axis {
                // Where the new blocks go: after everything that sorts before them.
                let (key_below, key_above) = (
                    new_below[..].first().map(|e| e.key()),
                    new_above[..].first().map(|e| e.key()),
                );
                let split_below = list.partition_point(|e| Some(e.key()) <= key_below);
                let split_above = list.partition_point(|e| Some(e.key()) <= key_above);
                for (i, e) in list.iter().enumerate() {
                    if i == split_below {
                        below[nb..nb + new_below.len()].copy_from_slice(new_below);
                        nb += new_below.len();
                    }
                    if i == split_above {
                        above[na..na + new_above.len()].copy_from_slice(new_above);
                        na += new_above.len();
                    }
                    let flags = sides[e.prim() as usize];
                    let straddles = flags & STRADDLES != 0;
                    below[nb] = *e;
                    nb += usize::from(flags & BELOW != 0 && !(straddles && e.kind() == END));
                    above[na] = *e;
                    na += usize::from(flags & ABOVE != 0 && !(straddles && e.kind() == START));
                }
                if split_below == list.len() {
                    below[nb..nb + new_below.len()].copy_from_slice(new_below);
                    nb += new_below.len();
                }
                if split_above == list.len() {
                    above[na..na + new_above.len()].copy_from_slice(new_above);
                    na += new_above.len();
                }
            } else {
                for e in list {
                    let flags = sides[e.prim() as usize];
                    below[nb] = *e;
                    nb += usize::from(flags & BELOW != 0);
                    above[na] = *e;
                    na += usize::from(flags & ABOVE != 0);
                }
            }
            ends[0][a] = nb;
            ends[1][a] = na;
        }
        let above_start = self.list.len();
        self.list.extend_from_slice(&above[..na]);
        let below_start = self.list.len();
        self.list.extend_from_slice(&below[..nb]);
        [
            Events {
                start: below_start,
                ends: ends[0].map(|e| below_start + e),
            },
            Events {
                start: above_start,
                ends: ends[1].map(|e| above_start + e),
            },
        ]
    }
}
