//! What the scene-file and share-link targets check once a state has been read: the lab's
//! promises about a state that passed its checks.

use bvhlab_app::model::{Action, Lab};
use bvhlab_app::persist::{SavedState, from_file, from_fragment, link_fragment, to_file};

/// A state that `from_file` or `from_fragment` accepted must pass `check`, open in a fresh lab
/// (which then runs one frame: its structures built and queried, as the next frame would),
/// and come back from the scene file and the share link the lab writes for it (export then
/// import).
///
/// # Panics
/// When any of that fails: the fuzzer reports it as a crash.
pub fn accepted(state: SavedState) {
    assert_eq!(state.check(), Ok(()), "an accepted state fails its check");
    let mut lab = Lab::default();
    let restore = match state.apply() {
        Ok(action) => action,
        Err(error) => panic!("an accepted state gives no action: {error}"),
    };
    if let Err(error) = lab.apply(restore) {
        panic!("an accepted state does not apply: {error}");
    }
    if let Err(error) = lab.apply(Action::Tick {
        seconds: 0.0,
        build_ms: 50.0,
    }) {
        panic!("the frame after opening it fails: {error}");
    }
    if let Err(error) = from_file(&to_file(&lab)) {
        panic!("the exported scene file does not read back: {error}");
    }
    // A state may be too large for a link (the lab says so); one that fits must read back.
    if let Ok(link) = link_fragment(&SavedState::capture(&lab))
        && let Err(error) = from_fragment(&link)
    {
        panic!("the share link made for it does not open: {error}");
    }
}

/// Gives the hash maps of the code under test the same keys in every run, so that a run of
/// `tests/fuzz.sh check` (a fixed seed, a fixed count of runs) explores the same inputs every
/// time: the mesh readers, the lab's model and their dependencies keep `HashMap`s whose
/// iteration order, and so the coverage libFuzzer steers by, follows their random keys.
///
/// It defines `getrandom`, the C library's call that the standard library asks for those keys
/// (weakly linked, so the program's own definition is the one it calls), filling the buffer
/// with zeros. Nothing under test needs random numbers otherwise; libFuzzer seeds its own
/// generator from `-seed` or the clock, not from `getrandom`. One line in each target:
/// `bvhlab_fuzz::same_hash_keys_every_run!();`.
#[macro_export]
macro_rules! same_hash_keys_every_run {
    () => {
        /// `getrandom(2)` of the C library, answered with zeros: see
        /// `bvhlab_fuzz::same_hash_keys_every_run`.
        #[unsafe(no_mangle)]
        pub extern "C" fn getrandom(buf: *mut u8, len: usize, _flags: u32) -> isize {
            if !buf.is_null() {
                // SAFETY: the caller (the standard library, as the C function's contract
                // says) hands a buffer of `len` writable bytes.
                unsafe { ::std::ptr::write_bytes(buf, 0, len) };
            }
            len as isize
        }
    };
}
