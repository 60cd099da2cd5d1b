//! The envelope around a saved structure: a fixed 32-byte header, then the payload.
//!
//! ```text
//! offset  0  magic          8 bytes   b"bvhlab\xb7T": "not a tree file" is told at once
//! offset  8  version        u32 LE    FORMAT_VERSION; read before anything else is trusted
//! offset 12  structure      u8        StructureKind tag
//! offset 13  volume         u8        VolumeKind tag (0: no node volume)
//! offset 14  primitive      u8        PrimitiveKind tag
//! offset 15  reserved       u8        0
//! offset 16  payload bytes  u64 LE    so that a cut file is told from a damaged one
//! offset 24  checksum       u64 LE    FNV-1a of the payload: a flipped bit is refused here
//! offset 32  payload                  the structure in postcard's encoding
//! ```
//!
//! The header's integers are fixed-width little-endian, so that any later version can read
//! this one's version and kind before deciding how to read the rest.

use super::FORMAT_VERSION;
use super::error::LoadError;
use super::kind::{FileKind, PrimitiveKind, StructureKind, VolumeKind};

/// The first bytes of every tree file.
pub const MAGIC: [u8; 8] = *b"bvhlab\xb7T";

/// The header's length; the payload follows it.
pub const HEADER_LEN: usize = 32;

/// What a header says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Header {
    pub kind: FileKind,
    pub payload_len: u64,
    pub checksum: u64,
}

impl Header {
    pub(super) fn new(kind: FileKind, payload: &[u8]) -> Self {
        Self {
            kind,
            payload_len: payload.len() as u64,
            checksum: checksum(payload),
        }
    }

    pub(super) fn to_bytes(self) -> [u8; HEADER_LEN] {
        let mut bytes = [0; HEADER_LEN];
        bytes[..8].copy_from_slice(&MAGIC);
        bytes[8..12].copy_from_slice(&FORMAT_VERSION.to_le_bytes());
        bytes[12] = self.kind.structure.tag();
        bytes[13] = VolumeKind::tag(self.kind.volume);
        bytes[14] = self.kind.primitive.tag();
        bytes[16..24].copy_from_slice(&self.payload_len.to_le_bytes());
        bytes[24..32].copy_from_slice(&self.checksum.to_le_bytes());
        bytes
    }

    /// Reads the header in the order a reader can trust it: magic, version, kind, lengths.
    pub(super) fn read(bytes: &[u8]) -> Result<Self, LoadError> {
        let magic_len = bytes.len().min(MAGIC.len());
        if bytes.is_empty() || bytes[..magic_len] != MAGIC[..magic_len] {
            return Err(LoadError::NotATreeFile);
        }
        let truncated = || LoadError::Truncated {
            needed: HEADER_LEN as u64,
            found: bytes.len() as u64,
        };
        let version = u32::from_le_bytes(field(bytes, 8).ok_or_else(truncated)?);
        if version != FORMAT_VERSION {
            return Err(LoadError::Version { found: version });
        }
        if bytes.len() < HEADER_LEN {
            return Err(truncated());
        }
        let kind = FileKind {
            structure: StructureKind::from_tag(bytes[12]).ok_or_else(|| {
                LoadError::corrupt(format!("unknown structure tag {}", bytes[12]))
            })?,
            volume: match bytes[13] {
                0 => None,
                tag => Some(
                    VolumeKind::from_tag(tag)
                        .ok_or_else(|| LoadError::corrupt(format!("unknown volume tag {tag}")))?,
                ),
            },
            primitive: PrimitiveKind::from_tag(bytes[14]).ok_or_else(|| {
                LoadError::corrupt(format!("unknown primitive tag {}", bytes[14]))
            })?,
        };
        if bytes[15] != 0 {
            return Err(LoadError::corrupt(format!(
                "reserved byte is {}",
                bytes[15]
            )));
        }
        Ok(Self {
            kind,
            payload_len: u64::from_le_bytes(field(bytes, 16).ok_or_else(truncated)?),
            checksum: u64::from_le_bytes(field(bytes, 24).ok_or_else(truncated)?),
        })
    }
}

/// `N` bytes at `at`, or `None` past the end.
fn field<const N: usize>(bytes: &[u8], at: usize) -> Option<[u8; N]> {
    bytes.get(at..at + N)?.try_into().ok()
}

/// FNV-1a, 64 bits: no dependency, and any single flipped bit changes it.
pub(super) fn checksum(payload: &[u8]) -> u64 {
    payload.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
    })
}
