//! Example 2: the diffuse shader. Ambient `ka * ambient_light_color` plus,
//! for each light of a host-filled `Buffer<BasicLight>`, Lambert's `kd *
//! N.L * light.color`, with the shading normal turned to face the viewer
//! (`faceforward` against the geometric normal).

use crate::common::*;
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::Vec3;
use rt_runtime::{Context, Scope};
use rt_std::prelude::*;

/// The world-space shading normal of a hit, turned towards the ray's origin
/// (by the geometric normal, which is what a bump map leaves alone).
#[rt_function]
pub fn facing_normal(shading_normal: Vec3, geometric_normal: Vec3, ray_direction: Vec3) -> Vec3 {
    let n = rt_transform_normal(ObjectToWorld, shading_normal).normalize();
    let g = rt_transform_normal(ObjectToWorld, geometric_normal).normalize();
    // rt-std's `faceforward` is GLSL's (`i` is the incident direction), not
    // OptiX's (`i` toward the viewer): pass the ray direction itself.
    faceforward(n, ray_direction, g)
}

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
    let ffnormal = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let mut color = ka * ambient_light_color;
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

/// Diffuse colours of the floor, the sphere and the box.
pub const FLOOR_KD: Vec3 = Vec3::new(0.75, 0.74, 0.7);
pub const SPHERE_KD: Vec3 = Vec3::new(0.85, 0.3, 0.18);
pub const BOX_KD: Vec3 = Vec3::new(0.2, 0.62, 0.5);
/// The ambient light of examples 2 to 7.
pub const AMBIENT: Vec3 = Vec3::new(0.16, 0.17, 0.2);

/// Sets `ka = kd` and `kd` on each material, and the ambient light.
pub fn set_colors(ctx: &mut Context, materials: &Materials) -> Result<(), Error> {
    for (m, kd) in [(materials.floor, FLOOR_KD), (materials.sphere, SPHERE_KD), (materials.block, BOX_KD)] {
        ctx.set_var(m, "ka", kd)?;
        ctx.set_var(m, "kd", kd)?;
    }
    ctx.set_var(Scope::Context, "ambient_light_color", AMBIENT)?;
    Ok(())
}

/// The tutorial scene, diffuse.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &diffuse::PROGRAM)?;
    set_colors(&mut ctx, &materials)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
