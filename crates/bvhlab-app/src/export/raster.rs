//! The canvas as pixels: a region cut out of egui's window screenshot, encoded as PNG, for
//! when a picture must look exactly as the lab drew it.

use egui::{Color32, ColorImage, Rect};

/// A PNG file of an egui image (e.g. a screenshot region).
///
/// egui's pixels hold premultiplied alpha and PNG's straight alpha, so each pixel is
/// unmultiplied (opaque pixels, all of a screenshot's, are unchanged).
///
/// # Errors
/// On an empty image, one whose pixel count does not match its size, or one too large for
/// PNG.
pub fn png_bytes(image: &ColorImage) -> Result<Vec<u8>, String> {
    let [width, height] = image.size;
    if width == 0 || height == 0 {
        return Err("the image is empty: nothing to save".to_owned());
    }
    if image.pixels.len() != width * height {
        return Err(format!(
            "the image has {} pixels, not {width} × {height}",
            image.pixels.len()
        ));
    }
    let too_large = |_| format!("{width} × {height} pixels is too large for a PNG");
    let (w, h) = (
        u32::try_from(width).map_err(too_large)?,
        u32::try_from(height).map_err(too_large)?,
    );
    let rgba: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(Color32::to_srgba_unmultiplied)
        .collect();
    let failed = |e: png::EncodingError| format!("PNG encoding failed: {e}");
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    // egui's colours are sRGB: say so, so that viewers do not guess.
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(failed)?;
    writer.write_image_data(&rgba).map_err(failed)?;
    writer.finish().map_err(failed)?;
    Ok(bytes)
}

/// Crops a full-window screenshot (`ViewportCommand::Screenshot` gives one, in physical
/// pixels) to a rect in points.
///
/// The rect's edges are scaled by `pixels_per_point` and rounded to the nearest pixel
/// boundary, then clamped to the image: a rect reaching past the window gives the part
/// inside it, one wholly outside (or not finite) an empty image.
pub fn crop(image: &ColorImage, rect: Rect, pixels_per_point: f32) -> ColorImage {
    let [width, height] = image.size;
    if image.pixels.len() != width * height {
        return ColorImage::new([0, 0], Vec::new());
    }
    // A NaN edge counts as 0 and infinite ones clamp to the image's edges.
    let to_pixel = |points: f32, limit: usize| -> usize {
        let pixels = (points * pixels_per_point).round();
        if pixels.is_nan() {
            0
        } else {
            pixels.clamp(0.0, limit as f32) as usize
        }
    };
    let (x0, y0) = (to_pixel(rect.min.x, width), to_pixel(rect.min.y, height));
    let x1 = to_pixel(rect.max.x, width).max(x0);
    let y1 = to_pixel(rect.max.y, height).max(y0);
    if x0 == x1 || y0 == y1 {
        return ColorImage::new([0, 0], Vec::new());
    }
    let pixels = image
        .pixels
        .chunks_exact(width)
        .take(y1)
        .skip(y0)
        .flat_map(|row| &row[x0..x1])
        .copied()
        .collect();
    ColorImage::new([x1 - x0, y1 - y0], pixels)
}
