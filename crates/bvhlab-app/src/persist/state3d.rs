//! The 3D half's part of a [`SavedState`](super::SavedState): which half is shown, the mesh
//! (a built-in by slug; a dropped file only by name, since its bytes can be hundreds of
//! megabytes), the structure's settings (and the comparison's), the camera, the ray, the
//! point, the radius, the half's own task, k and playback, and §2's volumes and boxes
//! ([`super::volumes3d`]). A file from before the halves
//! kept their own question takes the 2D half's for both, as that lab did.
//!
//! A file mesh cannot come back by itself after a reload: the state keeps its name, the
//! built-in bunny is shown in its place with everything else as it was, and the status line
//! asks the student to drop the file again.

use bvhlab::Ray3;
use bvhlab::glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::model::lab3d::{DEFAULT_MESH, Placement3d};
use crate::model::mesh::MeshSource;
use crate::model::orbit_camera::OrbitCamera;
use crate::model::restore::{Restore3d, RestoreHalf};
use crate::model::structures::BuildSettings;
use crate::model::{Dimension, Lab};

use super::names::{Coord, TaskName, VariantName, shorten};
use super::state::{PlaybackState, SettingsState};
use super::volumes3d::{Collision3dState, ObbPair3State, Volumes3dState};
use crate::model::volumes3d::Volumes3d;

/// A point or direction in 3D as stored: `[x, y, z]`.
pub type StoredPoint3 = [Coord; 3];

/// The 3D half's state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ThreeState {
    /// Whether the 3D half is the one shown.
    pub shown: bool,
    /// The mesh.
    pub mesh: MeshState,
    /// The structure's build settings.
    pub structure: SettingsState,
    /// The camera (absent: frame the mesh).
    pub camera: Option<CameraState>,
    /// The ray, if one was cast.
    pub ray: Option<Ray3State>,
    /// The query point, if one was placed.
    pub point: Option<StoredPoint3>,
    /// The range query's radius (absent: a tenth of the mesh's size).
    pub radius: Option<Coord>,
    // The fields below are not in states saved before each half kept its own question and
    // playback. Absent, each is `None` (not the default lab's value, which the struct's
    // `default` would give): the restore then takes the 2D half's, as that lab did.
    /// The comparison structure's settings, when two are shown.
    #[serde(default)]
    pub compare: Option<SettingsState>,
    /// What the 3D half steps through (absent: the 2D half's task).
    #[serde(default)]
    pub task: Option<TaskName>,
    /// Which version of the algorithm (absent: the 2D half's).
    #[serde(default)]
    pub variant: Option<VariantName>,
    /// How many nearest neighbours (absent: the 2D half's k).
    #[serde(default)]
    pub k: Option<usize>,
    /// Where the 3D half's playback is (absent: where the 2D half's is).
    #[serde(default)]
    pub playback: Option<PlaybackState>,
    /// §2 in 3D: the volumes shown and what they are fitted to (absent: not shown).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub volumes: Option<Volumes3dState>,
    /// The two boxes of the separating-axis test (absent: the test is off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obb_pair: Option<ObbPair3State>,
    /// The collision query's copy of the part (absent: the query is off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision: Option<Collision3dState>,
}

/// The mesh: `{"builtin": "bunny"}` or `{"file": "part.stl"}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MeshState {
    /// A built-in mesh, by slug.
    #[serde(rename = "builtin")]
    Builtin(String),
    /// A file the student opened, by name (its bytes are not kept).
    #[serde(rename = "file")]
    File(String),
}

/// The orbit camera.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraState {
    /// The point looked at.
    pub target: StoredPoint3,
    /// The eye's distance from it.
    pub distance: Coord,
    /// The turn about the up axis, in radians.
    pub yaw: Coord,
    /// The tilt above the horizon, in radians.
    pub pitch: Coord,
}

/// A ray in 3D: origin and direction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ray3State {
    /// Where it starts.
    pub origin: StoredPoint3,
    /// Where it goes (any non-zero length).
    pub direction: StoredPoint3,
}

impl Default for ThreeState {
    fn default() -> Self {
        Self::capture(&Lab::default())
    }
}

impl Default for CameraState {
    fn default() -> Self {
        camera_state(&OrbitCamera::default())
    }
}

/// A stored camera, checked.
fn camera(c: &CameraState) -> Result<OrbitCamera, String> {
    let distance = finite("the camera's distance", c.distance)?;
    if distance <= 0.0 {
        return Err(format!(
            "the camera's distance is {distance}; it must be more than 0"
        ));
    }
    Ok(OrbitCamera {
        target: point3("the camera's target", c.target)?,
        distance,
        yaw: finite("the camera's yaw", c.yaw)?,
        pitch: finite("the camera's pitch", c.pitch)?.clamp(-1.55, 1.55),
        ..OrbitCamera::default()
    })
}

/// The longest mesh name kept.
const MAX_NAME_CHARS: usize = 200;

