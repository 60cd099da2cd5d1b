//! The lab's state, what is derived from it (the built structure, the query outcomes), and
//! the top-level layout: controls on the left in the lecture's order, the canvas in the
//! middle, a status line at the bottom.

use bvhlab::glam::Vec2;
use bvhlab::{NodeId, Ray2};
use web_time::Instant;

use crate::frame_clock::FrameClock;
use crate::lab3d::Lab3d;
use crate::lane::Lane;
use crate::playback::Playback;
use crate::presets::Preset;
use crate::pseudocode::{Task, Variant};
use crate::recording::Question;
use crate::report::Report;
use crate::scene::Scene;
use crate::tool::{Interaction, Tool};
use crate::view::View;
use crate::volumes::{ObbPair, VolumeToggles};

/// Which half of the lab is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Dimension {
    /// Segments drawn on the 2D canvas.
    #[default]
    Two,
    /// Meshes in the 3D view.
    Three,
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
#[allow(clippy::struct_excessive_bools)] // independent switches (panels shown, hover linking)
pub struct LabApp {
    /// The 2D canvas or the 3D view.
    pub dimension: Dimension,
    /// The 3D view's mesh, structure, camera, ray and point.
    pub lab3d: Lab3d,
    /// The GPU the lab draws with (none in headless tests): the 3D view draws through it.
    pub render_state: Option<eframe::egui_wgpu::RenderState>,
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
    /// The structure, and what was derived from it.
    pub lane: Lane,
    /// A second structure on the same scene and question, shown side by side.
    pub compare: Option<Lane>,
    /// What playback steps through.
    pub task: Task,
    /// Which version of the algorithm.
    pub variant: Variant,
    /// The transport.
    pub playback: Playback,
    /// The range query's radius.
    pub radius: f32,
    /// The node hovered on the canvas or in a tree diagram this frame: (lane, node).
    pub hovered: Option<(usize, NodeId)>,
    /// Last frame's hovered node, which the tree diagrams (drawn before the canvas) show.
    pub linked: Option<(usize, NodeId)>,
    /// Hovering the canvas finds the node under the pointer (and the tree diagram shows it).
    pub link_hover: bool,
    /// The whole drawing area (both halves when comparing), in points.
    pub canvas_rect: egui::Rect,
    /// The tree diagram's area, when one is shown.
    pub tree_rect: Option<egui::Rect>,
    /// The tree diagrams, one per lane.
    pub trees: crate::tree_panel::Trees,
    /// Whether the tree diagrams are shown.
    pub show_tree: bool,
    /// Whether the controls (left) are shown; a page embedding a small lab may hide them.
    pub show_controls: bool,
    /// Whether the "Step through" panel (right) is shown.
    pub show_stepper: bool,
    /// A PNG export waiting for its screenshot.
    pub pending_png: Option<crate::export_ui::PendingPng>,
    /// The query ray.
    pub ray: Option<RayHandles>,
    /// The query point.
    pub point: Option<Vec2>,
    /// How many neighbours the point query finds.
    pub k: usize,
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
}

