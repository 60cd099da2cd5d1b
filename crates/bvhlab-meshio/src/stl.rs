//! STL files, ASCII and binary, read with `stl_io` and welded into shared vertices.
//!
//! Binary STL: an 80-byte header of free text, a little-endian `u32` triangle count, then 50
//! bytes per triangle (normal, three corners, a 2-byte attribute), so a well-formed file has
//! exactly 84 + 50·n bytes. This reader checks that first and names both numbers when they
//! disagree (a cut-off download is the usual cause).
//!
//! ASCII STL: `solid name`, then `facet normal … / outer loop / vertex x y z ×3 / endloop /
//! endfacet` blocks, then `endsolid`. Some files hold several solids one after another;
//! `stl_io` stops at the first `endsolid`, so each solid is handed to it on its own.
//!
//! Normals are ignored (the lab computes its own), and so is the binary attribute word.

use std::io;

use bvhlab::glam::Vec3;

use crate::format::trim_start;
use crate::spliced::Spliced;
use crate::weld::Welder;
use crate::{Format, Geometry, LoadError, MAX_TRIANGLES};

/// The binary header and count.
const HEADER: usize = 84;
/// One binary triangle record.
const RECORD: usize = 50;
/// How far into an ASCII file the test for text looks.
const TEXT_SNIFF_BYTES: usize = 1024;

/// Whether `bytes` has the exact size of a binary STL with the count it declares.
pub(crate) fn is_binary(bytes: &[u8]) -> bool {
    declared_count(bytes)
        .is_some_and(|n| HEADER as u64 + RECORD as u64 * u64::from(n) == bytes.len() as u64)
}

/// Whether `bytes` starts (after white space) with the word `solid` and is text at its start.
/// Only meaningful once [`is_binary`] has said no.
pub(crate) fn is_ascii(bytes: &[u8]) -> bool {
    let text = trim_start(bytes);
    text.strip_prefix(b"solid")
        .is_some_and(|rest| rest.first().is_none_or(u8::is_ascii_whitespace))
        && !bytes[..bytes.len().min(TEXT_SNIFF_BYTES)].contains(&0)
}

/// The count at bytes 80 to 83, if the file is that long.
fn declared_count(bytes: &[u8]) -> Option<u32> {
    let count = bytes.get(80..HEADER)?;
    Some(u32::from_le_bytes([count[0], count[1], count[2], count[3]]))
}

/// Reads an STL file (ASCII or binary, decided as `format` explains).
pub(crate) fn read(file: &str, bytes: &[u8]) -> Result<Geometry, LoadError> {
    if !is_binary(bytes) && is_ascii(bytes) {
        read_ascii(file, bytes)
    } else {
        read_binary(file, bytes)
    }
}

fn read_binary(file: &str, bytes: &[u8]) -> Result<Geometry, LoadError> {
    let Some(declared) = declared_count(bytes) else {
        return Err(LoadError::malformed(
            file,
            Format::Stl,
            format!(
                "a binary STL file has an {HEADER}-byte header, but this file has only {} \
                 bytes (and it does not start with `solid`, as an ASCII STL file would)",
                bytes.len()
            ),
        ));
    };
    let body = bytes.len() - HEADER;
    if !is_binary(bytes) {
        return Err(LoadError::StlCount {
            file: file.to_owned(),
            declared,
            holds: body / RECORD,
            stray_bytes: body % RECORD,
        });
    }
    let triangles = declared as usize;
    if triangles > MAX_TRIANGLES {
        return Err(LoadError::TooManyTriangles {
            file: file.to_owned(),
            triangles,
        });
    }
    // A neutral header, so that `stl_io` does not take a header starting "solid " for ASCII.
    let mut stream = Spliced::new(&[0; 80], &bytes[80..]);
    let reader = stl_io::create_stl_reader(&mut stream)
        .map_err(|e| LoadError::malformed(file, Format::Stl, format!("binary STL: {e}")))?;
    let mut out = Soup::with_capacity(triangles);
    for (k, triangle) in reader.enumerate() {
        let triangle = triangle.map_err(|e| {
            LoadError::malformed(file, Format::Stl, format!("binary STL, triangle {k}: {e}"))
        })?;
        out.push(file, &triangle, || format!("triangle {k}"))?;
    }
    Ok(out.finish())
}

