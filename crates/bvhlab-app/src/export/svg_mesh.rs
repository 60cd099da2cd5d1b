//! Triangle meshes as SVG paths. SVG has no per-vertex colours, so each triangle takes the
//! average of its three; runs of triangles with the same colour share one `<path>`, which keeps
//! files small and avoids the hairline seams renderers draw between separately
//! anti-aliased neighbours.

use egui::epaint::{Mesh, Vertex, WHITE_UV};
use egui::{Color32, Rect, TextureId};

use super::svg::Skip;
use super::svg_syntax::{Element, PathData, comment};

/// Writes the solid-coloured triangles of `mesh` that reach into `crop` (a mesh is often a
/// whole layer, most of it off a cropped picture).
///
/// Only untextured triangles are exported: those whose vertices all sample egui's white
/// texel ([`WHITE_UV`] in the default texture), which is how egui paints flat colour. Image
/// meshes and text glyphs sample real texels that SVG cannot reach, and are left out.
pub(super) fn mesh(out: &mut String, mesh: &Mesh, crop: Rect) -> Result<(), Skip> {
    if mesh.texture_id != TextureId::default() {
        return Err(Skip::Unsupported("image meshes are not exported"));
    }
    if !mesh.is_valid() {
        return Err(Skip::Unsupported("an index is out of range"));
    }
    let mut run: Option<(Color32, PathData)> = None;
    let (mut textured, mut not_finite) = (0_usize, 0_usize);
    for triangle in mesh.triangles() {
        let Some(vertices) = triangle_vertices(mesh, triangle) else {
            continue;
        };
        if vertices.iter().any(|v| v.uv != WHITE_UV) {
            textured += 1;
            continue;
        }
        if vertices.iter().any(|v| !v.pos.is_finite()) {
            not_finite += 1;
            continue;
        }
        let [a, b, c] = vertices.map(|v| v.pos);
        if !Rect::from_points(&[a, b, c]).intersects(crop) {
            continue;
        }
        let color = average(vertices.map(|v| v.color));
        if color.a() == 0 {
            continue;
        }
        if run.as_ref().is_some_and(|(c, _)| *c != color) {
            flush(out, run.take());
        }
        let (_, d) = run.get_or_insert_with(|| (color, PathData::default()));
        d.move_to(a);
        d.line_to(b);
        d.line_to(c);
        d.close();
    }
    flush(out, run);
    if textured > 0 {
        comment(out, format_args!("{textured} textured triangles skipped"));
    }
    if not_finite > 0 {
        comment(
            out,
            format_args!("{not_finite} triangles skipped: not finite"),
        );
    }
    Ok(())
}

/// The three vertices of a triangle, if its indices are in range.
fn triangle_vertices(mesh: &Mesh, [a, b, c]: [u32; 3]) -> Option<[&Vertex; 3]> {
    let vertex = |i: u32| mesh.vertices.get(i as usize);
    Some([vertex(a)?, vertex(b)?, vertex(c)?])
}

/// The mean of three colours, channel by channel. Averaging premultiplied values is what
/// blending does, so a half-transparent corner weighs less than an opaque one.
fn average(colors: [Color32; 3]) -> Color32 {
    let channel = |i: usize| {
        let sum: u32 = colors.iter().map(|c| u32::from(c.to_array()[i])).sum();
        ((sum + 1) / 3) as u8
    };
    Color32::from_rgba_premultiplied(channel(0), channel(1), channel(2), channel(3))
}

/// Writes a run of same-coloured triangles as one `<path>`.
fn flush(out: &mut String, run: Option<(Color32, PathData)>) {
    if let Some((color, d)) = run
        && !d.is_empty()
    {
        Element::open(out, "path")
            .attr("d", d.as_str())
            .fill(color)
            .close();
    }
}
