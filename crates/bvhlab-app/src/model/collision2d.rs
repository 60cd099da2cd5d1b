//! The collision query in 2D: the selected shapes (A) against the other shapes (B), each in
//! its own tree; the run is kept until the scene, the selection or the trees' kind changes.
//! The student moves the selection (drag, or the arrow keys) and sees the pairs change.

use bvhlab::Segment2;
use bvhlab::glam::Vec2;

use super::collision::{CollisionRun, CollisionTree};
use super::scene::Primitives;

/// Which trees are built and how far the walk is stepped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Collision2d {
    /// Both trees' kind.
    pub tree: CollisionTree,
    /// How many of the walk's events are shown; `None`: all of them (the answer).
    pub step: Option<usize>,
}

/// The collision query of the selection against the rest, made again only when what it
/// depends on changes.
#[derive(Clone, Debug, Default)]
pub struct Collision2dCache {
    key: Option<(u64, Vec<usize>, CollisionTree)>,
    /// The scene's index of each of A's segments.
    pub a: Vec<u32>,
    /// ... and of B's.
    pub b: Vec<u32>,
    /// The run; `None` when either side has no segment.
    pub run: Option<CollisionRun<Vec2>>,
}

impl Collision2dCache {
    /// Brings the run up to date with the scene's `prims` (of `revision`), the `selection`
    /// and `tree`.
    pub fn refresh(
        &mut self,
        prims: &Primitives,
        revision: u64,
        selection: &[usize],
        tree: CollisionTree,
    ) {
        let key = (revision, selection.to_vec(), tree);
        if self.key.as_ref() == Some(&key) {
            return;
        }
        self.key = Some(key);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for (i, owner) in prims.owner.iter().enumerate() {
            if selection.contains(owner) {
                a.push(i as u32);
            } else {
                b.push(i as u32);
            }
        }
        let side = |ids: &[u32]| -> Vec<Segment2> {
            ids.iter().map(|&i| prims.segments[i as usize]).collect()
        };
        let (sa, sb) = (side(&a), side(&b));
        self.run = (!sa.is_empty() && !sb.is_empty()).then(|| CollisionRun::run(&sa, &sb, tree));
        (self.a, self.b) = (a, b);
    }
}
