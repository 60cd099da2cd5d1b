//! Why an OBJ file could not be loaded, said so that the person who made the file can fix it.

use std::fmt;

/// An OBJ file that [`Mesh::from_obj`](super::Mesh::from_obj) refuses, or vertices and
/// triangles that [`Mesh::from_indexed`](super::Mesh::from_indexed) refuses, with where and
/// why.
///
/// In an OBJ file, lines and faces are counted from 1, as text editors and the OBJ format count
/// them (a face is an `f` statement, before triangulation). Vertices and triangles given to
/// `from_indexed` are counted from 0, as the slices that hold them count.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// A line is not text: it has a NUL byte (a binary file), or it is a `v` or `f` statement
    /// that is not UTF-8 (a binary file, or one cut off inside a character).
    NotText {
        /// The line.
        line: usize,
        /// The byte's position in the line, from 1.
        column: usize,
    },
    /// A token that should be a number is not one.
    BadNumber {
        /// The line.
        line: usize,
        /// The token as written.
        token: String,
    },
    /// A vertex statement with fewer than three coordinates.
    MissingCoordinates {
        /// The line.
        line: usize,
        /// How many numbers it has.
        found: usize,
    },
    /// A vertex coordinate that is NaN or infinite (or too large for `f32`).
    NonFinite {
        /// The line.
        line: usize,
        /// The vertex number (its 1-based OBJ index).
        vertex: usize,
        /// The coordinate as written.
        token: String,
    },
    /// A face corner whose vertex index is malformed, zero or out of range.
    BadIndex {
        /// The line.
        line: usize,
        /// The face number.
        face: usize,
        /// The corner as written (`7`, `7/2/1`, `-3`...).
        token: String,
        /// What is wrong with it.
        problem: IndexProblem,
    },
    /// A face with fewer than three corners.
    TooFewCorners {
        /// The line.
        line: usize,
        /// The face number.
        face: usize,
        /// How many corners it has.
        found: usize,
    },
    /// More vertices than a 32-bit index can name.
    TooManyVertices {
        /// The line of the first vertex past the limit.
        line: usize,
    },
    /// A vertex given to `from_indexed` with a NaN or infinite coordinate.
    NonFiniteVertex {
        /// The vertex, counted from 0.
        vertex: usize,
    },
    /// A triangle given to `from_indexed` that names a vertex past the last one.
    IndexOutOfRange {
        /// The triangle, counted from 0.
        triangle: usize,
        /// The index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
}

/// What is wrong with a face corner's vertex index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum IndexProblem {
    /// Not an integer, or not of the form `v`, `v/vt`, `v//vn`, `v/vt/vn`.
    Malformed,
    /// Zero: OBJ indices start at 1.
    Zero,
    /// Past the last vertex of the file.
    PastEnd {
        /// How many vertices the file has.
        vertices: usize,
    },
    /// A negative (relative) index reaching back before the first vertex.
    BeforeStart {
        /// How many vertices precede the face.
        preceding: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotText { line, column } => write!(
                f,
                "line {line}, column {column}: this is not text; an OBJ file is plain text \
                 (is this a binary file, such as a binary STL, a .blend or a zip, or a file \
                 cut off in the middle of a character?)"
            ),
            Self::BadNumber { line, token } => write!(
                f,
                "line {line}: `{token}` is not a number; write vertices as `v x y z` with \
                 decimal numbers such as `-1.5` or `2e-3`"
            ),
            Self::MissingCoordinates { line, found } => write!(
                f,
                "line {line}: a vertex needs three coordinates (`v x y z`), this one has {found}"
            ),
            Self::NonFinite {
                line,
                vertex,
                token,
            } => write!(
                f,
                "line {line} (vertex {vertex}): the coordinate `{token}` is not a finite \
                 32-bit number; every coordinate must be finite (no NaN, no infinity, \
                 magnitude below 3.4e38)"
            ),
            Self::BadIndex {
                line,
                face,
                token,
                problem,
            } => {
                write!(f, "line {line} (face {face}): the corner `{token}` ")?;
                match problem {
                    IndexProblem::Malformed => write!(
                        f,
                        "is not a vertex index; write corners as `v`, `v/vt`, `v//vn` or \
                         `v/vt/vn` with integer indices"
                    ),
                    IndexProblem::Zero => write!(
                        f,
                        "uses index 0; OBJ indices start at 1 (negative ones count back from \
                         the latest vertex)"
                    ),
                    IndexProblem::PastEnd { vertices } => write!(
                        f,
                        "refers past the last vertex: the file has {vertices} vertices"
                    ),
                    IndexProblem::BeforeStart { preceding } => write!(
                        f,
                        "counts back past the first vertex: only {preceding} vertices come \
                         before this face"
                    ),
                }
            }
            Self::TooFewCorners { line, face, found } => write!(
                f,
                "line {line} (face {face}): a face needs at least three corners, this one has \
                 {found} (write lines as `l` statements, points as `p`)"
            ),
            Self::TooManyVertices { line } => write!(
                f,
                "line {line}: more than {} vertices; split the mesh into smaller files",
                u32::MAX
            ),
            Self::NonFiniteVertex { vertex } => write!(
                f,
                "vertex {vertex} (counting from 0) has a coordinate that is not a finite \
                 number (NaN or infinity)"
            ),
            Self::IndexOutOfRange {
                triangle,
                index,
                vertices,
            } => {
                write!(
                    f,
                    "triangle {triangle} (counting from 0) names vertex {index}, but "
                )?;
                match vertices {
                    0 => write!(f, "there are no vertices"),
                    n => write!(f, "there are only {n} (0 to {})", n - 1),
                }
            }
        }
    }
}

impl std::error::Error for MeshError {}
