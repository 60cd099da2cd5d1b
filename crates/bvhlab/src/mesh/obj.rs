//! Reading the geometry of a Wavefront OBJ file: `v` (vertex positions) and `f` (faces).
//!
//! Everything else is skipped, as the format allows a reader to do: texture coordinates and
//! normals (`vt`, `vn`), groups and objects (`g`, `o`), smoothing (`s`), materials (`mtllib`,
//! `usemtl`; a missing `.mtl` file is therefore no problem), free-form geometry, and lines and
//! points (`l`, `p`), which have no surface to hit. Comments start at `#`.
//!
//! The format is Wavefront's "Object Files (.obj)" appendix to the Advanced Visualizer
//! manual: indices count from 1 in file order, a negative index `-k` is the `k`-th vertex
//! before the face, and a corner may carry texture and normal indices as `v/vt/vn`.

use glam::Vec3;

use super::error::{IndexProblem, MeshError};

/// The geometry of an OBJ file: positions, and faces as runs of corner indices (0-based,
/// validated) into `corners`.
#[derive(Debug, Default)]
pub(super) struct Obj {
    pub positions: Vec<Vec3>,
    pub corners: Vec<u32>,
    /// `(first corner, corner count)` of each face, in file order.
    pub faces: Vec<(usize, usize)>,
}

/// A face corner with a positive index past the vertices read so far: legal if the vertex
/// comes later in the file, checked at the end.
struct ForwardReference {
    line: usize,
    face: usize,
    token: String,
    index: usize,
}

/// Parses the geometry of an OBJ file.
pub(super) fn parse(bytes: &[u8]) -> Result<Obj, MeshError> {
    let mut obj = Obj::default();
    let mut forward = Vec::new();
    for (number, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = number + 1;
        let Some(statement) = statement(raw, line)? else {
            continue;
        };
        match statement.keyword {
            b"v" => vertex(statement.text(line)?, line, &mut obj.positions)?,
            b"f" => face(statement.text(line)?, line, &mut obj, &mut forward)?,
            _ => {}
        }
    }
    let vertices = obj.positions.len();
    if let Some(bad) = forward.into_iter().find(|r| r.index >= vertices) {
        return Err(MeshError::BadIndex {
            line: bad.line,
            face: bad.face,
            token: bad.token,
            problem: IndexProblem::PastEnd { vertices },
        });
    }
    Ok(obj)
}

/// A line's keyword and the bytes after it (comment removed).
struct Statement<'a> {
    keyword: &'a [u8],
    rest: &'a [u8],
    /// Where `rest` starts in the line.
    offset: usize,
}

impl<'a> Statement<'a> {
    /// The words after the keyword, or where in the line they stop being text.
    fn text(&self, line: usize) -> Result<std::str::SplitAsciiWhitespace<'a>, MeshError> {
        std::str::from_utf8(self.rest)
            .map(str::split_ascii_whitespace)
            .map_err(|e| MeshError::NotText {
                line,
                column: self.offset + e.valid_up_to() + 1,
            })
    }
}

/// The statement on a line; `None` for a blank or comment line.
///
/// A NUL byte anywhere means the input is not text (binary files are full of them, and text
/// in any encoding has none), so it is refused rather than skipped. Other bytes are looked at
/// only on the lines that are read, so a comment or group name in Latin-1 does no harm.
fn statement(raw: &[u8], line: usize) -> Result<Option<Statement<'_>>, MeshError> {
    if let Some(at) = raw.iter().position(|&b| b == 0) {
        return Err(MeshError::NotText {
            line,
            column: at + 1,
        });
    }
    let code = raw.split(|&b| b == b'#').next().unwrap_or_default();
    let start = code.iter().position(|b| !b.is_ascii_whitespace());
    Ok(start.map(|start| {
        let code = &code[start..];
        let end = code
            .iter()
            .position(u8::is_ascii_whitespace)
            .unwrap_or(code.len());
        let (keyword, rest) = code.split_at(end);
        Statement {
            keyword,
            rest,
            offset: start + end,
        }
    }))
}

