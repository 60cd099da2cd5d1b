//! Saving and loading built structures (the `serde` feature): build once, save the bytes,
//! load them later without the build's cost.
//!
//! [`save`] writes any structure of this crate ([`Bvh`](crate::Bvh) with box, sphere or OBB
//! nodes, [`Bvh4`](crate::Bvh4), [`KdTree`](crate::KdTree), [`BspTree`](crate::BspTree),
//! [`Grid`](crate::Grid), [`Orthtree`](crate::Orthtree), [`BruteForce`](crate::BruteForce))
//! over [`Segment2`](crate::Segment2), [`Triangle3`](crate::Triangle3) or points; [`load`]
//! reads it back as the type the caller names:
//!
//! ```
//! use bvhlab::glam::Vec3;
//! use bvhlab::prelude::*;
//! use bvhlab::saved::{self, LoadError};
//!
//! let floor = Triangle3::new(Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
//! let tree = AabbTree3::build(&[floor]);
//! let bytes = saved::save(&tree)?;
//!
//! let loaded: AabbTree3 = saved::load(&bytes)?;
//! let down = Ray3::new(Vec3::new(1.0, 1.0, 3.0), -Vec3::Z)?;
//! assert_eq!(loaded.ray_first_hit(&down, f32::INFINITY), tree.ray_first_hit(&down, f32::INFINITY));
//!
//! // A file is loaded only as what it holds.
//! let err = saved::load::<KdTree3>(&bytes).unwrap_err();
//! assert!(matches!(err, LoadError::WrongKind { .. }));
//! assert_eq!(err.to_string(), "the file holds a Bvh with Aabb nodes over Triangle3, not a KdTree over Triangle3");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## What a load guarantees
//!
//! A file is untrusted input. [`load`] refuses, with a [`LoadError`] that says why, a file
//! that is not a tree file, one from another [`FORMAT_VERSION`], one that holds another
//! structure, node volume or primitive ([`FileKind`]), one cut short, one whose checksum
//! does not match, and one whose payload decodes into a structure that breaks its
//! invariants: every loaded structure has passed its own full check
//! ([`SpatialIndex::validate`](crate::SpatialIndex::validate), [`Bvh4::validate`](crate::Bvh4::validate)),
//! which checks every child, primitive and cell index, the tree's order (so no walk loops),
//! its depth (so no walk's fixed stack overflows) and every volume around its primitives.
//! It never panics, and a tree it returns answers as brute force does over its primitives.
//!
//! The layout of the bytes is in `header.rs` (a 32-byte header) and the payload is the
//! structure in [postcard](https://docs.rs/postcard)'s encoding.

mod error;
mod header;
mod kind;

pub use error::{LoadError, SaveError};
pub use header::{HEADER_LEN, MAGIC};
pub use kind::{
    FileKind, PrimitiveKind, Saved, SavedPrimitive, SavedVolume, StructureKind, VolumeKind,
};

use header::{Header, checksum};

/// The version of the file format this library writes and reads. It changes whenever a
/// saved structure's layout does; a file of another version is refused, never misread.
///
/// Version 2 (issue 28): a primitive with a NaN or infinite coordinate is never an answer, so
/// the 2^D trees lost their list of such primitives and a grid's unplaced list no longer holds
/// them.
///
/// Version 3 (issue 33): a [`Bvh4`](crate::Bvh4) keeps the primitives it leaves out, so that
/// its `remove` gives them back.
///
/// Version 4 (issue 33): a [`Bvh4`](crate::Bvh4) over triangles holds its leaves' triangles
/// in blocks of four (with padding ids), and every build's options say how many primitives a
/// leaf tests at once (`BvhOptions::leaf_block`).
pub const FORMAT_VERSION: u32 = 4;

/// The structure as bytes: the header, then the payload.
///
/// # Errors
/// [`SaveError`] if the encoder refuses a value (not expected for this crate's structures).
pub fn save<T: Saved>(tree: &T) -> Result<Vec<u8>, SaveError> {
    let payload = postcard::to_allocvec(tree).map_err(|e| SaveError {
        message: e.to_string(),
    })?;
    let mut bytes = Vec::with_capacity(HEADER_LEN + payload.len());
    bytes.extend_from_slice(&Header::new(T::KIND, &payload).to_bytes());
    bytes.extend_from_slice(&payload);
    Ok(bytes)
}

/// The structure saved in `bytes`, checked in full.
///
/// # Errors
/// A [`LoadError`] saying why the file is refused: not a tree file, another format version,
/// another kind of structure, truncated, corrupt, or a structure that fails its check.
pub fn load<T: Saved>(bytes: &[u8]) -> Result<T, LoadError> {
    let header = Header::read(bytes)?;
    if header.kind != T::KIND {
        return Err(LoadError::WrongKind {
            found: header.kind,
            wanted: T::KIND,
        });
    }
    let payload = &bytes[HEADER_LEN..];
    let needed = (HEADER_LEN as u64).saturating_add(header.payload_len);
    if (payload.len() as u64) < header.payload_len {
        return Err(LoadError::Truncated {
            needed,
            found: bytes.len() as u64,
        });
    }
    if payload.len() as u64 > header.payload_len {
        return Err(LoadError::corrupt(format!(
            "{} bytes after the payload",
            payload.len() as u64 - header.payload_len
        )));
    }
    if checksum(payload) != header.checksum {
        return Err(LoadError::corrupt(
            "the checksum does not match the payload",
        ));
    }
    let (tree, rest) = postcard::take_from_bytes::<T>(payload)
        .map_err(|e| LoadError::corrupt(format!("the payload does not decode: {e}")))?;
    if !rest.is_empty() {
        return Err(LoadError::corrupt(format!(
            "{} payload bytes left over after the structure",
            rest.len()
        )));
    }
    tree.check().map_err(LoadError::Invalid)?;
    Ok(tree)
}

/// What a tree file holds, from its header alone (to choose the type to [`load`] it as).
///
/// # Errors
/// As [`load`]'s, for the header: not a tree file, another version, truncated, unknown tags.
pub fn kind_of(bytes: &[u8]) -> Result<FileKind, LoadError> {
    Header::read(bytes).map(|header| header.kind)
}

/// Rewrites the header's payload length and checksum to match the bytes after it, so that a
/// test or a fuzzer can hand [`load`] an edited payload and reach the structure checks
/// instead of the checksum's refusal. Does nothing to a buffer shorter than the header.
#[doc(hidden)]
pub fn reseal(bytes: &mut [u8]) {
    if bytes.len() < HEADER_LEN {
        return;
    }
    let (header, payload) = bytes.split_at_mut(HEADER_LEN);
    header[16..24].copy_from_slice(&(payload.len() as u64).to_le_bytes());
    header[24..32].copy_from_slice(&checksum(payload).to_le_bytes());
}
