//! The binary glTF container (glTF 2.0 specification, section 4.4 "GLB File Format"): a
//! 12-byte header (`glTF`, version 2, total length), then chunks of (length, type, data): a
//! `JSON` chunk first, then optionally a `BIN\0` chunk holding buffer 0. All numbers are
//! little-endian `u32`.
//!
//! Read here rather than by `gltf::Glb`, which subtracts the header size from the declared
//! length without a check (a panic in debug builds for a length below 12).

/// A chunk's type (four bytes) and data.
type Chunk<'a> = (&'a [u8], &'a [u8]);

/// The JSON chunk and the binary chunk, if any, of a GLB file; or what is wrong with it.
pub(super) fn split(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), String> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize)
    };
    if !bytes.starts_with(b"glTF") {
        return Err("a GLB file starts with the bytes `glTF`, and this one does not".into());
    }
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(format!(
            "a GLB file starts with a 12-byte header, and this one has only {} bytes",
            bytes.len()
        ));
    };
    match version {
        2 => {}
        1 => return Err("this is a glTF 1.0 binary file; the lab reads glTF 2.0".into()),
        v => {
            return Err(format!(
                "the GLB header says version {v}; the lab reads version 2"
            ));
        }
    }
    if length > bytes.len() {
        return Err(format!(
            "the GLB header says the file has {length} bytes, but it has {} (a cut-off file?)",
            bytes.len()
        ));
    }
    let chunk = |at: usize| -> Result<Option<Chunk<'_>>, String> {
        if at >= length {
            return Ok(None);
        }
        let (Some(size), Some(kind)) = (word(at), bytes.get(at + 4..at + 8)) else {
            return Err(format!(
                "the GLB chunk at byte {at} is cut off inside its header"
            ));
        };
        let data = at
            .checked_add(8 + size)
            .filter(|&end| end <= length)
            .map(|end| &bytes[at + 8..end])
            .ok_or_else(|| {
                format!(
                    "the GLB chunk at byte {at} says it has {size} bytes, but the file ends \
                     {} bytes later (a cut-off file?)",
                    length.saturating_sub(at + 8)
                )
            })?;
        Ok(Some((kind, data)))
    };
    let json = match chunk(12)? {
        Some((b"JSON", json)) => json,
        Some(_) => return Err("the first GLB chunk is not the JSON chunk".into()),
        None => return Err("the GLB file has no JSON chunk".into()),
    };
    // Chunks of other types may follow and are to be ignored (section 4.4.3.1).
    let mut at = 20 + json.len();
    while let Some((kind, data)) = chunk(at)? {
        if kind == b"BIN\0" {
            return Ok((json, Some(data)));
        }
        at += 8 + data.len();
    }
    Ok((json, None))
}

#[cfg(test)]
mod tests {
    use super::split;

    fn glb(chunks: &[(&[u8; 4], &[u8])], declared: Option<u32>) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend_from_slice(&(data.len() as u32).to_le_bytes());
            body.extend_from_slice(*kind);
            body.extend_from_slice(data);
        }
        let length = declared.unwrap_or(12 + body.len() as u32);
        let mut out = b"glTF".to_vec();
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&length.to_le_bytes());
        out.extend(body);
        out
    }

    #[test]
    fn json_and_bin_chunks() {
        let file = glb(
            &[(b"JSON", b"{}  "), (b"XTRA", b"1234"), (b"BIN\0", b"abcd")],
            None,
        );
        assert_eq!(split(&file), Ok((&b"{}  "[..], Some(&b"abcd"[..]))));
        let file = glb(&[(b"JSON", b"{}  ")], None);
        assert_eq!(split(&file), Ok((&b"{}  "[..], None)));
    }

    #[test]
    fn cut_off_and_lying_files_are_refused() {
        let file = glb(&[(b"JSON", b"{}  "), (b"BIN\0", b"abcd")], None);
        for cut in [3, 11, 20, 25, file.len() - 1] {
            assert!(split(&file[..cut]).is_err(), "cut at {cut}");
        }
        for length in [0, 5, 12, 1000] {
            let lying = glb(&[(b"JSON", b"{}  ")], Some(length));
            assert!(split(&lying).is_err(), "declared length {length}");
        }
        let bin_first = glb(&[(b"BIN\0", b"abcd")], None);
        assert!(split(&bin_first).is_err());
    }
}
