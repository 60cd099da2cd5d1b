//! The traversal-cost heat map in the 3D view: every pixel's camera ray asked of the
//! selected structure, coloured by the nodes (or triangle tests) it needed.
//!
//! Where the GPU runs compute shaders (WebGPU, Vulkan) and the structure is an AABB tree, the
//! map is traced by [`GpuHeatMap`]'s WGSL shader, which gives exactly the core's counts;
//! otherwise (WebGL2, the other structures, or when the student picks it) the CPU asks the
//! core ray by ray, a slice of rows per frame, and the image fills in as it goes.

use bvhlab::{QueryCost, Ray3};
use egui::{Color32, TextureHandle, TextureOptions};
use web_time::Instant;

use super::Lab3d;
use super::report::HeatReport;
use crate::app::LabApp;
use crate::structures::Built;
use crate::view3d::camera::OrbitCamera;
use crate::view3d::heatmap::{CpuHeatMap, GpuHeatMap, Metric, gpu_heatmap_supported, legend};

/// Frames spent reading the GPU image's largest count back after a trace.
const SETTLE_FRAMES: u32 = 30;

/// Milliseconds of CPU tracing per frame.
const CPU_BUDGET_MS: f64 = 15.0;

/// Where the map is computed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Device {
    /// The GPU when it can, else the CPU.
    #[default]
    Auto,
    /// Always the CPU.
    Cpu,
}

/// What a map depends on: when any of it changes, the map is traced again.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    camera: OrbitCamera,
    size: [u32; 2],
    structure: (u64, crate::structures::BuildSettings),
    metric: Metric,
    gpu: bool,
}

/// The heat map's state.
#[derive(Default)]
pub struct Heat {
    /// Whether it is shown.
    pub on: bool,
    /// What a pixel counts.
    pub metric: Metric,
    /// Where it is computed.
    pub device: Device,
    key: Option<Key>,
    cpu: Option<CpuHeatMap>,
    cpu_texture: Option<TextureHandle>,
    gpu: Option<GpuHeatMap>,
    /// The structure the GPU holds: (mesh revision, settings).
    gpu_tree: Option<(u64, crate::structures::BuildSettings)>,
    gpu_texture: Option<egui::TextureId>,
    gpu_error: Option<String>,
    /// The GPU image's largest count, once read back (for the legend and the report).
    gpu_max: Option<u32>,
    /// Frames left to read the largest count back after a trace.
    settle_frames: u32,
    /// Whether the image shown came from the GPU.
    shown_gpu: bool,
}

impl Lab3d {
    /// The heat map's report, when it is on.
    pub fn heat_report(&self) -> Option<HeatReport> {
        let heat = &self.heat;
        if !heat.on {
            return None;
        }
        Some(if heat.shown_gpu {
            HeatReport {
                device: "gpu".to_owned(),
                progress: if heat.gpu_max.is_some() { 1.0 } else { 0.0 },
                max: heat.gpu_max.unwrap_or(0),
            }
        } else {
            HeatReport {
                device: "cpu".to_owned(),
                progress: heat.cpu.as_ref().map_or(0.0, CpuHeatMap::fraction),
                max: heat.cpu.as_ref().map_or(0, CpuHeatMap::max_count),
            }
        })
    }
}

/// The heat map's controls and legend.
pub fn section(app: &mut LabApp, ui: &mut egui::Ui) {
    let heat = &mut app.lab3d.heat;
    ui.checkbox(&mut heat.on, "show the heat map")
        .on_hover_text("each pixel: how much work its camera ray needed for the first hit");
    if !heat.on {
        return;
    }
    ui.horizontal(|ui| {
        ui.radio_value(&mut heat.metric, Metric::Nodes, "nodes visited");
        ui.radio_value(&mut heat.metric, Metric::PrimitiveTests, "triangle tests");
    });
    ui.horizontal(|ui| {
        ui.label("computed on:");
        ui.radio_value(&mut heat.device, Device::Auto, "GPU where it can");
        ui.radio_value(&mut heat.device, Device::Cpu, "CPU");
    });
    if let Some(e) = &heat.gpu_error {
        ui.colored_label(crate::paint::colors::PRUNED, e);
    }
    if heat.shown_gpu {
        ui.label("traced on the GPU (WGSL compute shader)");
        if let Some(top) = heat.gpu_max {
            legend(ui, top.max(1), heat.metric);
        }
    } else if let Some(cpu) = &heat.cpu {
        ui.label(format!(
            "traced on the CPU: {:.0}% of {}×{} rays",
            cpu.fraction() * 100.0,
            cpu.frame().width,
            cpu.frame().height
        ));
        legend(ui, cpu.max_count().max(1), heat.metric);
    }
}

