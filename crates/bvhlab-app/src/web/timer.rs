//! The page's clock and its one-shot timers, for the parts of the lab that tell the page
//! something at most so often (the mirror for screen readers, the live region).

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// Milliseconds since the page opened (`performance.now()`; 0 where there is none).
pub fn now_ms() -> f64 {
    web_sys::window()
        .and_then(|w| w.performance())
        .map_or(0.0, |p| p.now())
}

/// Calls `f` once in `ms` milliseconds; whether the page took the timer.
pub fn after_ms(ms: f64, f: impl FnOnce() + 'static) -> bool {
    let Some(window) = web_sys::window() else {
        return false;
    };
    let callback = Closure::once_into_js(f);
    window
        .set_timeout_with_callback_and_timeout_and_arguments_0(
            callback.unchecked_ref(),
            ms.ceil() as i32,
        )
        .is_ok()
}
