//! Share links: the state's compact JSON, deflated in a zlib stream (RFC 1950/1951: its
//! Adler-32 checksum catches a link damaged in transit) and base64url-encoded (RFC 4648 §5,
//! no padding) into the address's fragment, `#s=...`. The fragment never reaches a server,
//! so the lab stays a static page.

use base64::Engine as _;
use base64::alphabet::URL_SAFE;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use miniz_oxide::inflate::TINFLStatus;

use super::file::from_json;
use super::state::SavedState;
use super::{MAX_LINK_CHARS, MAX_LINK_JSON_BYTES};

/// What starts a share link's fragment.
pub const LINK_PREFIX: &str = "#s=";

/// base64url without padding, reading padded input as well.
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &URL_SAFE,
    GeneralPurposeConfig::new()
        .with_encode_padding(false)
        .with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

/// The fragment that opens `state`: `#s=` and its JSON, deflated and base64url-encoded.
///
/// # Errors
/// When the fragment would be longer than [`MAX_LINK_CHARS`]: a message saying to export
/// the scene as a file instead.
pub fn link_fragment(state: &SavedState) -> Result<String, String> {
    let json =
        serde_json::to_vec(state).map_err(|e| format!("the state cannot be written: {e}"))?;
    let packed = miniz_oxide::deflate::compress_to_vec_zlib(&json, 10);
    let fragment = format!("{LINK_PREFIX}{}", BASE64.encode(packed));
    if fragment.len() > MAX_LINK_CHARS {
        return Err(format!(
            "this scene needs a link of {} characters, more than the {MAX_LINK_CHARS} a link \
             carries safely: export the scene as a file instead",
            fragment.len()
        ));
    }
    Ok(fragment)
}

/// The state a share link's fragment carries (with or without the leading `#`).
///
/// # Errors
/// When the fragment is not a share link, is longer than [`MAX_LINK_CHARS`], is not
/// base64url, does not inflate (or inflates past [`MAX_LINK_JSON_BYTES`]), or its JSON is not
/// a usable state.
pub fn from_fragment(fragment: &str) -> Result<SavedState, String> {
    let fragment = fragment.trim();
    let body = fragment.strip_prefix('#').unwrap_or(fragment);
    let Some(data) = body.strip_prefix(&LINK_PREFIX[1..]) else {
        return Err("the link carries no scene (its address has no #s= part)".to_owned());
    };
    if fragment.len() > MAX_LINK_CHARS {
        return Err(format!(
            "the link is {} characters long, more than any link the lab makes ({MAX_LINK_CHARS})",
            fragment.len()
        ));
    }
    let packed = BASE64
        .decode(data)
        .map_err(|e| format!("the link is damaged (not base64url: {e})"))?;
    let json =
        miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(&packed, MAX_LINK_JSON_BYTES)
            .map_err(|e| match e.status {
                TINFLStatus::HasMoreOutput => format!(
                    "the link's scene inflates past {} MiB, more than any link the lab makes",
                    MAX_LINK_JSON_BYTES >> 20
                ),
                _ => format!("the link is damaged (its data does not inflate: {e})"),
            })?;
    from_json(&json, "the link's scene")
}
