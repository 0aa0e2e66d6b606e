//! Constants: `#[rt_const]` items of scalar, vector, array and struct type,
//! constants computed from other constants, and `const` items inside a
//! function body (one infinite: a `let` in WGSL, where infinity is a
//! run-time value).
use super::seed_common::*;
use rt_std::prelude::*;

/// Number of stratification cells per side.
#[rt_const]
pub const STRATA: u32 = 4;
/// Cells per pixel, from another constant.
#[rt_const]
pub const CELLS: u32 = STRATA * STRATA;
/// A signed offset.
#[rt_const]
pub const BIAS: i32 = -2;
/// Sky colours.
#[rt_const]
pub const HORIZON: Vec3 = Vec3::new(0.9, 0.9, 1.0);
#[rt_const]
pub const ZENITH: Vec3 = Vec3::new(0.2, 0.4, 0.9);
/// Exposure stops.
#[rt_const]
pub const STOPS: [f32; 3] = [0.5, 1.0, 2.0];

#[rt_program(miss)]
pub fn consts(prd: &mut Radiance) {
    const GAMMA: f32 = 1.0 / 2.2;
    const STEPS: i32 = 3;
    const FAR: f32 = f32::INFINITY;
    let d = current_ray().direction;
    let t = d.y.max(0.0);
    let sky = HORIZON.lerp(ZENITH, t.powf(GAMMA));
    let cell = (prd.depth + BIAS + STEPS) as u32 % CELLS;
    let stops = STOPS;
    let exposure = stops[(cell % STRATA) as usize % 3] + STOPS[cell as usize % 3];
    prd.result = sky * exposure * RADIANCE_RAY as f32;
    prd.importance = prd.importance.min(FAR);
}
