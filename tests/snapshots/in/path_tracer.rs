//! A small path tracer: a ray generation program that averages jittered
//! samples into an accumulation buffer, and a diffuse closest-hit program
//! that scatters one cosine-weighted bounce per hit, with Russian
//! roulette. The RNG state travels in the payload.
use rt_std::prelude::*;

/// Per-path state.
#[rt_payload]
pub struct PathState {
    pub radiance: Vec3,
    pub throughput: Vec3,
    pub origin: Vec3,
    pub direction: Vec3,
    pub seed: u32,
    pub done: bool,
}

/// Ray type of path segments.
#[rt_const]
pub const PATH_RAY: u32 = 0;

/// A 32-bit LCG step, returning a float in [0, 1).
#[rt_function]
pub fn lcg_next(seed: &mut u32) -> f32 {
    *seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
    (*seed >> 8) as f32 * (1.0 / 16777216.0)
}

/// A direction about `n`, cosine-weighted (Malley's method).
#[rt_function]
pub fn cosine_sample_hemisphere(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = TAU * u2;
    let local = vec3(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(0.0).sqrt());
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = vec3(b, sign + n.y * n.y * a, -n.y);
    (t * local.x + bt * local.y + n * local.z).normalize()
}

#[rt_program(closest_hit)]
pub fn path_diffuse(
    prd: &mut PathState,
    attr: &super::seed_common::Normals,
    #[var] albedo: Vec3,
    #[var] emission: Vec3,
) {
    let ray = current_ray();
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let n = if n.dot(ray.direction) > 0.0 { -n } else { n };
    prd.radiance += prd.throughput * emission;
    prd.throughput *= albedo;
    let p = prd.throughput.max_element();
    if lcg_next(&mut prd.seed) > p {
        prd.done = true;
        return;
    }
    prd.throughput /= p;
    let u1 = lcg_next(&mut prd.seed);
    let u2 = lcg_next(&mut prd.seed);
    prd.origin = ray.origin + t_hit() * ray.direction;
    prd.direction = cosine_sample_hemisphere(n, u1, u2);
}

#[rt_program(ray_generation)]
pub fn path_camera(
    #[var] eye: Vec3,
    #[var] camera: Mat3,
    #[var] frame: u32,
    #[var] spp: u32,
    #[var] max_bounces: u32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut accum: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim().as_vec2();
    let mut seed = (idx.y * launch_dim().x + idx.x) ^ (frame * 0x9e3779b9);
    let mut color = Vec3::ZERO;
    for _ in 0..spp {
        let jitter = vec2(lcg_next(&mut seed), lcg_next(&mut seed));
        let d = (idx.as_vec2() + jitter) / dim * 2.0 - 1.0;
        let mut prd = PathState {
            radiance: Vec3::ZERO,
            throughput: Vec3::ONE,
            origin: eye,
            direction: (camera * vec3(d.x, -d.y, 1.0)).normalize(),
            seed,
            done: false,
        };
        let mut bounce = 0;
        while bounce < max_bounces && !prd.done {
            let ray = Ray::new(prd.origin, prd.direction, PATH_RAY, scene_epsilon, f32::INFINITY);
            rt_trace(top_object, ray, &mut prd);
            bounce += 1;
        }
        seed = prd.seed;
        color += prd.radiance;
    }
    let sample = color / spp.max(1) as f32;
    let prev = accum[idx];
    let blended = prev.truncate().lerp(sample, 1.0 / (frame + 1) as f32);
    accum[idx] = blended.extend(1.0);
}

/// The sky: paths that escape end here.
#[rt_program(miss)]
pub fn path_sky(prd: &mut PathState, #[var] sky: Vec3) {
    prd.radiance += prd.throughput * sky * (0.5 + 0.5 * current_ray().direction.y);
    prd.done = true;
}
