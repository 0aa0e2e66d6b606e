//! Example 5: a reflective floor, stopped by depth and by importance.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_function]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(vec3(0.3, 0.59, 0.11))
}

#[rt_program(closest_hit)]
pub fn floor_reflect(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] floor_color: Vec3,
    #[var] reflectivity: Vec3,
    #[var] max_depth: i32,
    #[var] importance_cutoff: f32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
) {
    let ray = current_ray();
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let hit_point = ray.origin + t_hit() * ray.direction;
    let mut result = floor_color;
    let importance = prd.importance * luminance(reflectivity);
    if importance > importance_cutoff && prd.depth < max_depth {
        let mut refl = Radiance { result: Vec3::ZERO, importance, depth: prd.depth + 1 };
        let r = reflect(ray.direction, n);
        rt_trace(top_object, Ray::new(hit_point, r, RADIANCE_RAY, scene_epsilon, f32::INFINITY), &mut refl);
        result += reflectivity * refl.result;
    }
    prd.result = result;
}
