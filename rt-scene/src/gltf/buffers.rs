//! The bytes behind a glTF document: the GLB container's header, and each
//! buffer's data from the GLB's binary chunk, a `data:` URI (base64) or a
//! file beside the document. Also the byte ranges accessors read, checked
//! against those bytes before anything is read, so an accessor out of range
//! is an error naming it rather than a short read.
//!
//! The `gltf` crate's `import` feature does this too, but pulls in base64
//! 0.13, urlencoding and image's JPEG decoder; the little needed is here.

use super::Reader;
use crate::clip::{clip, clip_path};
use crate::error::GltfError;
use std::path::Path;

/// Checks a GLB container's 12-byte header against the file's length, so a
/// truncated file is reported as truncated (and the `gltf` crate never sees
/// a header whose length it would underflow on).
pub(super) fn check_glb_header(r: &Reader, bytes: &[u8]) -> Result<(), GltfError> {
    if bytes.len() < 12 {
        return Err(r.file_error(format!("truncated GLB: {} bytes, shorter than its 12-byte header", bytes.len())));
    }
    let word = |i: usize| u32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    let (version, length) = (word(4), word(8) as usize);
    if version != 2 {
        return Err(r.file_error(format!("GLB version {version}; only glTF 2.0 is supported")));
    }
    if length < 12 {
        return Err(r.file_error(format!("corrupt GLB: its header gives a length of {length} bytes")));
    }
    if length > bytes.len() {
        return Err(
            r.file_error(format!("truncated GLB: its header says {length} bytes, the file has {}", bytes.len()))
        );
    }
    Ok(())
}

/// Every buffer's bytes, in document order, each at least as long as the
/// buffer declares.
pub(super) fn load_buffers(
    r: &Reader,
    doc: &gltf::Document,
    blob: Option<Vec<u8>>,
    dir: Option<&Path>,
) -> Result<Vec<Vec<u8>>, GltfError> {
    let mut blob = blob;
    let mut out = Vec::new();
    let mut total = 0u64;
    for buffer in doc.buffers() {
        let object = format!("buffers[{}]", buffer.index());
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                r.error(&object, "refers to the GLB binary chunk, but the file has none (or it is used twice)".into())
            })?,
            gltf::buffer::Source::Uri(uri) => read_uri(r, &object, uri, dir)?,
        };
        total += buffer.length() as u64;
        r.within(Some(&object), "the count of buffer bytes", total, r.limits.max_buffer_bytes, "max_buffer_bytes")?;
        if data.len() < buffer.length() {
            return Err(
                r.error(&object, format!("declares {} bytes, but its data has only {}", buffer.length(), data.len()))
            );
        }
        out.push(data);
    }
    Ok(out)
}

/// The bytes of a buffer's or image's URI: a base64 `data:` URI, or a path
/// relative to the document (percent-escapes decoded).
pub(super) fn read_uri(r: &Reader, object: &str, uri: &str, dir: Option<&Path>) -> Result<Vec<u8>, GltfError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, payload)) = rest.split_once(";base64,") else {
            return Err(r.error(object, "a `data:` URI that is not base64".into()));
        };
        let limit = r.limits.max_data_uri_bytes;
        r.within(
            Some(object),
            "the `data:` URI's count of bytes",
            payload.len() as u64 / 4 * 3,
            limit,
            "max_data_uri_bytes",
        )?;
        return base64(payload).ok_or_else(|| r.error(object, "a `data:` URI whose base64 does not decode".into()));
    }
    if uri.contains("://") {
        return Err(
            r.error(object, format!("URI `{}` is not a local file; only relative paths and data: URIs", clip(uri)))
        );
    }
    let relative = percent_decode(uri);
    let path = crate::limits::resolve(dir, &relative, &r.limits)
        .map_err(|why| r.error(object, format!("URI `{}`: cannot read {why}", clip(uri))))?;
    crate::limits::read_file(&path, &r.limits)
        .map_err(|why| r.error(object, format!("URI `{}`: cannot read {}: {why}", clip(uri), clip_path(&path))))
}

fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (padding optional, whitespace ignored); `None` for any
/// other character.
pub(crate) fn base64(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for &c in text.as_bytes() {
        if c == b'=' || c.is_ascii_whitespace() {
            continue;
        }
        acc = (acc << 6) | value(c)?;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// Checks that `accessor`'s elements lie inside its buffer view and the
/// view inside its buffer; `object` names where it is used.
pub(super) fn check_accessor(
    r: &Reader,
    object: &str,
    accessor: &gltf::Accessor,
    buffers: &[Vec<u8>],
) -> Result<(), GltfError> {
    let at = format!("{object} (accessors[{}])", accessor.index());
    if accessor.sparse().is_some() {
        return Err(r.error(&at, "sparse accessors are not supported".into()));
    }
    let Some(view) = accessor.view() else {
        return Err(r.error(&at, "has no buffer view (all zeros); not supported for geometry".into()));
    };
    let buffer_len = buffers[view.buffer().index()].len();
    let view_end = view.offset().saturating_add(view.length());
    if view_end > buffer_len {
        return Err(r.error(
            &at,
            format!(
                "bufferViews[{}] spans bytes {}..{view_end} of buffers[{}], which has {buffer_len}",
                view.index(),
                view.offset(),
                view.buffer().index()
            ),
        ));
    }
    let size = accessor.size();
    let stride = view.stride().unwrap_or(size);
    let count = accessor.count();
    let needed = if count == 0 { 0 } else { accessor.offset() + stride * (count - 1) + size };
    if needed > view.length() {
        return Err(r.error(
            &at,
            format!(
                "{count} elements of {size} bytes (stride {stride}) from offset {} need {needed} bytes, but bufferViews[{}] has {}: out of range",
                accessor.offset(),
                view.index(),
                view.length()
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn base64_decodes_with_and_without_padding() {
        assert_eq!(super::base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(super::base64("aGVsbG8").unwrap(), b"hello");
        assert_eq!(super::base64("AAECAw==").unwrap(), [0, 1, 2, 3]);
        assert!(super::base64("a*b").is_none());
    }

    #[test]
    fn percent_escapes_decode() {
        assert_eq!(super::percent_decode("my%20mesh.bin"), "my mesh.bin");
        assert_eq!(super::percent_decode("100%"), "100%");
    }
}
