//! The lab's state, what is derived from it (the built structure, the query outcomes), and
//! the top-level layout: controls on the left in the lecture's order, the canvas in the
//! middle, a status line at the bottom.

use bvhlab::glam::Vec2;
use bvhlab::{BruteForce, NodeOutline, Ray2, Segment2, SpatialIndex, Stats};
use web_time::Instant;

use crate::frame_clock::FrameClock;
use crate::presets::Preset;
use crate::query::{NodeMarks, PointOutcome, RayOutcome};
use crate::report::Report;
use crate::scene::{Primitives, Scene};
use crate::structures::{BuildSettings, Built};
use crate::tool::{Interaction, Tool};
use crate::view::View;
use crate::volumes::{ObbPair, VolumeToggles};

/// The structure built on the current scene, and everything read from it once.
pub struct Built2d {
    /// The settings it was built with.
    pub settings: BuildSettings,
    /// The scene revision it was built on.
    pub revision: u64,
    /// The primitives and their shapes.
    pub prims: Primitives,
    /// The structure.
    pub structure: Built,
    /// The baseline.
    pub brute: BruteForce<Segment2>,
    /// Its nodes, for drawing.
    pub outline: Vec<NodeOutline<Vec2>>,
    /// Its statistics.
    pub stats: Stats,
    /// How long the build took, in milliseconds.
    pub build_ms: f64,
    /// For leaf colouring: the first leaf listing each primitive.
    pub leaf_of: Vec<Option<u32>>,
}

impl Built2d {
    fn new(scene: &Scene, settings: BuildSettings) -> Self {
        let prims = scene.primitives();
        let start = Instant::now();
        let structure = Built::build(&prims.segments, &settings);
        let build_ms = start.elapsed().as_secs_f64() * 1e3;
        let outline = structure.outline();
        let mut leaf_of = vec![None; prims.segments.len()];
        for node in outline.iter().filter(|n| n.is_leaf()) {
            for &p in &node.primitives {
                let slot = &mut leaf_of[p as usize];
                if slot.is_none() {
                    *slot = Some(node.id.0);
                }
            }
        }
        Self {
            settings,
            revision: scene.revision(),
            stats: structure.stats(),
            brute: BruteForce::build(&prims.segments),
            prims,
            structure,
            outline,
            build_ms,
            leaf_of,
        }
    }
}

/// How the structure is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::struct_excessive_bools)] // independent switches, one per checkbox
pub struct Display {
    /// Draw the structure's nodes.
    pub structure: bool,
    /// Draw nodes down to this depth.
    pub max_depth: u32,
    /// Colour primitives by the leaf that holds them.
    pub leaf_colours: bool,
    /// Mark the nodes the query visited, culled and pruned.
    pub query_marks: bool,
    /// Show the selection's bounding volumes.
    pub volumes: bool,
    /// Show the slab test of the ray against the selection's AABB.
    pub slab_test: bool,
}

impl Default for Display {
    fn default() -> Self {
        Self {
            structure: true,
            max_depth: 64,
            leaf_colours: false,
            query_marks: true,
            volumes: false,
            slab_test: false,
        }
    }
}

/// The ray the student drags: from `origin` through `target`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHandles {
    /// Where the ray starts (e).
    pub origin: Vec2,
    /// A point it passes through (s), giving the direction s - e.
    pub target: Vec2,
}

impl RayHandles {
    /// The ray, or why there is none (the two points coincide).
    ///
    /// # Errors
    /// The core's message for a zero or non-finite direction.
    pub fn ray(&self) -> Result<Ray2, String> {
        Ray2::through(self.origin, self.target).map_err(|e| e.to_string())
    }
}

/// What the cached fits were computed for: the scene revision and the selection.
pub type FitsKey = (u64, Vec<usize>);

/// The whole lab.
pub struct LabApp {
    /// What the student drew.
    pub scene: Scene,
    /// The selected shapes (by index).
    pub selection: Vec<usize>,
    /// Pan and zoom.
    pub view: View,
    /// Whether the view still needs fitting to the scene (first frame, new preset).
    pub fit_pending: bool,
    /// The active tool.
    pub tool: Tool,
    /// A drag or drawing in progress.
    pub interaction: Interaction,
    /// The structure to build.
    pub settings: BuildSettings,
    /// The structure built on the scene.
    pub built: Option<Built2d>,
    /// The query ray.
    pub ray: Option<RayHandles>,
    /// The query point.
    pub point: Option<Vec2>,
    /// How many neighbours the point query finds.
    pub k: usize,
    /// The ray query's outcome.
    pub ray_outcome: Option<RayOutcome>,
    /// The point query's outcome.
    pub point_outcome: Option<PointOutcome>,
    /// The marks of the most recent query (what the canvas highlights).
    pub marks: Option<NodeMarks>,
    /// Which query the marks belong to: true for the ray.
    pub marks_from_ray: bool,
    /// Drawing switches.
    pub display: Display,
    /// Which bounding volumes are drawn.
    pub volume_toggles: VolumeToggles,
    /// The separating-axis demo, when on.
    pub obb_pair: Option<ObbPair>,
    /// The preset chosen in the menu.
    pub preset: Preset,
    /// A message for the status line (errors say what went wrong and what was kept).
    pub message: Option<String>,
    /// Frame timing.
    pub clock: FrameClock,
    /// The renderer's name ("WebGPU", "WebGL2", "Vulkan", ...), once known.
    pub renderer: Option<String>,
    /// What the lab last reported to the page.
    pub report: Report,
    /// The selection's bounding volumes, keyed by scene revision and selection.
    pub fits_cache: Option<(FitsKey, Option<crate::volumes::Fits>)>,
    /// The structure and scene, tessellated for the current view.
    pub static_layer: Option<crate::canvas::StaticLayer>,
}

