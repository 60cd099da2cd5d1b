//! Text shapes as SVG `<text>`: one element per laid-out row, at the row's baseline, so that
//! the words stay text (editable and searchable in the slides) rather than egui's glyph
//! meshes. The viewer's font stands in for egui's, so widths differ a little.

use egui::Color32;
use egui::epaint::TextShape;
use egui::epaint::text::{ByteIndex, FontFamily, Galley, TextFormat};

use super::svg::{Skip, finite};
use super::svg_syntax::{Element, Num};

/// Writes each non-blank row of `shape`'s galley as a `<text>` element.
pub(super) fn text(out: &mut String, shape: &TextShape) -> Result<(), Skip> {
    finite(&[shape.pos], &[shape.angle, shape.opacity_factor])?;
    let galley = &shape.galley;
    for (row, format) in galley.rows.iter().zip(row_formats(galley)) {
        let Some(first) = row.glyphs.first() else {
            continue;
        };
        let line = row.text();
        if line.trim().is_empty() {
            continue;
        }
        // Glyph positions are relative to the row, whose position is relative to the galley;
        // a glyph's y is its baseline, which is where SVG puts text.
        let at = shape.pos + row.pos.to_vec2() + first.pos.to_vec2();
        finite(&[at], &[])?;
        let color = text_color(shape, format.map_or(Color32::PLACEHOLDER, |f| f.color));
        let size = format.map_or(galley.rect.height(), |f| f.font_id.size);
        let family = format.map_or(&FontFamily::Proportional, |f| &f.font_id.family);
        let element = Element::open(out, "text")
            .pos("x", "y", at)
            .attr("font-size", Num(size))
            .attr_text("font-family", &css_family(family))
            .fill(color)
            .rotate(shape.angle, shape.pos)
            .attr("xml:space", "preserve");
        let element = if format.is_some_and(|f| f.italics) {
            element.attr("font-style", "italic")
        } else {
            element
        };
        element.close_with_text(&line);
    }
    Ok(())
}

/// The colour a row is painted in: the shape's override, else the format's colour, with
/// egui's placeholder meaning the shape's fallback colour; then faded by the shape's opacity.
fn text_color(shape: &TextShape, format_color: Color32) -> Color32 {
    let color = match shape.override_text_color {
        Some(color) => color,
        None if format_color == Color32::PLACEHOLDER => shape.fallback_color,
        None => format_color,
    };
    if shape.opacity_factor < 1.0 {
        color.gamma_multiply(shape.opacity_factor.max(0.0))
    } else {
        color
    }
}

/// The format of each row: the layout section its first character comes from (a row with
/// several sections takes the first one's font and colour). Rows hold one glyph per
/// character, and a row ending in a newline is followed by that newline's character, so
/// counting characters row by row finds where each row starts in the job's text.
fn row_formats(galley: &Galley) -> Vec<Option<&TextFormat>> {
    let job = &galley.job;
    let starts: Vec<usize> = job.text.char_indices().map(|(i, _)| i).collect();
    let mut chars = 0;
    galley
        .rows
        .iter()
        .map(|row| {
            let byte = starts.get(chars).copied().unwrap_or(job.text.len());
            chars += row.glyphs.len() + usize::from(row.ends_with_newline);
            job.sections
                .iter()
                .find(|s| s.byte_range.contains(&ByteIndex(byte)))
                .or(job.sections.last())
                .map(|s| &s.format)
        })
        .collect()
}

/// A CSS font family for egui's: its built-in families map to the generic ones, a named
/// family keeps its name with a generic fallback.
fn css_family(family: &FontFamily) -> String {
    match family {
        FontFamily::Proportional => "sans-serif".to_owned(),
        FontFamily::Monospace => "monospace".to_owned(),
        FontFamily::Name(name) => format!("{name}, sans-serif"),
    }
}
