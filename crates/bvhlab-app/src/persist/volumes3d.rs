//! The 3D half's §2 in a saved state: whether the volumes are shown, which, fitted to which
//! part, the slab test, the two boxes of the separating-axis test, and the collision query's
//! copy. Absent in states from before §2 came to 3D: nothing of it is shown then.

use bvhlab::glam::Vec3;
use serde::{Deserialize, Serialize};

use super::names::Coord;
use super::state::VolumeState;
use super::state3d::StoredPoint3;
use crate::model::collision::CollisionTree;
use crate::model::collision3d::Collision3d;
use crate::model::obb_pair3d::{BoxPose3, CANDIDATES, ObbPair3};
use crate::model::volumes3d::{Part3d, Volumes3d};

/// The volumes' switches and part.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Volumes3dState {
    /// Whether they are shown.
    pub shown: bool,
    /// Which are drawn.
    pub toggles: VolumeState,
    /// What they are fitted to.
    pub part: PartName,
    /// Whether the slab test is drawn.
    pub slab_test: bool,
}

/// [`Part3d`] as stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PartName {
    /// The whole mesh.
    #[default]
    Mesh,
    /// The triangles within the radius of the query point.
    Brush,
}

/// One box of the separating-axis test.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxState3 {
    /// Its centre.
    pub center: StoredPoint3,
    /// Its half extents (none negative).
    pub half: StoredPoint3,
    /// Its turn about x, y and z, in degrees.
    pub degrees: StoredPoint3,
}

/// The two boxes and the axis looked at.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObbPair3State {
    /// Box A.
    pub a: BoxState3,
    /// Box B.
    pub b: BoxState3,
    /// The candidate axis looked at, 0 to 14.
    pub step: usize,
}

impl From<Volumes3d> for Volumes3dState {
    fn from(v: Volumes3d) -> Self {
        Self {
            shown: v.shown,
            toggles: v.toggles.into(),
            part: match v.part {
                Part3d::Mesh => PartName::Mesh,
                Part3d::Brush => PartName::Brush,
            },
            slab_test: v.slab_test,
        }
    }
}

impl From<Volumes3dState> for Volumes3d {
    fn from(v: Volumes3dState) -> Self {
        Self {
            shown: v.shown,
            toggles: v.toggles.into(),
            part: match v.part {
                PartName::Mesh => Part3d::Mesh,
                PartName::Brush => Part3d::Brush,
            },
            slab_test: v.slab_test,
        }
    }
}

fn stored(v: Vec3) -> StoredPoint3 {
    [Coord(v.x), Coord(v.y), Coord(v.z)]
}

impl From<&ObbPair3> for ObbPair3State {
    fn from(pair: &ObbPair3) -> Self {
        let pose = |p: &BoxPose3| BoxState3 {
            center: stored(p.center),
            half: stored(p.half),
            degrees: stored(p.degrees),
        };
        Self {
            a: pose(&pair.a),
            b: pose(&pair.b),
            step: pair.step,
        }
    }
}

impl ObbPair3State {
    /// The pair, or what is wrong with it.
    pub fn check(&self) -> Result<ObbPair3, String> {
        let pose = |name: &str, b: &BoxState3| -> Result<BoxPose3, String> {
            let read = |p: StoredPoint3| Vec3::new(p[0].0, p[1].0, p[2].0);
            let pose = BoxPose3 {
                center: read(b.center),
                half: read(b.half),
                degrees: read(b.degrees),
            };
            if pose.is_valid() {
                Ok(pose)
            } else {
                Err(format!(
                    "box {name} of the separating-axis test needs a finite centre and turn, and \
                     half extents of at least 0"
                ))
            }
        };
        if self.step >= CANDIDATES.len() {
            return Err(format!(
                "the separating-axis test's axis is {}; it must be 0 to 14",
                self.step
            ));
        }
        Ok(ObbPair3 {
            a: pose("A", &self.a)?,
            b: pose("B", &self.b)?,
            step: self.step,
        })
    }
}

/// The collision query's copy, trees and step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Collision3dState {
    /// The copy's move.
    pub offset: StoredPoint3,
    /// The copy's turn about x, y and z, in degrees.
    pub degrees: StoredPoint3,
    /// Both trees' kind.
    pub tree: TreeName,
    /// The walk's step shown (absent: all of it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<usize>,
}

/// [`CollisionTree`] as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TreeName {
    /// Sphere trees.
    Sphere,
    /// AABB trees.
    Aabb,
    /// OBB trees.
    Obb,
}

impl From<&Collision3d> for Collision3dState {
    fn from(c: &Collision3d) -> Self {
        Self {
            offset: stored(c.offset),
            degrees: stored(c.degrees),
            tree: match c.tree {
                CollisionTree::Sphere => TreeName::Sphere,
                CollisionTree::Aabb => TreeName::Aabb,
                CollisionTree::Obb => TreeName::Obb,
            },
            step: c.step,
        }
    }
}

impl Collision3dState {
    /// The collision query's settings, or what is wrong with them.
    pub fn check(&self) -> Result<Collision3d, String> {
        let read = |p: StoredPoint3| Vec3::new(p[0].0, p[1].0, p[2].0);
        let c = Collision3d {
            offset: read(self.offset),
            degrees: read(self.degrees),
            tree: match self.tree {
                TreeName::Sphere => CollisionTree::Sphere,
                TreeName::Aabb => CollisionTree::Aabb,
                TreeName::Obb => CollisionTree::Obb,
            },
            step: self.step,
        };
        if c.is_valid() {
            Ok(c)
        } else {
            Err("the collision query's copy needs a finite move and turn".to_owned())
        }
    }
}
