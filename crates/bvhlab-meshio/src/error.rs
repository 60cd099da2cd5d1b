//! Why a file could not be loaded, said so that a student who dropped it knows what is wrong
//! with it and what to try instead. Every message starts with the file's name.

use std::fmt;

use bvhlab::MeshError;

use crate::{Format, MAX_BYTES, MAX_TRIANGLES, MAX_VERTICES};

/// A file that [`load`](crate::load) refuses, with what is wrong with it.
///
/// Places in a file (faces, vertices, triangles) are counted from 0 unless the message says
/// otherwise; OBJ errors keep the OBJ reader's lines and faces, counted from 1.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum LoadError {
    /// The file has no bytes at all.
    Empty {
        /// The file's name.
        file: String,
    },
    /// The file is larger than [`MAX_BYTES`].
    TooLarge {
        /// The file's name.
        file: String,
        /// Its size in bytes.
        bytes: usize,
    },
    /// Neither the content nor the name says OBJ, PLY, STL or glTF.
    UnknownFormat {
        /// The file's name.
        file: String,
    },
    /// More triangles than [`MAX_TRIANGLES`] (as declared by the file, or as counted).
    TooManyTriangles {
        /// The file's name.
        file: String,
        /// How many triangles it has or declares (at least).
        triangles: usize,
    },
    /// More vertices than [`MAX_VERTICES`] (as declared by the file, or as counted).
    TooManyVertices {
        /// The file's name.
        file: String,
        /// How many vertices it has or declares.
        vertices: usize,
    },
    /// A well-formed file without a single triangle.
    NoTriangles {
        /// The file's name.
        file: String,
        /// Its format.
        format: Format,
    },
    /// A coordinate that is NaN or infinite (or, from a double or a transform, too large for
    /// a 32-bit float).
    NonFinite {
        /// The file's name.
        file: String,
        /// Its format.
        format: Format,
        /// Where: "vertex 12", "facet 3", "vertex 5 of mesh `Cube`"...
        place: String,
    },
    /// A face corner that names a vertex the file does not have.
    BadIndex {
        /// The file's name.
        file: String,
        /// Its format.
        format: Format,
        /// The face (or triangle), counted from 0.
        face: usize,
        /// The index as written (negative ones included).
        index: i64,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A binary STL whose triangle count (bytes 80 to 83) does not match its size.
    StlCount {
        /// The file's name.
        file: String,
        /// The count the file declares.
        declared: u32,
        /// The whole 50-byte triangle records the file holds after its 84-byte header.
        holds: usize,
        /// Bytes left over after the last whole record.
        stray_bytes: usize,
    },
    /// A `.gltf` file that keeps a buffer in a separate file, which one dropped file cannot
    /// bring along.
    ExternalBuffer {
        /// The file's name.
        file: String,
        /// The buffer's URI as written.
        uri: String,
    },
    /// An OBJ file that the core's OBJ reader refuses.
    Obj {
        /// The file's name.
        file: String,
        /// The reader's error, with line and face.
        error: MeshError,
    },
    /// Any other fault in the file's structure, described in `detail`.
    Malformed {
        /// The file's name.
        file: String,
        /// Its format.
        format: Format,
        /// What is wrong, as a sentence that names the format.
        detail: String,
    },
}

impl LoadError {
    /// A [`LoadError::Malformed`], for the readers.
    pub(crate) fn malformed(file: &str, format: Format, detail: impl Into<String>) -> Self {
        Self::Malformed {
            file: file.to_owned(),
            format,
            detail: detail.into(),
        }
    }

    /// A [`LoadError::NonFinite`], for the readers.
    pub(crate) fn non_finite(file: &str, format: Format, place: impl Into<String>) -> Self {
        Self::NonFinite {
            file: file.to_owned(),
            format,
            place: place.into(),
        }
    }

    /// The name of the file the error is about.
    pub fn file(&self) -> &str {
        match self {
            Self::Empty { file }
            | Self::TooLarge { file, .. }
            | Self::UnknownFormat { file }
            | Self::TooManyTriangles { file, .. }
            | Self::TooManyVertices { file, .. }
            | Self::NoTriangles { file, .. }
            | Self::NonFinite { file, .. }
            | Self::BadIndex { file, .. }
            | Self::StlCount { file, .. }
            | Self::ExternalBuffer { file, .. }
            | Self::Obj { file, .. }
            | Self::Malformed { file, .. } => file,
        }
    }
}

/// `n` with a comma between groups of three digits: `12,000,000`.
pub(crate) fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, digit) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(digit);
    }
    out
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty { file } => write!(f, "{file} is empty (0 bytes)"),
            Self::TooLarge { file, bytes } => write!(
                f,
                "{file} is {} MiB; the lab reads files up to {} MiB",
                bytes.div_ceil(1 << 20),
                MAX_BYTES >> 20
            ),
            Self::UnknownFormat { file } => write!(
                f,
                "{file} is not a mesh file this lab reads (OBJ, PLY, STL, glTF/GLB)"
            ),
            Self::TooManyTriangles { file, triangles } => write!(
                f,
                "{file} has {} triangles; the lab's limit is {}",
                grouped(*triangles),
                grouped(MAX_TRIANGLES)
            ),
            Self::TooManyVertices { file, vertices } => write!(
                f,
                "{file} has {} vertices; the lab's limit is {}",
                grouped(*vertices),
                grouped(MAX_VERTICES)
            ),
            Self::NoTriangles { file, format } => {
                write!(f, "{file} has no triangles (read as {})", format.label())
            }
            Self::NonFinite {
                file,
                format,
                place,
            } => write!(
                f,
                "{file}: {place} has a coordinate that is not a finite number (NaN or \
                 infinity); {} files must hold finite 32-bit coordinates",
                format.label()
            ),
            Self::BadIndex {
                file,
                format,
                face,
                index,
                vertices,
            } => {
                write!(
                    f,
                    "{file}: {} face {face} names vertex {index}",
                    format.label()
                )?;
                if *index < 0 {
                    write!(f, ", but vertex indices cannot be negative")
                } else if *vertices == 0 {
                    write!(f, ", but the file has no vertices")
                } else {
                    write!(
                        f,
                        ", but the file has only {} vertices (0 to {})",
                        grouped(*vertices),
                        grouped(vertices - 1)
                    )
                }
            }
            Self::StlCount {
                file,
                declared,
                holds,
                stray_bytes,
            } => {
                write!(
                    f,
                    "{file}: binary STL says {} triangles but holds {}",
                    grouped(*declared as usize),
                    grouped(*holds)
                )?;
                if *stray_bytes > 0 {
                    write!(f, " and {stray_bytes} stray bytes")?;
                }
                write!(f, " (a cut-off download, or not an STL file?)")
            }
            Self::ExternalBuffer { file, uri } => write!(
                f,
                "{file}: the glTF file keeps its geometry in a separate file, `{uri}`, which \
                 cannot come along with a single dropped file; export as .glb (binary glTF) \
                 or as .gltf with embedded buffers"
            ),
            Self::Obj { file, error } => write!(f, "{file}: {error}"),
            Self::Malformed { file, detail, .. } => write!(f, "{file}: {detail}"),
        }
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Obj { error, .. } => Some(error),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::grouped;

    #[test]
    fn thousands_are_grouped() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(12_000_000), "12,000,000");
        assert_eq!(grouped(123_456_789), "123,456,789");
    }
}
