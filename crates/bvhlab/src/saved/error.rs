//! Why a tree could not be saved or loaded.

use std::fmt;

use super::FORMAT_VERSION;
use super::kind::FileKind;
use crate::structure::ValidationError;

/// Why [`save`](super::save) failed: the byte format refused a value (not expected for the
/// structures of this crate, which hold only numbers and lists).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SaveError {
    /// What the encoder said.
    pub message: String,
}

impl fmt::Display for SaveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "the tree could not be encoded: {}", self.message)
    }
}

impl std::error::Error for SaveError {}

/// Why [`load`](super::load) refused a file. A refused file never gives a tree: every
/// loaded tree has passed its structure's full check.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LoadError {
    /// The file does not start with bvhlab's magic bytes.
    NotATreeFile,
    /// The file ends before its header or its payload does.
    Truncated {
        /// The bytes the file would need.
        needed: u64,
        /// The bytes it has.
        found: u64,
    },
    /// The file was written in another format version.
    Version {
        /// The file's version.
        found: u32,
    },
    /// The file holds another structure, node volume or primitive than the one asked for.
    WrongKind {
        /// What the file holds.
        found: FileKind,
        /// What the caller asked for.
        wanted: FileKind,
    },
    /// The bytes are damaged: an unknown tag, a checksum that does not match, a payload that
    /// does not decode, or bytes left over.
    Corrupt {
        /// What is wrong.
        message: String,
    },
    /// The payload decodes, but into a structure that breaks its invariants (an index out of
    /// range, a cycle, a volume that misses its primitives...).
    Invalid(ValidationError),
}

impl LoadError {
    pub(super) fn corrupt(message: impl Into<String>) -> Self {
        Self::Corrupt {
            message: message.into(),
        }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotATreeFile => write!(f, "not a bvhlab tree file"),
            Self::Truncated { needed, found } => write!(
                f,
                "truncated: the file has {found} bytes, its contents need {needed}"
            ),
            Self::Version { found } => write!(
                f,
                "saved by format version {found}, this library reads version {FORMAT_VERSION}"
            ),
            Self::WrongKind { found, wanted } => {
                write!(f, "the file holds a {found}, not a {wanted}")
            }
            Self::Corrupt { message } => write!(f, "corrupt: {message}"),
            Self::Invalid(why) => write!(f, "corrupt: {}", why.message),
        }
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Invalid(why) => Some(why),
            _ => None,
        }
    }
}
