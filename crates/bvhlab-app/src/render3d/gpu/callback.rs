//! The 3D view inside egui: a paint callback that renders the frame offscreen in `prepare`
//! (on egui's command encoder, before egui's own pass) and copies the image into egui's pass
//! in `paint`.
//!
//! The pipelines live in egui's callback resources ([`install`] puts them there once, knowing
//! egui's target); each view, named by an `egui::Id`, keeps its own [`Renderer3d`] there, so
//! two views side by side keep two meshes and two images. A view not painted for a while
//! gives its GPU memory back.

use std::collections::HashMap;

use eframe::egui_wgpu::{self, CallbackResources, CallbackTrait, ScreenDescriptor};
use eframe::wgpu;

use super::blit::{BlitBinding, BlitPipeline, BlitUniform, EguiTarget};
use super::frame::Frame3d;
use super::renderer::{Renderer3d, preferred_samples};

/// Frames a view may go unpainted before its renderer (and its GPU copy of the mesh) is
/// dropped: long enough to survive a tab switch's flicker, short enough not to hoard memory.
const KEEP_UNPAINTED_FRAMES: u64 = 300;

/// One view's renderer and its blit binding.
struct ViewSlot {
    renderer: Renderer3d,
    blit: BlitBinding,
    last_frame: u64,
    /// The mesh revision whose error was last logged (each failure is logged once).
    logged_revision: Option<u64>,
}

/// Everything the callbacks share, stored in egui's callback resources.
struct View3dResources {
    blit: BlitPipeline,
    /// Samples per pixel of every view's offscreen image.
    samples: u32,
    views: HashMap<egui::Id, ViewSlot>,
}

/// Makes the 3D view's pipelines for egui's target and stores them in egui's renderer. Call
/// once, with eframe's render state (`CreationContext::wgpu_render_state` or
/// `eframe::Frame::wgpu_render_state()`) and the target that matches the options eframe was
/// started with; calling again replaces everything (dropping every view's GPU data). The 3D
/// images are multisampled as [`preferred_samples`] says for the render state's adapter.
pub fn install(render_state: &egui_wgpu::RenderState, target: EguiTarget) {
    let samples = preferred_samples(&render_state.adapter);
    install_in(
        &mut render_state.renderer.write(),
        &render_state.device,
        target,
        samples,
    );
}

/// As [`install`], into an egui renderer made by hand (headless tests, custom set-ups), with
/// `samples` samples per pixel for the 3D images.
pub fn install_in(
    renderer: &mut egui_wgpu::Renderer,
    device: &wgpu::Device,
    target: EguiTarget,
    samples: u32,
) {
    renderer.callback_resources.insert(View3dResources {
        blit: BlitPipeline::new(device, target),
        samples,
        views: HashMap::new(),
    });
}

/// Whether [`install`] has been called for this render state.
pub fn is_installed(render_state: &egui_wgpu::RenderState) -> bool {
    render_state
        .renderer
        .read()
        .callback_resources
        .contains::<View3dResources>()
}

/// Paints `frame` into `rect` of `ui` as the 3D view named `id` (one id per view on screen).
/// Nothing is drawn until [`install`] was called.
pub fn paint_3d(ui: &egui::Ui, rect: egui::Rect, id: egui::Id, frame: Frame3d) {
    let callback = View3dCallback {
        id,
        rect,
        frame_nr: ui.ctx().cumulative_frame_nr(),
        frame,
    };
    ui.painter()
        .add(egui_wgpu::Callback::new_paint_callback(rect, callback));
}

/// The paint callback of one 3D view for one frame (see the module comment).
pub struct View3dCallback {
    /// Which view this is (its renderer is kept under this id).
    pub id: egui::Id,
    /// The view's rectangle in points (the callback's rectangle).
    pub rect: egui::Rect,
    /// egui's frame number, to let go of views no longer painted.
    pub frame_nr: u64,
    /// What to draw.
    pub frame: Frame3d,
}

