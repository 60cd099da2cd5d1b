//! A starting state in a few words: the scene or mesh, the structure (and one to compare),
//! the task and its version, the ray or point, and the playback step. The page's address
//! (`?preset=kd-tree&ray=...`) and each lesson step say where the lab starts with one, and
//! [`Lab::apply_setup`] puts it in place with ordinary actions, so its rules (a preset
//! clears the ray, a ray makes the task a ray task, ...) are the same as by hand.

use bvhlab::Ray3;
use bvhlab::glam::{Vec2, Vec3};

use super::lab2d::RayHandles;
use super::mesh::MeshSource;
use super::obb_pair3d::{BoxPose3, ObbPair3};
use super::presets::Preset;
use super::question::{Task, Variant};
use super::structures::StructureKind;
use super::tools::Tool;
use super::volumes::{BoxPose, ObbPair};
use super::volumes3d::{Part3d, Volumes3d};
use super::{Action, Action2d, Action3d, Dimension, HalfAction, Lab, PlaybackAction};

/// Where the lab starts: each part that is `Some` is put in place, in the order of the
/// fields.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Setup {
    /// A 2D scene (shows the 2D half).
    pub preset: Option<Preset>,
    /// A built-in mesh's slug (shows the 3D half).
    pub mesh: Option<String>,
    /// The structure of the half shown (its other build options stay).
    pub structure: Option<StructureKind>,
    /// A second structure beside the first.
    pub compare: Option<StructureKind>,
    /// How a BVH splits its nodes (the structure's and the comparison's).
    pub split: Option<bvhlab::structure::SplitMethod>,
    /// The ray: `x,y,dx,dy` in 2D or `x,y,z,dx,dy,dz` in 3D.
    pub ray: Option<Vec<f32>>,
    /// A polygon added to the 2D scene and selected: its corners, 2 numbers each.
    pub polygon: Option<Vec<f32>>,
    /// The separating-axis test's two boxes: for each, centre, half extents and angle in
    /// degrees (2D, 5 numbers), or centre, half extents and turn about x, y, z in degrees
    /// (3D, 9 numbers).
    pub obbs: Option<Vec<f32>>,
    /// The 3D view's bounding volumes, shown and fitted to the mesh or the brush.
    pub volumes: Option<Part3d>,
    /// The query point: `x,y` or `x,y,z`.
    pub point: Option<Vec<f32>>,
    /// What is stepped through.
    pub task: Option<Task>,
    /// Which version of the algorithm.
    pub variant: Option<Variant>,
    /// The playback step (held until the recording is that long).
    pub step: Option<usize>,
}

impl Lab {
    /// Puts `setup` in place; returns what could not be used, one sentence each, naming
    /// `source` ("the address", "lesson slab-test, step 2"). The rest still applies.
    pub fn apply_setup(&mut self, setup: &Setup, source: &str) -> Vec<String> {
        let mut problems = Vec::new();
        let apply = |lab: &mut Self, action: Action, problems: &mut Vec<String>| {
            if let Err(e) = lab.apply(action) {
                problems.push(format!("{source}: {e}"));
            }
        };
        if let Some(preset) = setup.preset {
            apply(self, Action2d::LoadPreset(preset).into(), &mut problems);
        }
        if let Some(slug) = &setup.mesh {
            apply(
                self,
                Action3d::OpenMesh(MeshSource::Builtin(slug.clone())).into(),
                &mut problems,
            );
        }
        let three = self.dimension() == Dimension::Three;
        let settings = if three {
            self.three().half.lane.settings
        } else {
            self.two().half.lane.settings
        };
        let settings = super::structures::BuildSettings {
            bvh_split: setup.split.unwrap_or(settings.bvh_split),
            ..settings
        };
        if setup.structure.is_some() || setup.split.is_some() {
            let kind = setup.structure.unwrap_or(settings.kind);
            apply(
                self,
                HalfAction::SetStructure(super::structures::BuildSettings { kind, ..settings })
                    .into(),
                &mut problems,
            );
        }
        if let Some(kind) = setup.compare {
            apply(
                self,
                HalfAction::SetCompare(Some(super::structures::BuildSettings { kind, ..settings }))
                    .into(),
                &mut problems,
            );
        }
        if let Some(numbers) = &setup.ray {
            let action = if three {
                ray3(numbers).map(|r| Action3d::SetRay(Some(r)).into())
            } else {
                ray2(numbers).map(|r| Action2d::SetRay(Some(r)).into())
            };
            match action {
                Ok(action) => apply(self, action, &mut problems),
                Err(e) => problems.push(format!("{source}'s ray {e}")),
            }
        }
        if let Some(numbers) = &setup.point {
            let action: Result<Action, String> = match (three, numbers.as_slice()) {
                (false, &[x, y]) => Ok(Action2d::SetPoint(Some(Vec2::new(x, y))).into()),
                (true, &[x, y, z]) => Ok(Action3d::SetPoint(Some(Vec3::new(x, y, z))).into()),
                _ => Err(format!(
                    "{source}'s point has {} numbers; the {} view takes {}",
                    numbers.len(),
                    if three { "3D" } else { "2D" },
                    if three { 3 } else { 2 }
                )),
            };
            match action {
                // With a ray too, the ray's task stays (the point is placed for later).
                Ok(action) => {
                    let task = if three {
                        self.three().half.task
                    } else {
                        self.two().half.task
                    };
                    apply(self, action, &mut problems);
                    if setup.ray.is_some() {
                        apply(self, HalfAction::SetTask(task).into(), &mut problems);
                    }
                }
                Err(e) => problems.push(e),
            }
        }
        problems.extend(self.place_shapes(setup, three, source));
        if let Some(task) = setup.task {
            apply(self, HalfAction::SetTask(task).into(), &mut problems);
        }
        if let Some(tool) = setup.task.and_then(|task| tool_for(task, three)) {
            apply(self, tool, &mut problems);
        }
        if let Some(variant) = setup.variant {
            apply(self, HalfAction::SetVariant(variant).into(), &mut problems);
        }
        if let Some(step) = setup.step {
            apply(self, PlaybackAction::Hold(step).into(), &mut problems);
        }
        problems
    }
}

