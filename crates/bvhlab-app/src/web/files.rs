//! The browser's side of saving and sharing: the clipboard, the file dialog and dropped
//! files. The browser answers later (promises); the answers wait in an inbox
//! ([`take_news`]) that the lab reads on its next frame.

use std::cell::RefCell;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

thread_local! {
    /// What the browser answered since the last frame.
    static INBOX: RefCell<Vec<News>> = const { RefCell::new(Vec::new()) };
}

/// Something the browser answered.
pub enum News {
    /// A file picked in the dialog or dropped on the page was read (or could not be).
    Opened {
        /// Its name.
        name: String,
        /// Its bytes, or why they could not be read.
        bytes: Result<Vec<u8>, String>,
    },
    /// The lesson file named by the address's `lesson-url=` was fetched (or could not be).
    FetchedLesson {
        /// The address it was fetched from.
        url: String,
        /// Its bytes, or why they could not be fetched.
        bytes: Result<Vec<u8>, String>,
    },
    /// The clipboard took the share link (or refused it).
    Copied(Result<(), String>),
    /// A share link was opened in the page already showing the lab (only the address's
    /// fragment changed, so the page did not reload): its fragment.
    Link(String),
}

/// What the browser answered since the last call.
pub fn take_news() -> Vec<News> {
    INBOX.with(|inbox| std::mem::take(&mut *inbox.borrow_mut()))
}

/// Puts an answer in the inbox and asks for a frame to read it.
pub(super) fn deliver(ctx: &egui::Context, news: News) {
    INBOX.with(|inbox| inbox.borrow_mut().push(news));
    ctx.request_repaint();
}

/// Copies `text` to the clipboard; the outcome arrives as [`News::Copied`].
pub fn copy_text(ctx: &egui::Context, text: &str) {
    let clipboard = web_sys::window().map(|w| w.navigator().clipboard());
    // `navigator.clipboard` is undefined outside secure contexts (plain http).
    let Some(clipboard) = clipboard.filter(|c| !c.is_undefined()) else {
        deliver(
            ctx,
            News::Copied(Err("this page may not use the clipboard".to_owned())),
        );
        return;
    };
    let promise = clipboard.write_text(text);
    let ctx = ctx.clone();
    wasm_bindgen_futures::spawn_local(async move {
        let result = JsFuture::from(promise)
            .await
            .map(|_| ())
            .map_err(|e| describe(&e));
        deliver(&ctx, News::Copied(result));
    });
}

/// Opens the browser's file dialog for one file of the `accept` types; the file arrives as
/// [`News::Opened`] once read.
///
/// # Errors
/// When the page cannot make the dialog's `<input type=file>`.
pub fn pick_file(ctx: &egui::Context, accept: &str) -> Result<(), String> {
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or("the page has no document")?;
    let input: web_sys::HtmlInputElement = document
        .create_element("input")
        .map_err(|e| describe(&e))?
        .dyn_into()
        .map_err(|_| "not an input element".to_owned())?;
    input.set_type("file");
    input.set_accept(accept);
    let picked = input.clone();
    let ctx = ctx.clone();
    // Called once, when a file is chosen (a cancelled dialog never calls it).
    let on_change = Closure::once_into_js(move || {
        if let Some(file) = picked.files().and_then(|files| files.get(0)) {
            let limit = crate::persist::read_limit(&file.name());
            read_file(ctx, file, limit);
        }
    });
    input.set_onchange(Some(on_change.unchecked_ref()));
    input.click();
    Ok(())
}

/// Fetches the teacher's lesson file at `url` (relative to the page, or another server that
/// allows it with CORS); it arrives as [`News::FetchedLesson`].
pub fn fetch_lesson(ctx: &egui::Context, url: String) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let promise = window.fetch_with_str(&url);
    let ctx = ctx.clone();
    wasm_bindgen_futures::spawn_local(async move {
        let bytes = fetch_bytes(promise, crate::lessons::format::MAX_TEACHER_BYTES).await;
        deliver(&ctx, News::FetchedLesson { url, bytes });
    });
}

/// The body of the response `promise` resolves to, at most `limit` bytes.
async fn fetch_bytes(promise: js_sys::Promise, limit: usize) -> Result<Vec<u8>, String> {
    let response: web_sys::Response = JsFuture::from(promise)
        .await
        .map_err(|e| {
            format!(
                "the server did not answer, or does not allow this page to read it (CORS, or \
                 the page's policy): {}",
                describe(&e)
            )
        })?
        .dyn_into()
        .map_err(|_| "the answer is not a response".to_owned())?;
    if !response.ok() {
        return Err(format!(
            "the server answered {} {}",
            response.status(),
            response.status_text()
        ));
    }
    let buffer = JsFuture::from(response.array_buffer().map_err(|e| describe(&e))?)
        .await
        .map_err(|e| describe(&e))?;
    let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
    if bytes.len() > limit {
        return Err(crate::persist::too_large(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

/// Reads a file dropped on the page; it arrives as [`News::Opened`].
pub fn read_dropped(ctx: &egui::Context, file: &egui::DroppedFileHandle, limit: usize) {
    let name = file.path().display().to_string();
    match file.web_file() {
        Some(web_file) => read_file(ctx.clone(), web_file.clone(), limit),
        None => deliver(
            ctx,
            News::Opened {
                name,
                bytes: Err("the browser gave no file to read".to_owned()),
            },
        ),
    }
}

/// Reads `file`'s bytes (`Blob.arrayBuffer()`: binary meshes must not pass through text),
/// refusing it unread when it is over `limit` bytes.
fn read_file(ctx: egui::Context, file: web_sys::File, limit: usize) {
    let name = file.name();
    if file.size() > limit as f64 {
        let bytes = Err(crate::persist::too_large(file.size() as u64, limit));
        deliver(&ctx, News::Opened { name, bytes });
        return;
    }
    wasm_bindgen_futures::spawn_local(async move {
        let bytes = JsFuture::from(file.array_buffer())
            .await
            .map_err(|e| describe(&e))
            .map(|buffer| js_sys::Uint8Array::new(&buffer).to_vec());
        deliver(&ctx, News::Opened { name, bytes });
    });
}

/// A JavaScript error as text.
fn describe(error: &JsValue) -> String {
    error
        .as_string()
        .or_else(|| {
            error
                .dyn_ref::<js_sys::Error>()
                .map(|e| String::from(e.message()))
        })
        .unwrap_or_else(|| format!("{error:?}"))
}
