//! Writing output buffers as images: PNG (8-bit, clamped to `[0, 1]`),
//! Radiance HDR (float RGB) and OpenEXR (float RGBA, values as they are). Launch index `(0, 0)` is the bottom-left pixel, as
//! in OptiX's samples, so rows are flipped on the way out.

use crate::error::{IoError, Result, RtError, SceneError};
use crate::{BufferId, Context};
use glam::{Vec3, Vec4};

fn image_err(path: &std::path::Path, e: impl std::fmt::Display) -> RtError {
    IoError::Image { path: path.display().to_string(), problem: e.to_string() }.into()
}

/// The buffer's pixels as RGBA, for `Vec4`, `Vec3` and `f32` buffers.
fn rgba(ctx: &Context, b: BufferId) -> Result<(u32, u32, Vec<Vec4>)> {
    let (w, h) = ctx.buffer_size(b)?;
    let px = if let Ok(v) = ctx.read_buffer::<Vec4>(b) {
        v
    } else if let Ok(v) = ctx.read_buffer::<Vec3>(b) {
        v.into_iter().map(|c| c.extend(1.0)).collect()
    } else {
        let v = ctx.read_buffer::<f32>(b).map_err(|_| SceneError::BadBuffer {
            buffer: b.index(),
            problem: "only Vec4, Vec3 and f32 buffers can be saved as images".into(),
        })?;
        v.into_iter().map(|x| Vec4::new(x, x, x, 1.0)).collect()
    };
    Ok((w, h, px))
}

impl Context {
    /// Saves a 2D output buffer as an 8-bit PNG (values clamped to `[0, 1]`).
    pub fn save_png(&self, b: BufferId, path: impl AsRef<std::path::Path>) -> Result<()> {
        let path = path.as_ref();
        let (w, h, px) = rgba(self, b)?;
        save_png(path, w, h, &px)
    }

    /// Saves a 2D output buffer as a Radiance HDR image (float RGB).
    pub fn save_hdr(&self, b: BufferId, path: impl AsRef<std::path::Path>) -> Result<()> {
        let path = path.as_ref();
        let (w, h, px) = rgba(self, b)?;
        let mut rows: Vec<image::Rgb<f32>> = Vec::with_capacity(px.len());
        for y in (0..h).rev() {
            for x in 0..w {
                let c = px[(y * w + x) as usize];
                rows.push(image::Rgb([c.x, c.y, c.z]));
            }
        }
        let file = std::fs::File::create(path).map_err(|e| image_err(path, e))?;
        image::codecs::hdr::HdrEncoder::new(std::io::BufWriter::new(file))
            .encode(&rows, w as usize, h as usize)
            .map_err(|e| image_err(path, e))
    }
}

impl Context {
    /// Saves a 2D output buffer as an OpenEXR image: 32-bit float RGBA,
    /// every value as the buffer holds it (no clamping, no gamma), so a
    /// reader gets back the same bits.
    pub fn save_exr(&self, b: BufferId, path: impl AsRef<std::path::Path>) -> Result<()> {
        let path = path.as_ref();
        let (w, h, px) = rgba(self, b)?;
        let bytes = encode_exr(w, h, &px).map_err(|e| image_err(path, e))?;
        std::fs::write(path, bytes).map_err(|e| image_err(path, e))
    }
}

/// RGBA pixels (row 0 at the bottom) as OpenEXR bytes (32-bit float RGBA,
/// row 0 at the top).
pub fn encode_exr(w: u32, h: u32, px: &[Vec4]) -> std::result::Result<Vec<u8>, String> {
    let mut rows = Vec::with_capacity(px.len() * 4);
    for y in (0..h).rev() {
        for x in 0..w {
            rows.extend(px[(y * w + x) as usize].to_array());
        }
    }
    let image = image::Rgba32FImage::from_raw(w, h, rows).ok_or("the pixels do not fill the image")?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgba32F(image)
        .write_to(&mut bytes, image::ImageFormat::OpenExr)
        .map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// Writes RGBA pixels (row 0 at the bottom) as an 8-bit PNG.
pub fn save_png(path: &std::path::Path, w: u32, h: u32, px: &[Vec4]) -> Result<()> {
    let img = to_rgba8(w, h, px);
    img.save_with_format(path, image::ImageFormat::Png).map_err(|e| image_err(path, e))
}

/// RGBA pixels (row 0 at the bottom) as an 8-bit image (row 0 at the top).
pub fn to_rgba8(w: u32, h: u32, px: &[Vec4]) -> image::RgbaImage {
    image::RgbaImage::from_fn(w, h, |x, y| {
        let c = px[((h - 1 - y) * w + x) as usize];
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
        image::Rgba([q(c.x), q(c.y), q(c.z), q(c.w)])
    })
}
