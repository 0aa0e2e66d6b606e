//! The denoiser's temporal mode: the temporal part of SVGF (Schied et al.
//! 2017), run before the spatial filter ([`super::denoise`]) when the
//! stage's `temporal` is 1. This file is the reference; the wgpu backend
//! runs the same pass as WGSL (`postprocess/gpu/temporal.wgsl`).
//!
//! The stage keeps a history of its last run, per pixel: the accumulated
//! colour and how many frames it holds, the first two moments of the
//! demodulated luminance, the unit normal and the world position. Each
//! pixel of a new frame is reprojected: its world position (the
//! `input_position_buffer` guide) is projected through the camera of the
//! history's frame ([`Pinhole`], the stage's `camera_eye`, `camera_u`,
//! `camera_v`, `camera_w`, as the examples' cameras name them) to the
//! pixel it was seen at then. That pixel's history is taken when it saw
//! the same surface: both hit something, normals within
//! [`NORMAL_AGREEMENT`], and the old position within
//! [`PLANE_TOLERANCE`] of the new one's tangent plane (relative to its
//! distance from the eye); else the pixel is disoccluded and starts again.
//! The new colour and moments are blended into the history's by
//! `alpha = max(alpha_min, 1 / length)`. The luminance's variance is
//! the moments' (times `alpha`: the variance of the blended mean) once a
//! pixel holds [`VARIANCE_FRAMES`] frames; before, it is unknown (-1)
//! and the spatial filter estimates it from the neighbours.
//!
//! The accumulated colour and variance are what the spatial filter then
//! takes as its input and per-pixel variance. A history of another size
//! than the run's is no history; `Context::reset_stage_history` drops it.
//! A pixel whose camera ray hit nothing (position `w` of 0) keeps none.
//!
//! Where the history lives: on the CPU backend on the host; on the wgpu
//! backend in device buffers the stage owns (`gpu.rs`'s `DeviceHistory`),
//! read and written inside the run's submission, never read back by a
//! run (`Context::stage_history` reads it when asked). A run on the other
//! backend takes it along (one upload, or one read back); one on a device
//! lost since is dropped, and the next run starts again.

use super::denoise::{demodulation, luminance, unit_normal};
use glam::{Vec2, Vec3, Vec4, Vec4Swizzles};

/// The normals of a pixel and of its reprojected history must agree by
/// at least this cosine.
pub const NORMAL_AGREEMENT: f32 = 0.9;

/// The history's position may lie this far (times the new position's
/// distance from the eye) off the new one's tangent plane.
pub const PLANE_TOLERANCE: f32 = 0.02;

/// Frames a pixel's history must hold before its moments give its
/// variance.
pub const VARIANCE_FRAMES: f32 = 4.0;

/// A history's frame count stops growing here.
pub const MAX_FRAMES: f32 = 256.0;

/// History texels a pixel: colour (rgb) and frames (w), moments (x, y),
/// unit normal (xyz), position (xyz, w 1 where it hit something).
pub const TEXELS: usize = 4;

/// A pinhole camera as the examples' cameras take it: a ray through
/// `d` in `[-1, 1]^2` (`(-1, -1)` the bottom-left corner, launch index
/// `(0, 0)`) leaves `eye` along `d.x * u + d.y * v + w`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pinhole {
    /// Where the rays leave from.
    pub eye: Vec3,
    /// Half the picture's width, to the right.
    pub u: Vec3,
    /// Half its height, up.
    pub v: Vec3,
    /// To the picture's centre (at `d` of 0).
    pub w: Vec3,
}

impl Pinhole {
    /// The pixel (launch index) of a `width` x `height` picture where
    /// point `p` appears, if in front of the camera and in the frame.
    pub fn pixel_of(&self, p: Vec3, width: usize, height: usize) -> Option<(usize, usize)> {
        let d = p - self.eye;
        let w_len2 = self.w.length_squared();
        let depth = d.dot(self.w) / w_len2;
        if depth <= 0.0 || !depth.is_finite() {
            return None;
        }
        let screen =
            Vec2::new(d.dot(self.u) / self.u.length_squared(), d.dot(self.v) / self.v.length_squared()) / depth;
        let px = (screen + 1.0) * 0.5 * Vec2::new(width as f32, height as f32);
        let inside = px.x >= 0.0 && px.y >= 0.0 && px.x < width as f32 && px.y < height as f32;
        inside.then_some((px.x as usize, px.y as usize))
    }
}

/// A frame's images for the temporal pass, row-major, `width * height`
/// pixels each.
pub struct Frame<'a> {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The frame's (noisy) colour.
    pub color: &'a [Vec4],
    /// The first hit's albedo (the luminance is demodulated by it).
    pub albedo: &'a [Vec4],
    /// The first hit's shading normal.
    pub normal: &'a [Vec4],
    /// The world position of what each pixel's camera ray hit (xyz over
    /// w; w 0 where it hit nothing).
    pub position: &'a [Vec4],
    /// The frame's camera.
    pub camera: Pinhole,
}

/// The pass's result: the colour and variance the spatial filter takes,
/// and the next history ([`TEXELS`] a pixel).
pub struct Accumulated {
    /// The blended colour (the input's alpha).
    pub color: Vec<Vec4>,
    /// The blended luminance's variance in x, -1 where unknown.
    pub variance: Vec<Vec4>,
    /// The next history.
    pub history: Vec<Vec4>,
}

