//! The 3D view's camera: an orbit camera (yaw and pitch about a target, at a distance) and
//! the one definition of "the ray through a pixel" that picking, the heat map on the CPU and
//! the heat map's compute shader all share.
//!
//! Pixel rays are written as `dir = corner + (x + ½)·step_x + (y + ½)·step_y` with every
//! vector precomputed once per frame ([`RayFrame`]), so the shader and the CPU perform the
//! same few `f32` operations in the same order and agree on every ray.

use bvhlab::glam::{Mat4, Vec2, Vec3, Vec4};
use bvhlab::prelude::BoundingVolume;
use bvhlab::{Aabb3, Ray3};

/// An orbit camera: it looks at `target` from `distance` away, turned by `yaw` about the
/// world's y axis (up) and tilted by `pitch` above the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at (orbited, and panned with the view).
    pub target: Vec3,
    /// The eye's distance from the target (zoom), in world units; always positive.
    pub distance: f32,
    /// The turn about the up axis, in radians (0 looks along −z).
    pub yaw: f32,
    /// The tilt above the horizon, in radians, kept inside (−π/2, π/2).
    pub pitch: f32,
    /// The vertical field of view, in radians.
    pub fov_y: f32,
}

/// The steepest pitch the camera takes, short of looking straight down (where yaw would be
/// undefined and the up vector degenerate).
const MAX_PITCH: f32 = 1.55;

impl Default for OrbitCamera {
    fn default() -> Self {
        Self {
            target: Vec3::ZERO,
            distance: 3.0,
            yaw: 0.6,
            pitch: 0.35,
            fov_y: 45f32.to_radians(),
        }
    }
}

/// The camera's orthonormal frame: where it looks, its right and its up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraBasis {
    /// Unit vector from the eye towards the target.
    pub forward: Vec3,
    /// Unit vector to the right on screen.
    pub right: Vec3,
    /// Unit vector up on screen.
    pub up: Vec3,
}

/// Everything needed to make the ray of any pixel of a `width × height` image: see the
/// module comment. Pixel `(0, 0)` is the top-left one; y grows downwards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayFrame {
    /// Every ray's origin: the eye.
    pub origin: Vec3,
    /// The direction through the image's top-left corner (not normalised).
    pub corner: Vec3,
    /// The change of direction from one pixel to the next one to the right.
    pub step_x: Vec3,
    /// The change of direction from one pixel to the next one down.
    pub step_y: Vec3,
    /// The image width in pixels.
    pub width: u32,
    /// The image height in pixels.
    pub height: u32,
}

impl RayFrame {
    /// The (unnormalised) direction through the centre of pixel `(x, y)`, computed with the
    /// same operations in the same order as the compute shader does.
    pub fn direction(&self, x: u32, y: u32) -> Vec3 {
        let fx = x as f32 + 0.5;
        let fy = y as f32 + 0.5;
        Vec3::new(
            self.corner.x + self.step_x.x * fx + self.step_y.x * fy,
            self.corner.y + self.step_x.y * fx + self.step_y.y * fy,
            self.corner.z + self.step_x.z * fx + self.step_y.z * fy,
        )
    }

    /// The ray through the centre of pixel `(x, y)`; `None` only for a degenerate frame
    /// (non-finite camera), which [`OrbitCamera::ray_frame`] never makes.
    pub fn ray(&self, x: u32, y: u32) -> Option<Ray3> {
        Ray3::new(self.origin, self.direction(x, y)).ok()
    }
}

impl OrbitCamera {
    /// A camera that frames `bounds` whole, seen from the default direction. An empty box
    /// gives the default camera.
    pub fn framing(bounds: &Aabb3) -> Self {
        let mut camera = Self::default();
        camera.frame(bounds);
        camera
    }

    /// As [`frame`](Self::frame), for a view `aspect` (width / height) wide: in a view
    /// narrower than it is tall the horizontal field of view is the tighter one, and the
    /// camera backs off until the sphere fits that too.
    pub fn frame_in(&mut self, bounds: &Aabb3, aspect: f32) {
        self.frame(bounds);
        let half_h = (self.fov_y * 0.5).tan();
        let half_w = half_h * aspect;
        if aspect.is_finite() && aspect > 0.0 && half_w < half_h {
            // The same sphere, fitted to the horizontal half-angle instead.
            let ratio = (half_h.atan().sin()) / (half_w.atan().sin());
            self.distance *= ratio;
        }
    }

    /// Moves the target to the centre of `bounds` and backs off until the box's bounding
    /// sphere fits the vertical field of view; keeps yaw and pitch.
    pub fn frame(&mut self, bounds: &Aabb3) {
        if bounds.is_empty() {
            return;
        }
        let centre = (bounds.min + bounds.max) * 0.5;
        let radius = ((bounds.max - bounds.min).length() * 0.5).max(1e-6);
        if !centre.is_finite() || !radius.is_finite() {
            return;
        }
        self.target = centre;
        self.distance = radius / (self.fov_y * 0.5).sin() * 1.05;
    }

