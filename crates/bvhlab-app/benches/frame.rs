//! The CPU cost of one lab frame with 10,000 segments while a ray is dragged: the query, the
//! UI, the drawing and egui's tessellation into triangles — everything but the GPU's
//! rasterisation. The frame budget at 60 frames per second is 16.7 ms.
//!
//! And what the page's mirror for screen readers ([`bvhlab_app::a11y`]) adds to a frame while
//! a query plays on the same scene (its first 24 steps, a frame each, per iteration: divide
//! by 24 for a frame; the labs with and without it take turns, so that they share the
//! machine's load), as the web page runs it: egui builds its AccessKit tree
//! only on the passes whose tree the page takes, every 200 ms (every 12th frame at 60 frames
//! per second), and the mirror works out the page's changes from it; against the same frames
//! without the mirror. `with the mirror, every frame's tree` is the cost of building the
//! tree on every pass (the first version, and what a platform adapter asks for).
//!
//! `cargo bench -p bvhlab-app --bench frame`

use std::hint::black_box;
use std::time::{Duration, Instant};

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

/// Draws a ray from the canvas's left edge to the middle of its right edge, and shows a
/// frame with it; returns the ray.
fn ray_across(ctx: &egui::Context, app: &mut LabApp) -> RayHandles {
    let screen = app.canvas_screen();
    let rect = screen.rect;
    let ray = RayHandles {
        origin: screen.to_world(pos2(rect.left() + 20.0, rect.center().y)),
        target: screen.to_world(rect.right_center()),
    };
    app.apply(Action2d::SetRay(Some(ray)))
        .expect("a ray across the canvas");
    frame(ctx, app);
    ray
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
        // The first ray before timing, so that the check below holds when a filter skips
        // this benchmark.
        let RayHandles { origin, target } = ray_across(&ctx, &mut app);
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
const FRAMES_PER_PAGE_UPDATE: usize = 12;

/// Frames per iteration: playback's first steps, one a frame, so that every variant times
/// the same frames (a frame's cost follows the step shown).
const FRAMES_PER_RUN: usize = 2 * FRAMES_PER_PAGE_UPDATE;

/// A lab playing the 10k-segment preset's ray query, with or without the mirror.
struct Player {
    ctx: egui::Context,
    app: LabApp,
    mirror: Mirror,
    /// egui builds its tree on every `every`-th frame; `None`: never (no mirror).
    every: Option<usize>,
}

impl Player {
    fn new(every: Option<usize>) -> Self {
        let ctx = egui::Context::default();
        let mut app = LabApp::with([Action2d::LoadPreset(Preset::TenThousand).into()]);
        frame(&ctx, &mut app);
        frame(&ctx, &mut app);
        ray_across(&ctx, &mut app);
        let steps = app.lab().steps();
        assert!(steps >= FRAMES_PER_RUN, "{steps} steps to play");
        Self {
            ctx,
            app,
            mirror: Mirror::new(),
            every,
        }
    }

    /// Frame `i` of a run (step `i` shown), as the page runs it: egui builds its tree on the
    /// frames whose tree the page takes, and the mirror works out the page's changes then.
    /// Returns the frame's time.
    fn frame(&mut self, i: usize) -> Duration {
        let start = Instant::now();
        self.app.apply(PlaybackAction::GoTo(i)).expect("a step");
        match self.every {
            Some(every) if i.is_multiple_of(every) => self.ctx.enable_accesskit(),
            _ => self.ctx.disable_accesskit(),
        }
        let mirror = &mut self.mirror;
        black_box(frame_then(&self.ctx, &mut self.app, |output| {
            if let Some(update) = output.platform_output.accesskit_update.take() {
                mirror.update(update);
                if i.is_multiple_of(FRAMES_PER_PAGE_UPDATE) {
                    black_box(mirror.changes());
                }
            }
        }));
        start.elapsed()
    }
}

/// The three labs play in turns, a frame each, in every iteration of every benchmark of the
/// group, and each benchmark counts the time of its own lab's frames: on a shared machine the
/// three see the same load, so the ratio of their times is the mirror's cost.
fn playing_with_the_mirror(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_10k_segments_playing_24_frames");
    let variants = [
        ("without the mirror", None),
        ("with the mirror", Some(FRAMES_PER_PAGE_UPDATE)),
        ("with the mirror, every frame's tree", Some(1)),
    ];
    let mut players: Vec<Player> = variants
        .iter()
        .map(|(_, every)| Player::new(*every))
        .collect();
    for (timed, (name, _)) in variants.iter().enumerate() {
        group.bench_function(*name, |b| {
            b.iter_custom(|iters| {
                let mut time = Duration::ZERO;
                for _ in 0..iters {
                    for i in 1..=FRAMES_PER_RUN {
                        for (p, player) in players.iter_mut().enumerate() {
                            let t = player.frame(i);
                            if p == timed {
                                time += t;
                            }
                        }
                    }
                }
                time
            });
        });
    }
    group.finish();
    for player in &mut players {
        // A page update's worth, so that the check holds when a filter skipped the group.
        for i in 1..=FRAMES_PER_PAGE_UPDATE {
            player.frame(i);
        }
        assert_eq!(
            !player.mirror.is_empty(),
            player.every.is_some(),
            "the mirror holds the tree exactly when AccessKit is on"
        );
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = dragging_a_ray, playing_with_the_mirror
}
criterion_main!(benches);
