//! Which reader a file goes to: its content decides first, its name second.
//!
//! Content first, because names lie (a binary STL saved as `.obj`, a download renamed by a
//! browser) and every format but OBJ has a signature: binary glTF starts with `glTF`, PLY with
//! a `ply` line, glTF JSON with `{`. STL is the trap: an ASCII STL starts with `solid`, but so
//! does the free 80-byte header of many binary STL files. The binary layout has a size that
//! can be checked exactly (84 + 50·n bytes, n at bytes 80 to 83), so that test comes first,
//! and `solid` counts as ASCII only when the start of the file is text (no NUL byte).

use crate::stl;

/// A mesh file format the lab reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (text).
    Obj,
    /// Stanford PLY, ASCII or binary (either byte order).
    Ply,
    /// STL (stereolithography), ASCII or binary.
    Stl,
    /// glTF 2.0 as JSON (`.gltf`), with its buffers embedded as base64 data URIs.
    Gltf,
    /// glTF 2.0 binary (`.glb`).
    Glb,
}

impl Format {
    /// All formats, in the order a file menu would list them.
    pub const ALL: [Self; 5] = [Self::Obj, Self::Ply, Self::Stl, Self::Gltf, Self::Glb];

    /// The format's short name, for a status line: `OBJ`, `PLY`, `STL`, `glTF`, `GLB`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Obj => "OBJ",
            Self::Ply => "PLY",
            Self::Stl => "STL",
            Self::Gltf => "glTF",
            Self::Glb => "GLB",
        }
    }

    /// The file extension the format usually has, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Ply => "ply",
            Self::Stl => "stl",
            Self::Gltf => "gltf",
            Self::Glb => "glb",
        }
    }

    /// The format a file name's extension names (any case), if any.
    pub fn from_file_name(file_name: &str) -> Option<Self> {
        let (_, extension) = file_name.rsplit_once('.')?;
        Self::ALL
            .into_iter()
            .find(|format| extension.eq_ignore_ascii_case(format.extension()))
    }

    /// The format the bytes themselves show, if they show one. The tests, in order:
    ///
    /// 1. GLB: the first four bytes are `glTF`.
    /// 2. PLY: the first line is `ply`.
    /// 3. Binary STL: the file has exactly 84 + 50·n bytes, n being the little-endian count
    ///    at bytes 80 to 83. This comes before the ASCII test because many binary STL files
    ///    start their free 80-byte header with `solid`, as ASCII STL files start.
    /// 4. ASCII STL: the first word is `solid` and the first KiB has no NUL byte.
    /// 5. glTF JSON: the first character (after white space) is `{`.
    /// 6. OBJ: the first statement within 64 KiB, past blank and `#` lines, is an OBJ keyword
    ///    (`v`, `f`, `o`, `g`, `mtllib`...), and that stretch has no NUL byte.
    pub fn from_content(bytes: &[u8]) -> Option<Self> {
        let text = trim_start(bytes);
        if bytes.starts_with(b"glTF") {
            Some(Self::Glb)
        } else if starts_with_line(bytes, b"ply") {
            Some(Self::Ply)
        } else if stl::is_binary(bytes) || stl::is_ascii(bytes) {
            Some(Self::Stl)
        } else if text.starts_with(b"{") {
            Some(Self::Gltf)
        } else if looks_like_obj(bytes) {
            Some(Self::Obj)
        } else {
            None
        }
    }
}

/// The format `load` reads a file as: the content's, or else the name's. The second value is
/// a warning when the two disagree.
pub(crate) fn detect(file_name: &str, bytes: &[u8]) -> Option<(Format, Option<String>)> {
    let named = Format::from_file_name(file_name);
    match (Format::from_content(bytes), named) {
        (Some(content), Some(named)) if content != named => Some((
            content,
            Some(format!(
                "{file_name} is named .{} but holds {}; read as {}",
                named.extension(),
                content.label(),
                content.label()
            )),
        )),
        (Some(format), _) | (None, Some(format)) => Some((format, None)),
        (None, None) => None,
    }
}

/// The bytes after leading ASCII white space and a UTF-8 byte-order mark.
pub(crate) fn trim_start(bytes: &[u8]) -> &[u8] {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    &bytes[start..]
}

/// Whether the first line of `bytes` is `word` (ended by `\n` or `\r\n`, trailing blanks
/// allowed).
pub(crate) fn starts_with_line(bytes: &[u8], word: &[u8]) -> bool {
    let Some(rest) = bytes.strip_prefix(word) else {
        return false;
    };
    let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
    rest.len() > end
        && rest[..end]
            .iter()
            .all(|&b| b == b' ' || b == b'\t' || b == b'\r')
}

/// How far into a file the OBJ test looks for its first statement.
const OBJ_SNIFF_BYTES: usize = 64 * 1024;

/// Whether the first statement of the file (past blank and `#` comment lines, within its
/// first 64 KiB) is an OBJ keyword, and that stretch is text.
fn looks_like_obj(bytes: &[u8]) -> bool {
    const KEYWORDS: [&[u8]; 12] = [
        b"v", b"vt", b"vn", b"vp", b"f", b"l", b"p", b"o", b"g", b"s", b"mtllib", b"usemtl",
    ];
    let head = &bytes[..bytes.len().min(OBJ_SNIFF_BYTES)];
    if head.contains(&0) {
        return false;
    }
    head.split(|&b| b == b'\n')
        .map(trim_start)
        .find(|line| !line.is_empty() && !line.starts_with(b"#"))
        .and_then(|line| line.split(u8::is_ascii_whitespace).next())
        .is_some_and(|keyword| KEYWORDS.contains(&keyword))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_in_any_case() {
        assert_eq!(Format::from_file_name("a.OBJ"), Some(Format::Obj));
        assert_eq!(
            Format::from_file_name("dir.v2/bunny.Ply"),
            Some(Format::Ply)
        );
        assert_eq!(Format::from_file_name("scene.glb"), Some(Format::Glb));
        assert_eq!(Format::from_file_name("stl"), None);
        assert_eq!(Format::from_file_name("mesh.obj.zip"), None);
    }

    #[test]
    fn first_lines() {
        assert!(starts_with_line(b"ply\nformat", b"ply"));
        assert!(starts_with_line(b"ply \r\n", b"ply"));
        assert!(!starts_with_line(b"plywood\n", b"ply"));
        assert!(!starts_with_line(b"ply", b"ply"));
    }

    #[test]
    fn obj_by_its_first_statement() {
        assert!(looks_like_obj(b"# made by hand\n\nv 0 0 0\n"));
        assert!(looks_like_obj(b"mtllib a.mtl\r\no cube\n"));
        assert!(!looks_like_obj(b"# only a comment\n"));
        assert!(!looks_like_obj(b"hello world\n"));
        assert!(!looks_like_obj(b"v 0 0 0\0"));
    }
}
