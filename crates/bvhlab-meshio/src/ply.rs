//! Stanford PLY files (Turk, "The PLY Polygon File Format", 1994), ASCII and binary in both
//! byte orders, read with `ply-rs-bw`.
//!
//! A PLY file is a header that declares elements (a name, a count, typed properties) and then
//! the elements' data in that order. The lab needs two: `vertex` (properties `x`, `y`, `z`, of
//! any numeric type) and `face` (a list property `vertex_indices`, or `vertex_index`, of any
//! integer type). Other elements and properties (normals, colours, edges, materials) are read
//! through and dropped.
//!
//! Before reading any data, the declared counts are checked against what the file can hold
//! (the smallest size of an element in binary, one line per element in ASCII), so a header
//! that promises more than the file has is named as such rather than found out halfway.
//!
//! Faces of more than three corners are cut into a fan of triangles from their first corner:
//! right for the convex faces (mostly quads) that scanners and modellers write; a concave face
//! would need ear clipping, which the core does for OBJ files but does not offer on its own.

mod elements;

use std::io::BufRead;

use bvhlab::glam::Vec3;
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Encoding, Header, PropertyAccess, PropertyType, ScalarType};

use self::elements::{CORNER_LISTS, Face, Skip, Vertex};
use crate::format::starts_with_line;
use crate::{Format, Geometry, LoadError, MAX_TRIANGLES, MAX_VERTICES};

/// Reads a PLY file.
pub(crate) fn read(
    file: &str,
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<Geometry, LoadError> {
    let fault = |detail: String| LoadError::malformed(file, Format::Ply, detail);
    if !starts_with_line(bytes, b"ply") {
        return Err(fault(
            "a PLY file starts with the line `ply`, and this one does not".into(),
        ));
    }
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| fault(header_fault(bytes, &e)))?;
    let (vertices, faces) = check_header(file, &header)?;
    let header_lines = reader.line() - 1;
    let body = reader.into_inner();
    check_room(&header, body).map_err(fault)?;

    let mut data = Data {
        file,
        encoding: header.encoding,
        body,
        line: header_lines,
        vertices: vertices.count,
        geometry: Geometry::default(),
        fanned: 0,
    };
    for element in header.elements.values() {
        if element.name == vertices.name {
            data.read_vertices(element)?;
        } else if element.name == faces.name {
            data.read_faces(element)?;
        } else {
            data.skip(element)?;
        }
    }
    if data.fanned > 0 {
        warnings.push(format!(
            "{file}: {} faces with more than three corners were cut into triangles as fans \
             from their first corner (right for convex faces)",
            data.fanned
        ));
    }
    let ignored = match header.encoding {
        Encoding::Ascii => data.body.iter().any(|b| !b.is_ascii_whitespace()),
        _ => !data.body.is_empty(),
    };
    if ignored {
        warnings.push(format!(
            "{file}: {} bytes after the last element the header declares were ignored",
            data.body.len()
        ));
    }
    Ok(data.geometry)
}

/// A header parse error as a sentence: the line and its text, and what `ply-rs-bw` says.
fn header_fault(bytes: &[u8], e: &ParseError) -> String {
    let says = e.to_string();
    let says = says.lines().next().unwrap_or_default();
    let text = e
        .line()
        .and_then(|n| bytes.split(|&b| b == b'\n').nth(n.checked_sub(1)?));
    match (e.kind(), e.line(), text) {
        (std::io::ErrorKind::UnexpectedEof, ..) => {
            "the PLY header has no `end_header` line: the file ends inside its header".into()
        }
        (_, Some(line), Some(text)) => format!(
            "PLY header, line {line}: `{}` is not a header line this reader understands \
             ({says})",
            String::from_utf8_lossy(text).trim()
        ),
        _ => format!("the PLY header is not valid: {says}"),
    }
}

