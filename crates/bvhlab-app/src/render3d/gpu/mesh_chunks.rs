//! Cutting a mesh into pieces that each fit in one GPU buffer.
//!
//! A device caps every buffer at `max_buffer_size` bytes (256 MiB by default on WebGPU). A
//! mesh's index buffer needs 12 bytes per triangle and its vertex buffer 12 bytes per vertex,
//! so meshes of more than about 22 million triangles (or vertices) need several buffers and
//! several draws. When the vertices fit in one buffer only the triangles are cut into ranges
//! that share it; otherwise each range of triangles gets its own vertices, renumbered.
//!
//! Indices are checked here too, once per upload, so a bad index is reported by name instead
//! of drawing garbage.

use std::borrow::Cow;
use std::fmt;

/// Bytes of one vertex (three `f32`) and of one triangle's indices (three `u32`).
const VERTEX_BYTES: u64 = 12;
const TRIANGLE_BYTES: u64 = 12;

/// One piece of a mesh, drawn with one indexed draw.
#[derive(Debug)]
pub(crate) struct MeshChunk<'a> {
    /// This piece's own vertices, renumbered from 0; `None` when it indexes the mesh's
    /// shared vertex buffer.
    pub positions: Option<Vec<[f32; 3]>>,
    /// The triangles, indexing `positions` (or the shared vertices).
    pub indices: Cow<'a, [[u32; 3]]>,
}

/// Why a mesh cannot be drawn.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshUploadError {
    /// A triangle refers to a vertex the mesh does not have.
    VertexOutOfRange {
        /// The triangle's index.
        triangle: usize,
        /// The vertex index it holds.
        vertex: u32,
        /// How many vertices the mesh has.
        vertex_count: usize,
    },
    /// The device's buffers are too small to hold even one triangle's vertices.
    BufferLimitTooSmall {
        /// The device's `max_buffer_size`, in bytes.
        max_buffer_size: u64,
    },
}

impl fmt::Display for MeshUploadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::VertexOutOfRange {
                triangle,
                vertex,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} refers to vertex {vertex}, but the mesh has only \
                 {vertex_count} vertices"
            ),
            Self::BufferLimitTooSmall { max_buffer_size } => write!(
                f,
                "the graphics device allows buffers of only {max_buffer_size} bytes, too small \
                 for a triangle"
            ),
        }
    }
}

impl std::error::Error for MeshUploadError {}

/// Checks every index, then cuts the mesh into pieces whose vertex and index buffers each
/// take at most `max_buffer_size` bytes. Returns whether the pieces share one vertex buffer
/// (the whole of `positions`), and the pieces in order.
pub(crate) fn split_mesh<'a>(
    positions: &[[f32; 3]],
    indices: &'a [[u32; 3]],
    max_buffer_size: u64,
) -> Result<(bool, Vec<MeshChunk<'a>>), MeshUploadError> {
    check_indices(positions.len(), indices)?;
    // Worst case for a piece with its own vertices: three new vertices per triangle.
    let own_vertices_limit = max_buffer_size / (3 * VERTEX_BYTES).max(TRIANGLE_BYTES);
    if own_vertices_limit == 0 {
        return Err(MeshUploadError::BufferLimitTooSmall { max_buffer_size });
    }
    let shared = positions.len() as u64 * VERTEX_BYTES <= max_buffer_size;
    if shared {
        let per_chunk = usize::try_from(max_buffer_size / TRIANGLE_BYTES).unwrap_or(usize::MAX);
        let chunks = indices
            .chunks(per_chunk)
            .map(|part| MeshChunk {
                positions: None,
                indices: Cow::Borrowed(part),
            })
            .collect();
        return Ok((true, chunks));
    }
    let per_chunk = usize::try_from(own_vertices_limit).unwrap_or(usize::MAX);
    // `local[v]` is vertex v's number inside the current piece, or u32::MAX if not yet used.
    let mut local = vec![u32::MAX; positions.len()];
    let chunks = indices
        .chunks(per_chunk)
        .map(|part| {
            let mut own = Vec::new();
            let renumbered = part
                .iter()
                .map(|triangle| {
                    triangle.map(|v| {
                        let slot = &mut local[v as usize];
                        if *slot == u32::MAX {
                            *slot = own.len() as u32;
                            own.push(positions[v as usize]);
                        }
                        *slot
                    })
                })
                .collect::<Vec<_>>();
            for triangle in part {
                for &v in triangle {
                    local[v as usize] = u32::MAX;
                }
            }
            MeshChunk {
                positions: Some(own),
                indices: Cow::Owned(renumbered),
            }
        })
        .collect();
    Ok((false, chunks))
}

