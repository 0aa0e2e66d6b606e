//! What every Whitted-style example shares, on the device side: the per-ray
//! data of radiance and shadow rays, the attributes geometry reports, the
//! light type, and example 1's pinhole camera, background and exception
//! programs. The snapshot corpus lowers these programs as they are here
//! (`tests/tests/snapshots.rs`), and its shared types file
//! (`tests/snapshots/in/seed_common.rs`) is held equal to the types above.

use rt_std::prelude::*;

/// Per-ray data of radiance rays: the colour found, how much it still
/// matters to the pixel, and how many bounces deep it is.
#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub importance: f32,
    pub depth: i32,
}

/// Per-ray data of shadow rays: how much light gets through.
#[rt_payload]
pub struct Shadow {
    pub attenuation: Vec3,
}

/// What intersection reports to the hit programs (triangles fill both by
/// field name; custom primitives write them).
#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

/// A point light, as the host writes it into a `Buffer<BasicLight>`.
#[rt_struct]
pub struct BasicLight {
    pub pos: Vec3,
    pub color: Vec3,
    pub casts_shadow: i32,
}

/// Ray type of camera, reflection and refraction rays.
#[rt_const]
pub const RADIANCE_RAY: u32 = 0;
/// Ray type of shadow (and ambient-occlusion) rays.
#[rt_const]
pub const SHADOW_RAY: u32 = 1;

/// Example 1's camera: one ray through the centre of each pixel, `eye + d.x
/// * u + d.y * v + w` with `d` in `[-1, 1]^2` (launch index (0, 0) is the
/// bottom-left pixel).
#[rt_program(ray_generation)]
pub fn pinhole_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let d = (idx.as_vec2() + Vec2::splat(0.5)) / launch_dim().as_vec2() * 2.0 - Vec2::ONE;
    let ray_direction = (d.x * u + d.y * v + w).normalize();
    let ray = Ray::new(eye, ray_direction, RADIANCE_RAY, scene_epsilon, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    rt_trace(top_object, ray, &mut prd);
    output_buffer[idx] = prd.result.extend(1.0);
}

/// Radiance rays that hit nothing see the background colour.
#[rt_program(miss)]
pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

/// Shadow rays that hit nothing keep the attenuation they started with.
#[rt_program(miss)]
pub fn shadow_miss(prd: &mut Shadow) {
    prd.attenuation = prd.attenuation.max(Vec3::ZERO);
}

/// Any hit is enough to shadow (example 4): block all light and stop.
#[rt_program(any_hit)]
pub fn any_hit_shadow(prd: &mut Shadow) {
    prd.attenuation = Vec3::ZERO;
    rt_terminate_ray();
}

/// A launch index that raised an exception is painted `bad_color`.
#[rt_program(exception)]
pub fn exception(#[var] bad_color: Vec3, #[var] mut output_buffer: RwBuffer2d<Vec4>) {
    output_buffer[launch_index()] = bad_color.extend(1.0);
}

/// One line of a lat/long lookup: the texture coordinates of direction `d`
/// (`theta = atan2(d.x, d.z)`, `phi = pi/2 - acos(d.y)`), `v = 1` at the
/// zenith.
#[rt_function]
pub fn latlong_uv(d: Vec3) -> Vec2 {
    let theta = d.x.atan2(d.z);
    let phi = FRAC_PI_2 - d.y.clamp(-1.0, 1.0).acos();
    vec2((theta + PI) * (0.5 * FRAC_1_PI), 0.5 * (1.0 + phi.sin()))
}

/// OptiX SDK's `lcg`/`rnd`: advances `seed` and returns a float in `[0, 1)`.
#[rt_function]
pub fn rnd(seed: &mut u32) -> f32 {
    *seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
    (*seed & 0x00FF_FFFF) as f32 / 16777216.0
}

/// Tiny Encryption Algorithm, 4 rounds (OptiX SDK's `tea<4>`): decorrelated
/// RNG seeds from a launch index and a frame number.
#[rt_function]
pub fn tea4(val0: u32, val1: u32) -> u32 {
    let mut v0 = val0;
    let mut v1 = val1;
    let mut s0 = 0u32;
    for _ in 0..4 {
        s0 = s0.wrapping_add(0x9e37_79b9);
        v0 = v0.wrapping_add(
            (v1 << 4).wrapping_add(0xa341_316c) ^ v1.wrapping_add(s0) ^ (v1 >> 5).wrapping_add(0xc801_3ea4),
        );
        v1 = v1.wrapping_add(
            (v0 << 4).wrapping_add(0xad90_777d) ^ v0.wrapping_add(s0) ^ (v0 >> 5).wrapping_add(0x7e95_761e),
        );
    }
    v0
}

/// A direction about unit normal `n`, cosine-weighted (Malley's method:
/// uniform on the disk, projected up), from two uniform numbers.
#[rt_function]
pub fn cosine_sample_hemisphere(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = TAU * u2;
    let local = vec3(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(0.0).sqrt());
    // An orthonormal basis about n (Duff et al. 2017).
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = vec3(b, sign + n.y * n.y * a, -n.y);
    (t * local.x + bt * local.y + n * local.z).normalize()
}
