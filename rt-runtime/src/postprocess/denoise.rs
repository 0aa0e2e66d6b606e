//! The denoiser: an edge-avoiding à-trous wavelet filter (Dammertz et al.
//! 2010) steered by a luminance variance, the spatial part of SVGF
//! (Schied et al. 2017). This file is the reference; the wgpu backend
//! runs the same passes as WGSL (`postprocess/gpu/stages.wgsl`).
//!
//! The passes, each over every pixel:
//!
//! 1. **Prepare**: the colour is divided by the albedo guide (where a
//!    channel's albedo is not about zero), so that texture and material
//!    colour are not blurred: what is filtered is the light that reached
//!    the surface. Its luminance's variance is the renderer's per-pixel
//!    one where given ([`Guided::variance`]: the sample variance of the
//!    pixel's samples over their count, the variance of their mean, as
//!    SVGF keeps it), so that an edge no sample disagrees about (a
//!    contact shadow's) stops the filter; where not given (or unknown for
//!    a pixel), it is estimated from the neighbouring pixels facing the
//!    same way (3x3 by default), which takes such edges for noise too.
//! 2. **À-trous**, [`Tuning::iterations`] times (3) with the taps 1, 2, 4 pixels
//!    apart: a 5x5 B3-spline kernel whose weights stop at edges: normals
//!    apart (`dot^`[`Tuning::sigma_normal`]), albedos apart, and luminances
//!    apart by more than [`Tuning::sigma_luminance`] standard deviations (of the
//!    variance blurred 3x3). Each pass also carries the variance of its
//!    result, so later, wider passes stop at smaller differences.
//! 3. **Finish**: the filtered light times the albedo, blended with the
//!    input by `blend` (OptiX's: 0 all denoised, 1 the input); alpha is
//!    the input's.
//!
//! A flat, noise-free image is a fixed point: every weighted mean of one
//! value is that value.

use glam::{Vec3, Vec4, Vec4Swizzles};

/// The denoiser's tunings; [`Tuning::default`] is what the stage runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tuning {
    /// À-trous passes: the last one's taps are `2^(iterations - 1)` pixels
    /// apart.
    pub iterations: u32,
    /// Luminance differences are measured in standard deviations times
    /// this.
    pub sigma_luminance: f32,
    /// The normal weight is `max(0, n_p . n_q)` to this power.
    pub sigma_normal: f32,
    /// Albedos whose squared distance is this apart weigh `1/e`.
    pub sigma_albedo: f32,
    /// The radius of the variance estimate's neighbourhood.
    pub variance_radius: i32,
}

/// The default is the best of a sweep over the path-traced Cornell box at
/// 4 and 16 samples a pixel (`examples/tests/denoise.rs` measures it):
/// wider kernels (more passes) and a wider variance neighbourhood blur its
/// shadows; looser luminance stops blur them too, tighter ones keep noise.
impl Default for Tuning {
    fn default() -> Tuning {
        Tuning { iterations: 3, sigma_luminance: 3.0, sigma_normal: 64.0, sigma_albedo: 0.01, variance_radius: 1 }
    }
}

/// Below this, an albedo channel is about black and is not divided by.
pub const ALBEDO_FLOOR: f32 = 1e-3;

/// The B3-spline kernel's weights for offsets -2..=2.
const KERNEL: [f32; 5] = [1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0];

/// A denoiser's images, row-major, `width * height` pixels each.
pub struct Guided<'a> {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The noisy image.
    pub color: &'a [Vec4],
    /// The first hit's albedo (a guide).
    pub albedo: &'a [Vec4],
    /// The first hit's shading normal (a guide).
    pub normal: &'a [Vec4],
    /// The variance of each pixel's mean luminance (of its colour divided
    /// by its albedo, [`demodulation`]) in x, where the renderer keeps
    /// it; a negative x is unknown (fewer than two samples), and such a
    /// pixel's variance is estimated from its neighbours.
    pub variance: Option<&'a [Vec4]>,
}

/// The luminance of linear RGB (Rec. 709).
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The albedo the colour is divided by: about-black channels count as 1.
pub fn demodulation(albedo: Vec4) -> Vec3 {
    let a = albedo.xyz();
    Vec3::select(a.cmpgt(Vec3::splat(ALBEDO_FLOOR)), a, Vec3::ONE)
}

