//! What the "Save and share" buttons do, and opening the scene files dropped on the window or
//! picked in the browser's file dialog. Each says what it changes in the lab as actions (a
//! restored state, a mesh to open, a message for the status line). The browser's side
//! (downloads, the file dialog, the clipboard) is in [`crate::web`]; natively, files are read
//! and written directly.

use std::sync::Arc;

use crate::model::{Action, Action3d, Lab};

use super::state::SavedState;
use super::{MAX_FILE_BYTES, link_fragment, open_file, to_file};

/// The name exported scenes are saved under.
const FILE_NAME: &str = "bvh-lab-scene.json";

/// Where the last share link is kept (egui's memory of the UI), to show it until the next.
fn link_id() -> egui::Id {
    egui::Id::unique("bvh-lab share link")
}

/// "Export scene": saves the full state as a scene file; what the status line says.
pub fn export_scene(lab: &Lab) -> Action {
    let bytes = to_file(lab);
    Action::SetMessage(Some(
        match crate::export::save_file(FILE_NAME, "application/json", &bytes) {
            Ok(done) => format!("Scene exported: {done}"),
            Err(e) => format!("The scene could not be exported: {e}."),
        },
    ))
}

/// "Import scene…": opens the browser's file dialog (the file is opened when it has been
/// read, by [`poll_imports`]); natively, says to drop the file on the window. What the status
/// line says, if anything.
pub fn import_scene(ctx: &egui::Context) -> Option<Action> {
    #[cfg(target_arch = "wasm32")]
    {
        crate::web::pick_file(ctx, ".json,application/json")
            .err()
            .map(|e| say(format!("The file dialog could not be opened: {e}.")))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        Some(say(
            "Drop a .json scene file on the window to open it.".to_owned()
        ))
    }
}

/// "Open a lesson file…": the browser's file dialog for `.toml` lesson files (opened when
/// read, by [`poll_imports`]); natively, says to drop the file on the window.
pub fn pick_lesson_file(ctx: &egui::Context) -> Option<Action> {
    #[cfg(target_arch = "wasm32")]
    {
        crate::web::pick_file(ctx, ".toml")
            .err()
            .map(|e| say(format!("The file dialog could not be opened: {e}.")))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        Some(say(
            "Drop a .toml lesson file on the window to open it.".to_owned()
        ))
    }
}

/// A message for the status line.
fn say(message: String) -> Action {
    Action::SetMessage(Some(message))
}

/// "Copy share link": makes the link (on the web, the page's full address; natively, its
/// fragment), keeps it for [`share_link_text`] and, on the web, copies it to the clipboard.
pub fn copy_share_link(lab: &Lab, ctx: &egui::Context) -> Option<Action> {
    match link_fragment(&SavedState::capture(lab)) {
        Ok(fragment) => {
            #[cfg(target_arch = "wasm32")]
            let link = {
                let link = format!("{}{fragment}", crate::web::page_address());
                crate::web::copy_text(ctx, &link);
                link
            };
            #[cfg(target_arch = "wasm32")]
            let said = None;
            #[cfg(not(target_arch = "wasm32"))]
            let (link, said) = (
                fragment,
                Some(say(
                    "Share link made: add it to the lab's web address to open this state."
                        .to_owned(),
                )),
            );
            ctx.data_mut(|d| d.insert_temp(link_id(), Arc::<str>::from(link)));
            said
        }
        Err(e) => {
            ctx.data_mut(|d| d.remove::<Arc<str>>(link_id()));
            Some(say(format!("No share link: {e}.")))
        }
    }
}

/// The last share link made, to show in a field it can be copied from by hand.
pub fn share_link_text(ctx: &egui::Context) -> Option<Arc<str>> {
    ctx.data(|d| d.get_temp(link_id()))
}

/// Opens a scene file dropped on the window this frame, and (on the web) what the file
/// dialog, the clipboard and the address bar (a share link pasted into the open page)
/// reported since the last frame: the actions that open them and say how it went. Runs
/// every frame.
pub fn poll_imports(ctx: &egui::Context) -> Vec<Action> {
    let mut actions = Vec::new();
    let dropped = ctx.input(|i| i.raw.dropped_files.clone());
    if let Some(file) = dropped.first() {
        #[cfg(target_arch = "wasm32")]
        crate::web::read_dropped(ctx, file, read_limit(&file.path().display().to_string()));
        #[cfg(not(target_arch = "wasm32"))]
        actions.extend(open_named(
            &file.path().display().to_string(),
            read_limited(file.path()),
        ));
        if dropped.len() > 1 {
            let more = format!(
                "Only the first of the {} dropped files is opened.",
                dropped.len()
            );
            // Said after what opening the first one said.
            match actions.last_mut() {
                Some(Action::SetMessage(Some(opened))) => *opened = format!("{opened} {more}"),
                _ => actions.push(say(more)),
            }
        }
    }
    #[cfg(target_arch = "wasm32")]
    for news in crate::web::take_news() {
        match news {
            crate::web::News::Opened { name, bytes } => actions.extend(open_named(&name, bytes)),
            crate::web::News::FetchedLesson { url, bytes } => {
                actions.extend(crate::lessons::open::open_lesson_file(&url, bytes));
            }
            crate::web::News::Copied(Ok(())) => {
                actions.push(say("Share link copied to the clipboard.".to_owned()));
            }
            crate::web::News::Link(fragment) => {
                crate::web::forget_link();
                match super::open_fragment(&fragment) {
                    Ok(open) => {
                        actions.push(open);
                        actions.push(say("Opened the share link.".to_owned()));
                    }
                    Err(e) => actions.push(say(e)),
                }
            }
            crate::web::News::Copied(Err(e)) => {
                actions.push(say(format!(
                    "The link could not be copied ({e}): select it in the field and copy it by hand."
                )));
            }
        }
    }
    actions
}

/// What opening the bytes read from file `name` does, with what the status line says. A
/// mesh file (by its extension) opens in the 3D view; anything else is read as a scene
/// file.
fn open_named(name: &str, bytes: Result<Vec<u8>, String>) -> Vec<Action> {
    let short = name.rsplit(['/', '\\']).next().unwrap_or(name);
    if crate::lessons::open::is_lesson_file(name) {
        return crate::lessons::open::open_lesson_file(short, bytes);
    }
    if crate::panels::mesh::is_mesh_file(name) {
        return match bytes {
            Ok(bytes) => {
                vec![
                    Action3d::OpenMesh(crate::model::mesh::MeshSource::File {
                        name: short.to_owned(),
                        bytes: bytes.into(),
                    })
                    .into(),
                    Action::SetMessage(None),
                ]
            }
            Err(e) => vec![say(format!(
                "{name} could not be read ({e}). The current mesh was kept."
            ))],
        };
    }
    let opened = bytes
        .map_err(|e| format!("{name} could not be read ({e}). The current scene was kept."))
        .and_then(|bytes| open_file(&bytes));
    match opened {
        Ok(open) => vec![open, say(format!("Opened {name}."))],
        Err(e) if e.starts_with(name) => vec![say(e)],
        Err(e) => vec![say(format!("{name}: {e}"))],
    }
}

/// The most bytes read from a file called `name`: a mesh may be large, a scene file not.
pub fn read_limit(name: &str) -> usize {
    if crate::lessons::open::is_lesson_file(name) {
        crate::lessons::format::MAX_TEACHER_BYTES
    } else if crate::panels::mesh::is_mesh_file(name) {
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
        return Err(super::too_large(len, limit));
    }
    let mut bytes = Vec::new();
    file.take(limit as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}
