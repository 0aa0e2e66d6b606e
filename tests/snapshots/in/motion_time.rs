//! Motion blur: a camera tracing each path at its own time with
//! `rt_trace_at`, a closest hit passing its ray's `current_time()` on to a
//! shadow ray (nested traces inherit no time), a miss and an intersection
//! program reading it.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn motion_camera(#[var] top_object: Object, #[var] shutter: Vec2, #[var] mut image: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let dim = launch_dim();
    // A time per pixel spread over the shutter interval.
    let u = ((idx.x * 7 + idx.y * 13) % 16) as f32 / 16.0;
    let time = shutter.x + (shutter.y - shutter.x) * u;
    let d = vec3(idx.x as f32 / dim.x as f32 - 0.5, idx.y as f32 / dim.y as f32 - 0.5, -1.0);
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), d.normalize(), RADIANCE_RAY, 0.001, f32::INFINITY);
    rt_trace_at(top_object, ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, time);
    image[idx] = prd.result.extend(time);
}

#[rt_program(closest_hit)]
pub fn motion_shade(prd: &mut Radiance, attr: &Normals, #[var] light_pos: Vec3, #[var] top_object: Object) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let l = (light_pos - p).normalize();
    let mut shadow = Shadow { attenuation: Vec3::ONE };
    let shadow_ray = Ray::new(p, l, SHADOW_RAY, 0.001, f32::INFINITY);
    let flags = RAY_FLAG_TERMINATE_ON_FIRST_HIT | RAY_FLAG_DISABLE_CLOSESTHIT;
    rt_trace_at(top_object, shadow_ray, &mut shadow, flags, RAY_MASK_ALL, current_time());
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    prd.result = shadow.attenuation * n.dot(l).max(0.0);
}

#[rt_program(miss)]
pub fn motion_sky(prd: &mut Radiance) {
    prd.result = Vec3::new(0.2, 0.3, current_time());
}

/// A sphere whose radius pulses with the ray's time.
#[rt_program(intersection)]
pub fn pulsing_sphere(prim: u32, attr: &mut Normals) {
    let _ = prim;
    let ray = current_ray();
    let r = 0.5 + 0.25 * current_time().clamp(0.0, 1.0);
    let b = ray.origin.dot(ray.direction);
    let c = ray.origin.dot(ray.origin) - r * r;
    let a = ray.direction.dot(ray.direction);
    let disc = b * b - a * c;
    if disc > 0.0 {
        let t = (-b - disc.sqrt()) / a;
        if rt_potential_intersection(t) {
            let n = (ray.origin + t * ray.direction) / r;
            attr.geometric_normal = n;
            attr.shading_normal = n;
            rt_report_intersection(0);
        }
    }
}
