//! What a file holds: the structure, its node volume (for a [`Bvh`]) and its primitive, as
//! three one-byte tags in the header, and the traits that give each saved type its tags.

use std::fmt;

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::structure::bvh::NodeVolume;
use crate::structure::{SpatialIndex, ValidationError};
use crate::volume::{Aabb, Obb, Sphere};
use crate::{
    BruteForce, BspTree, Bvh, Bvh4, Grid, KdTree, Orthtree, Primitive, Segment2, Triangle3,
};
use glam::{Vec2, Vec3};

/// Which structure a file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum StructureKind {
    /// A binary [`Bvh`] (AABB, sphere or OBB tree).
    Bvh,
    /// A 4-wide [`Bvh4`].
    Bvh4,
    /// A [`KdTree`].
    KdTree,
    /// A [`BspTree`].
    BspTree,
    /// A uniform [`Grid`].
    Grid,
    /// A quadtree or octree ([`Orthtree`]).
    Orthtree,
    /// [`BruteForce`]: the primitives alone.
    BruteForce,
}

/// The node volume of a saved [`Bvh`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum VolumeKind {
    /// Axis-aligned boxes ([`Aabb`]).
    Aabb,
    /// Spheres or circles ([`Sphere`]).
    Sphere,
    /// Oriented boxes ([`Obb`]).
    Obb,
}

/// The primitives of a saved structure (which also says its dimension).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PrimitiveKind {
    /// [`Segment2`], in 2D.
    Segment2,
    /// [`Triangle3`], in 3D.
    Triangle3,
    /// 2D points ([`Vec2`]).
    Vec2,
    /// 3D points ([`Vec3`]).
    Vec3,
}

/// Everything a file's header says about its contents: a load asks for one and refuses a
/// file that holds another.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FileKind {
    /// The structure.
    pub structure: StructureKind,
    /// Its node volume: `Some` for a [`Bvh`] only.
    pub volume: Option<VolumeKind>,
    /// Its primitives.
    pub primitive: PrimitiveKind,
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.structure)?;
        if let Some(volume) = self.volume {
            write!(f, " with {volume:?} nodes")?;
        }
        write!(f, " over {:?}", self.primitive)
    }
}

// The byte of each tag in the header. Numbers, once given, never change meaning: a new kind
// takes a new number, so that old files keep loading.

impl StructureKind {
    const ALL: [Self; 7] = [
        Self::Bvh,
        Self::Bvh4,
        Self::KdTree,
        Self::BspTree,
        Self::Grid,
        Self::Orthtree,
        Self::BruteForce,
    ];

    pub(super) fn tag(self) -> u8 {
        Self::ALL
            .iter()
            .position(|&k| k == self)
            .map_or(0, |i| i as u8 + 1)
    }

    pub(super) fn from_tag(tag: u8) -> Option<Self> {
        Self::ALL.get(usize::from(tag).checked_sub(1)?).copied()
    }
}

impl VolumeKind {
    const ALL: [Self; 3] = [Self::Aabb, Self::Sphere, Self::Obb];

    /// 0 stands for no volume (every structure but a [`Bvh`]).
    pub(super) fn tag(volume: Option<Self>) -> u8 {
        volume.map_or(0, |v| {
            Self::ALL
                .iter()
                .position(|&k| k == v)
                .map_or(0, |i| i as u8 + 1)
        })
    }

    /// The volume of a non-zero tag (0, no volume, is the header's to read).
    pub(super) fn from_tag(tag: u8) -> Option<Self> {
        Self::ALL.get(usize::from(tag).checked_sub(1)?).copied()
    }
}

impl PrimitiveKind {
    const ALL: [Self; 4] = [Self::Segment2, Self::Triangle3, Self::Vec2, Self::Vec3];

    pub(super) fn tag(self) -> u8 {
        Self::ALL
            .iter()
            .position(|&k| k == self)
            .map_or(0, |i| i as u8 + 1)
    }

