//! The 3D view's pointer: drag to orbit (shift-drag or right-drag to pan), scroll to zoom,
//! click the mesh to cast a ray from the camera or to place the query point, and drag the
//! gizmo's handles to move the ray's origin or direction or the point, freely in the view's
//! plane or along one axis. The handle held is the view's own state; the camera, ray and
//! point change through actions.

use bvhlab::Ray3;
use bvhlab::glam::{Vec2, Vec3};
use egui::{Pos2, Rect, Response};

use crate::model::Action3d;
use crate::model::lab3d::Lab3d;
use crate::model::orbit_camera::OrbitCamera;
use crate::model::tools::Tool3d;
use crate::ui_state::Cx;

/// A gizmo handle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Handle {
    /// The ray's origin, moved in the view's plane.
    RayOrigin,
    /// The ray's direction: the handle sits one gizmo length along it.
    RayDirection,
    /// The query point, moved in the view's plane.
    Point,
    /// An axis arrow (0 = x, 1 = y, 2 = z) from `base`: drags along that axis.
    Axis(usize, Vec3),
}

/// How close to a handle (in points) a press grabs it.
const GRAB_RADIUS: f32 = 10.0;

/// The gizmo's length at `at`: a constant share of the view's size (as gizmos in modelling
/// programs keep their size on screen), measured at the point's depth.
fn gizmo_length(lab: &Lab3d, rect: Rect, at: Vec3) -> f32 {
    let camera = &lab.camera;
    let depth = (at - camera.eye())
        .dot(camera.basis().forward)
        .max(camera.distance * 0.1);
    // In a view narrower than tall, a share of its width.
    let aspect = if rect.is_positive() {
        rect.aspect_ratio().min(1.0)
    } else {
        1.0
    };
    depth * (camera.fov_y * 0.5).tan() * 0.3 * aspect
}

/// The handles shown, with where each is.
pub fn handles(lab: &Lab3d, rect: Rect) -> Vec<(Handle, Vec3)> {
    let mut out = Vec::new();
    let base = match lab.tool {
        Tool3d::Ray => lab.ray.map(|ray| {
            let origin = ray.origin();
            out.push((Handle::RayOrigin, origin));
            let dir = ray.dir().normalize_or_zero();
            out.push((
                Handle::RayDirection,
                origin + dir * gizmo_length(lab, rect, origin),
            ));
            origin
        }),
        Tool3d::Point => lab.point.inspect(|&p| out.push((Handle::Point, p))),
    };
    if let Some(base) = base {
        let len = gizmo_length(lab, rect, base) * 0.7;
        for (axis, unit) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            out.push((Handle::Axis(axis, base), base + unit * len));
        }
    }
    out
}

/// A point of the view in the viewport's pixels (top-left origin).
fn local(rect: Rect, p: Pos2) -> Vec2 {
    Vec2::new(p.x - rect.min.x, p.y - rect.min.y)
}

/// Turns the pointer over the view at `rect` into actions: the camera, the ray, the point.
pub fn handle_input(cx: &mut Cx<'_>, response: &Response, rect: Rect) {
    let lab = cx.lab.three();
    let size = Vec2::new(rect.width(), rect.height());
    let mut camera = lab.camera;
    if response.hovered() {
        let scroll = response.ctx.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            camera.zoom((-scroll * 0.002).exp());
        }
    }
    // A handle is grabbed where the press began, not where the drag was recognised.
    let press = response.ctx.input(|i| i.pointer.press_origin());
    if response.drag_started()
        && let Some(pos) = press.or_else(|| response.interact_pointer_pos())
    {
        let pointer = local(rect, pos);
        cx.ui.view3d.dragging = handles(lab, rect)
            .into_iter()
            .filter_map(|(h, at)| {
                let screen = lab.camera.project(at, size)?;
                let d = screen.distance(pointer);
                (d <= GRAB_RADIUS).then_some((h, d))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(h, _)| h);
    }
    if response.dragged() {
        let delta = response.drag_delta();
        let delta = Vec2::new(delta.x, delta.y);
        let (shift, secondary) = response.ctx.input(|i| {
            (
                i.modifiers.shift,
                i.pointer.secondary_down() || i.pointer.middle_down(),
            )
        });
        match cx.ui.view3d.dragging {
            Some(handle) => {
                if let Some(action) = drag_handle(lab, rect, handle, delta, size) {
                    cx.act(action);
                }
            }
            None if shift || secondary => camera.pan(delta, size.y),
            None => camera.orbit(delta),
        }
    }
    if response.drag_stopped() {
        cx.ui.view3d.dragging = None;
    }
    if camera != lab.camera {
        cx.act(Action3d::SetCamera(camera));
    }
    if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
        && let Some(action) = click(lab, &lab.camera, local(rect, pos), size)
    {
        cx.act(action);
    }
}