/// A normal guide made unit length (zero stays zero: a pixel that hit
/// nothing).
pub fn unit_normal(n: Vec4) -> Vec3 {
    n.xyz().normalize_or_zero()
}

/// How much two pixels' normals agree: 1 when both are zero (a pixel
/// that hit nothing) or equal.
pub fn normal_weight(a: Vec3, b: Vec3, t: &Tuning) -> f32 {
    if a == b {
        // Zero for both, or one surface: skips the power.
        return 1.0;
    }
    a.dot(b).max(0.0).powf(t.sigma_normal)
}

/// How much two pixels' albedos agree.
pub fn albedo_weight(a: Vec3, b: Vec3, t: &Tuning) -> f32 {
    if a == b {
        return 1.0;
    }
    (-(a - b).length_squared() / t.sigma_albedo).exp()
}

/// The denoised image.
pub fn denoise(images: &Guided, blend: f32) -> Vec<Vec4> {
    denoise_with(images, blend, &Tuning::default())
}

/// [`denoise`] with a tuning of its own.
pub fn denoise_with(images: &Guided, blend: f32, t: &Tuning) -> Vec<Vec4> {
    let normals: Vec<Vec3> = images.normal.iter().map(|&n| unit_normal(n)).collect();
    let albedos: Vec<Vec3> = images.albedo.iter().map(|&a| demodulation(a)).collect();
    let mut light = prepare(images, &normals, &albedos, t);
    let mut next = vec![Vec4::ZERO; light.len()];
    for i in 0..t.iterations {
        atrous(images, &normals, &albedos, &light, &mut next, 1 << i, t);
        std::mem::swap(&mut light, &mut next);
    }
    (0..light.len()).map(|p| finish(images.color[p], light[p].xyz() * albedos[p], blend)).collect()
}

/// The output pixel from the input's and the filtered one's.
pub fn finish(input: Vec4, filtered: Vec3, blend: f32) -> Vec4 {
    input.xyz().lerp(filtered, 1.0 - blend).extend(input.w)
}

/// Pass 1: the demodulated colour and its luminance's variance (in w):
/// the given one, or else the spatial estimate.
fn prepare(images: &Guided, normals: &[Vec3], albedos: &[Vec3], t: &Tuning) -> Vec<Vec4> {
    let (w, h) = (images.width as i32, images.height as i32);
    let light: Vec<Vec3> = (0..normals.len()).map(|p| images.color[p].xyz() / albedos[p]).collect();
    let mut out = vec![Vec4::ZERO; light.len()];
    for_each_row(&mut out, images.width, |y, row| {
        for (x, o) in row.iter_mut().enumerate() {
            let p = y * images.width + x;
            let given = images.variance.map_or(-1.0, |v| v[p].x);
            if given >= 0.0 {
                *o = light[p].extend(given);
                continue;
            }
            let (mut m1, mut m2, mut sum) = (0.0f32, 0.0f32, 0.0f32);
            for dy in -t.variance_radius..=t.variance_radius {
                for dx in -t.variance_radius..=t.variance_radius {
                    let (qx, qy) = (x as i32 + dx, y as i32 + dy);
                    if qx < 0 || qy < 0 || qx >= w || qy >= h {
                        continue;
                    }
                    let q = (qy * w + qx) as usize;
                    let weight = if q == p { 1.0 } else { normal_weight(normals[p], normals[q], t) };
                    let l = luminance(light[q]);
                    m1 += weight * l;
                    m2 += weight * l * l;
                    sum += weight;
                }
            }
            let (m1, m2) = (m1 / sum, m2 / sum);
            *o = light[p].extend((m2 - m1 * m1).max(0.0));
        }
    });
    out
}

