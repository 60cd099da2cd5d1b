//! The 3D mesh: the built-in meshes, a file to open, and what it is made of.

use super::Panel;
use crate::model::dimension::thousands;
use crate::model::mesh::MeshSource;
use crate::model::{Action, Action3d};
use crate::ui_state::Cx;

/// The file types the mesh dialog offers.
pub const MESH_FILE_TYPES: &str = ".obj,.ply,.stl,.gltf,.glb";

/// Whether a file name looks like a mesh the lab reads.
pub fn is_mesh_file(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    [".obj", ".ply", ".stl", ".gltf", ".glb"]
        .iter()
        .any(|ext| lower.ends_with(ext))
}

/// The mesh panel.
pub struct Mesh;

impl Panel for Mesh {
    fn title(&self) -> &'static str {
        "Mesh"
    }

    fn show(&self, cx: &mut Cx<'_>, ui: &mut egui::Ui) {
        mesh_section(cx, ui);
    }
}

fn mesh_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    let current = lab
        .mesh
        .as_ref()
        .map_or_else(|| "loading…".to_owned(), |m| m.name.clone());
    egui::ComboBox::from_label("built-in")
        .selected_text(&current)
        .show_ui(ui, |ui| {
            for b in bvhlab_meshio::builtin::list() {
                if ui
                    .selectable_label(current == b.name, b.name)
                    .on_hover_text(b.about)
                    .clicked()
                {
                    cx.act(Action3d::OpenMesh(MeshSource::Builtin(b.slug.to_owned())));
                }
            }
        });
    if ui
        .button("Open mesh file…")
        .on_hover_text("OBJ, PLY, STL, glTF or GLB; or drop the file on the page")
        .clicked()
        && let Some(a) = open_mesh_dialog(ui.ctx())
    {
        cx.act(a);
    }
    if let Some(m) = &lab.mesh {
        ui.label(format!(
            "{} triangles, {} vertices{}",
            thousands(m.stats.triangles),
            thousands(m.stats.vertices),
            if m.stats.degenerate_triangles > 0 {
                format!(", {} degenerate", thousands(m.stats.degenerate_triangles))
            } else {
                String::new()
            }
        ));
    }
    if lab.pending.is_some() {
        ui.label("Loading…");
    }
    super::motion::motion_section(cx, ui);
}

/// Opens the browser's file dialog for a mesh; natively, says to drop the file.
#[cfg_attr(
    not(target_arch = "wasm32"),
    expect(
        clippy::unnecessary_wraps,
        reason = "on the web the dialog can fail and has nothing to say otherwise"
    )
)]
fn open_mesh_dialog(ctx: &egui::Context) -> Option<Action> {
    #[cfg(target_arch = "wasm32")]
    {
        crate::web::pick_file(ctx, MESH_FILE_TYPES)
            .err()
            .map(|e| Action::SetMessage(Some(format!("The file dialog could not be opened: {e}."))))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        Some(Action::SetMessage(Some(
            "Drop an OBJ, PLY, STL or glTF file on the window to open it.".to_owned(),
        )))
    }
}
