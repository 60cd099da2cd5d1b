//! The collision query in 3D: the part of the mesh the volumes are fitted to (A) against a
//! copy of it moved and turned (B), each in its own tree; the run is kept until the mesh,
//! the part, the copy's pose or the trees' kind changes.

use bvhlab::glam::{EulerRot, Quat, Vec3};
use bvhlab::{Aabb3, Triangle3};

use super::collision::{CollisionRun, CollisionTree};

/// The most triangles in the part for a collision query: two trees over a million
/// triangles each would stop the page for seconds at every change of the copy's pose.
pub const MAX_COLLISION_TRIANGLES: usize = 50_000;

/// Where the copy B is and which trees are built, and how far the walk is stepped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision3d {
    /// B's move from A, after the turn.
    pub offset: Vec3,
    /// B's turn about the part's centre, in degrees about x, then y, then z (as the boxes').
    pub degrees: Vec3,
    /// Both trees' kind.
    pub tree: CollisionTree,
    /// How many of the walk's events are shown; `None`: all of them (the answer).
    pub step: Option<usize>,
}

impl Collision3d {
    /// A copy moved half the part's width along x and turned a little, so that part of it
    /// still meets A.
    pub fn beside(part: &Aabb3) -> Self {
        // An empty part (no fits yet) has an inverted box: the copy starts on A.
        let size = (part.max - part.min).max(Vec3::ZERO);
        let size = if size.is_finite() { size } else { Vec3::ZERO };
        Self {
            offset: Vec3::new(size.x * 0.5, size.y * 0.1, 0.0),
            degrees: Vec3::new(0.0, 30.0, 0.0),
            tree: CollisionTree::default(),
            step: None,
        }
    }

    /// Whether the numbers are finite.
    pub fn is_valid(&self) -> bool {
        self.offset.is_finite() && self.degrees.is_finite()
    }

    /// `triangles` moved to where B is: turned about `pivot`, then moved by the offset.
    pub fn place(&self, triangles: &[Triangle3], pivot: Vec3) -> Vec<Triangle3> {
        let r = self.degrees * (std::f32::consts::PI / 180.0);
        let turn = Quat::from_euler(EulerRot::XYZ, r.x, r.y, r.z);
        let at = |p: Vec3| turn * (p - pivot) + pivot + self.offset;
        triangles
            .iter()
            .map(|t| Triangle3::new(at(t.a), at(t.b), at(t.c)))
            .collect()
    }
}

/// What a run was made from: the part (by its [`PartFits::generation`], which follows the
/// mesh's revisions too), the pose and the kind.
///
/// [`PartFits::generation`]: super::volumes3d::PartFits::generation
#[derive(Clone, Copy, Debug, PartialEq)]
struct RunKey {
    part: u64,
    offset: [u32; 3],
    degrees: [u32; 3],
    tree: CollisionTree,
}

/// The collision query of the part against its copy, made again only when what it depends
/// on changes.
#[derive(Clone, Debug, Default)]
pub struct CollisionCache {
    key: Option<RunKey>,
    /// The mesh's index of each of A's triangles (A's primitive `i` is mesh triangle
    /// `part[i]`).
    pub part: Vec<u32>,
    /// B's triangles, where they are.
    pub copy: Vec<Triangle3>,
    /// The run; `None` for an empty part or one past [`MAX_COLLISION_TRIANGLES`].
    pub run: Option<CollisionRun<Vec3>>,
}

impl CollisionCache {
    /// Brings the run up to date with the mesh's `triangles`, the `part`'s indices into them
    /// (selected for the `generation`-th time), and `collision`.
    pub fn refresh(
        &mut self,
        triangles: &[Triangle3],
        (part, generation): (&[u32], u64),
        collision: &Collision3d,
    ) {
        let key = RunKey {
            part: generation,
            offset: collision.offset.to_array().map(f32::to_bits),
            degrees: collision.degrees.to_array().map(f32::to_bits),
            tree: collision.tree,
        };
        if self.key == Some(key) {
            return;
        }
        self.key = Some(key);
        self.part = part.to_vec();
        let a: Vec<Triangle3> = part
            .iter()
            .filter_map(|&t| triangles.get(t as usize).copied())
            .collect();
        if a.is_empty() || a.len() > MAX_COLLISION_TRIANGLES {
            self.copy.clear();
            self.run = None;
            return;
        }
        let pivot = part_centre(&a);
        self.copy = collision.place(&a, pivot);
        self.run = Some(CollisionRun::run(&a, &self.copy, collision.tree));
    }
}

/// The centre of the triangles' box: what B turns about.
pub fn part_centre(triangles: &[Triangle3]) -> Vec3 {
    let points: Vec<Vec3> = triangles
        .iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .filter(|p| p.is_finite())
        .collect();
    Aabb3::from_points(&points).center()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_copy_turns_about_the_centre_and_then_moves() {
        let t = Triangle3::new(Vec3::X, Vec3::Y, Vec3::Z);
        let c = Collision3d {
            offset: Vec3::new(10.0, 0.0, 0.0),
            degrees: Vec3::new(0.0, 0.0, 90.0),
            tree: CollisionTree::Aabb,
            step: None,
        };
        let moved = c.place(&[t], Vec3::ZERO)[0];
        assert!(
            (moved.a - Vec3::new(10.0, 1.0, 0.0)).length() < 1e-6,
            "{moved:?}"
        );
        assert!(
            (moved.b - Vec3::new(9.0, 0.0, 0.0)).length() < 1e-6,
            "{moved:?}"
        );
        assert!(
            (moved.c - Vec3::new(10.0, 0.0, 1.0)).length() < 1e-6,
            "{moved:?}"
        );
    }
}
