//! bvh-lab's interactive lab (the lecture in ../shared/LECTURE.md, in 2D): draw a scene, fit
//! bounding volumes, build a spatial structure, and drag rays and query points through it.
//!
//! The lab only consumes what the core reports: each structure's
//! [`Outline`](bvhlab::Outline) to draw it, query answers and costs, and the observer's
//! [`Event`](bvhlab::Event)s to show what a query visited, culled and pruned.
//!
//! - [`app`]: the state and the layout; [`panels`]: the controls; [`canvas`]: input and drawing.
//! - [`scene`], [`presets`]: what is drawn; [`structures`]: one dispatch over the core's
//!   structures; [`query`]: queries and their events; [`volumes`]: lecture §2 as data.
//! - [`recording`], [`playback`]: a query or build recorded as events and folded at any step;
//!   [`pseudocode`]: each algorithm's listing and the line of each event; [`stepper`],
//!   [`build_view`]: the "Step through" panel; [`tree_view`], [`tree_panel`]: the tree diagrams;
//!   [`lane`]: one structure and what is derived from it (two when comparing).
//! - [`export`], [`export_ui`]: SVG and PNG for slides.
//! - [`report`]: the lab's state for the page (the browser test and screen readers read it).
//! - [`persist`]: scene files, share links and the state kept across reloads; `native`: the
//!   native window's saved state and caught panics; [`embed`]: address parameters and the
//!   scripting API for course pages.

pub mod app;
pub mod build_view;
pub mod canvas;
pub mod embed;
pub mod export;
pub mod export_ui;
pub mod frame_clock;
pub mod lab3d;
pub mod lane;
#[cfg(not(target_arch = "wasm32"))]
pub mod native;
pub mod paint;
pub mod panels;
pub mod persist;
pub mod playback;
pub mod presets;
pub mod pseudocode;
pub mod query;
pub mod recording;
pub mod report;
pub mod scene;
pub mod stepper;
pub mod structures;
pub mod tool;
pub mod tree_panel;
pub mod tree_view;
pub mod view;
pub mod view3d;
pub mod volumes;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use app::LabApp;
