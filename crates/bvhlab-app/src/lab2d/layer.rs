//! The canvas's static layer: the structure's nodes and the scene's primitives, tessellated
//! once into one mesh and reused while only the queries change, so that a frame during a ray
//! drag costs about the same with 10 or 10,000 segments. A view cache, not lab state.

use crate::model::lab2d::Display;
use crate::model::structures::BuildSettings;

use super::Screen;

/// The most shapes the static layer anti-aliases (see [`StaticLayer::tessellate`]).
const FEATHERING_LIMIT: usize = 4000;

/// What the static layer was drawn for: when none of it changes (while a ray or a query
/// point is dragged), the cached mesh is reused.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerKey {
    /// The scene's revision.
    pub revision: u64,
    /// The structure's settings.
    pub settings: BuildSettings,
    /// Whether the structure was built on this revision (it is drawn only then).
    pub built: bool,
    /// How many times the lane's structure was updated (built or refitted): "Rebuild now"
    /// gives a new tree on the same revision.
    pub updates: u64,
    /// Where it is drawn.
    pub screen: Screen,
    /// The drawing switches (with the structure off while a build is stepped through).
    pub display: Display,
    /// The selected shapes, drawn in their own colour.
    pub selection: Vec<usize>,
    /// The display's scale.
    pub pixels_per_point: f32,
}

/// The structure and scene of one lane, tessellated for the view.
pub struct StaticLayer {
    pub(super) key: LayerKey,
    mesh: std::sync::Arc<egui::Mesh>,
}

impl StaticLayer {
    /// Tessellates `shapes` into one mesh, culled to `clip`, as egui would each frame.
    ///
    /// Above `FEATHERING_LIMIT` shapes the edges are not anti-aliased: feathering doubles
    /// the vertices, and egui copies and uploads every vertex each frame.
    pub fn tessellate(
        key: LayerKey,
        ctx: &egui::Context,
        shapes: Vec<egui::Shape>,
        clip: egui::Rect,
    ) -> Self {
        let mut options = ctx.tessellation_options(|o| *o);
        options.feathering &= shapes.len() <= FEATHERING_LIMIT;
        let mut tessellator =
            egui::epaint::Tessellator::new(ctx.pixels_per_point(), options, [1, 1], Vec::new());
        tessellator.set_clip_rect(clip);
        let mut mesh = egui::Mesh::default();
        for shape in shapes {
            tessellator.tessellate_shape(shape, &mut mesh);
        }
        Self {
            key,
            mesh: std::sync::Arc::new(mesh),
        }
    }

    /// The mesh, to paint.
    pub fn shape(&self) -> egui::Shape {
        egui::Shape::Mesh(self.mesh.clone())
    }
}
