//! The lab's integration tests in one test binary: each file beside this one is a module, so
//! eframe, wgpu and `egui_kittest` are linked once rather than once per file (issue 28). One
//! file's tests: `cargo test -p bvhlab-app --test all persist::`.

mod common;

mod a11y;
mod a11y_names;
mod collision2d;
mod collision3d;
mod deform3d;
mod embed;
mod export;
mod first_hour_words;
mod heatmap;
mod keys2d;
mod layout;
mod lesson_layout;
mod lesson_steps;
mod lesson_writer;
mod lessons;
mod native;
mod persist;
mod playback;
mod predict;
mod predict_shown;
mod pseudocode;
mod readable;
mod refit;
mod render3d;
mod sat3d;
mod shaders;
mod shown_as_said;
mod stepping;
mod teacher_lessons;
mod tree_diagram;
mod ui;
mod view3d;
mod view3d_gains;
mod view3d_keys;
mod volumes3d;
