//! The 3D view's keyboard parity with 2D (issue 32, part 3): R picks the ray's start, its
//! point or the query point, the arrow keys move the picked handle along the camera's right
//! and up axes, and R after the last handle gives the arrows back to the camera. Driven
//! headless, key by key, as a keyboard user drives it.

use bvhlab::glam::Vec3;
use bvhlab_app::lab3d::input::Handle;
use bvhlab_app::model::Action3d;
use egui::Key;

use crate::common::{act, click, press};
use crate::view3d::{handle_on_screen, lab_3d, three};

/// The status line's message.
fn message(h: &egui_kittest::Harness<'_, bvhlab_app::LabApp>) -> String {
    h.state().lab().message().unwrap_or_default().to_owned()
}

#[test]
fn r_and_the_arrows_move_the_rays_start_and_point_along_the_cameras_axes() {
    let mut h = lab_3d();
    click(&mut h, "casts a ray");
    let camera = three(&h).camera;
    let basis = camera.basis();
    // No ray (the one the lab opens with is cleared): R makes one across the middle of the
    // view and picks its start.
    act(&mut h, Action3d::SetRay(None));
    press(&mut h, Key::R);
    let made = three(&h).ray.expect("R makes a ray");
    assert!(
        made.dir().normalize().dot(basis.right) > 0.999,
        "left to right"
    );
    assert!(message(&h).contains("the ray's start e"), "{}", message(&h));
    // Three presses right: the start moves along the camera's right axis only, the
    // direction is kept, and the camera stays.
    let before = handle_on_screen(&h, Handle::RayOrigin);
    for _ in 0..3 {
        press(&mut h, Key::ArrowRight);
    }
    let moved = three(&h).ray.expect("still a ray");
    let step = moved.origin() - made.origin();
    assert!(step.dot(basis.right) > 1e-3, "moved right: {step}");
    assert!(
        step.dot(basis.up).abs() < 1e-4 * step.length(),
        "not up: {step}"
    );
    assert!(
        step.dot(basis.forward).abs() < 1e-4 * step.length(),
        "not in depth: {step}"
    );
    assert_eq!(moved.dir(), made.dir());
    assert_eq!(
        three(&h).camera,
        camera,
        "the arrows moved the handle, not the camera"
    );
    // 30 screen points on screen, as three drags of 10 would.
    let after = handle_on_screen(&h, Handle::RayOrigin);
    assert!(
        ((after - before).x - 30.0).abs() < 1.0,
        "{before:?} -> {after:?}"
    );
    assert!((after - before).y.abs() < 1.0, "{before:?} -> {after:?}");
    // R: the point s; Up turns the ray upward about its start, which stays.
    press(&mut h, Key::R);
    assert!(message(&h).contains("the ray's point s"), "{}", message(&h));
    press(&mut h, Key::ArrowUp);
    let turned = three(&h).ray.expect("still a ray");
    assert_eq!(turned.origin(), moved.origin());
    assert!(turned.dir().dot(basis.up) > 1e-3, "up: {}", turned.dir());
    // Shift: one point a press, a tenth of the turn.
    let tip = handle_on_screen(&h, Handle::RayDirection);
    h.key_press_modifiers(egui::Modifiers::SHIFT, Key::ArrowDown);
    h.run();
    let fine = handle_on_screen(&h, Handle::RayDirection);
    assert!(((fine - tip).y - 1.0).abs() < 0.3, "{tip:?} -> {fine:?}");
    // R again: the camera. The arrows turn it, and the ray stays.
    press(&mut h, Key::R);
    assert!(message(&h).contains("turn the camera"), "{}", message(&h));
    let ray = three(&h).ray;
    press(&mut h, Key::ArrowLeft);
    assert_ne!(three(&h).camera, camera, "the camera turned");
    assert_eq!(three(&h).ray, ray);
}

#[test]
fn with_the_point_tool_r_picks_the_query_point_and_the_arrows_move_it_in_the_view_plane() {
    let mut h = lab_3d();
    click(&mut h, "places the point");
    let camera = three(&h).camera;
    let basis = camera.basis();
    let start = three(&h).point.expect("a point is placed on load");
    press(&mut h, Key::R);
    assert!(message(&h).contains("the query point q"), "{}", message(&h));
    for key in [Key::ArrowLeft, Key::ArrowLeft, Key::ArrowDown] {
        press(&mut h, key);
    }
    let moved = three(&h).point.expect("still placed");
    let step: Vec3 = moved - start;
    assert!(step.dot(basis.right) < -1e-3, "left: {step}");
    assert!(step.dot(basis.up) < -1e-3, "down: {step}");
    assert!(
        step.dot(basis.forward).abs() < 1e-4 * step.length(),
        "in the plane: {step}"
    );
    assert_eq!(three(&h).camera, camera);
    // The answer follows the point, and agrees with brute force.
    let rec = three(&h).half.lane.recorded().expect("recorded");
    assert_eq!(rec.question.point, Some(moved));
    assert!(rec.agrees());
    // One handle with this tool: the next R gives the arrows back to the camera.
    press(&mut h, Key::R);
    assert!(message(&h).contains("turn the camera"), "{}", message(&h));
    // A tool change drops a handle the tool does not show.
    press(&mut h, Key::R);
    click(&mut h, "casts a ray");
    press(&mut h, Key::ArrowUp);
    assert_ne!(three(&h).camera, camera, "the arrows turn the camera again");
}
