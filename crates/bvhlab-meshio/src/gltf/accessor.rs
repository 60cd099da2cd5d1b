//! Reading glTF accessors (glTF 2.0 specification, section 3.6 "Binary Data Storage") with
//! every offset checked, so that a broken file gives an error rather than a panic.
//!
//! An accessor is `count` elements of a type (`VEC3` of `FLOAT` for positions, `SCALAR` of an
//! unsigned integer for indices) in a buffer view, which is a stretch of a buffer, with a byte
//! stride between elements. Element `k` starts at
//! `view.byteOffset + accessor.byteOffset + k · stride` and must end inside the view. An
//! accessor without a view holds zeros; a sparse accessor then replaces some elements.
//!
//! `gltf`'s own reader (its `utils` feature) is not used: it computes `count − 1` unchecked
//! (a panic for an empty accessor in debug builds) and only debug-asserts the element type.

use std::borrow::Cow;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::buffer::View;
use ::gltf::{Accessor, Document};
use base64::Engine;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use bvhlab::glam::Vec3;

use crate::MAX_VERTICES;
use crate::error::grouped;

/// Why an accessor could not be read.
pub(super) enum Fault {
    /// Its data lives in a separate file (the URI).
    External(String),
    /// Anything else, as a sentence.
    Broken(String),
}

/// The glTF buffers: bytes (from the GLB's binary chunk or a base64 data URI), or the URI of
/// the separate file that a single dropped file cannot bring along.
pub(super) struct Buffers<'a> {
    data: Vec<Result<Cow<'a, [u8]>, Fault>>,
}

/// base64 as data URIs carry it, with or without `=` padding.
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

impl<'a> Buffers<'a> {
    /// Decodes the embedded buffers of `document`; `bin` is the GLB binary chunk.
    pub(super) fn new(document: &'a Document, bin: Option<&'a [u8]>) -> Self {
        let data = document
            .buffers()
            .map(|buffer| {
                let bytes = match buffer.source() {
                    ::gltf::buffer::Source::Bin => bin.map(Cow::Borrowed).ok_or_else(|| {
                        Fault::Broken(format!(
                            "buffer {} has no URI, but there is no GLB binary chunk to hold it",
                            buffer.index()
                        ))
                    })?,
                    ::gltf::buffer::Source::Uri(uri) => Cow::Owned(decode_data_uri(uri)?),
                };
                if bytes.len() < buffer.length() {
                    return Err(Fault::Broken(format!(
                        "buffer {} declares {} bytes but holds {}",
                        buffer.index(),
                        buffer.length(),
                        bytes.len()
                    )));
                }
                Ok(bytes)
            })
            .collect();
        Self { data }
    }

    /// The bytes of a buffer view.
    fn view(&self, view: &View<'_>) -> Result<&[u8], Fault> {
        let index = view.buffer().index();
        let buffer = match self.data.get(index) {
            Some(Ok(bytes)) => bytes,
            Some(Err(Fault::External(uri))) => return Err(Fault::External(uri.clone())),
            Some(Err(Fault::Broken(why))) => return Err(Fault::Broken(why.clone())),
            None => return Err(Fault::Broken(format!("there is no buffer {index}"))),
        };
        view.offset()
            .checked_add(view.length())
            .and_then(|end| buffer.get(view.offset()..end))
            .ok_or_else(|| {
                Fault::Broken(format!(
                    "buffer view {} reaches past the end of buffer {index} ({} bytes)",
                    view.index(),
                    buffer.len()
                ))
            })
    }
}

/// The bytes of a `data:…;base64,…` URI; any other URI names a separate file.
fn decode_data_uri(uri: &str) -> Result<Vec<u8>, Fault> {
    let Some(rest) = uri.strip_prefix("data:") else {
        return Err(Fault::External(uri.to_owned()));
    };
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Err(Fault::Broken(
            "a buffer's data URI is not base64 (`data:…;base64,…`)".into(),
        ));
    };
    BASE64
        .decode(payload)
        .map_err(|e| Fault::Broken(format!("a buffer's base64 data is broken: {e}")))
}

/// `count` elements of `size` bytes, `stride` apart, in `data` (all checked on creation).
struct Strided<'a> {
    data: &'a [u8],
    stride: usize,
    size: usize,
}

impl<'a> Strided<'a> {
    /// The elements of `count` at `offset` in a view's bytes, or why they do not fit.
    fn new(
        data: &'a [u8],
        offset: usize,
        stride: Option<usize>,
        size: usize,
        count: usize,
    ) -> Result<Self, String> {
        let stride = stride.unwrap_or(size);
        if stride < size {
            return Err(format!(
                "its byte stride {stride} is less than its element size {size}"
            ));
        }
        let end = count
            .checked_sub(1)
            .map_or(Some(offset), |last| {
                last.checked_mul(stride)
                    .and_then(|x| x.checked_add(offset))
                    .and_then(|x| x.checked_add(size))
            })
            .filter(|&end| end <= data.len())
            .ok_or_else(|| {
                format!(
                    "its {count} elements of {size} bytes ({stride} apart, from byte {offset}) \
                     do not fit in its buffer view of {} bytes",
                    data.len()
                )
            })?;
        Ok(Self {
            data: &data[offset.min(end)..end],
            stride,
            size,
        })
    }