/// Picks the tool a task's question is moved with in the view: the ray's for a ray task,
/// the point's for a point task (none for a build: nothing on the canvas moves it). A lesson
/// that asks for a ray while the Select tool is on makes the student's first drag move a
/// shape instead.
fn tool_for(task: Task, three: bool) -> Option<Action> {
    let ray = match task {
        Task::FirstHit | Task::AnyHit | Task::AllHits => true,
        Task::Nearest | Task::Range => false,
        Task::Build => return None,
    };
    Some(match (three, ray) {
        (false, true) => Action2d::SetTool(Tool::Ray).into(),
        (false, false) => Action2d::SetTool(Tool::Point).into(),
        (true, true) => Action3d::SetTool(super::tools::Tool3d::Ray).into(),
        (true, false) => Action3d::SetTool(super::tools::Tool3d::Point).into(),
    })
}

/// A 2D ray from `x,y,dx,dy`, or what is wrong with them (to follow "the ray").
fn ray2(n: &[f32]) -> Result<RayHandles, String> {
    let &[x, y, dx, dy] = n else {
        return Err(format!(
            "has {} numbers; the 2D view takes 4 (x,y,dx,dy)",
            n.len()
        ));
    };
    let handles = RayHandles {
        origin: Vec2::new(x, y),
        target: Vec2::new(x + dx, y + dy),
    };
    handles
        .ray()
        .map(|_| handles)
        .map_err(|e| format!("cannot be used: {e}"))
}

/// A 3D ray from `x,y,z,dx,dy,dz`, or what is wrong with them.
fn ray3(n: &[f32]) -> Result<Ray3, String> {
    let &[x, y, z, dx, dy, dz] = n else {
        return Err(format!(
            "has {} numbers; the 3D view takes 6 (x,y,z,dx,dy,dz)",
            n.len()
        ));
    };
    Ray3::new(Vec3::new(x, y, z), Vec3::new(dx, dy, dz)).map_err(|e| format!("cannot be used: {e}"))
}

impl Lab {
    /// Adds the polygon with corners `numbers` (x, y pairs) to the 2D scene and selects it;
    /// what went wrong, one sentence each.
    fn add_polygon(&mut self, numbers: &[f32], three: bool, source: &str) -> Vec<String> {
        if three {
            return vec![format!(
                "{source}'s polygon is drawn in the 2D view; the 3D view shows a mesh"
            )];
        }
        let points = numbers
            .chunks_exact(2)
            .map(|xy| Vec2::new(xy[0], xy[1]))
            .collect();
        let add = Action2d::AddShape {
            kind: super::scene::ShapeKind::Polygon,
            points,
        };
        if let Err(e) = self.apply(add.into()) {
            return vec![format!("{source}: {e}")];
        }
        let added = self.two().scene.shapes().len() - 1;
        self.apply(Action2d::Select(vec![added]).into())
            .err()
            .map(|e| format!("{source}: {e}"))
            .into_iter()
            .collect()
    }

