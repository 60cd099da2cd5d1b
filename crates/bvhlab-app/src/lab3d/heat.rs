//! The traversal-cost heat map in the 3D view: every pixel's camera ray asked of the
//! selected structure, coloured by the nodes (or triangle tests) it needed.
//!
//! Where the GPU runs compute shaders (WebGPU, Vulkan) and the structure is an AABB tree, the
//! map is traced by [`GpuHeatMap`]'s WGSL shader, which gives exactly the core's counts;
//! otherwise (WebGL2, the other structures, or when the student picks it) the CPU asks the
//! core ray by ray, a slice of rows per frame, and the image fills in as it goes.

use bvhlab::{QueryCost, Ray3, Triangle3};
use egui::{Color32, TextureHandle, TextureOptions};
use web_time::Instant;

use crate::model::build_job::Structure;
use crate::model::heat::{Device, Metric};
use crate::model::orbit_camera::OrbitCamera;
use crate::model::structures::{BuildSettings, Built};
use crate::render3d::heatmap::{CpuHeatMap, GpuHeatMap, gpu_heatmap_supported};
use crate::report::HeatReport;
use crate::ui_state::Cx;

/// Frames spent reading the GPU image's largest count back after a trace.
const SETTLE_FRAMES: u32 = 30;

/// Milliseconds of CPU tracing per frame.
const CPU_BUDGET_MS: f64 = 15.0;

/// What a map depends on: when any of it changes, the map is traced again.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    camera: OrbitCamera,
    size: [u32; 2],
    structure: (u64, BuildSettings),
    metric: Metric,
    gpu: bool,
}

/// The heat map's tracing and images (its settings are the lab's:
/// [`HeatSettings`](crate::model::heat::HeatSettings)).
#[derive(Default)]
pub struct HeatMap {
    key: Option<Key>,
    metric: Metric,
    cpu: Option<CpuHeatMap>,
    cpu_texture: Option<TextureHandle>,
    gpu: Option<GpuHeatMap>,
    /// The structure the GPU holds: (mesh revision, settings).
    gpu_tree: Option<(u64, BuildSettings)>,
    gpu_texture: Option<egui::TextureId>,
    gpu_error: Option<String>,
    /// The GPU image's largest count, once read back (for the legend and the report).
    gpu_max: Option<u32>,
    /// Frames left to read the largest count back after a trace.
    settle_frames: u32,
    /// Whether the image shown came from the GPU.
    shown_gpu: bool,
}

impl HeatMap {
    /// The map's report, when it is `on`.
    pub fn report(&self, on: bool) -> Option<HeatReport> {
        if !on {
            return None;
        }
        Some(if self.shown_gpu {
            HeatReport {
                device: "gpu".to_owned(),
                progress: if self.gpu_max.is_some() { 1.0 } else { 0.0 },
                max: self.gpu_max.unwrap_or(0),
            }
        } else {
            HeatReport {
                device: "cpu".to_owned(),
                progress: self.cpu.as_ref().map_or(0.0, CpuHeatMap::fraction),
                max: self.cpu.as_ref().map_or(0, CpuHeatMap::max_count),
            }
        })
    }

    /// Why the GPU could not trace the map, if it could not.
    pub fn gpu_error(&self) -> Option<&str> {
        self.gpu_error.as_deref()
    }

    /// Where the image shown came from and its largest count so far: `(true, max)` from the
    /// GPU (max once read back), `(false, max)` from the CPU, with its progress and size.
    pub fn shown(&self) -> Shown {
        if self.shown_gpu {
            Shown::Gpu(self.gpu_max)
        } else if let Some(cpu) = &self.cpu {
            Shown::Cpu {
                fraction: cpu.fraction(),
                size: [cpu.frame().width, cpu.frame().height],
                max: cpu.max_count(),
            }
        } else {
            Shown::Nothing
        }
    }

    /// What the pixels count.
    pub fn metric(&self) -> Metric {
        self.metric
    }
}

/// Where the image shown came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shown {
    /// No image yet.
    Nothing,
    /// The GPU's, with its largest count once read back.
    Gpu(Option<u32>),
    /// The CPU's, this far along, of this many pixels, with its largest count so far.
    Cpu {
        /// 0 to 1.
        fraction: f32,
        /// Width and height.
        size: [u32; 2],
        /// The largest count so far.
        max: u32,
    },
}

/// Traces (more of) the map for the view at `rect` and draws it over the view.
pub fn overlay(cx: &mut Cx<'_>, ui: &mut egui::Ui, rect: egui::Rect) {
    let lab = cx.lab.three();
    let settings = lab.heat;
    let camera = &lab.camera;
    let heat = &mut cx.ui.view3d.heat;
    heat.metric = settings.metric;
    if !settings.on {
        return;
    }
    let Some(built) = lab.half.lane.current(lab.revision()) else {
        return;
    };
    let size = [
        rect.width().round().max(1.0) as u32,
        rect.height().round().max(1.0) as u32,
    ];
    let gpu_ready = settings.device == Device::Auto
        && matches!(built.built, Built::AabbTree(_))
        && cx.ui.render_state.as_ref().is_some_and(|s| {
            gpu_heatmap_supported(&s.adapter.get_downlevel_capabilities(), &s.device.limits())
        });
    let key = Key {
        camera: *camera,
        size,
        structure: (built.revision, built.settings),
        metric: settings.metric,
        gpu: gpu_ready,
    };
    let fresh = heat.key != Some(key);
    heat.key = Some(key);
    let frame = camera.ray_frame(size[0], size[1]);
    if gpu_ready && let Some(state) = &cx.ui.render_state {
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
        heat.cpu = Some(CpuHeatMap::new(frame, settings.metric));
    }
    let Some(cpu) = &mut heat.cpu else { return };
    if !cpu.is_done() {
        let start = Instant::now();
        let structure = &built.built;
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
    heat: &mut HeatMap,
    built: &Structure<Triangle3>,
    state: &eframe::egui_wgpu::RenderState,
    frame: &crate::model::orbit_camera::RayFrame,
) {
    let Built::AabbTree(tree) = &built.built else {
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