impl ThreeState {
    /// The 3D half's state as the lab has it now.
    pub fn capture(whole: &Lab) -> Self {
        let lab = whole.three();
        let half = &lab.half;
        // A mesh still loading is the one to come back to.
        let mesh = match (&lab.pending, &lab.mesh) {
            (Some(MeshSource::Builtin(slug)), _) => MeshState::Builtin(slug.clone()),
            (Some(MeshSource::File { name, .. }), _) => MeshState::File(name.clone()),
            (None, Some(mesh)) => mesh.slug.as_ref().map_or_else(
                || MeshState::File(mesh.name.clone()),
                |slug| MeshState::Builtin(slug.clone()),
            ),
            (None, None) => MeshState::Builtin(DEFAULT_MESH.to_owned()),
        };
        // What waits to be put back over a loading mesh is what the student last saw; a mesh
        // not yet framed has no camera, ray or point of its own yet.
        let (camera, ray, point, radius) = match lab.placement {
            Some(p) => (p.camera, p.ray, p.point, p.radius),
            None if lab.placed() => (Some(lab.camera), lab.ray, lab.point, Some(half.radius)),
            None => (None, None, None, None),
        };
        Self {
            shown: whole.dimension() == Dimension::Three,
            mesh,
            structure: SettingsState::of_lane(&half.lane),
            camera: camera.as_ref().map(camera_state),
            ray: ray.map(|r| Ray3State {
                origin: stored3(r.origin()),
                direction: stored3(r.dir()),
            }),
            point: point.map(stored3),
            radius: radius.map(Coord),
            compare: half.compare.as_ref().map(SettingsState::of_lane),
            task: Some(half.task.into()),
            variant: Some(half.variant.into()),
            k: Some(half.k),
            playback: Some(PlaybackState {
                step: half.playback.step,
                live: half.playback.at_end,
            }),
            volumes: (lab.volumes != Volumes3d::default()).then(|| lab.volumes.into()),
            obb_pair: lab.obb_pair.as_ref().map(Into::into),
            collision: lab.collision.as_ref().map(Into::into),
        }
    }
}

/// A [`ThreeState`] that passed its checks, ready to restore, and the note for a mesh that
/// was a file.
pub(super) struct Checked3d {
    pub(super) shown: bool,
    pub(super) restore: Restore3d,
    pub(super) note: Option<String>,
}

impl Checked3d {
    /// Checks `state`, with `settings` and `compare` its checked build settings and `half`
    /// the 2D half's question and playback (what a file from before the halves kept their
    /// own gives both), or says what is wrong.
    pub(super) fn check(
        state: &ThreeState,
        settings: BuildSettings,
        compare: Option<BuildSettings>,
        two: &RestoreHalf,
    ) -> Result<Self, String> {
        if let MeshState::Builtin(slug) = &state.mesh
            && !bvhlab_meshio::builtin::list()
                .iter()
                .any(|b| b.slug == slug)
        {
            return Err(format!(
                "the 3D view's mesh \"{}\" is not one of the lab's built-in meshes",
                shorten(slug, 40)
            ));
        }
        let camera = state.camera.as_ref().map(camera).transpose()?;
        let radius = state
            .radius
            .map(|r| finite("the 3D radius", r))
            .transpose()?;
        if let Some(r) = radius.filter(|&r| r < 0.0) {
            return Err(format!("the 3D radius is {r}; it must be at least 0"));
        }
        let ray = state
            .ray
            .map(|r| -> Result<Ray3, String> {
                let origin = point3("the 3D ray's origin", r.origin)?;
                let direction = point3("the 3D ray's direction", r.direction)?;
                Ray3::new(origin, direction).map_err(|e| format!("the 3D ray: {e}"))
            })
            .transpose()?;
        let point = state
            .point
            .map(|p| point3("the 3D query point", p))
            .transpose()?;
        let k = state.k.unwrap_or(two.k);
        if !(1..=crate::model::half::MAX_K).contains(&k) {
            return Err(format!(
                "the 3D k is {k}; it must be 1 to {}",
                crate::model::half::MAX_K
            ));
        }
        let playback = state.playback.unwrap_or(PlaybackState {
            step: two.step,
            live: two.live,
        });
        let obb_pair = state.obb_pair.map(|p| p.check()).transpose()?;
        let collision = state.collision.map(|c| c.check()).transpose()?;
        let (mesh, note) = match &state.mesh {
            MeshState::File(name) => {
                let name = shorten(name, MAX_NAME_CHARS);
                (
                    MeshSource::Builtin(DEFAULT_MESH.to_owned()),
                    Some(format!(
                        "The 3D view showed {name}, a file: drop it on the page again to see it \
                         (the lab keeps only its name). The built-in bunny is shown meanwhile."
                    )),
                )
            }
            MeshState::Builtin(slug) => (MeshSource::Builtin(slug.clone()), None),
        };
        Ok(Self {
            shown: state.shown,
            restore: Restore3d {
                mesh,
                half: RestoreHalf {
                    settings,
                    compare,
                    update: [
                        state.structure.update.into(),
                        state
                            .compare
                            .map_or_else(Default::default, |c| c.update.into()),
                    ],
                    task: state.task.map_or(two.task, Into::into),
                    variant: state.variant.map_or(two.variant, Into::into),
                    k,
                    step: playback.step,
                    live: playback.live,
                },
                placement: Placement3d {
                    camera,
                    ray,
                    point,
                    radius,
                },
                volumes: state.volumes.map(Into::into).unwrap_or_default(),
                obb_pair,
                collision,
            },
            note,
        })
    }
}

fn camera_state(camera: &OrbitCamera) -> CameraState {
    CameraState {
        target: stored3(camera.target),
        distance: Coord(camera.distance),
        yaw: Coord(camera.yaw),
        pitch: Coord(camera.pitch),
    }
}

fn stored3(p: Vec3) -> StoredPoint3 {
    [Coord(p.x), Coord(p.y), Coord(p.z)]
}

/// A finite number, or why not (the [`Coord`] reader already bounds the magnitude).
fn finite(what: &str, value: Coord) -> Result<f32, String> {
    if value.0.is_finite() {
        Ok(value.0)
    } else {
        Err(format!("{what} is {}; it must be a finite number", value.0))
    }
}

fn point3(what: &str, p: StoredPoint3) -> Result<Vec3, String> {
    Ok(Vec3::new(
        finite(what, p[0])?,
        finite(what, p[1])?,
        finite(what, p[2])?,
    ))
}