    /// Element `k` (in range by construction when `k < count`).
    fn get(&self, k: usize) -> &'a [u8] {
        let start = k * self.stride;
        &self.data[start..start + self.size]
    }
}

/// An accessor's elements, decoded from `size`-byte slices by `decode`, sparse substitution
/// applied.
fn read<T: Copy>(
    accessor: &Accessor<'_>,
    buffers: &Buffers<'_>,
    zero: T,
    decode: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, Fault> {
    let broken = |why: String| Fault::Broken(format!("accessor {}: {why}", accessor.index()));
    let (count, size) = (accessor.count(), accessor.size());
    if count > MAX_VERTICES {
        return Err(broken(format!(
            "it has {} elements; the lab reads at most {}",
            grouped(count),
            grouped(MAX_VERTICES)
        )));
    }
    let mut out = match accessor.view() {
        Some(view) => {
            let data = buffers.view(&view)?;
            let elements = Strided::new(data, accessor.offset(), view.stride(), size, count)
                .map_err(broken)?;
            (0..count).map(|k| decode(elements.get(k))).collect()
        }
        None => vec![zero; count],
    };
    if let Some(sparse) = accessor.sparse() {
        let n = sparse.count();
        let indices = sparse.indices();
        let index_size = match indices.index_type() {
            ::gltf::accessor::sparse::IndexType::U8 => 1,
            ::gltf::accessor::sparse::IndexType::U16 => 2,
            ::gltf::accessor::sparse::IndexType::U32 => 4,
        };
        let index_data = buffers.view(&indices.view())?;
        let at = Strided::new(index_data, indices.offset(), None, index_size, n).map_err(broken)?;
        let values = sparse.values();
        let value_data = buffers.view(&values.view())?;
        let value = Strided::new(value_data, values.offset(), None, size, n).map_err(broken)?;
        for k in 0..n {
            let target = unsigned(at.get(k)) as usize;
            let slot = out.get_mut(target).ok_or_else(|| {
                broken(format!(
                    "sparse index {target} is past its {count} elements"
                ))
            })?;
            *slot = decode(value.get(k));
        }
    }
    Ok(out)
}

/// A little-endian unsigned integer of 1, 2 or 4 bytes.
fn unsigned(bytes: &[u8]) -> u32 {
    match *bytes {
        [a] => a.into(),
        [a, b] => u16::from_le_bytes([a, b]).into(),
        [a, b, c, d] => u32::from_le_bytes([a, b, c, d]),
        _ => 0,
    }
}

/// The positions of a `POSITION` accessor (`VEC3` of `FLOAT`).
pub(super) fn positions(
    accessor: &Accessor<'_>,
    buffers: &Buffers<'_>,
) -> Result<Vec<Vec3>, Fault> {
    if (accessor.data_type(), accessor.dimensions()) != (DataType::F32, Dimensions::Vec3) {
        return Err(Fault::Broken(format!(
            "accessor {} holds positions as {:?} of {:?}; the lab reads VEC3 of FLOAT (quantized \
             positions are not supported)",
            accessor.index(),
            accessor.dimensions(),
            accessor.data_type()
        )));
    }
    read(accessor, buffers, Vec3::ZERO, |b| {
        let f = |i: usize| f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
        Vec3::new(f(0), f(4), f(8))
    })
}

/// The indices of an index accessor (`SCALAR` of an unsigned integer type).
pub(super) fn indices(accessor: &Accessor<'_>, buffers: &Buffers<'_>) -> Result<Vec<u32>, Fault> {
    let unsigned_type = matches!(
        accessor.data_type(),
        DataType::U8 | DataType::U16 | DataType::U32
    );
    if !unsigned_type || accessor.dimensions() != Dimensions::Scalar {
        return Err(Fault::Broken(format!(
            "accessor {} holds indices as {:?} of {:?}; indices are SCALAR of an unsigned \
             integer type",
            accessor.index(),
            accessor.dimensions(),
            accessor.data_type()
        )));
    }
    read(accessor, buffers, 0, unsigned)
}

#[cfg(test)]
mod tests {
    use super::Strided;

    #[test]
    fn strided_elements_must_fit() {
        let data = [0u8, 1, 2, 3, 4, 5, 6, 7, 8, 9];
        let s = Strided::new(&data, 0, Some(4), 2, 3).expect("0..2, 4..6, 8..10");
        assert_eq!((s.get(0), s.get(2)), (&[0, 1][..], &[8, 9][..]));
        let s = Strided::new(&data, 1, Some(4), 2, 2).expect("1..3, 5..7");
        assert_eq!(s.get(1), &[5, 6][..]);
        assert!(Strided::new(&data, 1, Some(4), 2, 3).is_err());
        assert!(Strided::new(&data, 0, Some(1), 2, 3).is_err());
        assert!(Strided::new(&data, 0, None, 2, usize::MAX).is_err());
        assert!(Strided::new(&data, 11, None, 2, 0).is_err());
        assert!(Strided::new(&data, 10, None, 2, 0).is_ok());
    }
}