/// One à-trous pass with taps `step` pixels apart, from `light` (colour,
/// variance) into `out`.
fn atrous(
    images: &Guided,
    normals: &[Vec3],
    albedos: &[Vec3],
    light: &[Vec4],
    out: &mut [Vec4],
    step: i32,
    t: &Tuning,
) {
    let (w, h) = (images.width as i32, images.height as i32);
    for_each_row(out, images.width, |y, row| {
        for (x, o) in row.iter_mut().enumerate() {
            let (x, y) = (x as i32, y as i32);
            let p = (y * w + x) as usize;
            let center = light[p];
            let sigma = t.sigma_luminance * blurred_variance(light, w, h, x, y).sqrt() + 1e-6;
            let lp = luminance(center.xyz());
            let (mut color, mut variance, mut sum) = (Vec3::ZERO, 0.0f32, 0.0f32);
            for (j, ky) in KERNEL.iter().enumerate() {
                for (i, kx) in KERNEL.iter().enumerate() {
                    let (qx, qy) = (x + (i as i32 - 2) * step, y + (j as i32 - 2) * step);
                    if qx < 0 || qy < 0 || qx >= w || qy >= h {
                        continue;
                    }
                    let q = (qy * w + qx) as usize;
                    let s = light[q];
                    let weight = if q == p {
                        kx * ky
                    } else {
                        let wl = (-(lp - luminance(s.xyz())).abs() / sigma).exp();
                        kx * ky
                            * wl
                            * normal_weight(normals[p], normals[q], t)
                            * albedo_weight(albedos[p], albedos[q], t)
                    };
                    color += weight * s.xyz();
                    variance += weight * weight * s.w;
                    sum += weight;
                }
            }
            *o = (color / sum).extend(variance / (sum * sum));
        }
    });
}

/// The variance at `(x, y)` blurred by a 3x3 Gaussian (over the pixels
/// inside the image).
fn blurred_variance(light: &[Vec4], w: i32, h: i32, x: i32, y: i32) -> f32 {
    const G: [f32; 3] = [0.25, 0.5, 0.25];
    let (mut v, mut sum) = (0.0, 0.0);
    for (j, gy) in G.iter().enumerate() {
        for (i, gx) in G.iter().enumerate() {
            let (qx, qy) = (x + i as i32 - 1, y + j as i32 - 1);
            if qx >= 0 && qy >= 0 && qx < w && qy < h {
                v += gx * gy * light[(qy * w + qx) as usize].w;
                sum += gx * gy;
            }
        }
    }
    v / sum
}

