//! The 2D half: the scene the student draws, the selection and its bounding volumes, the
//! canvas's pan and zoom, the ray and the query point, what is drawn, and the structures
//! ([`Half`]) built on the scene's segments. Its rules (`Lab2d::apply`) say what each
//! [`Action2d`] changes besides itself.

use bvhlab::glam::Vec2;
use bvhlab::{Ray2, Segment2};

use super::Note;
use super::action::Action2d;
use super::animation::{Animation, preset_lanes};
use super::camera2d::Camera2d;
use super::collision2d::{Collision2d, Collision2dCache};
use super::half::Half;
use super::history::History;
use super::lane::BuildBudget;
use super::presets::Preset;
use super::scene::{Primitives, Scene, Shape, ShapeKind};
use super::tools::Tool;
use super::volumes::{Fits, ObbPair, VolumeToggles};

mod undo;

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

/// The separating-axis demo's boxes are this many screen points apart when they first
/// appear.
const OBB_PAIR_SCREEN_SIZE: f32 = 120.0;

/// The 2D half of the lab.
pub struct Lab2d {
    /// What the student drew.
    pub scene: Scene,
    /// The preset chosen in the menu (what "Reload preset" reloads).
    pub preset: Preset,
    /// The selected shapes (by index, ascending).
    pub selection: Vec<usize>,
    /// What a press on the canvas does.
    pub tool: Tool,
    /// Pan and zoom.
    pub camera: Camera2d,
    /// The scene is to be framed when the canvas next knows its size (a new preset, the
    /// first frame, a comparison that halves the canvas).
    pub fit_pending: bool,
    /// The query ray's handles.
    pub ray: Option<RayHandles>,
    /// The query point.
    pub point: Option<Vec2>,
    /// Drawing switches.
    pub display: Display,
    /// Which bounding volumes are drawn.
    pub volumes: VolumeToggles,
    /// The separating-axis demo's boxes, once the demo was opened.
    pub obb_pair: Option<ObbPair>,
    /// The collision query of the selection against the rest, while it is on.
    pub collision: Option<Collision2d>,
    /// The structures, the question and playback.
    pub half: Half<Segment2>,
    /// The drifting preset's motion (`None` for the other presets).
    pub animation: Option<Animation>,
    /// The scene edits that can be undone and redone.
    pub(super) history: History,
    /// The scene's primitives, derived once per scene revision.
    prims: Primitives,
    prims_revision: Option<u64>,
    /// The selection's bounding volumes, derived once per scene revision and selection.
    fits: Option<Fits>,
    fits_key: Option<(u64, Vec<usize>)>,
    /// The collision query's run.
    collision_run: Collision2dCache,
}

impl Default for Lab2d {
    fn default() -> Self {
        Self::with_preset(Preset::default())
    }
}

impl Lab2d {
    /// The 2D half opened on `preset`, with nothing to undo.
    pub fn with_preset(preset: Preset) -> Self {
        let (scene, settings) = preset.build();
        let mut lab = Self {
            scene,
            preset,
            selection: Vec::new(),
            tool: Tool::Ray,
            camera: Camera2d::default(),
            fit_pending: true,
            ray: None,
            point: None,
            display: Display::default(),
            volumes: VolumeToggles::default(),
            obb_pair: None,
            collision: None,
            collision_run: Collision2dCache::default(),
            half: Half::new(settings, 3.0),
            animation: None,
            history: History::default(),
            prims: Primitives::default(),
            prims_revision: None,
            fits: None,
            fits_key: None,
        };
        lab.animation = Animation::for_preset(preset);
        preset_lanes(&mut lab.half, Preset::default(), preset);
        lab
    }
}

impl Lab2d {
    /// The scene's primitives (segments; a point is a segment of length 0) and their shapes.
    pub fn prims(&self) -> &Primitives {
        &self.prims
    }

    /// The bounding volumes of the selected shapes (all shapes when none is selected); `None`
    /// for an empty scene.
    pub fn fits(&self) -> Option<&Fits> {
        self.fits.as_ref()
    }

    /// The collision query's run, while it is on.
    pub fn collision_run(&self) -> Option<&Collision2dCache> {
        self.collision.as_ref().map(|_| &self.collision_run)
    }

    /// The scene edits that can be undone and redone.
    pub fn history(&self) -> &History {
        &self.history
    }

    /// The ray, when its handles make one.
    pub fn valid_ray(&self) -> Option<Ray2> {
        self.ray.and_then(|r| r.ray().ok())
    }

