//! The tonemapper (OptiX's `TonemapperSimple`): linear radiance to
//! display values. Each channel is scaled by `exposure`, mapped through
//! Narkowicz's fit of the ACES filmic curve (a toe, a shoulder that
//! reaches 1 smoothly instead of clipping), and raised to `1 / gamma`
//! (2.2 by default: sRGB-ready values in [0, 1]). Alpha passes through.
//! `postprocess/gpu/stages.wgsl` computes the same on the device.

use glam::{Vec3, Vec4};

/// Narkowicz's ACES-fitted curve, clamped to [0, 1]; 0 at 0.
pub fn aces_fitted(x: f32) -> f32 {
    let x = x.max(0.0);
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// One pixel through exposure, the filmic curve and gamma.
pub fn tonemap_pixel(c: Vec4, exposure: f32, gamma: f32) -> Vec4 {
    let inv_gamma = 1.0 / gamma.max(1e-3);
    let mapped = (c.truncate() * exposure).to_array().map(|x| aces_fitted(x).powf(inv_gamma));
    Vec3::from_array(mapped).extend(c.w)
}

/// Every pixel of `input` tonemapped.
pub fn tonemap(input: &[Vec4], exposure: f32, gamma: f32) -> Vec<Vec4> {
    input.iter().map(|&c| tonemap_pixel(c, exposure, gamma)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_starts_at_zero_rises_and_saturates() {
        assert_eq!(aces_fitted(0.0), 0.0);
        assert_eq!(aces_fitted(-1.0), 0.0);
        let samples: Vec<f32> = (0..100).map(|i| aces_fitted(i as f32 * 0.1)).collect();
        assert!(samples.windows(2).all(|w| w[1] >= w[0]), "{samples:?}");
        assert!(aces_fitted(100.0) > 0.99 && aces_fitted(100.0) <= 1.0);
        // Mid grey (0.18) lands near the middle of the display range.
        assert!((aces_fitted(0.18) - 0.2669).abs() < 1e-3, "{}", aces_fitted(0.18));
    }

    #[test]
    fn exposure_and_gamma_apply_before_and_after_the_curve() {
        let c = Vec4::new(0.5, 0.1, 2.0, 0.25);
        let out = tonemap_pixel(c, 2.0, 1.0);
        assert_eq!(out, Vec4::new(aces_fitted(1.0), aces_fitted(0.2), aces_fitted(4.0), 0.25));
        let g = tonemap_pixel(c, 1.0, 2.2);
        assert!((g.x - aces_fitted(0.5).powf(1.0 / 2.2)).abs() < 1e-6);
    }
}
