//! The native window: its state kept in a file, and a panicking frame caught (the window
//! stays; the lab goes back to its last saved state and says so).

use crate::common;

use bvhlab::glam::Vec2;
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::structures::{BuildSettings, StructureKind};
use bvhlab_app::model::{Action, Action2d, HalfAction};
use bvhlab_app::native::NativeLab;
use egui_kittest::Harness;

/// The lab's frames, with a test switch that makes the next frame panic.
struct Guarded {
    lab: NativeLab,
    panic_next: bool,
    time: f64,
}

fn harness(lab: NativeLab) -> Harness<'static, Guarded> {
    let state = Guarded {
        lab,
        panic_next: false,
        time: 0.0,
    };
    Harness::builder().with_size(common::WINDOW).build_ui_state(
        |ui, g: &mut Guarded| {
            g.time += 1.0; // a second a frame: every change is saved at once
            let panic_now = std::mem::take(&mut g.panic_next);
            g.lab.frame(ui, g.time, |app, ui| {
                app.show(ui);
                assert!(!panic_now, "a bug in a frame, for the test");
            });
        },
        state,
    )
}

/// Applies `action` to the lab between frames (as the panels ask for it).
fn apply(h: &mut Harness<'_, Guarded>, action: impl Into<Action>) {
    let action = action.into();
    if let Err(e) = h.state_mut().lab.app.apply(action.clone()) {
        panic!("{action:?} was refused: {e}");
    }
}

/// The 2D structure's settings with `kind`.
fn structure(h: &Harness<'_, Guarded>, kind: StructureKind) -> HalfAction {
    HalfAction::SetStructure(BuildSettings {
        kind,
        ..h.state().lab.app.lab().two().half.lane.settings
    })
}

fn temp_state_file(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("bvhlab-native-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir.join("nested").join("state.json")
}

#[test]
fn a_panicking_frame_goes_back_to_the_last_saved_state_and_the_window_stays() {
    let path = temp_state_file("panic");
    let mut h = harness(NativeLab::open(Some(path.clone())));
    h.run();
    apply(&mut h, Action2d::LoadPreset(Preset::QuadtreeHandful));
    let action = structure(&h, StructureKind::Bsp);
    apply(&mut h, action);
    let ray = RayHandles {
        origin: Vec2::new(0.0, 4.5),
        target: Vec2::new(1.0, 4.5),
    };
    apply(&mut h, Action2d::SetRay(Some(ray)));
    h.run();
    let saved = std::fs::read_to_string(&path).expect("the state file was written");
    assert!(saved.contains("\"bsp\""), "{saved}");

    // A change not yet saved, then a frame that panics.
    let action = structure(&h, StructureKind::Grid);
    apply(&mut h, action);
    h.state_mut().panic_next = true;
    h.state_mut().time -= 0.9; // within the autosave interval: the grid is not saved yet
    h.step();
    let lab = h.state().lab.app.lab();
    assert_eq!(
        lab.two().half.lane.settings.kind,
        StructureKind::Bsp,
        "back to the saved state"
    );
    assert_eq!(lab.two().preset, Preset::QuadtreeHandful);
    assert_eq!(lab.two().ray, Some(ray));
    let message = lab.message().unwrap_or_default();
    assert!(
        message.contains("a bug in a frame, for the test") && message.contains("last saved"),
        "{message}"
    );
    // The lab goes on: the next frames draw and answer.
    h.run();
    assert!(h.state().lab.app.report.query.is_some());
    std::fs::remove_dir_all(path.parent().and_then(|p| p.parent()).expect("dir")).ok();
}

#[test]
fn a_restart_opens_the_saved_state_and_a_broken_file_falls_back_with_a_message() {
    let path = temp_state_file("restart");
    let mut h = harness(NativeLab::open(Some(path.clone())));
    h.run();
    apply(&mut h, Action2d::LoadPreset(Preset::RandomPoints));
    h.run();
    drop(h);
    let reopened = NativeLab::open(Some(path.clone()));
    assert_eq!(reopened.app.lab().two().preset, Preset::RandomPoints);

    std::fs::write(&path, "{\"version\": 1, \"scene\": 7}").expect("write");
    let broken = NativeLab::open(Some(path.clone()));
    assert_eq!(broken.app.lab().two().preset, Preset::default());
    let message = broken.app.lab().message().unwrap_or_default();
    assert!(message.contains("could not be restored"), "{message}");
    std::fs::remove_dir_all(path.parent().and_then(|p| p.parent()).expect("dir")).ok();
}