    /// Brings what is derived from the scene up to date: its primitives, the selection's
    /// volumes, the structures and recordings.
    pub(super) fn refresh(&mut self) {
        let revision = self.scene.revision();
        if self.prims_revision != Some(revision) {
            self.prims = self.scene.primitives();
            self.prims_revision = Some(revision);
        }
        let key = (revision, self.selection.clone());
        if self.fits_key.as_ref() != Some(&key) {
            self.fits = Fits::of(&self.scene.vertices(&self.selection));
            self.fits_key = Some(key);
        }
        if let Some(c) = &self.collision {
            let run = &mut self.collision_run;
            run.refresh(&self.prims, revision, &self.selection, c.tree);
        }
        let ray = self.valid_ray();
        self.half.refresh(
            &self.prims.segments,
            revision,
            ray,
            self.point,
            BuildBudget::All,
        );
    }

    /// What "Fit view" frames: the scene, its bounding volumes while they are shown, and the
    /// ray's handles and the query point.
    fn framed(&self) -> Option<(Vec2, Vec2)> {
        let (mut lo, mut hi) = self.scene.bounds()?;
        if let Some(fits) = self.fits().filter(|_| self.display.volumes) {
            let volumes = fits.bounds(&self.volumes);
            (lo, hi) = (lo.min(volumes.min), hi.max(volumes.max));
        }
        // The query's handles too: a lesson's ray that starts outside the scene and points
        // away from it was framed out, and with Predict on at step 0 nothing of the query
        // showed.
        let handles = self.ray.map(|r| [r.origin, r.target]);
        for p in handles.into_iter().flatten().chain(self.point) {
            (lo, hi) = (lo.min(p), hi.max(p));
        }
        Some((lo, hi))
    }

    /// Everything but the scene's undo history back to how [`Lab2d::with_preset`] opens the
    /// preset chosen (a lesson step's start: [`Lab::apply_lesson`](super::Lab)).
    pub(super) fn start_afresh(&mut self) {
        let history = std::mem::take(&mut self.history);
        *self = Self::with_preset(self.preset);
        self.history = history;
    }

    /// Replaces the scene with `preset`'s, with the structure it is best seen with.
    ///
    /// A preset is a section of the lecture: it starts clean, so the last section's
    /// overlays (the ray and point, the bounding volumes, the slab test, the two SAT boxes)
    /// do not bury the next idea. The bounding-volume preset shows its volumes.
    fn load_preset(&mut self, preset: Preset) {
        let (scene, settings) = preset.build();
        let old = std::mem::replace(&mut self.preset, preset);
        self.scene = scene;
        self.half.lane.settings = settings;
        preset_lanes(&mut self.half, old, preset);
        self.animation = Animation::for_preset(preset);
        self.selection.clear();
        self.ray = None;
        self.point = None;
        self.obb_pair = None;
        if self.tool == Tool::Obb {
            self.tool = Tool::Ray;
        }
        self.display.slab_test = false;
        self.display.volumes = preset == Preset::BoundingVolumes;
        if preset == Preset::BoundingVolumes {
            self.selection = vec![0];
        }
        self.fit_pending = true;
    }

    /// Carries out `action`, with the rules that go with it; what the status line says
    /// after it.
    ///
    /// # Errors
    /// Why the action cannot apply; nothing changed then.
    pub(super) fn apply(&mut self, action: Action2d) -> Result<Note, String> {
        if !matches!(action, Action2d::MoveSelection(_)) {
            // A drag's moves are one edit, until anything else happens.
            self.history.close_move();
        }
        if action.edits_scene() {
            self.stop_animation();
        }
        match action {
            Action2d::SetTool(tool) => {
                if tool == Tool::Obb && self.obb_pair.is_none() {
                    let size = self.camera.world_length(OBB_PAIR_SCREEN_SIZE);
                    self.obb_pair = Some(ObbPair::around(self.camera.center, size));
                }
                self.tool = tool;
                return Ok(Note::Clear);
            }
            Action2d::LoadPreset(preset) => {
                let before = self.scene_state(true);
                self.load_preset(preset);
                // Reloading a preset that was not touched changes nothing to undo.
                if before.scene.shapes() != self.scene.shapes()
                    || before.setup != Some(self.preset_setup())
                {
                    self.history
                        .record(before, format!("loading the preset \"{}\"", preset.label()));
                }
            }
            Action2d::Undo => return self.undo(),
            Action2d::Redo => return self.redo(),
            Action2d::SetAnimate(on) => return self.set_animate(on),
            Action2d::Clear
            | Action2d::AddShape { .. }
            | Action2d::AddToCloud { .. }
            | Action2d::Select(_)
            | Action2d::MoveSelection(_)
            | Action2d::DeleteSelection => return self.edit_scene(action),
            Action2d::SetCamera(camera) => {
                if !camera.is_valid() {
                    return Err(format!(
                        "the view's centre {} and scale {} are out of range",
                        camera.center, camera.scale
                    ));
                }
                self.camera = camera;
            }
            Action2d::FrameScene(size) => {
                if let Some((lo, hi)) = self.framed()
                    && let Some(camera) = Camera2d::framing(lo, hi, size)
                {
                    self.camera = camera;
                }
                self.fit_pending = false;
            }
            Action2d::SetRay(handles) => {
                if let Some(h) = handles
                    && !(h.origin.is_finite() && h.target.is_finite())
                {
                    return Err("the ray's handles must be finite points".to_owned());
                }
                self.ray = handles;
                if handles.is_some() {
                    self.half.ask_about_ray();
                }
            }
            Action2d::SetPoint(point) => {
                if point.is_some_and(|p| !p.is_finite()) {
                    return Err("the query point must be a finite point".to_owned());
                }
                self.point = point;
                if point.is_some() {
                    self.half.ask_about_point();
                }
            }
            Action2d::SetDisplay(display) => self.display = display,
            Action2d::SetVolumes(volumes) => self.volumes = volumes,
            Action2d::SetObbPair(pair) => self.obb_pair = Some(pair),
            Action2d::SetCollision(collision) => self.collision = collision,
        }
        Ok(Note::Keep)
    }

