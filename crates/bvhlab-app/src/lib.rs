//! bvh-lab's interactive lab (the lecture in ../shared/LECTURE.md): draw a 2D scene or open a
//! 3D mesh, fit bounding volumes, build a spatial structure, and drag rays and query points
//! through it, step by step.
//!
//! The lab only consumes what the core reports: each structure's
//! [`Outline`](bvhlab::Outline) to draw it, query answers and costs, and the observer's
//! [`Event`](bvhlab::Event)s to show what a query visited, culled and pruned.
//!
//! One model, changed only by actions, and views that read it:
//! - [`model`]: the lab's state with no egui in it ([`model::Lab`]), changed only by
//!   [`model::Lab::apply`] with an [`model::Action`]; the 2D and 3D halves are mirrors around
//!   one generic half (structures, question, playback) over a segment or a triangle.
//! - [`app`]: the frame ([`LabApp`]): input, panels and views say what they want as actions,
//!   applied once the frame is drawn; [`ui_state`]: what the UI keeps that is not the lab's
//!   (panels shown, hover, a drag in progress, caches).
//! - [`panels`]: one file per panel, in the lecture's order; "Step through"; the tree
//!   diagrams; the status line; export.
//! - [`lab2d`] and [`lab3d`]: the two views, laid out alike (the widget, `input`, `draw`);
//!   [`render3d`]: the wgpu renderer and the heat map; [`tree_diagram`]: the tree widget.
//! - [`pseudocode`]: each algorithm's listing and the line of each event; [`paint`]: the
//!   canvas's painter and the lab's colours.
//! - [`persist`]: scene files, share links and the state kept across reloads; [`embed`]:
//!   address parameters and the scripting API for course pages; [`report`]: the lab's state
//!   for the page; [`export`]: SVG and PNG for slides; `native` and `web`: the two shells.
//!
//! The feature `gui` (on by default) is the lab itself: egui, eframe and wgpu, and every
//! module above that draws. Without it the crate is the lab's model alone: [`model`],
//! [`address`], [`lessons`], [`pseudocode`] and [`persist`] (files, links, saved state), which
//! the fuzz targets build (`fuzz/`: instrumented, eframe and wgpu would be most of the build).

#[cfg(feature = "gui")]
pub mod a11y;
pub mod address;
#[cfg(feature = "gui")]
pub mod app;
#[cfg(feature = "gui")]
pub mod embed;
#[cfg(feature = "gui")]
pub mod export;
#[cfg(feature = "gui")]
pub mod frame_clock;
#[cfg(feature = "gui")]
pub mod lab2d;
#[cfg(feature = "gui")]
pub mod lab3d;
#[cfg(feature = "gui")]
pub mod legend;
pub mod lessons;
pub mod model;
#[cfg(all(feature = "gui", not(target_arch = "wasm32")))]
pub mod native;
#[cfg(feature = "gui")]
pub mod paint;
#[cfg(feature = "gui")]
pub mod panels;
pub mod persist;
pub mod pseudocode;
#[cfg(feature = "gui")]
pub mod render3d;
#[cfg(feature = "gui")]
pub mod report;
#[cfg(feature = "gui")]
pub mod theme;
#[cfg(feature = "gui")]
pub mod tree_diagram;
#[cfg(feature = "gui")]
pub mod ui_state;
#[cfg(all(feature = "gui", target_arch = "wasm32"))]
pub mod web;

#[cfg(feature = "gui")]
pub use app::LabApp;
