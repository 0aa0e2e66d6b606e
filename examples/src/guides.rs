//! What the path-traced examples' cameras keep per pixel for a denoiser
//! beside the mean radiance, on the device side: each sample's luminance
//! divided by its albedo (what the runtime's denoiser filters,
//! [`rt_runtime::postprocess::denoise`]), and the running moments of it
//! from which the variance of the pixel's mean follows (the denoiser's
//! `input_variance_buffer`). [`crate::bunny`]'s camera (which `render`
//! and the viewer use) and [`crate::cornell`]'s call these.

use rt_std::prelude::*;

/// Below this an albedo channel is about black and is not divided by (the
/// runtime denoiser's `ALBEDO_FLOOR`).
#[rt_const]
pub const ALBEDO_FLOOR: f32 = 1e-3;

/// The Rec. 709 luminance of colour `c` divided by `albedo` channel by
/// channel, where a channel's albedo is not about black.
#[rt_function]
pub fn demodulated_luminance(c: Vec3, albedo: Vec3) -> f32 {
    let ax = if albedo.x > ALBEDO_FLOOR { albedo.x } else { 1.0 };
    let ay = if albedo.y > ALBEDO_FLOOR { albedo.y } else { 1.0 };
    let az = if albedo.z > ALBEDO_FLOOR { albedo.z } else { 1.0 };
    0.2126 * c.x / ax + 0.7152 * c.y / ay + 0.0722 * c.z / az
}

/// A pixel's variance entry after its `n`th sample, of luminance `l`, from
/// `previous` (its entry before, not read when `n` is 1): y the mean of
/// the luminances, z the mean of their squares, w `n`, and x the variance
/// of their mean (the sample variance over `n`), -1 (unknown) below two
/// samples.
#[rt_function]
pub fn add_luminance_sample(previous: Vec4, l: f32, n: f32) -> Vec4 {
    let mut m1 = l;
    let mut m2 = l * l;
    let mut variance = -1.0;
    if n > 1.5 {
        let keep = (n - 1.0) / n;
        m1 = previous.y * keep + l / n;
        m2 = previous.z * keep + l * l / n;
        variance = (m2 - m1 * m1).max(0.0) / (n - 1.0);
    }
    vec4(variance, m1, m2, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rt_runtime::postprocess::denoise;

    #[test]
    fn a_sample_is_demodulated_as_the_denoiser_demodulates() {
        assert_eq!(ALBEDO_FLOOR, denoise::ALBEDO_FLOOR);
        let c = Vec3::new(0.3, 0.5, 0.9);
        for albedo in [Vec3::new(0.5, 0.25, 0.8), Vec3::new(0.0, 0.6, 1e-4), Vec3::ZERO] {
            let want = denoise::luminance(c / denoise::demodulation(albedo.extend(1.0)));
            assert!((demodulated_luminance(c, albedo) - want).abs() < 1e-6, "{albedo}");
        }
    }

    #[test]
    fn the_moments_give_the_variance_of_the_mean() {
        let samples = [0.2f32, 0.9, 0.4, 0.4, 1.5];
        let mut entry = add_luminance_sample(Vec4::splat(7.0), samples[0], 1.0);
        assert_eq!(entry, vec4(-1.0, 0.2, 0.2 * 0.2, 1.0), "one sample: the variance is unknown");
        for (i, &l) in samples.iter().enumerate().skip(1) {
            entry = add_luminance_sample(entry, l, (i + 1) as f32);
        }
        let n = samples.len() as f32;
        let mean = samples.iter().sum::<f32>() / n;
        let sample_variance = samples.iter().map(|l| (l - mean) * (l - mean)).sum::<f32>() / (n - 1.0);
        assert!((entry.y - mean).abs() < 1e-6 && entry.w == n, "{entry}");
        assert!((entry.x - sample_variance / n).abs() < 1e-6, "{entry} vs {}", sample_variance / n);
    }
}