impl Default for LabApp {
    fn default() -> Self {
        let preset = Preset::default();
        let (scene, settings) = preset.build();
        Self {
            dimension: Dimension::Two,
            lab3d: Lab3d::default(),
            render_state: None,
            scene,
            selection: Vec::new(),
            view: View::default(),
            fit_pending: true,
            tool: Tool::Ray,
            interaction: Interaction::None,
            lane: Lane::new(settings),
            compare: None,
            task: Task::FirstHit,
            variant: Variant::Full,
            playback: Playback::default(),
            radius: 3.0,
            hovered: None,
            linked: None,
            link_hover: true,
            canvas_rect: egui::Rect::NOTHING,
            tree_rect: None,
            pending_png: None,
            trees: Default::default(),
            show_tree: true,
            show_controls: true,
            show_stepper: true,
            ray: None,
            point: None,
            k: 1,
            display: Display::default(),
            volume_toggles: VolumeToggles::default(),
            obb_pair: None,
            preset,
            message: None,
            clock: FrameClock::default(),
            renderer: None,
            report: Report::default(),
            fits_cache: None,
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
        self.lane.settings = settings;
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

    /// The chosen variant where `kind` has it for the task, else the full algorithm.
    fn variant_for(&self, kind: crate::structures::StructureKind) -> Variant {
        if crate::pseudocode::variants(kind, self.task).contains(&self.variant) {
            self.variant
        } else {
            Variant::Full
        }
    }

    /// The question playback steps through, from the task, the ray and the point.
    pub fn question(&self) -> Question {
        Question {
            task: self.task,
            variant: self.variant_for(self.lane.settings.kind),
            ray: self.ray.and_then(|r| r.ray().ok()),
            point: self.point,
            k: self.k.max(1),
            radius: self.radius,
        }
    }

    /// The question the 3D view steps through.
    pub fn question_3d(&self) -> Question<bvhlab::glam::Vec3> {
        Question {
            task: self.task,
            variant: self.variant_for(self.lab3d.settings.kind),
            ray: self.lab3d.ray,
            point: self.lab3d.point,
            k: self.k.max(1),
            radius: self.lab3d.radius,
        }
    }

    /// Rebuilds the structures when the scene or the settings changed, re-records the
    /// question when anything it depends on changed, and brings the snapshots to the
    /// playback step.
    pub fn refresh(&mut self) {
        if self.dimension == Dimension::Three {
            let question = self.question_3d();
            let mut changed = self.lab3d.refresh(&question, self.clock.median_ms());
            // A mesh that just loaded brings its ray and point: record the question it asks.
            let after = self.question_3d();
            if after != question {
                changed |= self.lab3d.refresh(&after, self.clock.median_ms());
            }
            if changed {
                let len = self.steps();
                self.playback.fit(len);
            }
            self.lab3d.follow(&self.playback);
            return;
        }
        let question = self.question();
        let mut changed = self.lane.refresh(&self.scene, &question);
        if let Some(other) = &mut self.compare {
            changed |= other.refresh(&self.scene, &question);
        }
        if changed {
            let len = self.steps();
            self.playback.fit(len);
        }
        self.lane.follow(&self.playback);
        if let Some(other) = &mut self.compare {
            other.follow(&self.playback);
        }
    }

    /// Makes the question about the ray (first hit, unless another ray task is chosen).
    pub fn ask_about_ray(&mut self) {
        if !matches!(self.task, Task::FirstHit | Task::AnyHit | Task::AllHits) {
            self.task = Task::FirstHit;
        }
    }

    /// Makes the question about the point (nearest, unless the range task is chosen).
    pub fn ask_about_point(&mut self) {
        if !matches!(self.task, Task::Nearest | Task::Range) {
            self.task = Task::Nearest;
        }
    }

    /// Keyboard playback, when no text field has the focus: `.` one step forward, `,` one
    /// back, Home and End, Space to play or pause.
    fn playback_keys(&mut self, ui: &egui::Ui) {
        if ui.ctx().text_edit_focused() {
            return;
        }
        let len = self.steps();
        let p = &mut self.playback;
        ui.input(|i| {
            // Jumps first, then steps: "Home . ." in one frame means step 2.
            if i.key_pressed(egui::Key::Home) {
                p.playing = false;
                p.go(0, len);
            }
            if i.key_pressed(egui::Key::End) {
                p.go(len, len);
            }
            // Several presses can arrive in one frame (fast typing, a slow frame).
            let forward = i.num_presses(egui::Key::Period);
            let back = i.num_presses(egui::Key::Comma);
            if forward + back > 0 {
                p.step_by(forward as isize - back as isize, len);
            }
            if i.key_pressed(egui::Key::Space) {
                p.toggle(len);
            }
        });
        // H shows or hides the 3D view's heat map.
        if self.dimension == Dimension::Three && ui.input(|i| i.key_pressed(egui::Key::H)) {
            self.lab3d.heat.on = !self.lab3d.heat.on;
        }
    }

    /// The longest recording's length: the last step of playback.
    pub fn steps(&self) -> usize {
        if self.dimension == Dimension::Three {
            return self.lab3d.steps();
        }
        self.lane
            .steps()
            .max(self.compare.as_ref().map_or(0, Lane::steps))
    }

    /// Lane `index`: 1 is the comparison when on; anything else the main lane.
    pub fn lane_at(&self, index: usize) -> &Lane {
        match (index, &self.compare) {
            (1, Some(other)) => other,
            _ => &self.lane,
        }
    }

    /// The lanes shown: the main one, and the comparison when on.
    pub fn lanes(&self) -> impl Iterator<Item = &Lane> {
        std::iter::once(&self.lane).chain(self.compare.as_ref())
    }

    /// The lab's whole UI, inside `ui` (the native window, the web canvas, or a test
    /// harness).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let dt = ui.input(|i| f64::from(i.stable_dt));
        self.linked = self.hovered.take();
        self.clock.tick(Instant::now());
        self.refresh();
        self.playback_keys(ui);
        // Files dropped on the window (or picked in a dialog) open in either half.
        crate::persist::poll_imports(self, ui.ctx());
        crate::export_ui::finish_png(self, ui.ctx());
        if self.playback.advance(dt, self.steps()) {
            self.refresh();
        }
        if self.playback.playing || (self.dimension == Dimension::Three && self.lab3d.busy()) {
            ui.ctx().request_repaint();
        }
        let three = self.dimension == Dimension::Three;
        // Narrow windows (an embedded lab) give the panels less, so the view keeps room.
        let width = ui.available_width();
        if self.show_controls {
            egui::Panel::left("controls")
                .resizable(true)
                .default_size((width * 0.3).clamp(220.0, 340.0))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        self.dimension_switch(ui);
                        if three {
                            crate::lab3d::panel::controls(self, ui);
                        } else {
                            crate::panels::controls(self, ui);
                        }
                    });
                });
        }
        egui::Panel::bottom("status").show(ui, |ui| crate::panels::status_line(self, ui));
        if self.show_stepper {
            egui::Panel::right("stepper")
                .resizable(true)
                .default_size((width * 0.4).clamp(240.0, 440.0))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| crate::stepper::stepper(self, ui));
                });
        }
        if self.show_tree && !three {
            egui::Panel::bottom("tree")
                .resizable(true)
                .default_size(230.0)
                .show(ui, |ui| crate::tree_panel::tree_panel(self, ui));
        } else {
            self.tree_rect = None;
        }
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(egui::Color32::from_rgb(24, 26, 32)))
            .show(ui, |ui| {
                if three {
                    crate::lab3d::view::view(self, ui);
                } else {
                    crate::canvas::canvas(self, ui);
                }
            });
        self.report = Report::of(self);
    }

    /// The 2D / 3D switch at the top of the controls.
    fn dimension_switch(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let before = self.dimension;
            ui.selectable_value(&mut self.dimension, Dimension::Two, "2D: segments");
            ui.selectable_value(&mut self.dimension, Dimension::Three, "3D: meshes");
            if self.dimension != before {
                // Each half has its own recording (start its playback at the end) and its own
                // messages.
                self.playback = Playback::default();
                self.message = None;
                self.refresh();
            }
        });
        ui.separator();
    }
}

impl eframe::App for LabApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.renderer.is_none() {
            self.renderer = Some(renderer_name(frame));
            self.render_state = frame.wgpu_render_state().cloned();
            if let Some(state) = &self.render_state {
                // eframe's default options: one sample, no depth buffer in egui's pass.
                let target = crate::view3d::gpu::EguiTarget::new(state.target_format);
                crate::view3d::gpu::install(state, target);
            }
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