fn read_ascii(file: &str, bytes: &[u8]) -> Result<Geometry, LoadError> {
    let mut out = Soup::with_capacity(0);
    let solids = split_solids(bytes).map_err(|line| {
        LoadError::malformed(
            file,
            Format::Stl,
            format!(
                "ASCII STL, line {line}: expected `solid` to start another solid after \
                     `endsolid`"
            ),
        )
    })?;
    for (s, solid) in solids.iter().enumerate() {
        // `stl_io` wants "solid " and a name; the name is not needed, so a blank one is given.
        let mut stream = Spliced::new(b"solid \n", solid.body);
        let reader =
            stl_io::create_stl_reader(&mut stream).map_err(|e| ascii_fault(file, s, 0, &e))?;
        for (facet, triangle) in reader.enumerate() {
            let triangle = triangle.map_err(|e| ascii_fault(file, s, facet, &e))?;
            out.push(file, &triangle, || format!("solid {s}, facet {facet}"))?;
            if out.indices.len() > MAX_TRIANGLES {
                return Err(LoadError::TooManyTriangles {
                    file: file.to_owned(),
                    triangles: out.indices.len(),
                });
            }
        }
    }
    Ok(out.finish())
}

/// An `stl_io` error in facet `facet` of solid `solid`, said as the lab says it.
fn ascii_fault(file: &str, solid: usize, facet: usize, e: &io::Error) -> LoadError {
    let place = format!("solid {solid}, facet {facet}");
    let message = e.to_string();
    if message.contains("finite") {
        LoadError::non_finite(file, Format::Stl, place)
    } else if e.kind() == io::ErrorKind::UnexpectedEof {
        LoadError::malformed(
            file,
            Format::Stl,
            format!(
                "ASCII STL, {place}: the file ends inside the solid (no `endsolid`): {message}"
            ),
        )
    } else {
        LoadError::malformed(file, Format::Stl, format!("ASCII STL, {place}: {message}"))
    }
}

/// One `solid … endsolid` stretch: its lines after the `solid` line, through `endsolid`.
struct Solid<'a> {
    body: &'a [u8],
}

/// The solids of an ASCII file, or the line (from 1) of text found between two solids.
fn split_solids(bytes: &[u8]) -> Result<Vec<Solid<'_>>, usize> {
    let mut solids = Vec::new();
    let mut start = None;
    let mut offset = 0;
    for (number, line) in bytes.split_inclusive(|&b| b == b'\n').enumerate() {
        let word = first_word(line);
        match start {
            None if word == b"solid" => start = Some(offset + line.len()),
            None if word.is_empty() => {}
            None => return Err(number + 1),
            Some(body) if word == b"endsolid" => {
                solids.push(Solid {
                    body: &bytes[body..offset + line.len()],
                });
                start = None;
            }
            Some(_) => {}
        }
        offset += line.len();
    }
    if let Some(body) = start {
        // No `endsolid`: `stl_io` reports where the file ends.
        solids.push(Solid {
            body: &bytes[body..],
        });
    }
    Ok(solids)
}

/// The first word of a line (empty for a blank line).
fn first_word(line: &[u8]) -> &[u8] {
    let line = trim_start(line);
    let end = line
        .iter()
        .position(u8::is_ascii_whitespace)
        .unwrap_or(line.len());
    &line[..end]
}

/// Triangles as they come, welded into shared vertices.
struct Soup {
    welder: Welder,
    indices: Vec<[u32; 3]>,
}

impl Soup {
    fn with_capacity(triangles: usize) -> Self {
        Self {
            welder: Welder::default(),
            indices: Vec::with_capacity(triangles),
        }
    }

    /// Adds one triangle, refusing non-finite corners (`place` names the triangle).
    fn push(
        &mut self,
        file: &str,
        triangle: &stl_io::Triangle,
        place: impl Fn() -> String,
    ) -> Result<(), LoadError> {
        let mut corners = [0; 3];
        for (corner, vertex) in corners.iter_mut().zip(&triangle.vertices) {
            let p = Vec3::from(vertex.0);
            if !p.is_finite() {
                return Err(LoadError::non_finite(file, Format::Stl, place()));
            }
            *corner = self.welder.vertex(p);
        }
        self.indices.push(corners);
        Ok(())
    }

    fn finish(self) -> Geometry {
        Geometry {
            positions: self.welder.into_positions(),
            indices: self.indices,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solids_are_split_at_endsolid() {
        let text = b"solid a\nfacet\nendsolid a\n\nsolid b\r\nendsolid\n";
        let solids = split_solids(text).expect("two solids");
        assert_eq!(solids.len(), 2);
        assert_eq!(solids[0].body, b"facet\nendsolid a\n");
        assert_eq!(solids[1].body, b"endsolid\n");
        assert_eq!(split_solids(b"solid a\nendsolid\njunk\n").err(), Some(3));
        let open = split_solids(b"solid a\nfacet").expect("one open solid");
        assert_eq!(open[0].body, b"facet");
    }

    #[test]
    fn binary_size_formula() {
        let mut bytes = vec![0u8; 84 + 100];
        bytes[80] = 2;
        assert!(is_binary(&bytes));
        bytes.push(0);
        assert!(!is_binary(&bytes));
        assert!(!is_binary(&[0; 83]));
    }
}