    /// The scene's edits (adding, moving, selecting, deleting shapes, clearing), each kept
    /// in the history so that it can be undone (a drag's moves as one edit).
    fn edit_scene(&mut self, action: Action2d) -> Result<Note, String> {
        let selection = self.selection.clone();
        let what = match &action {
            Action2d::MoveSelection(_) if self.history.continues_move(&selection) => None,
            Action2d::Clear => Some("clearing the scene".to_owned()),
            Action2d::AddShape { kind, .. } => Some(format!("adding a {}", kind.label())),
            Action2d::AddToCloud { .. } => Some("adding a point to a point cloud".to_owned()),
            // Named by `record_move`.
            Action2d::MoveSelection(_) => Some(String::new()),
            Action2d::DeleteSelection if selection.len() == 1 => {
                Some("deleting a shape".to_owned())
            }
            Action2d::DeleteSelection => Some(format!("deleting {} shapes", selection.len())),
            // Selecting changes no shape.
            _ => None,
        };
        let is_move = matches!(action, Action2d::MoveSelection(_));
        let before = what.is_some().then(|| self.scene_state(false));
        let note = self.change_scene(action)?;
        if let (Some(before), Some(what)) = (before, what)
            && before.scene.shapes() != self.scene.shapes()
        {
            if is_move {
                self.history.record_move(before, &selection);
            } else {
                self.history.record(before, what);
            }
        }
        Ok(note)
    }

    /// What the scene edits change.
    fn change_scene(&mut self, action: Action2d) -> Result<Note, String> {
        match action {
            Action2d::Clear => {
                self.scene.clear();
                self.selection.clear();
            }
            Action2d::AddShape { kind, points } => {
                let shape = Shape::new(kind, points)?;
                self.scene.add(shape);
                return Ok(Note::Clear);
            }
            Action2d::AddToCloud { cloud, point } => {
                let is_cloud = self
                    .scene
                    .shapes()
                    .get(cloud)
                    .is_some_and(|s| s.kind == ShapeKind::Points);
                if !is_cloud {
                    return Err(format!("shape {cloud} is not a point cloud"));
                }
                if !point.is_finite() {
                    return Err(format!(
                        "the point {point} is not finite; nothing was added"
                    ));
                }
                self.scene.push_point(cloud, point);
            }
            Action2d::Select(mut shapes) => {
                let n = self.scene.shapes().len();
                if let Some(bad) = shapes.iter().find(|&&i| i >= n) {
                    return Err(format!("there is no shape {bad}: the scene has {n}"));
                }
                shapes.sort_unstable();
                shapes.dedup();
                self.selection = shapes;
            }
            Action2d::MoveSelection(delta) => {
                if !delta.is_finite() {
                    return Err(format!("the move {delta} is not finite"));
                }
                for &i in &self.selection {
                    self.scene.translate(i, delta);
                }
            }
            Action2d::DeleteSelection => {
                let removed = std::mem::take(&mut self.selection);
                if removed.is_empty() {
                    return Ok(Note::Keep);
                }
                self.scene.remove(&removed);
                return Ok(Note::Say(format!("Removed {} shape(s).", removed.len())));
            }
            _ => {}
        }
        Ok(Note::Keep)
    }
}
