//! Example 3: the Phong shader (Blinn's form). Adds to the diffuse shader a
//! specular term with the half vector `H = normalize(L - ray.direction)`:
//! `ks * light.color * pow(N.H, phong_exp)`.

use crate::common::*;
use crate::diffuse::{self, facing_normal};
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::Vec3;
use rt_runtime::Context;
use rt_std::prelude::*;

/// Diffuse plus Blinn-Phong specular light from direction `l` (unit) of
/// colour `light_color`, at a point with facing normal `n`, seen along
/// `ray_direction`.
#[rt_function]
pub fn blinn_phong(
    kd: Vec3,
    ks: Vec3,
    phong_exp: f32,
    n: Vec3,
    l: Vec3,
    ray_direction: Vec3,
    light_color: Vec3,
) -> Vec3 {
    let n_dot_l = n.dot(l);
    let mut color = Vec3::ZERO;
    if n_dot_l > 0.0 {
        color = kd * n_dot_l * light_color;
        let h = (l - ray_direction).normalize();
        let n_dot_h = n.dot(h);
        if n_dot_h > 0.0 {
            color += ks * light_color * n_dot_h.powf(phong_exp);
        }
    }
    color
}

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
) {
    let ray = current_ray();
    let ffnormal = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let mut color = ka * ambient_light_color;
    for i in 0..lights.len() {
        let light = lights[i];
        let l = (light.pos - hit_point).normalize();
        color += blinn_phong(kd, ks, phong_exp, ffnormal, l, ray.direction, light.color);
    }
    prd.result = color;
}

/// Diffuse colours as in example 2; a glossy sphere and box, a matte floor.
pub fn set_colors(ctx: &mut Context, materials: &Materials) -> Result<(), Error> {
    diffuse::set_colors(ctx, materials)?;
    for (m, ks, exp) in [
        (materials.floor, Vec3::splat(0.05), 10.0f32),
        (materials.sphere, Vec3::splat(0.6), 60.0),
        (materials.block, Vec3::splat(0.35), 30.0),
    ] {
        ctx.set_var(m, "ks", ks)?;
        ctx.set_var(m, "phong_exp", exp)?;
    }
    Ok(())
}

/// The tutorial scene, Phong-shaded, without shadows.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &phong::PROGRAM)?;
    set_colors(&mut ctx, &materials)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
