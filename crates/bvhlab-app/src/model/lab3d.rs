//! The 3D half: the mesh (built-in, or a file the student opened), the orbit camera, the ray
//! and the query point, what is drawn, the heat map's settings, and the structures ([`Half`])
//! built on the mesh's triangles. Its rules (`Lab3d::apply`) say what each [`Action3d`]
//! changes besides itself.
//!
//! A mesh loads on the frame after it is asked for (so the page can say "loading" first),
//! and a big mesh's BVH builds a slice per frame ([`Action::Tick`](super::Action::Tick)).

use bvhlab::glam::Vec3;
use bvhlab::{Ray3, Triangle3};

use super::Note;
use super::action::Action3d;
use super::collision3d::{Collision3d, CollisionCache};
use super::half::Half;
use super::heat::HeatSettings;
use super::lane::BuildBudget;
use super::mesh::{self, Mesh3d, MeshSource};
use super::motion::{self, Motion};
use super::obb_pair3d::ObbPair3;
use super::orbit_camera::OrbitCamera;
use super::refit::UpdateMode;
use super::structures::{BuildSettings, StructureKind};
use super::tools::Tool3d;
use super::volumes3d::{Part3d, PartFits, Volumes3d, closest_on, selected_triangles};

/// The built-in mesh the 3D view opens with.
pub const DEFAULT_MESH: &str = "bunny";

/// Milliseconds of build work per frame: enough to finish a small mesh at once, little
/// enough that the page stays responsive during a big one.
const BUILD_BUDGET_MS: f64 = 25.0;
/// The most build work per frame when frames are slow anyway (software rendering of a big
/// mesh takes hundreds of milliseconds a frame): half the frame time, up to this.
const SLOW_FRAME_BUILD_BUDGET_MS: f64 = 250.0;

/// The build work to do this frame, given the median frame interval: 25 ms, or half a slow
/// frame, so that a build keeps pace with a view that takes long to draw.
pub fn build_budget_ms(frame_ms: Option<f64>) -> f64 {
    frame_ms.map_or(BUILD_BUDGET_MS, |ms| {
        (ms * 0.5).clamp(BUILD_BUDGET_MS, SLOW_FRAME_BUILD_BUDGET_MS)
    })
}

/// What the 3D view shows besides the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Display3d {
    /// Draw the structure's nodes.
    pub structure: bool,
    /// Which level of nodes to draw (0 is the root).
    pub depth: u32,
    /// Draw the mesh translucent, so volumes inside show.
    pub xray: bool,
    /// Colour the nodes the query visited, culled and pruned.
    pub marks: bool,
}

impl Default for Display3d {
    fn default() -> Self {
        Self {
            structure: true,
            depth: 3,
            xray: true,
            marks: true,
        }
    }
}

/// What to put back over a mesh once it has loaded, instead of the defaults: a saved state's
/// camera, ray, point and radius, or the ray and point the page's address asks for (the
/// camera then frames the mesh as usual).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Placement3d {
    /// The camera; `None` frames the mesh.
    pub camera: Option<OrbitCamera>,
    /// The ray; `None` leaves none (or, when the camera frames the mesh, one through the
    /// middle of the view).
    pub ray: Option<Ray3>,
    /// The query point; `None` as for the ray.
    pub point: Option<Vec3>,
    /// The range query's radius; `None` takes a tenth of the mesh's size.
    pub radius: Option<f32>,
}

