//! The structure's hierarchy as a node-link tree diagram, below the 2D canvas or the 3D view
//! (one widget for both: it reads only the outline's links and depths).
//!
//! The canvas shows where each node's region is; the diagram shows how the nodes hang
//! together: which are deep, which are leaves, and the path a query took down the tree. It
//! is a self-contained widget: the caller passes the outline and what to highlight (a
//! query's marks, the playback's current node, the node hovered on the canvas, the nodes a
//! build playback has made so far) and gets back the node under the pointer and the node
//! clicked, to highlight on the canvas in turn.
//!
//! - `forest.rs`: the outline's links as one clean rooted tree;
//! - `tidy.rs`: the tidy drawing (Reingold and Tilford, 1981, in its linear-time form);
//! - `layout.rs`: positions, rows for culling, grids, and the cache key;
//! - `camera.rs`: pan and zoom; `draw.rs`: painting; `describe.rs`: the tooltip;
//! - `aria.rs`: the diagram as a tree of items for a screen reader.

mod aria;
mod camera;
mod describe;
mod draw;
mod forest;
mod layout;
#[cfg(test)]
mod tests;
mod tidy;

use bvhlab::{NodeId, NodeOutline, Vector};
use egui::{Color32, Pos2, Rect, Sense, Shape, vec2};

use camera::{Camera, Viewport};
use draw::Painting;
use layout::{Arrangement, Layout, LayoutKey};

/// What the widget says instead of a diagram when the outline has no nodes. (The tree
/// panel says why before it gets here: brute force has no tree, an empty scene builds none.)
pub const EMPTY_MESSAGE: &str = "No tree to show: the structure has no nodes.";

/// Within this many points of a node's dot, the pointer is on it.
const HOVER_SLOP: f32 = 4.0;
/// The least height of the diagram, in points.
pub const MIN_HEIGHT: f32 = 80.0;

/// What the diagram highlights this frame.
#[derive(Clone, Copy, Debug)]
pub struct TreeHighlight<'a> {
    /// What a query did to each node: visited, culled and pruned nodes take
    /// [`colors::VISITED`](crate::paint::colors::VISITED), `CULLED` and `PRUNED`.
    pub marks: Option<&'a crate::model::outcome::NodeMarks>,
    /// The playback's current node: a thick ring, and brought into view when it changes.
    pub current: Option<NodeId>,
    /// The node hovered on the canvas: a ring in
    /// [`colors::SELECTED`](crate::paint::colors::SELECTED), brought into view when it changes.
    pub linked: Option<NodeId>,
    /// Build playback: only nodes whose entry is `true` exist yet (ids past the end do not);
    /// the others are drawn faint. `None`: every node exists.
    pub existing: Option<&'a [bool]>,
    /// Nodes deeper than this are drawn faint.
    pub max_depth: u32,
    /// What Predict's question waiting is about: a ring in
    /// [`colors::ASKED`](crate::paint::colors::ASKED) and a question mark beside each.
    pub asked: &'a [NodeId],
}

impl Default for TreeHighlight<'_> {
    fn default() -> Self {
        Self {
            marks: None,
            current: None,
            linked: None,
            existing: None,
            max_depth: u32::MAX,
            asked: &[],
        }
    }
}

/// What the pointer did in the diagram this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TreeResponse {
    /// The node under the pointer (within a few points of its dot).
    pub hovered: Option<NodeId>,
    /// The node clicked.
    pub clicked: Option<NodeId>,
}

/// The diagram's state between frames: the layout, cached until the outline's topology
/// changes, and the pan and zoom.
///
/// The layout is keyed by a hash of the outline's children lists (and, for a grid, of its
/// cells' corners), computed each frame: the caller passes the outline and nothing else, and
/// a scene edit that keeps the topology keeps the student's pan and zoom. A new topology is
/// laid out again and fitted.
#[derive(Default)]
pub struct TreeDiagram {
    /// The diagram's height in points; `None` fills the available height.
    pub height: Option<f32>,
    /// Where the diagram was last drawn (`None` while there is no tree to draw).
    area: Option<Rect>,
    layout: Option<Layout>,
    viewport: Viewport,
    /// Reused every frame, so painting does not allocate a new list.
    shapes: Vec<Shape>,
}

impl TreeDiagram {
    /// Forgets the diagram drawn last, when the panel shows words in its place (brute
    /// force, an empty scene, a structure too large to list): nothing is hovered in it.
    pub fn forget(&mut self) {
        self.layout = None;
        self.area = None;
    }