    /// Shows the separating-axis demo with the boxes `numbers` give; what went wrong, one
    /// sentence each.
    fn place_obbs(&mut self, numbers: &[f32], three: bool, source: &str) -> Vec<String> {
        if three {
            let pair = match obb_pair3(numbers) {
                Ok(pair) => pair,
                Err(e) => return vec![format!("{source}'s obbs {e}")],
            };
            return self
                .apply(Action3d::SetObbPair(Some(pair)).into())
                .err()
                .map(|e| format!("{source}: {e}"))
                .into_iter()
                .collect();
        }
        let pair = match obb_pair(numbers) {
            Ok(pair) => pair,
            Err(e) => return vec![format!("{source}'s obbs {e}")],
        };
        [Action2d::SetTool(Tool::Obb), Action2d::SetObbPair(pair)]
            .into_iter()
            .filter_map(|a| self.apply(a.into()).err())
            .map(|e| format!("{source}: {e}"))
            .collect()
    }
}

impl Lab {
    /// The setup's added polygon, the 3D volumes and the separating-axis boxes; what went
    /// wrong, one sentence each.
    fn place_shapes(&mut self, setup: &Setup, three: bool, source: &str) -> Vec<String> {
        let mut problems = Vec::new();
        if let Some(numbers) = &setup.polygon {
            problems.extend(self.add_polygon(numbers, three, source));
        }
        if let Some(part) = setup.volumes {
            problems.extend(self.show_volumes_3d(part, three, source));
        }
        if let Some(numbers) = &setup.obbs {
            problems.extend(self.place_obbs(numbers, three, source));
        }
        problems
    }

    /// Shows the 3D volumes fitted to `part`; what went wrong, one sentence each.
    fn show_volumes_3d(&mut self, part: Part3d, three: bool, source: &str) -> Vec<String> {
        if !three {
            return vec![format!(
                "{source}'s volumes are the 3D view's; the 2D view shows its own (preset=bounding-volumes)"
            )];
        }
        let volumes = Volumes3d {
            shown: true,
            part,
            ..self.three().volumes
        };
        let mut actions: Vec<Action> = vec![Action3d::SetVolumes(volumes).into()];
        if part == Part3d::Brush {
            // The brush follows the query point: its gizmo and keys come with the Point tool.
            actions.push(Action3d::SetTool(super::tools::Tool3d::Point).into());
        }
        actions
            .into_iter()
            .filter_map(|a| self.apply(a).err())
            .map(|e| format!("{source}: {e}"))
            .collect()
    }
}

/// The 3D test's boxes from 18 numbers: for each, centre, half extents (at least 0) and turn
/// about x, y, z in degrees.
fn obb_pair3(numbers: &[f32]) -> Result<ObbPair3, String> {
    let &[
        ax,
        ay,
        az,
        aw,
        ah,
        ad,
        arx,
        ary,
        arz,
        bx,
        by,
        bz,
        bw,
        bh,
        bd,
        brx,
        bry,
        brz,
    ] = numbers
    else {
        return Err(format!("take 18 numbers in 3D, not {}", numbers.len()));
    };
    let pair = ObbPair3 {
        a: BoxPose3 {
            center: Vec3::new(ax, ay, az),
            half: Vec3::new(aw, ah, ad),
            degrees: Vec3::new(arx, ary, arz),
        },
        b: BoxPose3 {
            center: Vec3::new(bx, by, bz),
            half: Vec3::new(bw, bh, bd),
            degrees: Vec3::new(brx, bry, brz),
        },
        step: 0,
    };
    if pair.is_valid() {
        Ok(pair)
    } else {
        Err("have a half extent below 0; half extents must be at least 0".to_owned())
    }
}

/// The separating-axis demo's boxes from 10 numbers: for each, centre x and y, half width and
/// height (positive), and angle in degrees.
fn obb_pair(numbers: &[f32]) -> Result<ObbPair, String> {
    let pose = |n: &[f32]| -> Result<BoxPose, String> {
        let &[x, y, w, h, degrees] = n else {
            return Err(format!("take 10 numbers, not {}", numbers.len()));
        };
        if !(w > 0.0 && h > 0.0) {
            return Err(format!(
                "have a box of half size {w} by {h}; half sizes must be more than 0"
            ));
        }
        Ok(BoxPose {
            center: Vec2::new(x, y),
            half: Vec2::new(w, h),
            angle: degrees.to_radians(),
        })
    };
    if numbers.len() != 10 {
        return Err(format!("take 10 numbers, not {}", numbers.len()));
    }
    Ok(ObbPair {
        a: pose(&numbers[..5])?,
        b: pose(&numbers[5..])?,
    })
}
