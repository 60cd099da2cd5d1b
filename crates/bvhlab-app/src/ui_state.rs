//! What the lab's UI remembers between frames that is not the lab's state: which panels are
//! shown, what the pointer hovers, a drag in progress, the tree diagrams' pan and zoom, the
//! canvas's cached drawing, the 3D view's heat map and GPU resources, the frame clock. None
//! of it is saved; the lab ([`crate::model::Lab`]) changes only through actions.

use bvhlab::NodeId;

pub use crate::address::{PanelsShown, SideTab};
use crate::frame_clock::FrameClock;
use crate::model::{Action, Lab};
use crate::tree_diagram::TreeDiagram;

/// The UI's own state.
#[derive(Default)]
pub struct UiState {
    /// Which panels are shown.
    pub panels: PanelsShown,
    /// Hovering the canvas finds the node under the pointer (and the tree diagram shows it).
    pub link_hover: bool,
    /// The node hovered on the canvas or in a tree diagram this frame: (lane, node).
    pub hovered: Option<(usize, NodeId)>,
    /// Last frame's hovered node, which the tree diagrams (drawn before the view) show.
    pub linked: Option<(usize, NodeId)>,
    /// The 2D canvas: a drag in progress, its area, its cached drawing.
    pub canvas: crate::lab2d::CanvasState,
    /// The 3D view: a gizmo drag, its area, the heat map, the mesh on the GPU.
    pub view3d: crate::lab3d::ViewState,
    /// The tree diagrams, one per lane, for each half.
    pub trees: Trees,
    /// The tree diagrams' area, when they are shown.
    pub tree_rect: Option<egui::Rect>,
    /// The drawing's widget (the 2D canvas or the 3D view) this frame: the lab describes it
    /// in words for screen readers ([`crate::a11y::describe`]), and its keys act while it
    /// has the focus.
    pub drawing: Option<egui::Id>,
    /// The legend's strip this frame, above the view.
    pub legend_rect: Option<egui::Rect>,
    /// A PNG export waiting for its screenshot.
    pub pending_png: Option<crate::panels::export::PendingPng>,
    /// Frame timing.
    pub clock: FrameClock,
    /// The lesson writer is open but the pane shows the lesson it tries, as a student sees
    /// it.
    pub trying_lesson: bool,
    /// The renderer's name ("WebGPU", "WebGL2", "Vulkan", ...), once known.
    pub renderer: Option<String>,
    /// The GPU the lab draws with (none in headless tests): the 3D view draws through it.
    pub render_state: Option<eframe::egui_wgpu::RenderState>,
}

/// The tree diagrams of each half, one per lane (two when comparing).
#[derive(Default)]
pub struct Trees {
    /// The 2D half's.
    pub two: [TreeDiagram; 2],
    /// The 3D half's.
    pub three: [TreeDiagram; 2],
}

impl UiState {
    /// The UI as a lab starts: every panel shown, hovering linked to the tree.
    pub fn new() -> Self {
        Self {
            link_hover: true,
            ..Self::default()
        }
    }
}

/// What a panel or view works with this frame: the lab to read, the UI's own state, and the
/// actions it asks for (applied after the frame is drawn).
pub struct Cx<'a> {
    /// The lab, to read.
    pub lab: &'a Lab,
    /// The UI's own state.
    pub ui: &'a mut UiState,
    /// What the panels and views asked for this frame.
    pub actions: &'a mut Vec<Action>,
    /// The lesson being written, when the teacher writes one.
    pub writer: Option<&'a crate::lessons::writer::LessonWriter>,
    /// What the panels asked of the lesson writer this frame.
    pub writer_asks: &'a mut Vec<crate::lessons::writer::WriterCommand>,
}

impl Cx<'_> {
    /// Asks for `action`.
    pub fn act(&mut self, action: impl Into<Action>) {
        self.actions.push(action.into());
    }

    /// Asks the lesson writer for `command`.
    pub fn write(&mut self, command: crate::lessons::writer::WriterCommand) {
        self.writer_asks.push(command);
    }
}