/// Blends `frame` into `history` (the texels of the last run and its
/// camera, where there is one) with `alpha_min`.
pub fn accumulate(frame: &Frame, history: Option<(&[Vec4], &Pinhole)>, alpha_min: f32) -> Accumulated {
    let n = frame.width * frame.height;
    let history = history.filter(|(h, _)| h.len() == n * TEXELS);
    let mut out = Accumulated { color: Vec::with_capacity(n), variance: Vec::with_capacity(n), history: Vec::new() };
    out.history.reserve(n * TEXELS);
    for p in 0..n {
        let c = frame.color[p];
        let normal = unit_normal(frame.normal[p]);
        let position = frame.position[p];
        let hit = position.w > 0.0;
        let world = position.xyz() / position.w;
        let l = luminance(c.xyz() / demodulation(frame.albedo[p]));
        let previous = history.filter(|_| hit).and_then(|(h, camera)| {
            let (x, y) = camera.pixel_of(world, frame.width, frame.height)?;
            let q = (y * frame.width + x) * TEXELS;
            let old = &h[q..q + TEXELS];
            let tolerance = PLANE_TOLERANCE * (world - frame.camera.eye).length();
            let same = old[0].w >= 1.0
                && old[3].w > 0.0
                && normal.dot(old[2].xyz()) >= NORMAL_AGREEMENT
                && (old[3].xyz() - world).dot(normal).abs() <= tolerance;
            same.then_some((old[0], old[1]))
        });
        let (color, moments, frames, alpha) = match previous {
            Some((old_color, old_moments)) => {
                let frames = (old_color.w + 1.0).min(MAX_FRAMES);
                let alpha = alpha_min.max(1.0 / frames);
                let color = old_color.xyz().lerp(c.xyz(), alpha);
                (color, old_moments.xy().lerp(Vec2::new(l, l * l), alpha), frames, alpha)
            }
            None => (c.xyz(), Vec2::new(l, l * l), 1.0, 1.0),
        };
        let variance =
            if frames >= VARIANCE_FRAMES { (moments.y - moments.x * moments.x).max(0.0) * alpha } else { -1.0 };
        out.color.push(color.extend(c.w));
        out.variance.push(Vec4::new(variance, 0.0, 0.0, 0.0));
        out.history.push(color.extend(frames));
        out.history.push(moments.extend(0.0).extend(0.0));
        out.history.push(normal.extend(0.0));
        out.history.push(if hit { world.extend(1.0) } else { Vec4::ZERO });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Pinhole {
        Pinhole { eye: Vec3::new(0.0, 0.0, 5.0), u: Vec3::X, v: Vec3::Y, w: Vec3::NEG_Z }
    }

    #[test]
    fn a_point_projects_to_the_pixel_a_camera_ray_through_it_leaves_from() {
        let cam = camera();
        let (w, h) = (8usize, 4usize);
        for (x, y) in [(0usize, 0usize), (3, 1), (7, 3)] {
            let d = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32) * 2.0 - 1.0;
            let p = cam.eye + 2.5 * (d.x * cam.u + d.y * cam.v + cam.w);
            assert_eq!(cam.pixel_of(p, w, h), Some((x, y)));
        }
        assert_eq!(cam.pixel_of(Vec3::new(0.0, 0.0, 6.0), w, h), None, "behind the eye");
        assert_eq!(cam.pixel_of(Vec3::new(9.0, 0.0, 0.0), w, h), None, "outside the frame");
    }

    /// A still pixel seeing one surface: its colour is the running mean
    /// while `1 / frames` is above `alpha_min`, and its variance is
    /// unknown for the first frames.
    #[test]
    fn a_still_pixel_averages_its_frames() {
        let cam = camera();
        let frame = |value: f32| {
            let color = [Vec4::new(value, value, value, 1.0)];
            (color, [Vec4::ONE], [Vec4::Z], [Vec4::new(0.0, 0.0, 0.0, 1.0)])
        };
        let values = [1.0f32, 3.0, 2.0, 6.0];
        let mut history: Option<Vec<Vec4>> = None;
        let mut last = None;
        for (i, &value) in values.iter().enumerate() {
            let (color, albedo, normal, position) = frame(value);
            let f = Frame {
                width: 1,
                height: 1,
                color: &color,
                albedo: &albedo,
                normal: &normal,
                position: &position,
                camera: cam,
            };
            let out = accumulate(&f, history.as_deref().map(|h| (h, &cam)), 0.1);
            let mean = values[..=i].iter().sum::<f32>() / (i + 1) as f32;
            assert!((out.color[0].x - mean).abs() < 1e-5, "frame {i}: {} vs {mean}", out.color[0]);
            assert_eq!(out.history[0].w, (i + 1) as f32);
            history = Some(out.history.clone());
            last = Some(out);
        }
        let out = last.unwrap();
        // Four frames: the moments' variance over four.
        let mean = 3.0f32;
        let second = values.iter().map(|v| v * v).sum::<f32>() / 4.0;
        assert!((out.variance[0].x - (second - mean * mean) / 4.0).abs() < 1e-4, "{}", out.variance[0]);
    }
}
