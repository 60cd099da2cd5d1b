//! Exporting the canvas for slides: as SVG, drawn again from the egui shapes the canvas is
//! painted with (sharp at any size, text kept as text), or as PNG, cut from a window
//! screenshot (exactly what the lab showed); then handed to the user as a file.
//!
//! - [`svg_document`]: shapes → SVG text.
//! - [`crop`] and [`png_bytes`]: a screenshot → the canvas's pixels → a PNG file.
//! - [`save_file`]: a browser download on the web, a file in the current directory natively.
//!
//! The lab's wiring collects the shapes of a frame and calls these; nothing here knows the
//! lab's state. Shapes export best before tessellation: a tessellated layer (the canvas's
//! cached static mesh) comes out as many small triangles, anti-aliasing fringes included,
//! where the shapes it was made from come out as one line or polygon each.

mod download;
mod raster;
mod svg;
mod svg_mesh;
mod svg_syntax;
mod svg_text;

pub use download::save_file;
#[cfg(not(target_arch = "wasm32"))]
pub use download::save_file_in;
pub use raster::{crop, png_bytes};
pub use svg::svg_document;
