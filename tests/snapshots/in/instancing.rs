//! Transforms: a closest-hit program of an instanced mesh that moves the
//! hit point, the ray direction and normals between object and world space
//! with `rt_transform_point`, `rt_transform_vector` and
//! `rt_transform_normal`, for a procedural checker in object space.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn instanced_checker(prd: &mut Radiance, attr: &Normals, #[var] check_size: f32, #[var] colors: Buffer<Vec3>) {
    let ray = current_ray();
    let world_hit = ray.origin + t_hit() * ray.direction;
    let object_hit = rt_transform_point(WorldToObject, world_hit);
    let object_dir = rt_transform_vector(WorldToObject, ray.direction);
    let back_to_world = rt_transform_point(TransformKind::ObjectToWorld, object_hit);
    let cell = (object_hit / check_size).floor().as_ivec3();
    let parity = ((cell.x + cell.y + cell.z) & 1) as u32;
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let facing = -object_dir.normalize().dot(attr.shading_normal.normalize());
    let drift = (back_to_world - world_hit).length();
    prd.result = colors[parity] * facing.abs() * (n.y * 0.5 + 0.5) + Vec3::splat(drift);
}
