//! Exporting the canvas for slides: as SVG, drawn again from the egui shapes the canvas is
//! painted with (sharp at any size, text kept as text).
//!
//! - [`svg_document`]: shapes → SVG text.
//!
//! The lab's wiring collects the shapes of a frame and calls these; nothing here knows the
//! lab's state. Shapes export best before tessellation: a tessellated layer (the canvas's
//! cached static mesh) comes out as many small triangles, anti-aliasing fringes included,
//! where the shapes it was made from come out as one line or polygon each.

mod svg;
mod svg_mesh;
mod svg_syntax;
mod svg_text;

pub use svg::svg_document;
