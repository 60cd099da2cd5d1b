//! Handing an exported file to the user: on the web the browser downloads it; natively it is
//! written next to where the lab was started, never over an existing file (a second export
//! becomes `name (1).svg`, as browsers name repeated downloads).

#[cfg(not(target_arch = "wasm32"))]
use std::path::{Path, PathBuf};

/// Hands a file to the user: on the web a download (Blob + object URL + a temporary
/// `<a download>`, revoking the URL after), natively written to the current directory and the
/// path returned. Errors are messages for the status line.
///
/// `name` is a file name: any directories in it are dropped. See [`save_file_in`] to choose
/// the directory.
///
/// # Errors
/// When there is no current directory, or the file cannot be created or written.
#[cfg(not(target_arch = "wasm32"))]
pub fn save_file(name: &str, mime: &str, bytes: &[u8]) -> Result<String, String> {
    let _ = mime; // The file's extension says what it is; only the browser needs the type.
    let dir = std::env::current_dir()
        .map_err(|e| format!("could not save {name}: no current directory ({e})"))?;
    save_file_in(&dir, name, bytes).map(|path| path.display().to_string())
}

/// Writes `bytes` to a new file called `name` in `dir` (`name (1).ext`, `name (2).ext`, ...
/// when that exists) and returns its path. The file is created only if absent, so nothing is
/// overwritten even when two exports race.
///
/// # Errors
/// When `name` has no file name in it (`""`, `".."`), or the file cannot be created or
/// written (a half-written file is removed).
#[cfg(not(target_arch = "wasm32"))]
pub fn save_file_in(dir: &Path, name: &str, bytes: &[u8]) -> Result<PathBuf, String> {
    use std::io::Write as _;

    let name = file_name(name)?;
    let (stem, extension) = match name.rfind('.') {
        Some(dot) if dot > 0 => name.split_at(dot),
        _ => (name, ""),
    };
    for n in 0..1000 {
        let candidate = if n == 0 {
            name.to_owned()
        } else {
            format!("{stem} ({n}){extension}")
        };
        let path = dir.join(candidate);
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path);
        match file {
            Ok(mut file) => {
                return match file.write_all(bytes).and_then(|()| file.sync_all()) {
                    Ok(()) => Ok(path),
                    Err(e) => {
                        // Leave no half-written file behind.
                        drop(file);
                        let _ = std::fs::remove_file(&path);
                        Err(format!("could not write {}: {e}", path.display()))
                    }
                };
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(format!("could not create {}: {e}", path.display())),
        }
    }
    Err(format!(
        "could not save {name}: {} already holds a thousand files of that name",
        dir.display()
    ))
}

/// The last component of `name`, so that a name cannot write outside the directory.
#[cfg(not(target_arch = "wasm32"))]
fn file_name(name: &str) -> Result<&str, String> {
    name.rsplit(['/', '\\'])
        .next()
        .filter(|n| !n.is_empty() && *n != "." && *n != "..")
        .ok_or_else(|| format!("{name:?} is not a file name"))
}

/// Hands a file to the user: on the web a download (Blob + object URL + a temporary
/// `<a download>`, revoking the URL after), natively written to the current directory and the
/// path returned. Errors are messages for the status line.
///
/// On the web the browser picks the folder (and renames repeated downloads); the name is
/// returned.
///
/// # Errors
/// When the page has no window, document or body, or the browser refuses the Blob, URL or
/// link.
#[cfg(target_arch = "wasm32")]
pub fn save_file(name: &str, mime: &str, bytes: &[u8]) -> Result<String, String> {
    use wasm_bindgen::JsCast as _;
    use wasm_bindgen::closure::Closure;
    use web_sys::js_sys;

    /// How long the object URL outlives the click: browsers start the download
    /// asynchronously, and some still read the URL after `click` returns.
    const REVOKE_AFTER_MS: i32 = 10_000;

    let failed =
        |what: &'static str| move |e: wasm_bindgen::JsValue| format!("could not {what} {e:?}");
    let window = web_sys::window().ok_or("no browser window to download in")?;
    let document = window.document().ok_or("the page has no document")?;
    let body = document.body().ok_or("the page has no body")?;

    // The bytes are copied into JavaScript's memory: the Blob must not see wasm memory,
    // which moves when it grows.
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let options = web_sys::BlobPropertyBag::new();
    options.set_type(mime);
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options)
        .map_err(failed("make the file"))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(failed("make a URL"))?;

    let anchor = document
        .create_element("a")
        .map_err(failed("make a link"))?
        .dyn_into::<web_sys::HtmlAnchorElement>()
        .map_err(|_| "the page made a link that is not <a>".to_owned())?;
    anchor.set_href(&url);
    anchor.set_download(name);
    body.append_child(&anchor).map_err(failed("add the link"))?;
    anchor.click();
    anchor.remove();

    let revoke = Closure::once_into_js(move || {
        let _ = web_sys::Url::revoke_object_url(&url);
    });
    window
        .set_timeout_with_callback_and_timeout_and_arguments_0(
            revoke.unchecked_ref(),
            REVOKE_AFTER_MS,
        )
        .map_err(failed("schedule the URL's release"))?;
    Ok(name.to_owned())
}
