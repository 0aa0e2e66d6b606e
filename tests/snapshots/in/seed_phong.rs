//! Examples 3 and 4: Blinn-Phong with shadow rays.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn phong(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] ka: Vec3,
    #[var] kd: Vec3,
    #[var] ks: Vec3,
    #[var] phong_exp: f32,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
    #[var] scene_epsilon: f32,
    #[var] top_shadower: Object,
) {
    let ray = current_ray();
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let g = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let ffnormal = faceforward(n, ray.direction, g);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let mut color = ka * ambient_light_color;
    for i in 0..lights.len() {
        let light = lights.load(i);
        let to_light = light.pos - hit_point;
        let light_dist = to_light.length();
        let l = to_light / light_dist;
        let n_dot_l = ffnormal.dot(l);
        if n_dot_l > 0.0 {
            let mut shadow = Shadow { attenuation: Vec3::ONE };
            if light.casts_shadow != 0 {
                let shadow_ray = Ray::new(hit_point, l, SHADOW_RAY, scene_epsilon, light_dist);
                rt_trace(top_shadower, shadow_ray, &mut shadow);
            }
            let light_attenuation = shadow.attenuation;
            if light_attenuation.max_element() > 0.0 {
                let lc = light.color * light_attenuation;
                color += kd * n_dot_l * lc;
                let h = (l - ray.direction).normalize();
                let n_dot_h = ffnormal.dot(h);
                if n_dot_h > 0.0 {
                    color += ks * lc * n_dot_h.powf(phong_exp);
                }
            }
        }
    }
    prd.result = color;
}

/// Example 4: any hit is enough to shadow.
#[rt_program(any_hit)]
pub fn any_hit_shadow(prd: &mut Shadow) {
    prd.attenuation = Vec3::ZERO;
    rt_terminate_ray();
}
