//! The 2D view's keyboard: R picks the handle the arrow keys move (the ray's start, its point,
//! the query point), one handle per press, however many presses one frame gets.

use bvhlab::glam::Vec2;
use bvhlab_app::model::Action2d;
use bvhlab_app::model::lab2d::RayHandles;
use egui::Key;

use crate::common::{act, lab, settle};

/// The status line's message.
fn message(h: &egui_kittest::Harness<'_, bvhlab_app::LabApp>) -> String {
    h.state().lab().message().unwrap_or_default().to_owned()
}

#[test]
fn every_press_of_r_picks_the_next_handle_even_two_in_one_frame() {
    let mut h = lab();
    act(
        &mut h,
        Action2d::SetRay(Some(RayHandles {
            origin: Vec2::new(1.0, 1.0),
            target: Vec2::new(5.0, 2.0),
        })),
    );
    act(&mut h, Action2d::SetPoint(Some(Vec2::new(3.0, 4.0))));
    h.key_press(Key::R);
    settle(&mut h);
    assert!(message(&h).contains("the ray's start e"), "{}", message(&h));
    // A slow frame (software rendering) may get two presses: both count, as arrows do. (The
    // harness runs a frame per queued event, so both go into one frame's input.)
    for _ in 0..2 {
        for pressed in [true, false] {
            h.input_mut().events.push(egui::Event::Key {
                key: Key::R,
                pressed,
                repeat: false,
                modifiers: egui::Modifiers::default(),
                physical_key: None,
            });
        }
    }
    settle(&mut h);
    assert!(message(&h).contains("the query point q"), "{}", message(&h));
    // And the arrows move that handle: the point, not the ray.
    let ray = h.state().lab().two().ray;
    let point = h.state().lab().two().point.expect("a point");
    h.key_press(Key::ArrowRight);
    settle(&mut h);
    let moved = h.state().lab().two().point.expect("still a point");
    assert!(
        moved.x > point.x && moved.y == point.y,
        "{point} -> {moved}"
    );
    assert_eq!(h.state().lab().two().ray, ray);
}
