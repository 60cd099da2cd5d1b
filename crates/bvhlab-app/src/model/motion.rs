//! The 3D mesh that moves (`bvhlab_meshio::builtin::deforms`: the twisting torus): while its
//! animation is on, every frame ([`Action::Tick`](super::Action::Tick)) moves its clock on and
//! gives the mesh its vertices at the new time, with a new revision, so that each lane
//! brings its tree up to date (a refit, or a rebuild) and the live answers, the drawn nodes
//! and the heat map follow.

use super::mesh::Mesh3d;

/// The longest step the motion takes in one frame, in seconds: after a pause (a hidden tab, a
/// slow build) the mesh goes on from where it was instead of jumping.
const MAX_STEP_SECONDS: f64 = 0.1;

/// The motion of a mesh that moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Whether the mesh moves (the "Animate" switch; on for each mesh that moves as it
    /// opens).
    pub on: bool,
    /// How far into its motion the mesh is, in seconds.
    pub seconds: f64,
    /// How many frames it has moved since it opened.
    pub frames: u64,
}

impl Default for Motion {
    fn default() -> Self {
        Self {
            on: true,
            seconds: 0.0,
            frames: 0,
        }
    }
}

/// Whether `mesh` moves: it is a built-in that does.
pub fn moves(mesh: &Mesh3d) -> bool {
    mesh.slug
        .as_deref()
        .is_some_and(bvhlab_meshio::builtin::deforms)
}

impl Motion {
    /// Back to the start of the motion, moving (a mesh just opened).
    pub fn restart(&mut self) {
        *self = Self::default();
    }

    /// Moves `mesh` on by `seconds` (at most `MAX_STEP_SECONDS`) when it moves and the
    /// motion is on, giving it `revision`. Whether it moved.
    pub fn advance(&mut self, mesh: &mut Mesh3d, seconds: f64, revision: u64) -> bool {
        if !(self.on && moves(mesh) && seconds.is_finite() && seconds > 0.0) {
            return false;
        }
        let at = self.seconds + seconds.min(MAX_STEP_SECONDS);
        let Some(moved) = mesh
            .slug
            .as_deref()
            .and_then(|slug| bvhlab_meshio::builtin::make_at(slug, at))
        else {
            return false;
        };
        self.seconds = at;
        self.frames += 1;
        mesh.replace(moved, revision);
        true
    }
}