/// A click at `pixel` of a view of `size` seen through `camera`: casts a ray from the camera,
/// or puts the point where the click meets the mesh.
pub(super) fn click(
    lab: &Lab3d,
    camera: &OrbitCamera,
    pixel: Vec2,
    size: Vec2,
) -> Option<Action3d> {
    let ray = camera.ray_through(pixel, size)?;
    let ray = Ray3::new(ray.origin(), ray.dir().normalize_or_zero()).ok()?;
    match lab.tool {
        Tool3d::Ray => Some(Action3d::SetRay(Some(ray))),
        Tool3d::Point => {
            let built = lab.half.lane.current(lab.revision())?;
            let size = lab
                .mesh
                .as_ref()
                .map_or(1.0, crate::model::mesh::Mesh3d::size);
            let hit = built.built.ray_first_hit(&ray, &mut ()).answer;
            // Just off the surface, on the camera's side, so the distance is not zero.
            let at = match hit {
                Some(h) => ray.at(h.t) - ray.dir() * size * 0.03,
                None => camera.target,
            };
            Some(Action3d::SetPoint(Some(at)))
        }
    }
}

/// What a drag of `delta` points on `handle` does to the ray or the point (also what the
/// arrow keys do to a handle R picked: `keys.rs`).
pub(super) fn drag_handle(
    lab: &Lab3d,
    rect: Rect,
    handle: Handle,
    delta: Vec2,
    size: Vec2,
) -> Option<Action3d> {
    let camera = lab.camera;
    let basis = camera.basis();
    // World units per point at a given point's depth; at least a tenth of the way to the
    // target's, so that a ray's start at the eye (a clicked ray's) moves when the arrow keys
    // move it (the gizmo's length has the same floor).
    let per_point = |at: Vec3| {
        let depth = (at - camera.eye())
            .dot(basis.forward)
            .max(camera.distance * 0.1);
        2.0 * depth * (camera.fov_y * 0.5).tan() / size.y.max(1.0)
    };
    let in_plane = |at: Vec3| at + (basis.right * delta.x - basis.up * delta.y) * per_point(at);
    let moved = |at: Vec3, axis: usize| {
        let mut unit = Vec3::ZERO;
        unit[axis] = 1.0;
        let len = gizmo_length(lab, rect, at);
        let (Some(a), Some(b)) = (
            camera.project(at, size),
            camera.project(at + unit * len, size),
        ) else {
            return at;
        };
        let screen = b - a;
        if screen.length_squared() < 1.0 {
            return at;
        }
        at + unit * (delta.dot(screen) / screen.length_squared() * len)
    };
    let ray = |new: Result<Ray3, _>| new.ok().map(|r| Action3d::SetRay(Some(r)));
    match (handle, lab.tool) {
        (Handle::RayOrigin, _) => {
            let r = lab.ray?;
            ray(Ray3::new(in_plane(r.origin()), r.dir()))
        }
        (Handle::RayDirection, _) => {
            let r = lab.ray?;
            let tip =
                r.origin() + r.dir().normalize_or_zero() * gizmo_length(lab, rect, r.origin());
            ray(Ray3::new(
                r.origin(),
                (in_plane(tip) - r.origin()).normalize_or_zero(),
            ))
        }
        (Handle::Point, _) => Some(Action3d::SetPoint(Some(in_plane(lab.point?)))),
        (Handle::Axis(axis, _), Tool3d::Ray) => {
            let r = lab.ray?;
            ray(Ray3::new(moved(r.origin(), axis), r.dir()))
        }
        (Handle::Axis(axis, _), Tool3d::Point) => {
            Some(Action3d::SetPoint(Some(moved(lab.point?, axis))))
        }
    }
}
