//! Example 2: ambient plus Lambert over a buffer of lights.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn diffuse(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] ka: Vec3,
    #[var] kd: Vec3,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
) {
    let ray = current_ray();
    let world_shading_normal = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let world_geometric_normal = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let ffnormal = faceforward(world_shading_normal, ray.direction, world_geometric_normal);
    let mut color = ka * ambient_light_color;
    let hit_point = ray.origin + t_hit() * ray.direction;
    for i in 0..lights.len() {
        let light = lights[i];
        let l = (light.pos - hit_point).normalize();
        let n_dot_l = ffnormal.dot(l);
        if n_dot_l > 0.0 {
            color += kd * n_dot_l * light.color;
        }
    }
    prd.result = color;
}