/// The first index that points past the vertices, as an error.
fn check_indices(vertex_count: usize, indices: &[[u32; 3]]) -> Result<(), MeshUploadError> {
    for (triangle, corners) in indices.iter().enumerate() {
        if let Some(&vertex) = corners.iter().find(|&&v| v as usize >= vertex_count) {
            return Err(MeshUploadError::VertexOutOfRange {
                triangle,
                vertex,
                vertex_count,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` triangles over `n + 2` vertices, every vertex distinct.
    fn strip(n: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let positions = (0..n + 2)
            .map(|i| [i as f32, (i % 2) as f32, 0.0])
            .collect();
        let indices = (0..n).map(|i| [i, i + 1, i + 2]).collect();
        (positions, indices)
    }

    /// The triangles as world-space corners, whichever way they are stored.
    fn corners(
        shared: bool,
        positions: &[[f32; 3]],
        chunks: &[MeshChunk<'_>],
    ) -> Vec<[[f32; 3]; 3]> {
        chunks
            .iter()
            .flat_map(|chunk| {
                let vertices = if shared {
                    positions
                } else {
                    chunk.positions.as_deref().expect("own vertices")
                };
                chunk
                    .indices
                    .iter()
                    .map(|t| t.map(|v| vertices[v as usize]))
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    #[test]
    fn a_mesh_that_fits_is_one_piece_sharing_its_vertices() {
        let (positions, indices) = strip(10);
        let (shared, chunks) = split_mesh(&positions, &indices, 1 << 20).expect("valid");
        assert!(shared);
        assert_eq!(chunks.len(), 1);
        assert_eq!(chunks[0].indices.as_ref(), indices.as_slice());
    }

    #[test]
    fn too_many_triangles_share_the_vertices_across_index_ranges() {
        // Four vertices (48 bytes) used by 40 triangles (480 bytes of indices).
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let indices: Vec<[u32; 3]> = (0..40).map(|i| [i % 4, (i + 1) % 4, (i + 2) % 4]).collect();
        let limit = 48;
        let (shared, chunks) = split_mesh(&positions, &indices, limit).expect("valid");
        assert!(shared);
        assert_eq!(chunks.len(), 10);
        assert!(
            chunks
                .iter()
                .all(|c| c.indices.len() as u64 * TRIANGLE_BYTES <= limit)
        );
        assert_eq!(
            corners(shared, &positions, &chunks),
            brute(&positions, &indices)
        );
    }

    fn brute(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> Vec<[[f32; 3]; 3]> {
        indices
            .iter()
            .map(|t| t.map(|v| positions[v as usize]))
            .collect()
    }

    #[test]
    fn too_many_vertices_give_each_piece_its_own_within_the_limit() {
        let (positions, indices) = strip(50);
        let limit = 100; // bytes: 8 vertices, so 2 triangles (worst case 6 vertices) per piece
        let (shared, chunks) = split_mesh(&positions, &indices, limit).expect("valid");
        assert!(!shared);
        assert!(chunks.len() >= 25);
        for chunk in &chunks {
            let own = chunk.positions.as_ref().expect("own vertices");
            assert!(own.len() as u64 * VERTEX_BYTES <= limit);
            assert!(chunk.indices.len() as u64 * TRIANGLE_BYTES <= limit);
            assert!(
                chunk
                    .indices
                    .iter()
                    .flatten()
                    .all(|&v| (v as usize) < own.len())
            );
        }
        assert_eq!(
            corners(shared, &positions, &chunks),
            brute(&positions, &indices)
        );
    }

    #[test]
    fn a_bad_index_is_named() {
        let (positions, mut indices) = strip(5);
        indices[3][1] = 99;
        let error = split_mesh(&positions, &indices, 1 << 20).expect_err("index 99 is out");
        assert_eq!(
            error,
            MeshUploadError::VertexOutOfRange {
                triangle: 3,
                vertex: 99,
                vertex_count: 7
            }
        );
        assert!(error.to_string().contains("triangle 3 refers to vertex 99"));
        let too_small = split_mesh(&positions, &[], 20).expect_err("tiny limit");
        assert_eq!(
            too_small,
            MeshUploadError::BufferLimitTooSmall {
                max_buffer_size: 20
            }
        );
    }
}