    /// Shows the diagram in `ui`: a "Fit" button and a summary, then the diagram across the
    /// available width, [`height`](Self::height) points high (or the available height).
    /// Drag to pan, scroll or pinch to zoom, hover a node for its details.
    pub fn show<V: Vector>(
        &mut self,
        ui: &mut egui::Ui,
        outline: &[NodeOutline<V>],
        highlight: &TreeHighlight<'_>,
    ) -> TreeResponse {
        if outline.is_empty() {
            self.layout = None;
            self.area = None;
            ui.label(EMPTY_MESSAGE);
            return TreeResponse::default();
        }
        self.update_layout(outline);
        let Some(layout) = &self.layout else {
            return TreeResponse::default();
        };
        ui.horizontal(|ui| {
            if crate::a11y::describe::rename(ui.button("Fit"), "Fit the tree diagram")
                .on_hover_text("Show the whole tree")
                .clicked()
            {
                self.viewport.fit_requested = true;
            }
            ui.label(summary(layout, outline.len()));
        });
        if let Arrangement::Grid { cols, rows } = layout.arrangement {
            ui.label(grid_caption(outline.len(), cols, rows));
        }
        let height = self
            .height
            .unwrap_or_else(|| ui.available_height())
            .max(MIN_HEIGHT);
        let size = vec2(ui.available_width(), height);
        let (response, painter) = ui.allocate_painter(size, Sense::click_and_drag());
        let rect = response.rect;
        self.area = Some(rect);
        let camera = self.viewport.update(ui, &response, layout, highlight);
        let hovered = response
            .hover_pos()
            .and_then(|p| node_at(layout, outline, camera, p));
        let clicked = hovered.filter(|_| response.clicked());

        painter.rect_filled(rect, 4.0, ui.visuals().extreme_bg_color);
        let painting = Painting {
            layout,
            outline,
            highlight,
            camera,
            clip: rect,
            hovered,
            ink: ui.visuals().text_color(),
        };
        painting.paint(&mut self.shapes, &mut |text, size, color| {
            painter.layout_no_wrap(text, egui::FontId::proportional(size), color)
        });
        painter.extend(self.shapes.drain(..));
        aria::tree(
            ui,
            response.id,
            outline,
            layout,
            highlight,
            &summary(layout, outline.len()),
        );
        if let Some(id) = hovered {
            let text = describe::describe(
                &outline[id],
                layout.depth(id),
                painting.mark(id),
                highlight.existing.is_none_or(|e| e.get(id) == Some(&true)),
            );
            response.on_hover_ui_at_pointer(|ui| {
                ui.label(text);
            });
        }
        TreeResponse {
            hovered: hovered.map(|id| NodeId(id as u32)),
            clicked: clicked.map(|id| NodeId(id as u32)),
        }
    }

    /// Where the diagram (below its "Fit" button and summary) was last drawn, if a tree was.
    pub fn area(&self) -> Option<Rect> {
        self.area
    }

    /// Where node `id` was drawn in the last frame [`show`](Self::show) painted, if any.
    pub fn node_screen_pos(&self, id: NodeId) -> Option<Pos2> {
        let p = self.layout.as_ref()?.pos.get(id.index())?;
        Some(self.viewport.camera?.to_screen(*p))
    }

    /// The diagram as screen-space shapes inside `rect`, the whole tree fitted, for SVG or
    /// PNG export; `ctx` lays out the text (leaf counts, the grid's caption, the message for
    /// an empty outline). The interactive view is left as it is.
    pub fn export_shapes<V: Vector>(
        &mut self,
        outline: &[NodeOutline<V>],
        highlight: &TreeHighlight<'_>,
        rect: Rect,
        ctx: &egui::Context,
    ) -> Vec<Shape> {
        let ink = ctx.global_style().visuals.text_color();
        let mut text = |text: String, size: f32, color: Color32| {
            ctx.fonts_mut(|f| f.layout_no_wrap(text, egui::FontId::proportional(size), color))
        };
        let mut shapes = Vec::new();
        let caption = if outline.is_empty() {
            Some(EMPTY_MESSAGE.to_owned())
        } else {
            self.update_layout(outline);
            match self.layout.as_ref().map(|l| l.arrangement) {
                Some(Arrangement::Grid { cols, rows }) => {
                    Some(grid_caption(outline.len(), cols, rows))
                }
                _ => None,
            }
        };
        let mut area = rect;
        if let Some(caption) = caption {
            let galley = text(caption, 12.0, ink);
            area.min.y += galley.size().y + 4.0;
            shapes.push(Shape::galley(rect.min, galley, ink));
        }
        if let Some(layout) = self.layout.as_ref().filter(|_| !outline.is_empty()) {
            let painting = Painting {
                layout,
                outline,
                highlight,
                camera: Camera::fit(layout, area),
                clip: rect,
                hovered: None,
                ink,
            };
            painting.paint(&mut shapes, &mut text);
        }
        shapes
    }

    /// Lays `outline` out again if its key changed (and forgets the camera, to fit anew).
    fn update_layout<V: Vector>(&mut self, outline: &[NodeOutline<V>]) {
        let key = LayoutKey::of(outline);
        if self.layout.as_ref().is_none_or(|l| l.key != key) {
            self.viewport.camera = None;
            self.layout = Some(Layout::new(outline));
        }
    }
}

/// The node whose dot (or square) is within [`HOVER_SLOP`] points of `pointer`, the nearest
/// if several are.
fn node_at<V: Vector>(
    layout: &Layout,
    outline: &[NodeOutline<V>],
    camera: Camera,
    pointer: Pos2,
) -> Option<usize> {
    let [x, row] = camera.to_layout(pointer);
    let reach = camera.node_radius() + HOVER_SLOP;
    let first = row.floor();
    let rows = [first, first + 1.0]
        .into_iter()
        .filter(|&r| r >= 0.0 && r < layout.row_count() as f32);
    rows.flat_map(|r| layout.nearest_in_row(r as usize, x))
        .map(|id| {
            let d = camera.to_screen(layout.pos[id]) - pointer;
            let distance = if outline[id].is_leaf() {
                d.x.abs().max(d.y.abs())
            } else {
                d.length()
            };
            (distance, id)
        })
        .filter(|&(distance, _)| distance <= reach)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, id)| id)
}

/// "N nodes, L leaves, D levels".
fn summary(layout: &Layout, nodes: usize) -> String {
    match layout.arrangement {
        Arrangement::Tree { levels } => {
            format!("{nodes} nodes, {} leaves, {levels} levels", layout.leaves)
        }
        Arrangement::Grid { .. } => format!("{nodes} cells"),
    }
}

/// The grid's caption: why it is not drawn as a tree.
fn grid_caption(cells: usize, cols: usize, rows: usize) -> String {
    format!(
        "A uniform grid is not a tree: its {cells} cells ({cols} by {rows}) are all roots at depth 0, shown in their places."
    )
}