/// The view's whole rectangle in physical pixels, rounded as egui rounds the viewport but not
/// clamped to the screen: `(left, top, width, height)`.
fn full_pixel_rect(rect: egui::Rect, pixels_per_point: f32) -> (i32, i32, u32, u32) {
    let round = |v: f32| (v * pixels_per_point).round() as i32;
    let (left, top) = (round(rect.min.x), round(rect.min.y));
    let (right, bottom) = (round(rect.max.x), round(rect.max.y));
    let width = (right - left).max(1) as u32;
    let height = (bottom - top).max(1) as u32;
    (left, top, width, height)
}

/// The part of the full rectangle egui's (screen-clamped) viewport shows.
fn shown_part(
    rect: egui::Rect,
    pixels_per_point: f32,
    screen_size_px: [u32; 2],
) -> (BlitUniform, [u32; 2]) {
    let (left, top, width, height) = full_pixel_rect(rect, pixels_per_point);
    let viewport =
        egui::epaint::ViewportInPixels::from_points(&rect, pixels_per_point, screen_size_px);
    let (w, h) = (width as f32, height as f32);
    let uniform = BlitUniform {
        uv_min: [
            (viewport.left_px - left) as f32 / w,
            (viewport.top_px - top) as f32 / h,
        ],
        uv_max: [
            (viewport.left_px + viewport.width_px - left) as f32 / w,
            (viewport.top_px + viewport.height_px - top) as f32 / h,
        ],
    };
    (uniform, [width, height])
}

impl CallbackTrait for View3dCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        screen: &ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(resources) = resources.get_mut::<View3dResources>() else {
            log::error!("3D view painted before view3d::gpu::install: nothing drawn");
            return Vec::new();
        };
        resources.views.retain(|id, slot| {
            *id == self.id || self.frame_nr.saturating_sub(slot.last_frame) <= KEEP_UNPAINTED_FRAMES
        });
        let slot = resources.views.entry(self.id).or_insert_with(|| ViewSlot {
            renderer: Renderer3d::with_samples(device, resources.samples),
            blit: BlitBinding::new(device),
            last_frame: self.frame_nr,
            logged_revision: None,
        });
        slot.last_frame = self.frame_nr;
        let (shown, size) = shown_part(self.rect, screen.pixels_per_point, screen.size_in_pixels);
        if let Err(error) = slot
            .renderer
            .render(device, queue, encoder, size, &self.frame)
        {
            let revision = self.frame.mesh.as_ref().map(|m| m.revision);
            if slot.logged_revision != revision {
                log::error!("3D view: {error}");
                slot.logged_revision = revision;
            }
        }
        if let (Some(image), Some(size)) = (slot.renderer.color_view(), slot.renderer.size()) {
            slot.blit
                .update(device, queue, &resources.blit, image, size, shown);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        resources: &CallbackResources,
    ) {
        if let Some(resources) = resources.get::<View3dResources>()
            && let Some(slot) = resources.views.get(&self.id)
        {
            slot.blit.draw(render_pass, &resources.blit);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_inside_the_screen_shows_its_whole_image() {
        let rect = egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(100.5, 50.0));
        let (shown, size) = shown_part(rect, 2.0, [1000, 1000]);
        assert_eq!(size, [201, 100]);
        assert_eq!(shown.uv_min, [0.0, 0.0]);
        assert_eq!(shown.uv_max, [1.0, 1.0]);
    }

    #[test]
    fn a_view_past_the_screen_edge_shows_the_part_on_screen() {
        // 100 px wide, its left 25 px off screen and its bottom 40 of 80 px below it.
        let rect = egui::Rect::from_min_size(egui::pos2(-25.0, 60.0), egui::vec2(100.0, 80.0));
        let (shown, size) = shown_part(rect, 1.0, [300, 100]);
        assert_eq!(size, [100, 80]);
        assert_eq!(shown.uv_min, [0.25, 0.0]);
        assert_eq!(shown.uv_max, [1.0, 0.5]);
    }
}
