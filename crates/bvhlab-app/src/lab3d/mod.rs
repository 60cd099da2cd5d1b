//! The 3D half's view: the mesh and everything in [`draw::Draw3d`] drawn by the wgpu renderer
//! ([`crate::render3d`]) through an `egui_wgpu` paint callback, with the heat map, a build's
//! progress and a legend on top. Pointer input (orbit, pan, zoom, click to cast, the gizmo)
//! becomes actions ([`input`]). Comparing two structures shows two views side by side with one
//! camera. Hovering the mesh finds the leaf holding the triangle under the pointer, which
//! the tree diagram shows; a node hovered there is lit here.
//!
//! Mirrors [`crate::lab2d`]: `mod.rs` the widget, `input.rs` the pointer, `draw.rs` what is
//! drawn (the playback's state included); and `nodes.rs` (a structure's nodes at any size),
//! `wire.rs` (shapes as segments), `heat.rs` (the heat map), `side_view.rs` (the ray seen
//! from the side, in an inset).

pub mod collision;
pub mod draw;
pub mod heat;
pub mod input;
mod keys;
pub mod nodes;
pub mod picture;
pub mod sat;
pub mod side_view;
pub mod volumes;
pub mod wire;

use std::sync::Arc;

use bvhlab::NodeId;
use bvhlab::glam::Vec3;
use egui::{Align2, Color32, FontId, Sense};

use self::draw::{Draw3d, rgba};
use crate::model::Action3d;
use crate::model::lab3d::Lab3d;
use crate::paint::colors;
use crate::render3d::gpu::{self, Frame3d, Line3d, Marker, MeshData};
use crate::ui_state::Cx;

/// The view's background.
pub const BACKGROUND: Color32 = Color32::from_rgb(24, 26, 32);

/// The 3D view's state between frames.
pub struct ViewState {
    /// The gizmo handle being dragged, if any.
    pub dragging: Option<input::Handle>,
    /// The handle the arrow keys move, picked with R (`None`: they turn the camera).
    pub key_handle: Option<input::Handle>,
    /// The view's area on screen (both halves when comparing), set each frame.
    pub rect: egui::Rect,
    /// The traversal-cost heat map: its tracing and images.
    pub heat: heat::HeatMap,
    /// What each half of the view drew in the last frame (one list, or two when
    /// comparing).
    pub drawn: Vec<Draw3d>,
    /// The side view's inset as last drawn (when a ray is asked about).
    pub side: Option<side_view::SideView>,
    /// The mesh's triangles in the GPU's layout, made once per mesh (shared with the paint
    /// callback).
    mesh_gpu: Option<Arc<MeshData>>,
}

impl Default for ViewState {
    fn default() -> Self {
        Self {
            dragging: None,
            key_handle: None,
            rect: egui::Rect::NOTHING,
            heat: heat::HeatMap::default(),
            drawn: Vec::new(),
            side: None,
            mesh_gpu: None,
        }
    }
}

impl ViewState {
    /// The mesh for the GPU, made when the mesh changed.
    fn mesh_gpu(&mut self, lab: &Lab3d) -> Option<Arc<MeshData>> {
        let mesh = lab.mesh.as_ref()?;
        if self
            .mesh_gpu
            .as_ref()
            .is_none_or(|m| m.revision != mesh.revision)
        {
            self.mesh_gpu = Some(Arc::new(MeshData {
                revision: mesh.revision,
                positions: mesh.mesh.positions().iter().map(Vec3::to_array).collect(),
                indices: mesh.mesh.indices().to_vec(),
            }));
        }
        self.mesh_gpu.clone()
    }
}

