//! A material's texture: the image's bytes (from a buffer view or a URI),
//! its size read from its header and counted against
//! [`LoadLimits`](crate::LoadLimits)' texture bounds before it is decoded,
//! then decoded to linear RGBA (glTF colour textures are sRGB).

use super::Reader;
use super::buffers::read_uri;
use crate::Texture;
use crate::error::GltfError;
use glam::Vec4;
use std::path::Path;

/// `texture`'s image decoded, or `None` with a warning for a format this
/// build does not decode; `material` names where it is used.
pub(super) fn read_texture(
    r: &Reader,
    material: &str,
    texture: &gltf::Texture,
    buffers: &[Vec<u8>],
    dir: Option<&Path>,
    warnings: &mut Vec<String>,
) -> Result<Option<Texture>, GltfError> {
    let image = texture.source();
    let object = format!("images[{}]", image.index());
    let bytes = match image.source() {
        gltf::image::Source::View { view, .. } => {
            let data = &buffers[view.buffer().index()];
            let end = view.offset() + view.length();
            data.get(view.offset()..end)
                .ok_or_else(|| {
                    r.error(&object, format!("bufferViews[{}] is out of range of its buffer", view.index()))
                })?
                .to_vec()
        }
        gltf::image::Source::Uri { uri, .. } => read_uri(r, &object, uri, dir)?,
    };
    let format = image::guess_format(&bytes).ok();
    if format != Some(image::ImageFormat::Png) {
        warnings.push(format!(
            "{material}: {object} is {}, which this build does not decode (PNG only); base colour factor used alone",
            format.map_or("not a known image format".to_string(), |f| format!("{f:?}"))
        ));
        return Ok(None);
    }
    let (width, height) = image::ImageReader::with_format(std::io::Cursor::new(&bytes), image::ImageFormat::Png)
        .into_dimensions()
        .map_err(|e| r.error(&object, format!("the PNG's header does not decode: {e}")))?;
    let pixels = r.texture_pixels.get() + width as u64 * height as u64;
    let limits = &r.limits;
    let what = format!("a {width}x{height} image: the count of texture pixels");
    r.within(Some(&object), &what, pixels, limits.max_texture_pixels, "max_texture_pixels")?;
    let what = format!("a {width}x{height} image: the count of texture bytes (16 a pixel)");
    r.within(Some(&object), &what, pixels.saturating_mul(16), limits.max_texture_bytes, "max_texture_bytes")?;
    r.texture_pixels.set(pixels);
    let decoded = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .map_err(|e| r.error(&object, format!("the PNG does not decode: {e}")))?
        .to_rgba32f();
    let (width, height) = decoded.dimensions();
    // 0 and 1 map to themselves exactly.
    let linear = |c: f32| match c {
        c if c <= 0.04045 => c / 12.92,
        c if c >= 1.0 => c,
        c => ((c + 0.055) / 1.055).powf(2.4),
    };
    let texels = decoded.pixels().map(|p| Vec4::new(linear(p[0]), linear(p[1]), linear(p[2]), p[3])).collect();
    Ok(Some(Texture { width, height, texels }))
}
