//! What the "Save and share" buttons do, and opening the scene files dropped on the window or
//! picked in the browser's file dialog. The browser's side (downloads, the file dialog, the
//! clipboard) is in [`crate::web`]; natively, files are read and written directly.

use std::sync::Arc;

use crate::app::LabApp;

use super::state::SavedState;
use super::{MAX_FILE_BYTES, link_fragment, open_file, to_file};

/// The name exported scenes are saved under.
const FILE_NAME: &str = "bvh-lab-scene.json";

/// Where the last share link is kept (egui's memory of the UI), to show it until the next.
fn link_id() -> egui::Id {
    egui::Id::unique("bvh-lab share link")
}

/// "Export scene": saves the full state as a scene file; the status line says where.
pub fn export_scene(app: &mut LabApp) {
    let bytes = to_file(app);
    app.message = Some(
        match crate::export::save_file(FILE_NAME, "application/json", &bytes) {
            Ok(done) => format!("Scene exported: {done}"),
            Err(e) => format!("The scene could not be exported: {e}."),
        },
    );
}

/// "Import scene…": opens the browser's file dialog (the file is opened when it has been
/// read, by [`poll_imports`]); natively, says to drop the file on the window.
pub fn import_scene(app: &mut LabApp, ctx: &egui::Context) {
    #[cfg(target_arch = "wasm32")]
    if let Err(e) = crate::web::pick_file(ctx, ".json,application/json") {
        app.message = Some(format!("The file dialog could not be opened: {e}."));
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        app.message = Some("Drop a .json scene file on the window to open it.".to_owned());
    }
}

/// "Copy share link": makes the link (on the web, the page's full address; natively, its
/// fragment), keeps it for [`share_link_text`] and, on the web, copies it to the clipboard.
pub fn copy_share_link(app: &mut LabApp, ctx: &egui::Context) {
    match link_fragment(&SavedState::capture(app)) {
        Ok(fragment) => {
            #[cfg(target_arch = "wasm32")]
            let link = {
                let link = format!("{}{fragment}", crate::web::page_address());
                crate::web::copy_text(ctx, &link);
                link
            };
            #[cfg(not(target_arch = "wasm32"))]
            let link = {
                app.message = Some(
                    "Share link made: add it to the lab's web address to open this state."
                        .to_owned(),
                );
                fragment
            };
            ctx.data_mut(|d| d.insert_temp(link_id(), Arc::<str>::from(link)));
        }
        Err(e) => {
            ctx.data_mut(|d| d.remove::<Arc<str>>(link_id()));
            app.message = Some(format!("No share link: {e}."));
        }
    }
}

/// The last share link made, to show in a field it can be copied from by hand.
pub fn share_link_text(ctx: &egui::Context) -> Option<Arc<str>> {
    ctx.data(|d| d.get_temp(link_id()))
}

/// Opens a scene file dropped on the window this frame, and (on the web) what the file
/// dialog, the clipboard and the address bar (a share link pasted into the open page)
/// reported since the last frame. Runs every frame.
pub fn poll_imports(app: &mut LabApp, ctx: &egui::Context) {
    let dropped = ctx.input(|i| i.raw.dropped_files.clone());
    if let Some(file) = dropped.first() {
        #[cfg(target_arch = "wasm32")]
        crate::web::read_dropped(ctx, file, read_limit(&file.path().display().to_string()));
        #[cfg(not(target_arch = "wasm32"))]
        open_named(
            app,
            &file.path().display().to_string(),
            read_limited(file.path()),
        );
        if dropped.len() > 1 {
            let opened = app.message.take().unwrap_or_default();
            app.message = Some(format!(
                "{opened} Only the first of the {} dropped files is opened.",
                dropped.len()
            ));
        }
    }
    #[cfg(target_arch = "wasm32")]
    for news in crate::web::take_news() {
        match news {
            crate::web::News::Opened { name, bytes } => open_named(app, &name, bytes),
            crate::web::News::Copied(Ok(())) => {
                app.message = Some("Share link copied to the clipboard.".to_owned());
            }
            crate::web::News::Link(fragment) => {
                crate::web::forget_link();
                app.message = Some(match super::open_fragment(app, &fragment) {
                    Ok(()) => "Opened the share link.".to_owned(),
                    Err(e) => e,
                });
            }
            crate::web::News::Copied(Err(e)) => {
                app.message = Some(format!(
                    "The link could not be copied ({e}): select it in the field and copy it by hand."
                ));
            }
        }
    }
}

/// Opens the bytes read from file `name`, and says how it went in the status line. A mesh
/// file (by its extension) opens in the 3D view; anything else is read as a scene file.
fn open_named(app: &mut LabApp, name: &str, bytes: Result<Vec<u8>, String>) {
    if crate::lab3d::panel::is_mesh_file(name) {
        match bytes {
            Ok(bytes) => {
                let short = name.rsplit(['/', '\\']).next().unwrap_or(name).to_owned();
                app.dimension = crate::app::Dimension::Three;
                app.lab3d.open(crate::lab3d::mesh::MeshSource::File {
                    name: short,
                    bytes: bytes.into(),
                });
                app.message = None;
            }
            Err(e) => {
                app.message = Some(format!(
                    "{name} could not be read ({e}). The current mesh was kept."
                ));
            }
        }
        return;
    }
    let result = bytes
        .map_err(|e| format!("{name} could not be read ({e}). The current scene was kept."))
        .and_then(|bytes| open_file(app, &bytes));
    app.message = Some(match result {
        Ok(()) => format!("Opened {name}."),
        Err(e) if e.starts_with(name) => e,
        Err(e) => format!("{name}: {e}"),
    });
}

/// The most bytes read from a file called `name`: a mesh may be large, a scene file not.
pub fn read_limit(name: &str) -> usize {
    if crate::lab3d::panel::is_mesh_file(name) {
        bvhlab_meshio::MAX_BYTES
    } else {
        MAX_FILE_BYTES
    }
}

/// A file's bytes, refusing files over [`read_limit`] before reading them.
#[cfg(not(target_arch = "wasm32"))]
fn read_limited(path: &std::path::Path) -> Result<Vec<u8>, String> {
    use std::io::Read as _;
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let len = file.metadata().map_err(|e| e.to_string())?.len();
    let limit = read_limit(&path.display().to_string());
    if len > limit as u64 {
        return Err(format!(
            "it is {:.1} MiB; the lab reads at most {} MiB",
            len as f64 / f64::from(1 << 20),
            limit >> 20
        ));
    }
    let mut bytes = Vec::new();
    file.take(limit as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}