    /// The eye position.
    pub fn eye(&self) -> Vec3 {
        self.target - self.basis().forward * self.distance
    }

    /// The camera's frame.
    pub fn basis(&self) -> CameraBasis {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        // Looking down −z at yaw 0, tilted down towards the target as pitch grows.
        let forward = Vec3::new(-sy * cp, -sp, -cy * cp);
        let right = Vec3::new(cy, 0.0, -sy);
        let up = right.cross(forward);
        CameraBasis { forward, right, up }
    }

    /// The world-to-camera matrix (right-handed, looking down the camera's −z).
    pub fn view_matrix(&self) -> Mat4 {
        let CameraBasis { forward, right, up } = self.basis();
        let eye = self.eye();
        Mat4::from_cols(
            Vec4::new(right.x, up.x, -forward.x, 0.0),
            Vec4::new(right.y, up.y, -forward.y, 0.0),
            Vec4::new(right.z, up.z, -forward.z, 0.0),
            Vec4::new(-right.dot(eye), -up.dot(eye), forward.dot(eye), 1.0),
        )
    }

    /// The near and far clip distances: wide enough for a scene of about `distance` in size
    /// around the target, with the near plane far enough out for 24-bit depth.
    pub fn clip_range(&self) -> (f32, f32) {
        (self.distance * 1e-3, self.distance * 100.0)
    }

    /// The camera-to-clip matrix for an image of the given aspect ratio (width / height), in
    /// wgpu's clip space (depth 0 at the near plane, 1 at the far plane).
    pub fn projection_matrix(&self, aspect: f32) -> Mat4 {
        let (near, far) = self.clip_range();
        let f = 1.0 / (self.fov_y * 0.5).tan();
        let range = far / (near - far);
        Mat4::from_cols(
            Vec4::new(f / aspect.max(1e-6), 0.0, 0.0, 0.0),
            Vec4::new(0.0, f, 0.0, 0.0),
            Vec4::new(0.0, 0.0, range, -1.0),
            Vec4::new(0.0, 0.0, range * near, 0.0),
        )
    }

