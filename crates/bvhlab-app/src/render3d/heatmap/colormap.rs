//! The heat map's colour scale: counts to colours, identical on the CPU and in the shader, and
//! the legend that shows it.
//!
//! The ramp is ten control points sampled from viridis (van der Walt and Smith's default
//! colour map for matplotlib 2.0, 2015; the samples are those of R's `viridisLite::viridis(10)`):
//! it rises steadily in lightness from dark purple to yellow, so a larger count always looks
//! brighter, reads in grey scale and avoids red-green confusion. Between control points it
//! is interpolated linearly in integer arithmetic only, so that [`colour`] here and `ramp`
//! in the compute shader (generated from the same table by [`ramp_wgsl`]) give the same bytes.

use super::Metric;

/// The control points, evenly spaced from count 0 (first) to the scale's top (last), sRGB.
pub const RAMP: [[u8; 3]; 10] = [
    [0x44, 0x01, 0x54],
    [0x48, 0x28, 0x78],
    [0x3e, 0x4a, 0x89],
    [0x31, 0x68, 0x8e],
    [0x26, 0x82, 0x8e],
    [0x1f, 0x9e, 0x89],
    [0x35, 0xb7, 0x79],
    [0x6d, 0xcd, 0x59],
    [0xb4, 0xde, 0x2c],
    [0xfd, 0xe7, 0x25],
];

/// Steps between two control points.
const STEPS: u32 = 256;

/// The largest scale top the integer formula takes (`count × 2304` must fit a `u32`); a
/// larger top is clamped to it. No ray visits a million nodes in any tree the lab builds.
pub const MAX_SCALE_TOP: u32 = 1_000_000;

/// The colour of `count` on a scale from 0 to `top` (counts above `top` get the top colour;
/// with `top = 0` everything gets the bottom colour).
pub fn colour(count: u32, top: u32) -> [u8; 3] {
    let top = top.min(MAX_SCALE_TOP);
    if top == 0 {
        return RAMP[0];
    }
    let segments = RAMP.len() as u32 - 1;
    let pos = count.min(top) * (segments * STEPS) / top;
    let seg = (pos / STEPS).min(segments - 1);
    let f = pos - seg * STEPS;
    let (lo, hi) = (RAMP[seg as usize], RAMP[seg as usize + 1]);
    std::array::from_fn(|i| {
        ((u32::from(lo[i]) * (STEPS - f) + u32::from(hi[i]) * f + STEPS / 2) / STEPS) as u8
    })
}

/// The same function in WGSL (`fn ramp(count: u32, top: u32) -> vec3<u32>`), with [`RAMP`]
/// written in, for the colouring shader.
pub fn ramp_wgsl() -> String {
    let points: Vec<String> = RAMP
        .iter()
        .map(|[r, g, b]| format!("vec3<u32>({r}u, {g}u, {b}u)"))
        .collect();
    let segments = RAMP.len() - 1;
    format!(
        "fn ramp(count: u32, top_in: u32) -> vec3<u32> {{
    var points = array<vec3<u32>, {n}>({points});
    let top = min(top_in, {cap}u);
    if top == 0u {{
        return points[0];
    }}
    let pos = min(count, top) * {span}u / top;
    let seg = min(pos / {steps}u, {last}u);
    let f = pos - seg * {steps}u;
    return (points[seg] * ({steps}u - f) + points[seg + 1u] * f + {half}u) / {steps}u;
}}
",
        n = RAMP.len(),
        points = points.join(", "),
        cap = MAX_SCALE_TOP,
        span = segments as u32 * STEPS,
        steps = STEPS,
        last = segments - 1,
        half = STEPS / 2,
    )
}

/// Colours counts on a scale from 0 to `top`, or to the largest count when `top` is `None`.
pub fn colour_image(
    counts: &[u32],
    width: usize,
    height: usize,
    top: Option<u32>,
) -> egui::ColorImage {
    let top = top.unwrap_or_else(|| counts.iter().copied().max().unwrap_or(0));
    let pixels = counts
        .iter()
        .map(|&c| {
            let [r, g, b] = colour(c, top);
            egui::Color32::from_rgb(r, g, b)
        })
        .collect();
    egui::ColorImage::new([width, height], pixels)
}

/// The legend: the colour bar from 0 to `top`, numbered at both ends and in the middle, under
/// the metric's name.
pub fn legend(ui: &mut egui::Ui, top: u32, metric: Metric) {
    ui.label(metric.label());
    let width = ui.available_width().clamp(80.0, 240.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 14.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let stripes = 64;
    let mut mesh = egui::Mesh::default();
    for i in 0..stripes {
        let x0 = rect.left() + rect.width() * i as f32 / stripes as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / stripes as f32;
        let [r, g, b] = colour(i * 1000 / (stripes - 1), 1000);
        mesh.add_colored_rect(
            egui::Rect::from_x_y_ranges(x0..=x1, rect.y_range()),
            egui::Color32::from_rgb(r, g, b),
        );
    }
    painter.add(mesh);
    ui.horizontal(|ui| {
        let third = (width - 8.0) / 3.0;
        for (text, align) in [
            ("0".to_owned(), egui::Align::Min),
            ((top / 2).to_string(), egui::Align::Center),
            (top.to_string(), egui::Align::Max),
        ] {
            ui.allocate_ui_with_layout(
                egui::vec2(third, 14.0),
                egui::Layout::top_down(align),
                |ui| ui.small(text),
            );
        }
    });
}
