//! Example 4: shadows. For each light, a ray of a second ray type (shadow
//! rays, per-ray data [`Shadow`]) goes from the hit point toward the light,
//! bounded by the light's distance, against `top_shadower`. Every material's
//! any-hit program for that ray type sets the attenuation to 0 and
//! terminates the ray ([`any_hit_shadow`]): any hit is enough.

use crate::common::*;
use crate::diffuse::facing_normal;
use crate::phong::{self, blinn_phong};
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::Vec3;
use rt_std::prelude::*;

/// What reaches `hit_point` (facing normal `n`) from each light, through
/// shadow rays, shaded by [`blinn_phong`].
#[rt_function]
pub fn direct_light(
    hit_point: Vec3,
    n: Vec3,
    ray_direction: Vec3,
    kd: Vec3,
    ks: Vec3,
    phong_exp: f32,
    lights: Buffer<BasicLight>,
    scene_epsilon: f32,
    top_shadower: Object,
) -> Vec3 {
    let mut color = Vec3::ZERO;
    for i in 0..lights.len() {
        let light = lights[i];
        let to_light = light.pos - hit_point;
        let light_dist = to_light.length();
        let l = to_light / light_dist;
        if n.dot(l) > 0.0 {
            let mut shadow = Shadow { attenuation: Vec3::ONE };
            if light.casts_shadow != 0 {
                let shadow_ray = Ray::new(hit_point, l, SHADOW_RAY, scene_epsilon, light_dist);
                rt_trace(top_shadower, shadow_ray, &mut shadow);
            }
            if shadow.attenuation.max_element() > 0.0 {
                color += blinn_phong(kd, ks, phong_exp, n, l, ray_direction, light.color * shadow.attenuation);
            }
        }
    }
    color
}

#[rt_program(closest_hit)]
pub fn phong_shadowed(
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
    let ffnormal = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    prd.result = ka * ambient_light_color
        + direct_light(hit_point, ffnormal, ray.direction, kd, ks, phong_exp, lights, scene_epsilon, top_shadower);
}

/// The tutorial scene, Phong-shaded, with shadows.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &phong_shadowed::PROGRAM)?;
    materials.block_shadow_rays(&mut ctx)?;
    phong::set_colors(&mut ctx, &materials)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