impl Default for LabApp {
    fn default() -> Self {
        let preset = Preset::default();
        let (scene, settings) = preset.build();
        Self {
            scene,
            selection: Vec::new(),
            view: View::default(),
            fit_pending: true,
            tool: Tool::Ray,
            interaction: Interaction::None,
            settings,
            built: None,
            ray: None,
            point: None,
            k: 1,
            ray_outcome: None,
            point_outcome: None,
            marks: None,
            marks_from_ray: true,
            display: Display::default(),
            volume_toggles: VolumeToggles::default(),
            obb_pair: None,
            preset,
            message: None,
            clock: FrameClock::default(),
            renderer: None,
            report: Report::default(),
            fits_cache: None,
            static_layer: None,
        }
    }
}

impl LabApp {
    /// The lab opened on a preset scene.
    pub fn with_preset(preset: Preset) -> Self {
        let mut app = Self::default();
        app.load_preset(preset);
        app
    }

    /// Replaces the scene with a preset and frames it.
    pub fn load_preset(&mut self, preset: Preset) {
        let (scene, settings) = preset.build();
        self.preset = preset;
        self.scene = scene;
        self.settings = settings;
        self.selection.clear();
        self.interaction = Interaction::None;
        self.ray = None;
        self.point = None;
        self.fit_pending = true;
        if preset == Preset::BoundingVolumes {
            self.selection = vec![0];
            self.display.volumes = true;
        }
    }

    /// Rebuilds the structure when the scene or the settings changed, and reruns the
    /// queries when anything they depend on changed.
    pub fn refresh(&mut self) {
        let stale = self
            .built
            .as_ref()
            .is_none_or(|b| b.revision != self.scene.revision() || b.settings != self.settings);
        if stale {
            self.built = Some(Built2d::new(&self.scene, self.settings));
            self.ray_outcome = None;
            self.point_outcome = None;
        }
        let Some(built) = &self.built else { return };
        let mut changed = false;
        match self.ray.map(|r| r.ray()) {
            Some(Ok(ray)) => {
                if self.ray_outcome.as_ref().is_none_or(|o| o.ray != ray) {
                    self.ray_outcome = Some(RayOutcome::run(&built.structure, &built.brute, ray));
                    self.marks_from_ray = true;
                    changed = true;
                }
            }
            Some(Err(_)) | None => {
                if self.ray_outcome.take().is_some() {
                    changed = true;
                }
            }
        }
        match self.point {
            Some(p) => {
                let k = self.k.max(1);
                let same = self
                    .point_outcome
                    .as_ref()
                    .is_some_and(|o| o.point == p && o.k == k);
                if !same {
                    self.point_outcome =
                        Some(PointOutcome::run(&built.structure, &built.brute, p, k));
                    self.marks_from_ray = false;
                    changed = true;
                }
            }
            None => {
                if self.point_outcome.take().is_some() {
                    changed = true;
                }
            }
        }
        if changed || stale || self.marks.is_none() {
            let events = if self.marks_from_ray {
                self.ray_outcome.as_ref().map(|o| &o.events)
            } else {
                self.point_outcome.as_ref().map(|o| &o.events)
            }
            .or(self.ray_outcome.as_ref().map(|o| &o.events))
            .or(self.point_outcome.as_ref().map(|o| &o.events));
            self.marks = events.map(|e| NodeMarks::from_events(e, built.outline.len()));
        }
    }

    /// The lab's whole UI, inside `ui` (the native window, the web canvas, or a test
    /// harness).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        self.clock.tick(Instant::now());
        self.refresh();
        egui::Panel::left("controls")
            .resizable(true)
            .default_size(340.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| crate::panels::controls(self, ui));
            });
        egui::Panel::bottom("status").show(ui, |ui| crate::panels::status_line(self, ui));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(egui::Color32::from_rgb(24, 26, 32)))
            .show(ui, |ui| crate::canvas::canvas(self, ui));
        self.report = Report::of(self);
    }
}

impl eframe::App for LabApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.renderer.is_none() {
            self.renderer = Some(renderer_name(frame));
        }
        if let Some(seconds) = frame.info().cpu_usage {
            self.clock.record_cpu(f64::from(seconds) * 1e3);
        }
        self.show(ui);
        #[cfg(target_arch = "wasm32")]
        crate::web::publish(&self.report);
    }
}

/// The name of the graphics backend eframe chose.
fn renderer_name(frame: &eframe::Frame) -> String {
    use eframe::wgpu::Backend;
    frame.wgpu_render_state().map_or_else(
        || "none".to_owned(),
        |state| match state.adapter.get_info().backend {
            Backend::BrowserWebGpu => "WebGPU".to_owned(),
            Backend::Gl if cfg!(target_arch = "wasm32") => "WebGL2".to_owned(),
            other => format!("{other:?}"),
        },
    )
}
