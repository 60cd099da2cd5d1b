//! The live region (`#lab-status`): what a screen reader announces by itself as the lab
//! changes. It says only the news ([`crate::report::speech::news`]: the sentences that differ
//! from what it said last), and at most every [`GAP_MS`]: steps taken faster than that (a key
//! held down, playback) are coalesced into the last one, told against what was said before
//! them, so a student hears where playback is now rather than a queue of steps gone by.

use std::cell::RefCell;

use super::timer::{after_ms, now_ms};
use crate::report::speech::news;

/// The shortest time between two announcements, in milliseconds.
const GAP_MS: f64 = 500.0;

#[derive(Default)]
struct Live {
    /// The sentences as last told.
    told: Vec<String>,
    /// The sentences as they are now.
    now: Vec<String>,
    /// When the region was last written (milliseconds since the page opened).
    last_ms: Option<f64>,
    /// A timer is set to tell what is waiting.
    timer: bool,
}

thread_local! {
    static LIVE: RefCell<Live> = RefCell::new(Live::default());
}

/// The report's sentences are now `sentences`: tells the news now, or when [`GAP_MS`] have
/// passed since the last announcement.
pub fn tell(sentences: Vec<String>) {
    LIVE.with(|l| l.borrow_mut().now = sentences);
    tell_now_or_later(false);
}

fn tell_now_or_later(from_timer: bool) {
    let t = now_ms();
    let text = LIVE.with(|l| {
        let mut l = l.borrow_mut();
        if from_timer {
            l.timer = false;
        }
        if let Some(last) = l.last_ms
            && t - last < GAP_MS
        {
            if !l.timer {
                l.timer = set_timer(GAP_MS - (t - last));
            }
            return None;
        }
        let l = &mut *l;
        let text = news(&l.told, &l.now);
        l.told.clone_from(&l.now);
        if text.is_empty() {
            return None;
        }
        l.last_ms = Some(t);
        Some(text)
    });
    if let Some(text) = text
        && let Some(element) = web_sys::window()
            .and_then(|w| w.document())
            .and_then(|d| d.get_element_by_id("lab-status"))
    {
        element.set_text_content(Some(&text));
    }
}

/// Calls [`tell_now_or_later`] in `ms` milliseconds; whether the timer is set.
fn set_timer(ms: f64) -> bool {
    after_ms(ms, || tell_now_or_later(true))
}