/// The 3D half of the lab.
pub struct Lab3d {
    /// The mesh shown, once one is loaded.
    pub mesh: Option<Mesh3d>,
    /// A mesh to load on the next frame (so "loading…" shows first).
    pub pending: Option<MeshSource>,
    /// A saved camera, ray, point and radius to put back once the pending mesh has loaded,
    /// instead of framing it afresh (a reload, a scene file, a share link).
    pub placement: Option<Placement3d>,
    /// A mesh was loaded and the view has not framed it yet ([`Action3d::Frame`]).
    pub framing: bool,
    /// The camera.
    pub camera: OrbitCamera,
    /// What a click does.
    pub tool: Tool3d,
    /// The ray, once cast.
    pub ray: Option<Ray3>,
    /// The query point, once placed.
    pub point: Option<Vec3>,
    /// What is drawn.
    pub display: Display3d,
    /// The traversal-cost heat map's settings.
    pub heat: HeatSettings,
    /// The last message about the mesh (a load or build that failed, and why).
    pub message: Option<String>,
    /// The structures, the question and playback.
    pub half: Half<Triangle3>,
    /// The motion of a mesh that moves ([`motion`]).
    pub motion: Motion,
    /// The bounding volumes of the mesh or a part of it (lecture §2).
    pub volumes: Volumes3d,
    /// The part's triangles and fits, while the volumes are shown.
    part_fits: PartFits,
    /// The two boxes of the separating-axis test, while it is on.
    pub obb_pair: Option<ObbPair3>,
    /// The collision query of the part against a moved copy, while it is on.
    pub collision: Option<Collision3d>,
    /// Its run.
    collision_run: CollisionCache,
    revisions: u64,
}

impl Default for Lab3d {
    fn default() -> Self {
        Self {
            mesh: None,
            pending: Some(MeshSource::Builtin(DEFAULT_MESH.to_owned())),
            placement: None,
            framing: false,
            camera: OrbitCamera::default(),
            tool: Tool3d::Ray,
            ray: None,
            point: None,
            display: Display3d::default(),
            heat: HeatSettings::default(),
            message: None,
            half: Half::new(
                BuildSettings {
                    kind: StructureKind::AabbTree,
                    bvh_split: bvhlab::structure::SplitMethod::BinnedSah,
                    leaf_size: 4,
                    ..BuildSettings::default()
                },
                0.1,
            ),
            motion: Motion::default(),
            volumes: Volumes3d::default(),
            part_fits: PartFits::default(),
            obb_pair: None,
            collision: None,
            collision_run: CollisionCache::default(),
            revisions: 0,
        }
    }
}

impl Lab3d {
    /// Back to how the 3D half opens, its mesh to be loaded afresh (a lesson step's start,
    /// before its setup names the mesh); the mesh revisions keep counting, so that nothing
    /// built on the mesh shown is taken for the new one's.
    pub(super) fn start_afresh(&mut self) {
        *self = Self {
            revisions: self.revisions,
            ..Self::default()
        };
    }

    /// Whether a load or a build is under way (the caller keeps repainting).
    pub fn busy(&self) -> bool {
        self.pending.is_some() || self.half.lanes().any(|l| l.job.is_some())
    }

    /// Whether the camera, ray and point belong to the mesh shown: it has loaded, nothing else
    /// is loading, and the view has framed it.
    pub fn placed(&self) -> bool {
        self.mesh.is_some() && self.pending.is_none() && !self.framing
    }

    /// The mesh's triangles (none before one loads).
    pub fn triangles(&self) -> &[Triangle3] {
        self.mesh.as_ref().map_or(&[], |m| m.mesh.triangles())
    }

    /// Whether the mesh shown moves and its animation is on (the caller keeps repainting).
    pub fn moving(&self) -> bool {
        self.motion.on && self.pending.is_none() && self.mesh.as_ref().is_some_and(motion::moves)
    }

    /// The mesh's revision (0 before one loads).
    pub fn revision(&self) -> u64 {
        self.mesh.as_ref().map_or(0, |m| m.revision)
    }

    /// The mesh's triangle `index`.
    pub fn triangle(&self, index: u32) -> Option<Triangle3> {
        self.triangles().get(index as usize).copied()
    }

    /// Loads a mesh asked for, moves a mesh that moves on by `seconds`, and gives the builds
    /// `build_ms` milliseconds (a frame's work), then brings the recordings up to date.
    pub(super) fn tick(&mut self, seconds: f64, build_ms: f64) {
        if let Some(source) = self.pending.take() {
            self.load(&source);
        } else if let Some(mesh) = &mut self.mesh
            && self.motion.advance(mesh, seconds, self.revisions + 1)
        {
            self.revisions += 1;
        }
        self.refresh(BuildBudget::Millis(build_ms));
    }

    /// The part the volumes are fitted to, with its fits: `None` while they are not shown
    /// (or no mesh has loaded).
    pub fn part_fits(&self) -> Option<&PartFits> {
        (self.volumes.shown && self.mesh.is_some()).then_some(&self.part_fits)
    }

