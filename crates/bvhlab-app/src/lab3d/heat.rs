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
use crate::model::orbit_camera::{OrbitCamera, RayFrame};
use crate::model::structures::{BuildSettings, Built};
use crate::render3d::heatmap::{CpuHeatMap, GpuHeatMap, gpu_heatmap_supported};
use crate::report::HeatReport;
use crate::ui_state::Cx;

/// Frames spent reading the GPU image's largest count back after a trace.
const SETTLE_FRAMES: u32 = 30;

/// Milliseconds of CPU tracing per frame.
const CPU_BUDGET_MS: f64 = 15.0;

/// While the mesh moves, the CPU traces one ray per square of this many pixels a side, so that
/// a whole image of one moment takes a few frames instead of a hundred.
pub const MOVING_PIXEL: u32 = 4;

/// While the mesh moves, the GPU traces a new image every this many frames (each trace
/// uploads the refitted tree again).
pub const MOVING_GPU_EVERY: u32 = 2;

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
    /// The CPU image changed since it was last put in its texture.
    cpu_changed: bool,
    /// While the mesh moves: the tree the CPU image under way is traced on, a copy of the
    /// one of the frame it started in (with its revision).
    cpu_tree: Option<(u64, Built<Triangle3>)>,
    /// Whether the mesh moved in the last frame drawn.
    moving: bool,
    /// Frames since the last image while the mesh moves.
    moving_frames: u32,
    /// While the mesh moves: how many frames the last image took.
    moving_images: Option<u32>,
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
                metric: self.metric.label(),
            }
        } else {
            HeatReport {
                device: "cpu".to_owned(),
                progress: self.cpu.as_ref().map_or(0.0, CpuHeatMap::fraction),
                max: self.cpu.as_ref().map_or(0, CpuHeatMap::max_count),
                metric: self.metric.label(),
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

    /// While the mesh moves, the CPU's last finished image: the revision of the tree it was
    /// traced on, and its counts (row-major, one per [`MOVING_PIXEL`] square).
    pub fn moving_image(&self) -> Option<(u64, &[u32])> {
        let (revision, _) = self.cpu_tree.as_ref()?;
        let cpu = self.cpu.as_ref().filter(|c| c.is_done())?;
        Some((*revision, cpu.counts()))
    }

    /// While the mesh moves: every how many frames a new image of the moved mesh's tree is
    /// shown (`None` when it does not move, or before the first image).
    pub fn moving_every(&self) -> Option<u32> {
        self.moving_images.filter(|_| self.moving)
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
    let moving = lab.moving();
    let heat = &mut cx.ui.view3d.heat;
    heat.metric = settings.metric;
    heat.moving = moving;
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
    // The same view of another revision of the tree (the mesh moved) is not a new view.
    let fresh_view = heat.key.is_none_or(|k| {
        k != Key {
            structure: (k.structure.0, built.settings),
            ..key
        }
    });
    heat.key = Some(key);
    let frame = camera.ray_frame(size[0], size[1]);
    if gpu_ready
        && let Some(state) = &cx.ui.render_state
        && show_gpu(heat, built, state, &frame, (fresh, fresh_view), ui, rect)
    {
        return;
    }
    heat.shown_gpu = false;
    if moving {
        follow_on_cpu(heat, built, camera, size, settings.metric, fresh_view);
    } else {
        trace_on_cpu(heat, &built.built, frame, fresh);
    }
    if heat.cpu.as_ref().is_some_and(|c| !c.is_done()) {
        ui.ctx().request_repaint();
    }
    let image = heat.cpu.as_ref().filter(|c| !moving || c.is_done());
    if let Some(cpu) = image
        && heat.cpu_changed
    {
        heat.cpu_changed = false;
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

/// Traces the map on the GPU when it is `fresh` (for a mesh that moves: every
/// [`MOVING_GPU_EVERY`] frames, or at once for a `fresh_view`) and draws its image; whether
/// it did (else the CPU traces it).
fn show_gpu(
    heat: &mut HeatMap,
    built: &Structure<Triangle3>,
    state: &eframe::egui_wgpu::RenderState,
    frame: &RayFrame,
    (fresh, fresh_view): (bool, bool),
    ui: &egui::Ui,
    rect: egui::Rect,
) -> bool {
    heat.moving_frames = heat.moving_frames.saturating_add(1);
    let trace = if heat.moving {
        fresh_view || (fresh && heat.moving_frames >= MOVING_GPU_EVERY)
    } else {
        fresh
    };
    if trace {
        trace_on_gpu(heat, built, state, frame);
        if heat.moving {
            heat.moving_images = Some(heat.moving_frames);
            heat.moving_frames = 0;
        }
    }
    let Some(id) = heat.gpu_texture.filter(|_| heat.gpu_error.is_none()) else {
        return false;
    };
    heat.shown_gpu = true;
    ui.painter().image(id, rect, full_uv(), Color32::WHITE);
    if let Some(gpu) = &mut heat.gpu {
        gpu.after_submit();
        if trace {
            // A moving mesh keeps the last largest count for its legend until the next.
            if fresh_view || !heat.moving {
                heat.gpu_max = None;
            }
            heat.settle_frames = SETTLE_FRAMES;
        }
        // The largest count is read back a few frames after the image (the last read-back
        // may still be the previous image's): keep drawing a little while, reading it, for
        // the legend.
        if heat.settle_frames > 0 {
            heat.settle_frames -= 1;
            if !trace {
                heat.gpu_max = gpu.largest_count().or(heat.gpu_max);
            }
            ui.ctx().request_repaint();
        }
    }
    true
}

/// Traces more of the map of the structure shown (from the start when `fresh`).
fn trace_on_cpu(heat: &mut HeatMap, structure: &Built<Triangle3>, frame: RayFrame, fresh: bool) {
    // A coarse image of a mesh that has stopped moving is traced again in full.
    if fresh || heat.cpu.is_none() || heat.cpu_tree.is_some() {
        heat.cpu = Some(CpuHeatMap::new(frame, heat.metric));
        heat.cpu_tree = None;
    }
    if let Some(cpu) = &mut heat.cpu
        && !cpu.is_done()
    {
        trace_slice(cpu, structure);
        heat.cpu_changed = true;
    }
}

/// The map of a mesh that moves: each image is traced whole on a copy of the tree of one
/// frame, at a coarser resolution ([`MOVING_PIXEL`]), over as many frames as it takes; the
/// image shown is the last finished one, and the next starts on the tree of the frame it
/// starts in. A new view (camera, size, metric) starts one at once.
fn follow_on_cpu(
    heat: &mut HeatMap,
    built: &Structure<Triangle3>,
    camera: &OrbitCamera,
    size: [u32; 2],
    metric: Metric,
    fresh_view: bool,
) {
    let done = heat.cpu.as_ref().is_none_or(CpuHeatMap::is_done);
    let newer = heat
        .cpu_tree
        .as_ref()
        .is_none_or(|(revision, _)| *revision != built.revision);
    heat.moving_frames = heat.moving_frames.saturating_add(1);
    if fresh_view || heat.cpu_tree.is_none() || (done && newer) {
        let coarse = size.map(|s| s.div_ceil(MOVING_PIXEL).max(1));
        heat.cpu = Some(CpuHeatMap::new(
            camera.ray_frame(coarse[0], coarse[1]),
            metric,
        ));
        heat.cpu_tree = Some((built.revision, built.built.clone()));
    }
    if let (Some(cpu), Some((_, tree))) = (&mut heat.cpu, &heat.cpu_tree)
        && !cpu.is_done()
    {
        trace_slice(cpu, tree);
        if cpu.is_done() {
            heat.cpu_changed = true;
            heat.moving_images = Some(heat.moving_frames);
            heat.moving_frames = 0;
        }
    }
}

/// Traces rays of `cpu` on `structure` for [`CPU_BUDGET_MS`].
fn trace_slice(cpu: &mut CpuHeatMap, structure: &Built<Triangle3>) {
    let start = Instant::now();
    let mut cost_of = |ray: &Ray3| -> QueryCost { structure.ray_first_hit(ray, &mut ()).cost };
    while !cpu.is_done() && start.elapsed().as_secs_f64() * 1e3 < CPU_BUDGET_MS {
        cpu.step(&mut cost_of, 4_096);
    }
}

/// Uploads the tree when it changed, and traces the map on the GPU.
fn trace_on_gpu(
    heat: &mut HeatMap,
    built: &Structure<Triangle3>,
    state: &eframe::egui_wgpu::RenderState,
    frame: &RayFrame,
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
