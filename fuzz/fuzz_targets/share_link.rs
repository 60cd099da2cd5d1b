//! Share links, as a student pastes them: any address fragment. Random bytes rarely get past
//! base64 and zlib's checksum, so the first byte picks how the rest reaches the link reader:
//!
//! - as the fragment itself (hostile text: wrong prefix, bad base64, huge lengths);
//! - as a zlib stream, base64url-encoded behind `#s=` by this target (broken or bomb-like
//!   deflate data reaches the inflater);
//! - as the state's JSON, deflated and encoded by this target (the link's checks on JSON the
//!   lab did not write).
//!
//! A link that opens must then open in a lab and export again (see `bvhlab_fuzz::accepted`).

#![no_main]

use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use bvhlab_app::persist::from_fragment;
use libfuzzer_sys::fuzz_target;

bvhlab_fuzz::same_hash_keys_every_run!();

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let fragment = match mode % 3 {
        0 => String::from_utf8_lossy(rest).into_owned(),
        1 => format!("#s={}", URL_SAFE_NO_PAD.encode(rest)),
        _ => {
            let packed = miniz_oxide::deflate::compress_to_vec_zlib(rest, 1);
            format!("#s={}", URL_SAFE_NO_PAD.encode(packed))
        }
    };
    if let Ok(state) = from_fragment(&fragment) {
        bvhlab_fuzz::accepted(state);
    }
});