/// The vertex and face elements, checked for the properties the lab needs and the limits.
fn check_header<'h>(
    file: &str,
    header: &'h Header,
) -> Result<(&'h ElementDef, &'h ElementDef), LoadError> {
    let fault = |detail: String| LoadError::malformed(file, Format::Ply, detail);
    let vertex = header
        .elements
        .get("vertex")
        .ok_or_else(|| fault("the PLY header declares no `element vertex`".into()))?;
    for axis in ["x", "y", "z"] {
        match vertex.properties.get(axis).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(_)) => {}
            Some(PropertyType::List(..)) => {
                return Err(fault(format!("the vertex property `{axis}` is a list")));
            }
            None => {
                return Err(fault(format!(
                    "the vertex element has no `{axis}` property"
                )));
            }
        }
    }
    let face = header.elements.get("face").ok_or_else(|| {
        fault(
            "the PLY header declares vertices but no `element face`: a point cloud has no \
             triangles to build a structure over"
                .into(),
        )
    })?;
    let list = face
        .properties
        .values()
        .find(|p| CORNER_LISTS.contains(&p.name.as_str()));
    match list.map(|p| &p.data_type) {
        Some(PropertyType::List(_, ScalarType::Float | ScalarType::Double)) => {
            return Err(fault(
                "the face corner list holds floats, not integers".into(),
            ));
        }
        Some(PropertyType::List(..)) => {}
        _ => {
            return Err(fault(
                "the face element has no `vertex_indices` (or `vertex_index`) list".into(),
            ));
        }
    }
    if face.count > MAX_TRIANGLES {
        return Err(LoadError::TooManyTriangles {
            file: file.to_owned(),
            triangles: face.count,
        });
    }
    if vertex.count > MAX_VERTICES {
        return Err(LoadError::TooManyVertices {
            file: file.to_owned(),
            vertices: vertex.count,
        });
    }
    Ok((vertex, face))
}

/// Bytes of a scalar type in binary PLY.
fn scalar_bytes(scalar: &ScalarType) -> u64 {
    match scalar {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Whether the declared elements can fit in the data after the header: in binary, each at
/// its smallest size (a list holding nothing); in ASCII, each on its own line.
fn check_room(header: &Header, body: &[u8]) -> Result<(), String> {
    let elements = header.elements.values();
    if header.encoding == Encoding::Ascii {
        let declared: u64 = elements.map(|e| e.count as u64).sum();
        let lines = body
            .split(|&b| b == b'\n')
            .filter(|l| !l.is_empty())
            .count() as u64;
        if declared > lines {
            return Err(format!(
                "the PLY header declares {declared} elements (one per line), but only \
                 {lines} lines follow it"
            ));
        }
        return Ok(());
    }
    let mut need = 0u64;
    for element in elements {
        let smallest: u64 = element
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(scalar) | PropertyType::List(scalar, _) => {
                    scalar_bytes(scalar)
                }
            })
            .sum();
        need = need.saturating_add(smallest.saturating_mul(element.count as u64));
        if need > body.len() as u64 {
            return Err(format!(
                "the PLY header declares {} `{}` elements of at least {smallest} bytes each, \
                 but only {} bytes follow the header (a cut-off file, or a header that lies)",
                element.count,
                element.name,
                body.len()
            ));
        }
    }
    Ok(())
}

/// The reading of the data after the header.
struct Data<'a> {
    file: &'a str,
    encoding: Encoding,
    /// What is left to read.
    body: &'a [u8],
    /// The line last read (for ASCII messages).
    line: usize,
    /// The declared number of vertices (face corners are checked against it).
    vertices: usize,
    geometry: Geometry,
    /// Faces of more than three corners.
    fanned: usize,
}

/// Why one element could not be read.
enum Fault {
    /// The data ended.
    End,
    /// Anything else, said by `ply-rs-bw`.
    Parse(String),
    /// An ASCII line holding `nan` or `inf`.
    NonFinite,
}