    /// World to clip space for an image of the given aspect ratio.
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection_matrix(aspect) * self.view_matrix()
    }

    /// The rays of a `width × height` image (see [`RayFrame`]).
    pub fn ray_frame(&self, width: u32, height: u32) -> RayFrame {
        let basis = self.basis();
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        let half_h = (self.fov_y * 0.5).tan();
        let half_w = half_h * w / h;
        let step_x = basis.right * (2.0 * half_w / w);
        let step_y = -basis.up * (2.0 * half_h / h);
        let corner = basis.forward - basis.right * half_w + basis.up * half_h;
        RayFrame {
            origin: self.eye(),
            corner,
            step_x,
            step_y,
            width: width.max(1),
            height: height.max(1),
        }
    }

    /// The ray from the eye through a point of a `size`-pixel viewport (pixel coordinates,
    /// top-left origin, fractional allowed): what a click casts.
    pub fn ray_through(&self, pixel: Vec2, size: Vec2) -> Option<Ray3> {
        let basis = self.basis();
        let half_h = (self.fov_y * 0.5).tan();
        let half_w = half_h * size.x / size.y.max(1e-6);
        let sx = pixel.x / size.x.max(1e-6) * 2.0 - 1.0;
        let sy = 1.0 - pixel.y / size.y.max(1e-6) * 2.0;
        let dir = basis.forward + basis.right * (sx * half_w) + basis.up * (sy * half_h);
        Ray3::new(self.eye(), dir).ok()
    }

    /// Where a world point appears in a `size`-pixel viewport (top-left origin), or `None`
    /// when it is behind the eye.
    pub fn project(&self, point: Vec3, size: Vec2) -> Option<Vec2> {
        let clip = self.view_projection(size.x / size.y.max(1e-6)) * point.extend(1.0);
        if clip.w <= 1e-9 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(Vec2::new(
            (ndc.x + 1.0) * 0.5 * size.x,
            (1.0 - ndc.y) * 0.5 * size.y,
        ))
    }

    /// Turns the camera about its target by a screen-space drag of `delta` points.
    pub fn orbit(&mut self, delta: Vec2) {
        self.turn(-delta.x * 0.008, delta.y * 0.008);
    }

    /// Turns the camera about its target by `yaw` and `pitch` radians (the pitch kept short
    /// of straight up or down).
    pub fn turn(&mut self, yaw: f32, pitch: f32) {
        self.yaw += yaw;
        self.pitch = (self.pitch + pitch).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the target (and eye) with a screen-space drag of `delta` points in a viewport
    /// `viewport_height` points tall, so the point under the pointer at the target's depth
    /// follows it.
    pub fn pan(&mut self, delta: Vec2, viewport_height: f32) {
        let basis = self.basis();
        let per_point = 2.0 * self.distance * (self.fov_y * 0.5).tan() / viewport_height.max(1.0);
        self.target += (-basis.right * delta.x + basis.up * delta.y) * per_point;
    }

    /// Whether the camera can be shown: finite target and angles, a positive finite
    /// distance and field of view.
    pub fn is_valid(&self) -> bool {
        self.target.is_finite()
            && self.distance.is_finite()
            && self.distance > 0.0
            && self.yaw.is_finite()
            && self.pitch.is_finite()
            && self.fov_y.is_finite()
            && self.fov_y > 0.0
    }

    /// Zooms by `factor` (below 1 moves closer), keeping the target.
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(1e-5, 1e7);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_pixel_ray_hits_the_target_and_projects_back() {
        let camera = OrbitCamera {
            target: Vec3::new(1.0, 2.0, 3.0),
            ..OrbitCamera::default()
        };
        let size = Vec2::new(640.0, 480.0);
        let ray = camera.ray_through(size * 0.5, size).expect("finite camera");
        let along = (camera.target - ray.origin()).dot(ray.dir()) / ray.dir().length_squared();
        let closest = ray.origin() + ray.dir() * along;
        assert!((closest - camera.target).length() < 1e-4);
        let back = camera.project(camera.target, size).expect("in front");
        assert!((back - size * 0.5).length() < 1e-3);
    }

    #[test]
    fn pixel_rays_pass_through_the_points_that_project_to_them() {
        let camera = OrbitCamera::default();
        let frame = camera.ray_frame(64, 48);
        let size = Vec2::new(64.0, 48.0);
        for (x, y) in [(0, 0), (63, 0), (10, 40), (63, 47)] {
            let ray = frame.ray(x, y).expect("finite");
            let point = ray.origin() + ray.dir() * 2.0;
            let pixel = camera.project(point, size).expect("in front");
            let want = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            assert!((pixel - want).length() < 1e-2, "{pixel} vs {want}");
            let picked = camera.ray_through(want, size).expect("finite");
            assert!(picked.dir().normalize().dot(ray.dir().normalize()) > 1.0 - 1e-6);
        }
    }

    #[test]
    fn framing_puts_the_whole_box_in_view() {
        let bounds = Aabb3::new(Vec3::new(-5.0, 0.0, 2.0), Vec3::new(1.0, 0.5, 9.0));
        let camera = OrbitCamera::framing(&bounds);
        let size = Vec2::new(100.0, 100.0);
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 {
                    bounds.min.x
                } else {
                    bounds.max.x
                },
                if i & 2 == 0 {
                    bounds.min.y
                } else {
                    bounds.max.y
                },
                if i & 4 == 0 {
                    bounds.min.z
                } else {
                    bounds.max.z
                },
            );
            let p = camera.project(corner, size).expect("in front");
            assert!(
                (0.0..=100.0).contains(&p.x) && (0.0..=100.0).contains(&p.y),
                "{p}"
            );
        }
    }

    #[test]
    fn depth_runs_from_zero_at_near_to_one_at_far() {
        let camera = OrbitCamera::default();
        let (near, far) = camera.clip_range();
        let m = camera.view_projection(1.5);
        let forward = camera.basis().forward;
        for (d, want) in [(near, 0.0), (far, 1.0)] {
            let clip = m * (camera.eye() + forward * d).extend(1.0);
            assert!(
                (clip.z / clip.w - want).abs() < 1e-4,
                "{d}: {}",
                clip.z / clip.w
            );
        }
    }

    #[test]
    fn framing_a_tall_view_fits_the_box_across_too() {
        let bounds = Aabb3::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let mut camera = OrbitCamera::default();
        camera.frame_in(&bounds, 0.5);
        let size = Vec2::new(50.0, 100.0);
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            let p = camera.project(corner, size).expect("in front");
            assert!((0.0..=50.0).contains(&p.x), "{p}");
        }
    }

    #[test]
    fn orbit_keeps_the_distance_and_bounds_the_pitch() {
        let mut camera = OrbitCamera::default();
        let before = (camera.eye() - camera.target).length();
        camera.orbit(Vec2::new(300.0, 10_000.0));
        assert!(camera.pitch <= MAX_PITCH);
        assert!(((camera.eye() - camera.target).length() - before).abs() < 1e-4);
        let basis = camera.basis();
        assert!(basis.up.is_normalized() && basis.right.dot(basis.forward).abs() < 1e-6);
    }
}
