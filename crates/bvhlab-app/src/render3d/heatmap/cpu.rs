//! The heat map on the CPU, for every structure and wherever compute shaders are missing
//! (WebGL2): each pixel's count is the core's own [`QueryCost`] of the pixel's first-hit
//! query, computed a budget of rays at a time so that the UI stays responsive while the
//! image fills in row by row.

use bvhlab::Ray3;
use bvhlab::structure::QueryCost;

use super::Metric;
use super::colormap;
use crate::model::orbit_camera::RayFrame;

/// A heat map being computed: the frame's pixels in row-major order, top row first.
#[derive(Clone, Debug)]
pub struct CpuHeatMap {
    frame: RayFrame,
    metric: Metric,
    counts: Vec<u32>,
    /// Pixels done (they are done in order).
    done: usize,
}

impl CpuHeatMap {
    /// A heat map of `frame`'s pixels, nothing computed yet.
    pub fn new(frame: RayFrame, metric: Metric) -> Self {
        let len = frame.width as usize * frame.height as usize;
        Self {
            frame,
            metric,
            counts: vec![0; len],
            done: 0,
        }
    }

    /// Computes the next `budget_rays` pixels (at least one while any are left). `cost_of`
    /// answers one ray: for a structure `s`, `|r| s.ray_first_hit_observed(r, f32::INFINITY,
    /// &mut ()).cost`. A pixel whose ray cannot be made (a degenerate frame) counts 0.
    pub fn step(&mut self, cost_of: &mut dyn FnMut(&Ray3) -> QueryCost, budget_rays: usize) {
        let end = (self.done + budget_rays.max(1)).min(self.counts.len());
        let width = self.frame.width as usize;
        for i in self.done..end {
            let (x, y) = ((i % width) as u32, (i / width) as u32);
            self.counts[i] = self
                .frame
                .ray(x, y)
                .map_or(0, |ray| self.metric.count(&cost_of(&ray)));
        }
        self.done = end;
    }

    /// The share of pixels done, from 0 to 1.
    pub fn fraction(&self) -> f32 {
        if self.counts.is_empty() {
            1.0
        } else {
            self.done as f32 / self.counts.len() as f32
        }
    }

    /// Whether every pixel is done.
    pub fn is_done(&self) -> bool {
        self.done == self.counts.len()
    }

    /// The counts, row-major from the top-left pixel (0 for pixels not done yet).
    pub fn counts(&self) -> &[u32] {
        &self.counts
    }

    /// The frame the map is of.
    pub fn frame(&self) -> &RayFrame {
        &self.frame
    }

    /// What is counted.
    pub fn metric(&self) -> Metric {
        self.metric
    }

    /// The largest count so far.
    pub fn max_count(&self) -> u32 {
        self.counts[..self.done].iter().copied().max().unwrap_or(0)
    }

    /// The map coloured on a scale from 0 to `top` (the largest count so far when `None`),
    /// the pixels not done yet transparent: the image for an egui texture.
    pub fn image(&self, top: Option<u32>) -> egui::ColorImage {
        let (w, h) = (self.frame.width as usize, self.frame.height as usize);
        let mut image =
            colormap::colour_image(&self.counts, w, h, Some(top.unwrap_or(self.max_count())));
        for pixel in &mut image.pixels[self.done..] {
            *pixel = egui::Color32::TRANSPARENT;
        }
        image
    }
}