impl Data<'_> {
    /// Reads the next element with `parser`.
    fn next<E: PropertyAccess>(
        &mut self,
        parser: &Parser<E>,
        def: &ElementDef,
    ) -> Result<E, Fault> {
        let parsed = match self.encoding {
            Encoding::Ascii => {
                let mut line = String::new();
                match self.body.read_line(&mut line) {
                    Ok(0) => return Err(Fault::End),
                    Ok(_) => self.line += 1,
                    Err(e) => return Err(Fault::Parse(format!("not text: {e}"))),
                }
                let parsed = parser.read_ascii_element(&line, def);
                // `ply-rs-bw` reads only digits, so `nan` and `inf` fail as "not a number";
                // say what they are.
                let non_finite = |t: &str| t.parse::<f64>().is_ok_and(|v| !v.is_finite());
                if parsed.is_err() && line.split_ascii_whitespace().any(non_finite) {
                    return Err(Fault::NonFinite);
                }
                parsed
            }
            Encoding::BinaryLittleEndian => parser.read_little_endian_element(&mut self.body, def),
            Encoding::BinaryBigEndian => parser.read_big_endian_element(&mut self.body, def),
        };
        parsed.map_err(|e| match e.kind() {
            std::io::ErrorKind::UnexpectedEof => Fault::End,
            _ => Fault::Parse(e.to_string().lines().next().unwrap_or_default().to_owned()),
        })
    }

    /// A fault in element `index` of `def`, as a load error.
    fn fault(&self, def: &ElementDef, index: usize, fault: Fault) -> LoadError {
        let place = match self.encoding {
            Encoding::Ascii => format!("line {}, `{}` element {index}", self.line, def.name),
            _ => format!("`{}` element {index}", def.name),
        };
        match fault {
            Fault::End => LoadError::malformed(
                self.file,
                Format::Ply,
                format!(
                    "the PLY header declares {} `{}` elements, but the data ends after {index} \
                     (a cut-off file, or a header that lies)",
                    def.count, def.name
                ),
            ),
            Fault::NonFinite => LoadError::non_finite(self.file, Format::Ply, place),
            Fault::Parse(says) => {
                LoadError::malformed(self.file, Format::Ply, format!("PLY {place}: {says}"))
            }
        }
    }

    fn read_vertices(&mut self, def: &ElementDef) -> Result<(), LoadError> {
        let parser = Parser::<Vertex>::new();
        self.geometry.positions.reserve(def.count);
        for index in 0..def.count {
            let vertex = self
                .next(&parser, def)
                .map_err(|f| self.fault(def, index, f))?;
            let p = Vec3::from(vertex.xyz.map(|c| c as f32));
            if !p.is_finite() {
                return Err(self.fault(def, index, Fault::NonFinite));
            }
            self.geometry.positions.push(p);
        }
        Ok(())
    }

    fn read_faces(&mut self, def: &ElementDef) -> Result<(), LoadError> {
        let parser = Parser::<Face>::new();
        self.geometry.indices.reserve(def.count);
        for index in 0..def.count {
            let face = self
                .next(&parser, def)
                .map_err(|f| self.fault(def, index, f))?;
            let mut corners = Vec::with_capacity(face.corners.len());
            for &corner in &face.corners {
                match u32::try_from(corner) {
                    Ok(c) if (c as usize) < self.vertices => corners.push(c),
                    _ => {
                        return Err(LoadError::BadIndex {
                            file: self.file.to_owned(),
                            format: Format::Ply,
                            face: index,
                            index: corner,
                            vertices: self.vertices,
                        });
                    }
                }
            }
            let [first, rest @ ..] = corners.as_slice() else {
                return Err(self.too_few_corners(index, 0));
            };
            if rest.len() < 2 {
                return Err(self.too_few_corners(index, corners.len()));
            }
            self.fanned += usize::from(rest.len() > 2);
            for pair in rest.windows(2) {
                self.geometry.indices.push([*first, pair[0], pair[1]]);
            }
            if self.geometry.indices.len() > MAX_TRIANGLES {
                return Err(LoadError::TooManyTriangles {
                    file: self.file.to_owned(),
                    triangles: self.geometry.indices.len(),
                });
            }
        }
        Ok(())
    }

    fn too_few_corners(&self, face: usize, found: usize) -> LoadError {
        LoadError::malformed(
            self.file,
            Format::Ply,
            format!("PLY face {face} has {found} corners; a face needs at least three"),
        )
    }

    fn skip(&mut self, def: &ElementDef) -> Result<(), LoadError> {
        // In binary, an element without properties takes no bytes: nothing to read, however
        // large its count.
        if def.properties.is_empty() && self.encoding != Encoding::Ascii {
            return Ok(());
        }
        let parser = Parser::<Skip>::new();
        for index in 0..def.count {
            self.next(&parser, def)
                .map_err(|f| self.fault(def, index, f))?;
        }
        Ok(())
    }
}
