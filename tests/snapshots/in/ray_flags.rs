//! `rt_trace_with`: shadow rays traced with `RAY_FLAG_*` flags combined
//! with `|` and a visibility mask, next to a plain `rt_trace`; and an
//! any-hit program that filters hits by primitive with
//! `rt_ignore_intersection`.
use super::seed_common::*;
use rt_std::prelude::*;

/// Visibility mask bit of shadow casters.
#[rt_const]
pub const MASK_CASTERS: u32 = 1 << 1;

#[rt_program(closest_hit)]
pub fn ray_flags(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] light_pos: Vec3,
    #[var] cull_back: bool,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let to_light = light_pos - p;
    let dist = to_light.length();
    let l = to_light / dist;
    let mut shadow = Shadow { attenuation: Vec3::ONE };
    let mut flags = RAY_FLAG_TERMINATE_ON_FIRST_HIT | RAY_FLAG_DISABLE_CLOSESTHIT;
    if cull_back {
        flags |= RAY_FLAG_CULL_BACK_FACING;
    } else {
        flags |= RAY_FLAG_NONE;
    }
    let shadow_ray = Ray::new(p, l, SHADOW_RAY, scene_epsilon, dist);
    rt_trace_with(top_object, shadow_ray, &mut shadow, flags, MASK_CASTERS);
    let mut bounce = Radiance { result: Vec3::ZERO, importance: prd.importance * 0.5, depth: prd.depth + 1 };
    if prd.depth < 2 {
        let r = Ray::new(p, reflect(ray.direction, n), RADIANCE_RAY, scene_epsilon, f32::INFINITY);
        rt_trace_with(
            top_object,
            r,
            &mut bounce,
            RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_DISABLE_ANYHIT,
            RAY_MASK_ALL & !MASK_CASTERS,
        );
        rt_trace(top_object, r, &mut bounce);
    }
    prd.result = shadow.attenuation * n.dot(l).max(0.0) + bounce.result * 0.5;
}

/// Ignores hits on every other primitive: a lattice that lets light through.
#[rt_program(any_hit)]
pub fn lattice_any_hit(prd: &mut Shadow, #[var] transmission: Vec3) {
    if primitive_index() % 2 == 1 {
        rt_ignore_intersection();
        return;
    }
    prd.attenuation *= transmission;
    if prd.attenuation.max_element() < 0.01 {
        rt_terminate_ray();
    }
}