/// Calls `f(y, row)` for every row of `out` (`width` pixels a row), on
/// every core where there are threads.
fn for_each_row(out: &mut [Vec4], width: usize, f: impl Fn(usize, &mut [Vec4]) + Send + Sync) {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        out.par_chunks_mut(width).enumerate().for_each(|(y, row)| f(y, row));
    }
    #[cfg(target_arch = "wasm32")]
    out.chunks_mut(width).enumerate().for_each(|(y, row)| f(y, row));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(width: usize, height: usize, color: Vec4) -> Vec<Vec4> {
        let albedo = vec![Vec4::new(0.6, 0.3, 0.2, 1.0); width * height];
        let normal = vec![Vec4::new(0.0, 0.6, 0.8, 0.0); width * height];
        let color = vec![color; width * height];
        denoise(&Guided { width, height, color: &color, albedo: &albedo, normal: &normal, variance: None }, 0.0)
    }

    #[test]
    fn a_flat_noise_free_image_passes_unchanged() {
        let c = Vec4::new(0.7, 0.2, 0.05, 0.5);
        for p in flat(37, 21, c) {
            assert!((p - c).abs().max_element() < 1e-4, "{p} vs {c}");
        }
    }

    #[test]
    fn noise_on_one_surface_is_smoothed_but_a_normal_edge_is_kept() {
        let (w, h) = (32usize, 16usize);
        let mut seed = 12345u32;
        let mut rnd = move || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        let (mut color, mut normal) = (Vec::new(), Vec::new());
        for _y in 0..h {
            for x in 0..w {
                let left = x < w / 2;
                let base = if left { 0.2 } else { 0.8 };
                color.push(Vec4::new(base * 2.0 * rnd(), base * 2.0 * rnd(), base * 2.0 * rnd(), 1.0));
                normal.push(if left { Vec4::X } else { Vec4::Y });
            }
        }
        let albedo = vec![Vec4::ONE; w * h];
        let out = denoise(
            &Guided { width: w, height: h, color: &color, albedo: &albedo, normal: &normal, variance: None },
            0.0,
        );
        let error = |img: &[Vec4]| {
            let mut e = 0.0;
            for (i, p) in img.iter().enumerate() {
                let base = if i % w < w / 2 { 0.2 } else { 0.8 };
                e += (p.xyz() - Vec3::splat(base)).length_squared();
            }
            e
        };
        assert!(error(&out) * 10.0 < error(&color), "{} vs {}", error(&out), error(&color));
        // The two halves do not bleed into each other.
        let row = 8 * w;
        assert!((out[row + w / 2 - 1].x - 0.2).abs() < 0.1, "{}", out[row + w / 2 - 1]);
        assert!((out[row + w / 2].x - 0.8).abs() < 0.2, "{}", out[row + w / 2]);
    }

    /// One surface (one normal, one albedo) lit 0.2 on the left and 0.8 on
    /// the right, plus `noise` times a pseudo-random value in [-1, 1).
    fn shadow_edge(w: usize, h: usize, noise: f32) -> Vec<Vec4> {
        let mut seed = 777u32;
        let mut rnd = move || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1u32 << 23) as f32 - 1.0
        };
        (0..w * h).map(|p| Vec3::splat(if p % w < w / 2 { 0.2 } else { 0.8 } + noise * rnd()).extend(1.0)).collect()
    }

    #[test]
    fn a_given_variance_keeps_a_noise_free_edge_that_the_spatial_estimate_blurs() {
        let (w, h) = (32usize, 16usize);
        let color = shadow_edge(w, h, 0.0);
        let (albedo, normal) = (vec![Vec4::ONE; w * h], vec![Vec4::Z; w * h]);
        let run = |variance: Option<&[Vec4]>| {
            denoise(&Guided { width: w, height: h, color: &color, albedo: &albedo, normal: &normal, variance }, 0.0)
        };
        let zero = vec![Vec4::ZERO; w * h];
        for (p, (out, input)) in run(Some(&zero)).iter().zip(&color).enumerate() {
            assert!((*out - *input).abs().max_element() < 1e-6, "pixel {p}: {out} vs {input}");
        }
        // Without it, the spatial estimate sees the edge as noise.
        let spatial = run(None);
        let edge = 8 * w + w / 2 - 1;
        assert!((spatial[edge].x - 0.2).abs() > 0.05, "{}", spatial[edge]);
        // An unknown variance (negative) is estimated as without one.
        assert_eq!(run(Some(&vec![Vec4::splat(-1.0); w * h])), spatial);
    }

    #[test]
    fn a_given_variance_of_real_noise_smooths_it_and_keeps_the_edge() {
        let (w, h) = (32usize, 16usize);
        let noise = 0.1;
        let color = shadow_edge(w, h, noise);
        let clean = shadow_edge(w, h, 0.0);
        let (albedo, normal) = (vec![Vec4::ONE; w * h], vec![Vec4::Z; w * h]);
        // Uniform in [-a, a): variance a^2 / 3.
        let variance = vec![Vec4::new(noise * noise / 3.0, 0.0, 0.0, 0.0); w * h];
        let guided =
            Guided { width: w, height: h, color: &color, albedo: &albedo, normal: &normal, variance: Some(&variance) };
        let out = denoise(&guided, 0.0);
        let error =
            |img: &[Vec4]| img.iter().zip(&clean).map(|(a, b)| (a.xyz() - b.xyz()).length_squared()).sum::<f32>();
        assert!(error(&out) * 5.0 < error(&color), "{} vs {}", error(&out), error(&color));
        let row = 8 * w;
        assert!((out[row + w / 2 - 1].x - 0.2).abs() < 0.05, "{}", out[row + w / 2 - 1]);
        assert!((out[row + w / 2].x - 0.8).abs() < 0.05, "{}", out[row + w / 2]);
    }

    #[test]
    fn blend_one_gives_the_input() {
        let input = Vec4::new(1.0, 2.0, 3.0, 0.5);
        assert_eq!(finish(input, Vec3::ZERO, 1.0), input);
        assert_eq!(finish(input, Vec3::new(4.0, 4.0, 4.0), 0.0), Vec4::new(4.0, 4.0, 4.0, 0.5));
    }
}
