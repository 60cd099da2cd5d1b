//! Scene files: the full state as JSON a person can read and edit (a shape per line, each
//! point as `[x, y]`), and reading such a file (or a link's or the browser's JSON) back,
//! checked.

use std::io;

use serde::Deserialize;
use serde_json::ser::Formatter;

use crate::model::Lab;

use super::MAX_FILE_BYTES;
use super::names::shorten;
use super::state::{FORMAT_VERSION, SavedState};

/// The lab's full state (every shape written out) as a pretty JSON scene file. When the
/// pretty form would pass [`MAX_FILE_BYTES`] (a scene near the shape and point limits), the
/// compact form is written instead, so that every scene the lab holds can be read back.
pub fn to_file(lab: &Lab) -> Vec<u8> {
    let state = SavedState::capture_full(lab);
    let mut out = Vec::new();
    let mut serializer = serde_json::Serializer::with_formatter(&mut out, SceneFormatter::new());
    // Serializing this plain data into memory cannot fail (no maps with non-string keys,
    // no I/O errors); were it to, the compact form below is written instead.
    let pretty = serde::Serialize::serialize(&state, &mut serializer).is_ok();
    if !pretty || out.len() > MAX_FILE_BYTES {
        out = serde_json::to_vec(&state).unwrap_or_default();
    }
    out
}

/// Reads a scene file: at most [`MAX_FILE_BYTES`], UTF-8 JSON (a byte-order mark is
/// skipped), of [`FORMAT_VERSION`], within every limit [`SavedState`] lists.
///
/// # Errors
/// What is wrong with the file (its size, the JSON error with line and column, the version,
/// or the limit it breaks).
pub fn from_file(bytes: &[u8]) -> Result<SavedState, String> {
    from_json(bytes, "the scene file")
}

/// Reads the state's JSON from `what` (a file, a link, the browser's saved state), checked.
pub(super) fn from_json(bytes: &[u8], what: &str) -> Result<SavedState, String> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(format!(
            "{what} is {:.1} MiB; the lab reads at most {} MiB",
            bytes.len() as f64 / f64::from(1 << 20),
            MAX_FILE_BYTES >> 20
        ));
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(format!("{what} is empty"));
    }
    let invalid = |e: serde_json::Error| {
        format!(
            "{what} is not a bvh-lab scene: {}",
            shorten(&e.to_string(), 300)
        )
    };
    // The version first, so that a file of another version is told as such rather than by
    // the first field this version does not know.
    let probe: Probe = serde_json::from_slice(bytes).map_err(invalid)?;
    match probe.version {
        None => {
            return Err(format!(
                "{what} is not a bvh-lab scene (it has no \"version\")"
            ));
        }
        Some(v) if v != u64::from(FORMAT_VERSION) => {
            return Err(format!(
                "{what} is version {v} of the scene format; this lab reads version {FORMAT_VERSION}"
            ));
        }
        Some(_) => {}
    }
    let state: SavedState = serde_json::from_slice(bytes).map_err(invalid)?;
    state
        .check()
        .map_err(|e| format!("{what} is not usable: {e}"))?;
    Ok(state)
}

/// The one field read before the rest (serde skips the others without keeping them).
#[derive(Deserialize)]
struct Probe {
    version: Option<u64>,
}

/// How a container is laid out.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// Members on lines of their own, indented.
    Lines,
    /// On one line.
    Inline,
    /// A list whose first member has not come yet: on one line, unless that member is a
    /// list or an object, which then go on lines of their own.
    Open,
}

/// Pretty JSON with a shape per line: objects outside lists are indented a member per line,
/// a list of lists or objects has a member per line, and everything else (each shape,
/// each point, a list of numbers) is written on one line. So a file reads
/// `{"kind": "segment", "points": [[0.5, 0.5], [7.5, 4.0]]}` once per shape, as a person
/// would write it, and a 100,000-segment scene stays a few megabytes.
struct SceneFormatter {
    /// The open containers, innermost last: (layout, members so far, is a list).
    open: Vec<(Layout, usize, bool)>,
}

impl SceneFormatter {
    fn new() -> Self {
        Self { open: Vec::new() }
    }

    /// A new line at the current depth.
    fn newline<W: ?Sized + io::Write>(&self, w: &mut W) -> io::Result<()> {
        w.write_all(b"\n")?;
        for _ in 0..self.open.len() {
            w.write_all(b"  ")?;
        }
        Ok(())
    }

    /// Opens a list or object: on one line inside a list, on lines of its own elsewhere.
    fn open<W: ?Sized + io::Write>(&mut self, w: &mut W, list: bool) -> io::Result<()> {
        let layout = match self.open.last().copied() {
            // The first member of an open list is a container: the list goes on lines.
            Some((Layout::Open, 0, _)) => {
                if let Some(top) = self.open.last_mut() {
                    top.0 = Layout::Lines;
                }
                self.newline(w)?;
                Layout::Inline
            }
            Some((Layout::Lines, _, false)) | None => {
                if list {
                    Layout::Open
                } else {
                    Layout::Lines
                }
            }
            Some(_) => Layout::Inline,
        };
        self.open.push((layout, 0, list));
        w.write_all(if list { b"[" } else { b"{" })
    }

    /// Closes the innermost container.
    fn close<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        let Some((layout, members, list)) = self.open.pop() else {
            return Ok(());
        };
        if layout == Layout::Lines && members > 0 {
            self.newline(w)?;
        }
        w.write_all(if list { b"]" } else { b"}" })
    }

    /// Before a member: the separator, and a new line when the container is on lines.
    fn member<W: ?Sized + io::Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        let layout = self.open.last().map_or(Layout::Inline, |top| top.0);
        match (layout, first) {
            (Layout::Lines, true) => {
                // A list on lines writes its new line when its first member opens.
                if self.open.last().is_some_and(|top| !top.2) {
                    self.newline(w)?;
                }
                Ok(())
            }
            (Layout::Lines, false) => {
                w.write_all(b",")?;
                self.newline(w)
            }
            (_, true) => Ok(()),
            (_, false) => w.write_all(b", "),
        }
    }

    /// After a member.
    fn counted(&mut self) {
        if let Some(top) = self.open.last_mut() {
            top.1 += 1;
        }
    }
}

impl Formatter for SceneFormatter {
    fn begin_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open(w, true)
    }

    fn end_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w)
    }

    fn begin_array_value<W: ?Sized + io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.member(w, first)
    }

    fn end_array_value<W: ?Sized + io::Write>(&mut self, _w: &mut W) -> io::Result<()> {
        self.counted();
        Ok(())
    }

    fn begin_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open(w, false)
    }

    fn end_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w)
    }

    fn begin_object_key<W: ?Sized + io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.member(w, first)
    }

    fn begin_object_value<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn end_object_value<W: ?Sized + io::Write>(&mut self, _w: &mut W) -> io::Result<()> {
        self.counted();
        Ok(())
    }
}