/// Shows the 3D view in `ui`'s remaining space and turns its input into actions.
pub fn view(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    cx.ui.view3d.rect = rect;
    cx.ui.drawing = Some(response.id);
    let halves = crate::lab2d::halves(rect, lab.half.compare.is_some());
    if lab.framing && halves[0].is_positive() {
        cx.act(Action3d::Frame {
            aspect: halves[0].aspect_ratio(),
        });
    }
    // Input goes through the first half's projection (both show the same camera).
    input::handle_input(cx, &response, halves[0]);
    keys::handle_keys(cx, ui, halves[0], response.id);
    if cx.ui.link_hover
        && cx.ui.view3d.dragging.is_none()
        && !response.dragged()
        && let Some(p) = response.hover_pos()
        && let Some(i) = halves.iter().position(|r| r.contains(p))
    {
        cx.ui.hovered = leaf_under(lab, i, halves[i], p).map(|n| (i, n));
    }
    let mesh = cx.ui.view3d.mesh_gpu(lab);
    let painter = ui.painter_at(rect);
    let mut drawn_lists = Vec::with_capacity(halves.len());
    // What Predict's question waiting is about, lit in the main lane.
    let asked = cx.lab.predict_about();
    for (i, half) in halves.iter().enumerate() {
        let hovered = cx
            .ui
            .hovered
            .filter(|(lane, _)| *lane == i)
            .map(|(_, node)| node);
        let lit = draw::Lit {
            node: hovered,
            volume: cx.ui.canvas.volume_hover,
        };
        let drawn = draw::draw(lab, i, *half, i == 0, lit, &asked);
        if cx.ui.render_state.is_some() {
            let id = ui.make_persistent_id(("3d view", i));
            gpu::paint_3d(ui, *half, id, frame(lab, mesh.clone(), &drawn));
        } else {
            painter.rect_filled(*half, 0.0, BACKGROUND);
            painter.text(
                half.center(),
                Align2::CENTER_CENTER,
                "The 3D view draws with wgpu (WebGPU or WebGL2), which is not available here.",
                FontId::proportional(14.0),
                Color32::LIGHT_GRAY,
            );
        }
        if i == 0 {
            heat::overlay(cx, ui, *half);
        }
        if drawn.level_cut {
            painter.text(
                half.left_bottom() + egui::vec2(8.0, -8.0),
                Align2::LEFT_BOTTOM,
                format!(
                    "this level has more than {} nodes: only the first are drawn",
                    draw::LEVEL_CAP
                ),
                FontId::proportional(12.0),
                colors::PRUNED,
            );
        }
        let lane = lab.half.lane_at(i);
        if let Some(fraction) = lane.building() {
            painter.text(
                half.center_top() + egui::vec2(0.0, 24.0),
                Align2::CENTER_CENTER,
                format!(
                    "building the {}: {:.0}%",
                    lane.settings.kind.label_in(3),
                    fraction * 100.0
                ),
                FontId::proportional(16.0),
                Color32::WHITE,
            );
        }
        if lab.half.compare.is_some() {
            crate::lab2d::lane_title(
                &painter.with_clip_rect(*half),
                *half,
                &lab.half.lane_name(i),
            );
        }
        drawn_lists.push(drawn);
    }
    cx.ui.view3d.drawn = drawn_lists;
    if lab.half.compare.is_some() {
        painter.vline(
            halves[0].right() + 2.0,
            rect.y_range(),
            egui::Stroke::new(2.0, Color32::from_gray(70)),
        );
    }
    // A clicked ray runs straight into the screen: the inset shows it from the side.
    cx.ui.view3d.side = side_view::side_view(lab, lab.half.lane_at(0), halves[0], &painter);
    keys::draw_aim(ui, &painter, halves[0], response.id);
    keys::draw_picked(&painter, lab, halves[0], cx.ui.view3d.key_handle);
}

/// The leaf of lane `index`'s structure holding the triangle under `pointer` in the view of
/// `rect` (the first the camera's ray through it hits), when the structure is listed.
fn leaf_under(lab: &Lab3d, index: usize, rect: egui::Rect, pointer: egui::Pos2) -> Option<NodeId> {
    let built = lab.half.lane_at(index).current(lab.revision())?;
    let pixel = bvhlab::glam::Vec2::new(pointer.x - rect.min.x, pointer.y - rect.min.y);
    let size = bvhlab::glam::Vec2::new(rect.width(), rect.height());
    let ray = lab.camera.ray_through(pixel, size)?;
    let hit = built.built.ray_first_hit(&ray, &mut ()).answer?;
    let leaf = (*built.leaf_of.get(hit.prim)?)?;
    Some(NodeId(leaf))
}

/// The mesh and the draw list as the renderer's frame.
fn frame(lab: &Lab3d, mesh: Option<Arc<MeshData>>, drawn: &Draw3d) -> Frame3d {
    let line = |s: &wire::Segment| Line3d {
        a: s.a.to_array(),
        b: s.b.to_array(),
        color: s.color,
        width_px: s.width,
    };
    let mut triangles = Vec::new();
    for polygon in &drawn.polygons {
        let c = &polygon.corners;
        for i in 1..c.len().saturating_sub(1) {
            triangles.push(gpu::ColorTriangle {
                a: c[0].to_array(),
                b: c[i].to_array(),
                c: c[i + 1].to_array(),
                color: polygon.color,
            });
        }
    }
    let mesh_alpha = if lab.display.xray { 0.35 } else { 1.0 };
    Frame3d {
        camera: lab.camera,
        background: rgba(BACKGROUND, 1.0),
        mesh,
        mesh_color: rgba(colors::SCENE, mesh_alpha),
        highlights: drawn.highlights.clone(),
        lines: drawn.lines.iter().map(line).collect(),
        overlay_lines: drawn.overlay.iter().map(line).collect(),
        triangles,
        markers: drawn
            .dots
            .iter()
            .map(|d| Marker {
                pos: d.at.to_array(),
                radius_px: d.radius,
                color: d.color,
            })
            .collect(),
    }
}
