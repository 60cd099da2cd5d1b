//! The CPU cost of one lab frame with 10,000 segments while a ray is dragged: the query, the
//! UI, the drawing and egui's tessellation into triangles — everything but the GPU's
//! rasterisation. The frame budget at 60 frames per second is 16.7 ms.
//!
//! `cargo bench -p bvhlab-app --bench frame`

use std::hint::black_box;

use bvhlab::glam::Vec2;
use bvhlab_app::LabApp;
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::{Action2d, HalfAction};
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
    let mut output = ctx.run_ui(input(), |ui| app.show(ui));
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

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = dragging_a_ray
}
criterion_main!(benches);