    /// The collision query's run and B's triangles, while it is on and the volumes shown.
    pub fn collision_run(&self) -> Option<&CollisionCache> {
        self.part_fits()
            .and(self.collision.as_ref())
            .map(|_| &self.collision_run)
    }

    /// Brings the recordings up to date (builds advance only in [`Lab3d::tick`]), and the
    /// volumes' fits while they are shown.
    pub(super) fn refresh(&mut self, budget: BuildBudget) {
        let Some(mesh) = &self.mesh else { return };
        let revision = mesh.revision;
        if self.volumes.shown {
            let (part, point, radius) = (self.volumes.part, self.point, self.half.radius);
            self.part_fits
                .refresh(&mesh.mesh, revision, part, point, radius);
            if let Some(collision) = &self.collision {
                let part = (&self.part_fits.triangles[..], self.part_fits.generation);
                self.collision_run
                    .refresh(mesh.mesh.triangles(), part, collision);
            }
        }
        let triangles = mesh.mesh.triangles();
        self.half
            .refresh(triangles, revision, self.ray, self.point, budget);
        if let Some(e) = &self.half.lane.build_error
            && budget != BuildBudget::None
            && self.message.as_ref() != Some(e)
        {
            self.message = Some(e.clone());
        }
    }

    fn load(&mut self, source: &MeshSource) {
        self.revisions += 1;
        match mesh::load(source, self.revisions) {
            Ok(mesh) => {
                let saved = self.placement.take().unwrap_or_default();
                self.half.radius = saved.radius.unwrap_or(mesh.size() * 0.1);
                self.ray = saved.ray;
                self.point = saved.point;
                match saved.camera {
                    Some(camera) => {
                        self.camera = camera;
                        self.framing = false;
                    }
                    // The camera (and a missing ray and point) are placed by the view, which
                    // knows its shape.
                    None => self.framing = true,
                }
                self.message = (!mesh.warnings.is_empty()).then(|| mesh.warnings.join(" "));
                self.motion.restart();
                if motion::moves(&mesh) {
                    // A mesh that moves every frame is refitted every frame, unless the
                    // student switches to rebuilding.
                    self.half.lane.update = UpdateMode::Refit;
                }
                self.mesh = Some(mesh);
            }
            Err(e) => {
                self.placement = None;
                let kept = self
                    .mesh
                    .as_ref()
                    .map_or(String::new(), |m| format!(" {} stays open.", m.name));
                self.message = Some(format!("{e}{kept}"));
            }
        }
    }

    /// Frames the camera on the mesh for a view of `aspect` (width / height), and puts a
    /// first ray through the middle of the view and the point beside the mesh, so the view
    /// has answers to show straight away. Done once per loaded mesh.
    fn frame(&mut self, aspect: f32) {
        let Some(mesh) = &self.mesh else { return };
        // A view with no area frames nothing yet: the mesh waits for one that has.
        let usable = aspect.is_finite() && aspect > 0.0;
        if !usable || !std::mem::take(&mut self.framing) {
            return;
        }
        self.camera.frame_in(&mesh.bounds(), aspect);
        let size = mesh.size();
        if self.ray.is_none() {
            self.ray = Ray3::new(self.camera.eye(), self.camera.basis().forward).ok();
        }
        if self.point.is_none() {
            // Beside the mesh, to the right in the view, where the gizmo is on screen; on
            // it when the brush follows the point (`volumes=brush`), so the brush holds
            // triangles from the start.
            let beside = self.camera.target + self.camera.basis().right * size * 0.35;
            let brushing = self.volumes.shown && self.volumes.part == Part3d::Brush;
            self.point = Some(if brushing {
                closest_on(mesh.mesh.triangles(), beside).unwrap_or(beside)
            } else {
                beside
            });
        }
    }

    /// Whether lecture §2 is on screen: the volumes or the two boxes.
    fn section2_shown(&self) -> bool {
        self.volumes.shown || self.obb_pair.is_some()
    }

    /// §2's rule: while its volumes or boxes are shown the structure's nodes and the query's
    /// marks are not drawn (the lecture's §2 comes before any tree; the panel's switches show
    /// it and can turn them back on), and they come back when §2 is put away. Called after
    /// a change, with whether §2 was shown `before` it.
    fn put_trees_away_for_section2(&mut self, before: bool) {
        let now = self.section2_shown();
        if now != before {
            self.display.structure = !now;
            self.display.marks = !now;
        }
    }