    pub(super) fn from_tag(tag: u8) -> Option<Self> {
        Self::ALL.get(usize::from(tag).checked_sub(1)?).copied()
    }
}

/// A primitive that can be saved: its kind tag. Implemented for [`Segment2`], [`Triangle3`],
/// [`Vec2`] and [`Vec3`].
pub trait SavedPrimitive:
    Primitive<Point: Serialize + DeserializeOwned> + Serialize + DeserializeOwned
{
    /// Its tag in the header.
    const KIND: PrimitiveKind;
}

impl SavedPrimitive for Segment2 {
    const KIND: PrimitiveKind = PrimitiveKind::Segment2;
}
impl SavedPrimitive for Triangle3 {
    const KIND: PrimitiveKind = PrimitiveKind::Triangle3;
}
impl SavedPrimitive for Vec2 {
    const KIND: PrimitiveKind = PrimitiveKind::Vec2;
}
impl SavedPrimitive for Vec3 {
    const KIND: PrimitiveKind = PrimitiveKind::Vec3;
}

/// A node volume that can be saved: its kind tag. Implemented for [`Aabb`], [`Sphere`] and
/// [`Obb`] in 2D and 3D.
pub trait SavedVolume: NodeVolume + Serialize + DeserializeOwned {
    /// Its tag in the header.
    const KIND: VolumeKind;
}

impl SavedVolume for Aabb<Vec2> {
    const KIND: VolumeKind = VolumeKind::Aabb;
}
impl SavedVolume for Aabb<Vec3> {
    const KIND: VolumeKind = VolumeKind::Aabb;
}
impl SavedVolume for Sphere<Vec2> {
    const KIND: VolumeKind = VolumeKind::Sphere;
}
impl SavedVolume for Sphere<Vec3> {
    const KIND: VolumeKind = VolumeKind::Sphere;
}
impl SavedVolume for Obb<Vec2> {
    const KIND: VolumeKind = VolumeKind::Obb;
}
impl SavedVolume for Obb<Vec3> {
    const KIND: VolumeKind = VolumeKind::Obb;
}

/// A built structure that [`save`](super::save) writes and [`load`](super::load) reads:
/// what its file holds, and the full check a loaded copy must pass before anyone queries it.
pub trait Saved: Serialize + DeserializeOwned {
    /// What its file's header says.
    const KIND: FileKind;

    /// Checks every invariant the queries rely on (every index in range, no cycle, volumes
    /// around their primitives): the structure's own `validate`.
    ///
    /// # Errors
    /// The first violation found.
    fn check(&self) -> Result<(), ValidationError>;
}

/// `Saved` for the structures that answer [`SpatialIndex`], whose `validate` is the check.
macro_rules! saved_index {
    ($($structure:ident),*) => {$(
        impl<P: SavedPrimitive> Saved for $structure<P> {
            const KIND: FileKind = FileKind {
                structure: StructureKind::$structure,
                volume: None,
                primitive: P::KIND,
            };

            fn check(&self) -> Result<(), ValidationError> {
                SpatialIndex::validate(self)
            }
        }
    )*};
}

saved_index!(KdTree, BspTree, Grid, Orthtree, BruteForce);

impl<B, P> Saved for Bvh<B, P>
where
    B: SavedVolume<Point = P::Point>,
    P: SavedPrimitive,
{
    const KIND: FileKind = FileKind {
        structure: StructureKind::Bvh,
        volume: Some(B::KIND),
        primitive: P::KIND,
    };

    fn check(&self) -> Result<(), ValidationError> {
        SpatialIndex::validate(self)
    }
}

impl<P: SavedPrimitive> Saved for Bvh4<P> {
    const KIND: FileKind = FileKind {
        structure: StructureKind::Bvh4,
        volume: None,
        primitive: P::KIND,
    };

    fn check(&self) -> Result<(), ValidationError> {
        self.validate()
    }
}
