//! The CPU cost of one lab frame with 10,000 segments while a ray is dragged: the query, the
//! UI, the drawing and egui's tessellation into triangles — everything but the GPU's
//! rasterisation. The frame budget at 60 frames per second is 16.7 ms.
//!
//! And what the page's mirror for screen readers ([`bvhlab_app::a11y`]) adds to a frame while
//! a query plays on the same scene: egui's AccessKit tree built every frame and taken in by the
//! mirror, whose changes the page applies every 200 ms (every 12th frame at 60 frames per
//! second), against the same frames without it.
//!
//! `cargo bench -p bvhlab-app --bench frame`

use std::hint::black_box;

use bvhlab::glam::Vec2;
use bvhlab_app::LabApp;
use bvhlab_app::a11y::mirror::Mirror;
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::{Action2d, HalfAction, PlaybackAction};
use criterion::{Criterion, criterion_group, criterion_main};
use egui::{RawInput, Rect, pos2, vec2};

fn input() -> RawInput {
    RawInput {
        screen_rect: Some(Rect::from_min_size(pos2(0.0, 0.0), vec2(1280.0, 800.0))),
        ..RawInput::default()
    }
}

/// One frame: the app's UI, then tessellation. Returns the triangle count.
fn frame(ctx: &egui::Context, app: &mut LabApp) -> usize {
    frame_then(ctx, app, |_| {})
}

/// One frame, with `then` given the output before tessellation.
fn frame_then(
    ctx: &egui::Context,
    app: &mut LabApp,
    then: impl FnOnce(&mut egui::FullOutput),
) -> usize {
    let mut output = ctx.run_ui(input(), |ui| app.show(ui));
    then(&mut output);
    output.textures_delta.clear();
    let shapes = std::mem::take(&mut output.shapes);
    ctx.tessellate(shapes, output.pixels_per_point)
        .iter()
        .map(|p| match &p.primitive {
            egui::epaint::Primitive::Mesh(m) => m.indices.len() / 3,
            egui::epaint::Primitive::Callback(_) => 0,
        })
        .sum()
}

fn dragging_a_ray(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_10k_segments_ray_drag");
    for kind in [
        StructureKind::AabbTree,
        StructureKind::Grid,
        StructureKind::KdTree,
        StructureKind::BruteForce,
    ] {
        let ctx = egui::Context::default();
        let mut app = LabApp::with([Action2d::LoadPreset(Preset::TenThousand).into()]);
        let mut settings = app.lab().two().half.lane.settings;
        settings.kind = kind;
        app.apply(HalfAction::SetStructure(settings))
            .expect("every structure builds on 10,000 segments");
        // Two frames for layout, fitting the view and the first build.
        frame(&ctx, &mut app);
        frame(&ctx, &mut app);
        let rect = app.canvas_screen().rect;
        let origin = app
            .canvas_screen()
            .to_world(pos2(rect.left() + 20.0, rect.center().y));
        let target = app.canvas_screen().to_world(rect.right_center());
        let mut step = 0u32;
        group.bench_function(kind.label(), |b| {
            b.iter(|| {
                // The drag: the ray's far handle moves a little every frame.
                step = (step + 1) % 200;
                let wobble = (step as f32 * 0.05).sin() * 30.0;
                let ray = RayHandles {
                    origin,
                    target: target + Vec2::new(0.0, wobble),
                };
                app.apply(Action2d::SetRay(Some(ray)))
                    .expect("a ray across the canvas");
                black_box(frame(&ctx, &mut app))
            });
        });
        assert!(
            app.lab()
                .two()
                .half
                .lane
                .ray_outcome
                .as_ref()
                .is_some_and(bvhlab_app::model::outcome::RayOutcome::agrees)
        );
    }
    group.finish();
}

/// The page applies the mirror's changes at most every 200 ms: every 12th frame at 60 per
/// second (`MIN_GAP_MS` in `web/a11y`).
const FRAMES_PER_PAGE_UPDATE: u32 = 12;

fn playing_with_the_mirror(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_10k_segments_playing");
    for mirrored in [false, true] {
        let ctx = egui::Context::default();
        if mirrored {
            ctx.enable_accesskit();
        }
        let mut mirror = Mirror::new();
        let mut app = LabApp::with([Action2d::LoadPreset(Preset::TenThousand).into()]);
        frame(&ctx, &mut app);
        frame(&ctx, &mut app);
        let rect = app.canvas_screen().rect;
        let ray = RayHandles {
            origin: app
                .canvas_screen()
                .to_world(pos2(rect.left() + 20.0, rect.center().y)),
            target: app.canvas_screen().to_world(rect.right_center()),
        };
        app.apply(Action2d::SetRay(Some(ray)))
            .expect("a ray across the canvas");
        let mut count = 0u32;
        let name = if mirrored {
            "with the mirror"
        } else {
            "without the mirror"
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                if !app.lab().playing() {
                    app.apply(PlaybackAction::Play(true))
                        .expect("playback starts");
                }
                count += 1;
                black_box(frame_then(&ctx, &mut app, |output| {
                    if let Some(update) = output.platform_output.accesskit_update.take() {
                        mirror.update(update);
                        if count.is_multiple_of(FRAMES_PER_PAGE_UPDATE) {
                            black_box(mirror.changes());
                        }
                    }
                }))
            });
        });
        assert_eq!(
            !mirror.is_empty(),
            mirrored,
            "the mirror holds the tree exactly when AccessKit is on"
        );
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = dragging_a_ray, playing_with_the_mirror
}
criterion_main!(benches);