    /// The volumes' rules: [`Lab3d::put_trees_away_for_section2`], and a brush chosen where
    /// it would hold nothing starts at the query point's closest point on the mesh.
    fn set_volumes(&mut self, volumes: Volumes3d) {
        let before = self.section2_shown();
        if volumes.part == Part3d::Brush
            && self.volumes.part != Part3d::Brush
            && let Some(mesh) = &self.mesh
        {
            let from = self.point.unwrap_or_else(|| mesh.bounds().center());
            let radius = self.half.radius;
            if selected_triangles(&mesh.mesh, Part3d::Brush, Some(from), radius).is_empty() {
                self.point = closest_on(mesh.mesh.triangles(), from).or(self.point);
            }
        }
        self.volumes = volumes;
        self.put_trees_away_for_section2(before);
    }

    /// Carries out `action`, with the rules that go with it; what the status line says
    /// after it.
    ///
    /// # Errors
    /// Why the action cannot apply; nothing changed then.
    pub(super) fn apply(&mut self, action: Action3d) -> Result<Note, String> {
        match action {
            Action3d::SetTool(tool) => {
                self.tool = tool;
                match tool {
                    Tool3d::Ray => self.half.ask_about_ray(),
                    Tool3d::Point => self.half.ask_about_point(),
                }
            }
            Action3d::OpenMesh(source) => {
                if let MeshSource::Builtin(slug) = &source
                    && !bvhlab_meshio::builtin::list()
                        .iter()
                        .any(|b| b.slug == slug)
                {
                    return Err(format!("the lab has no built-in mesh \"{slug}\""));
                }
                self.pending = Some(source);
                return Ok(Note::Clear);
            }
            Action3d::SetCamera(camera) => {
                if !camera.is_valid() {
                    return Err(
                        "the camera must have a finite target and angles, and a positive distance"
                            .to_owned(),
                    );
                }
                self.camera = camera;
            }
            Action3d::Frame { aspect } => self.frame(aspect),
            Action3d::SetRay(ray) => {
                // A mesh still loading takes the ray once it has loaded.
                if self.pending.is_some() {
                    self.placement.get_or_insert_default().ray = ray;
                } else {
                    self.ray = ray;
                }
                if ray.is_some() {
                    self.half.ask_about_ray();
                }
            }
            Action3d::SetPoint(point) => {
                if point.is_some_and(|p| !p.is_finite()) {
                    return Err("the query point must be a finite point".to_owned());
                }
                if self.pending.is_some() {
                    self.placement.get_or_insert_default().point = point;
                } else {
                    self.point = point;
                }
                if point.is_some() {
                    self.half.ask_about_point();
                }
            }
            Action3d::SetDisplay(display) => self.display = display,
            Action3d::SetHeat(heat) => self.heat = heat,
            Action3d::Animate(on) => self.motion.on = on,
            Action3d::SetVolumes(volumes) => self.set_volumes(volumes),
            Action3d::SetCollision(collision) => {
                if collision.is_some_and(|c| !c.is_valid()) {
                    return Err("the copy's move and turn must be finite numbers".to_owned());
                }
                self.collision = collision;
            }
            Action3d::SetObbPair(pair) => {
                if pair.is_some_and(|p| !p.is_valid()) {
                    return Err(
                        "each box needs a finite centre, turn and half extents (none negative)"
                            .to_owned(),
                    );
                }
                let before = self.section2_shown();
                self.obb_pair = pair;
                self.put_trees_away_for_section2(before);
            }
        }
        Ok(Note::Keep)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_frames_give_the_build_more_time_up_to_a_cap() {
        assert_eq!(build_budget_ms(None), BUILD_BUDGET_MS);
        assert_eq!(build_budget_ms(Some(16.0)), BUILD_BUDGET_MS);
        assert_eq!(build_budget_ms(Some(300.0)), 150.0);
        assert_eq!(build_budget_ms(Some(5_000.0)), SLOW_FRAME_BUILD_BUDGET_MS);
    }
}
