//! The element types `ply-rs-bw` fills: a vertex keeps `x`, `y`, `z` (of any numeric type), a
//! face keeps its corner list (`vertex_indices`, or `vertex_index` as some writers name it),
//! and every other element (edges, materials, colours...) is read through and dropped.

use ply_rs_bw::ply::{PropertyAccess, PropertyAccessResult};

/// The names a face's corner list goes by.
pub(super) const CORNER_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// A vertex: its position, as read (widened to `f64`, so no type loses digits before the
/// check for finite `f32` values).
#[derive(Default)]
pub(super) struct Vertex {
    pub xyz: [f64; 3],
}

impl Vertex {
    fn set(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.xyz[axis] = value;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Self::default()
    }
    fn set_char(&mut self, name: &str, value: i8) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_uchar(&mut self, name: &str, value: u8) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_short(&mut self, name: &str, value: i16) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_ushort(&mut self, name: &str, value: u16) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_int(&mut self, name: &str, value: i32) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_uint(&mut self, name: &str, value: u32) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.set(name, value.into())
    }
    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.set(name, value)
    }
}

/// A face: its corners as written (signed, so that a negative index can be reported).
#[derive(Default)]
pub(super) struct Face {
    pub corners: Vec<i64>,
}

impl Face {
    fn set<T: Into<i64>>(&mut self, name: &str, list: Vec<T>) -> PropertyAccessResult {
        if CORNER_LISTS.contains(&name) {
            self.corners = list.into_iter().map(Into::into).collect();
            PropertyAccessResult::Set
        } else {
            PropertyAccessResult::Ignored
        }
    }
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Self::default()
    }
    fn set_list_char(&mut self, name: &str, list: Vec<i8>) -> PropertyAccessResult {
        self.set(name, list)
    }
    fn set_list_uchar(&mut self, name: &str, list: Vec<u8>) -> PropertyAccessResult {
        self.set(name, list)
    }
    fn set_list_short(&mut self, name: &str, list: Vec<i16>) -> PropertyAccessResult {
        self.set(name, list)
    }
    fn set_list_ushort(&mut self, name: &str, list: Vec<u16>) -> PropertyAccessResult {
        self.set(name, list)
    }
    fn set_list_int(&mut self, name: &str, list: Vec<i32>) -> PropertyAccessResult {
        self.set(name, list)
    }
    fn set_list_uint(&mut self, name: &str, list: Vec<u32>) -> PropertyAccessResult {
        self.set(name, list)
    }
}

/// Any other element: read, so that the next one starts in the right place, and dropped.
pub(super) struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Self
    }
}