/// `v x y z [w | r g b]`: the position; the optional weight or colour must be numbers too
/// but is not used.
fn vertex<'a>(
    tokens: impl Iterator<Item = &'a str>,
    line: usize,
    positions: &mut Vec<Vec3>,
) -> Result<(), MeshError> {
    let mut xyz = [0.0f32; 3];
    let mut found = 0;
    for token in tokens {
        let value: f32 = token.parse().map_err(|_| MeshError::BadNumber {
            line,
            token: token.to_owned(),
        })?;
        if found < 3 {
            if !value.is_finite() {
                return Err(MeshError::NonFinite {
                    line,
                    vertex: positions.len() + 1,
                    token: token.to_owned(),
                });
            }
            xyz[found] = value;
        }
        found += 1;
    }
    if found < 3 {
        return Err(MeshError::MissingCoordinates { line, found });
    }
    if positions.len() > u32::MAX as usize {
        return Err(MeshError::TooManyVertices { line });
    }
    positions.push(Vec3::from(xyz));
    Ok(())
}

/// `f c1 c2 c3 ...`: at least three corners, each `v`, `v/vt`, `v//vn` or `v/vt/vn`.
fn face<'a>(
    tokens: impl Iterator<Item = &'a str>,
    line: usize,
    obj: &mut Obj,
    forward: &mut Vec<ForwardReference>,
) -> Result<(), MeshError> {
    let (face, start, preceding) = (obj.faces.len() + 1, obj.corners.len(), obj.positions.len());
    for token in tokens {
        let bad = |problem| MeshError::BadIndex {
            line,
            face,
            token: token.to_owned(),
            problem,
        };
        let past_end = || {
            bad(IndexProblem::PastEnd {
                vertices: preceding,
            })
        };
        let index = match vertex_index(token).ok_or_else(|| bad(IndexProblem::Malformed))? {
            0 => return Err(bad(IndexProblem::Zero)),
            i if i < 0 => usize::try_from(i.unsigned_abs())
                .ok()
                .and_then(|back| preceding.checked_sub(back))
                .ok_or_else(|| bad(IndexProblem::BeforeStart { preceding }))?,
            i => usize::try_from(i - 1).map_err(|_| past_end())?,
        };
        let index32 = u32::try_from(index).map_err(|_| past_end())?;
        if index >= preceding {
            forward.push(ForwardReference {
                line,
                face,
                token: token.to_owned(),
                index,
            });
        }
        obj.corners.push(index32);
    }
    let found = obj.corners.len() - start;
    if found < 3 {
        return Err(MeshError::TooFewCorners { line, face, found });
    }
    obj.faces.push((start, found));
    Ok(())
}

/// The vertex index of a corner `v`, `v/vt`, `v//vn` or `v/vt/vn` (as written: 1-based or
/// negative), if the corner has that form.
fn vertex_index(token: &str) -> Option<i64> {
    let mut parts = token.split('/');
    let v = parts.next()?.parse().ok()?;
    let mut rest = 0;
    for part in parts {
        rest += 1;
        if rest > 2 || !(part.is_empty() || part.parse::<i64>().is_ok()) {
            return None;
        }
    }
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_with_texture_and_normal_indices() {
        assert_eq!(vertex_index("7"), Some(7));
        assert_eq!(vertex_index("7/2"), Some(7));
        assert_eq!(vertex_index("-7//3"), Some(-7));
        assert_eq!(vertex_index("7/2/3"), Some(7));
        assert_eq!(vertex_index("7/2/3/4"), None);
        assert_eq!(vertex_index("/2"), None);
        assert_eq!(vertex_index("7/x"), None);
        assert_eq!(vertex_index("1.5"), None);
    }

    #[test]
    fn forward_references_resolve_at_the_end() {
        let obj = parse(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").expect("valid");
        assert_eq!(
            (obj.corners.as_slice(), obj.faces.len()),
            (&[0, 1, 2][..], 1)
        );
        let err = parse(b"f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").expect_err("4 > 3");
        assert!(matches!(
            err,
            MeshError::BadIndex {
                line: 1,
                face: 1,
                problem: IndexProblem::PastEnd { vertices: 3 },
                ..
            }
        ));
    }
}