/// Traces (more of) the map for the view at `rect` and draws it over the view.
pub fn overlay(app: &mut LabApp, ui: &mut egui::Ui, rect: egui::Rect) {
    let Lab3d {
        heat,
        built,
        camera,
        ..
    } = &mut app.lab3d;
    if !heat.on {
        return;
    }
    let Some(built) = built.as_ref() else { return };
    let size = [
        rect.width().round().max(1.0) as u32,
        rect.height().round().max(1.0) as u32,
    ];
    let gpu_ready = heat.device == Device::Auto
        && matches!(built.structure, Built::AabbTree(_))
        && app.render_state.as_ref().is_some_and(|s| {
            gpu_heatmap_supported(&s.adapter.get_downlevel_capabilities(), &s.device.limits())
        });
    let key = Key {
        camera: *camera,
        size,
        structure: (built.revision, built.settings),
        metric: heat.metric,
        gpu: gpu_ready,
    };
    let fresh = heat.key != Some(key);
    heat.key = Some(key);
    let frame = camera.ray_frame(size[0], size[1]);
    if gpu_ready && let Some(state) = &app.render_state {
        if fresh {
            trace_on_gpu(heat, built, state, &frame);
        }
        if let Some(id) = heat.gpu_texture
            && heat.gpu_error.is_none()
        {
            heat.shown_gpu = true;
            ui.painter().image(id, rect, full_uv(), Color32::WHITE);
            if let Some(gpu) = &mut heat.gpu {
                gpu.after_submit();
                if fresh {
                    heat.gpu_max = None;
                    heat.settle_frames = SETTLE_FRAMES;
                }
                // The largest count is read back a few frames after the image (the last
                // read-back may still be the previous image's): keep drawing a little while,
                // reading it, for the legend.
                if heat.settle_frames > 0 {
                    heat.settle_frames -= 1;
                    if !fresh {
                        heat.gpu_max = gpu.largest_count().or(heat.gpu_max);
                    }
                    ui.ctx().request_repaint();
                }
            }
            return;
        }
    }
    heat.shown_gpu = false;
    if fresh || heat.cpu.is_none() {
        heat.cpu = Some(CpuHeatMap::new(frame, heat.metric));
    }
    let Some(cpu) = &mut heat.cpu else { return };
    if !cpu.is_done() {
        let start = Instant::now();
        let structure = &built.structure;
        let mut cost_of = |ray: &Ray3| -> QueryCost { structure.ray_first_hit(ray, &mut ()).cost };
        while !cpu.is_done() && start.elapsed().as_secs_f64() * 1e3 < CPU_BUDGET_MS {
            cpu.step(&mut cost_of, 4_096);
        }
        ui.ctx().request_repaint();
        let image = cpu.image(None);
        match &mut heat.cpu_texture {
            Some(t) => t.set(image, TextureOptions::NEAREST),
            None => {
                heat.cpu_texture = Some(ui.ctx().load_texture(
                    "heat map",
                    image,
                    TextureOptions::NEAREST,
                ));
            }
        }
    }
    if let Some(t) = &heat.cpu_texture {
        ui.painter().image(t.id(), rect, full_uv(), Color32::WHITE);
    }
}

/// Uploads the tree when it changed, and traces the map on the GPU.
fn trace_on_gpu(
    heat: &mut Heat,
    built: &super::build::Built3d,
    state: &eframe::egui_wgpu::RenderState,
    frame: &crate::view3d::camera::RayFrame,
) {
    let Built::AabbTree(tree) = &built.structure else {
        return;
    };
    let device = &state.device;
    let gpu = heat.gpu.get_or_insert_with(|| GpuHeatMap::new(device));
    let identity = (built.revision, built.settings);
    if heat.gpu_tree != Some(identity) {
        if let Err(e) = gpu.upload(device, tree) {
            heat.gpu_error = Some(format!("{e}: traced on the CPU instead."));
            return;
        }
        heat.gpu_tree = Some(identity);
    }
    let mut encoder = device.create_command_encoder(&eframe::wgpu::CommandEncoderDescriptor {
        label: Some("heat map"),
    });
    match gpu.dispatch(device, &state.queue, &mut encoder, frame, heat.metric, None) {
        Ok(()) => {
            state.queue.submit([encoder.finish()]);
            heat.gpu_error = None;
            heat.gpu_texture = gpu.register(&mut state.renderer.write(), device, heat.gpu_texture);
        }
        Err(e) => heat.gpu_error = Some(format!("{e}: traced on the CPU instead.")),
    }
}

/// The whole texture.
fn full_uv() -> egui::Rect {
    egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0))
}
