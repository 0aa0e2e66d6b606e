//! Example 5: reflections. The floor (a checkerboard) and the sphere
//! (nearly a mirror) trace a reflected ray and add `reflectivity *
//! reflected.result` to their Phong shading with shadows. Recursion stops two
//! ways: at `max_depth` bounces, and when a ray's contribution to its pixel
//! (its *importance*, the product of the reflectivities along its path)
//! falls below `importance_cutoff`.

use crate::common::*;
use crate::diffuse::facing_normal;
use crate::phong;
use crate::scene::{Error, Scene, Settings};
use crate::shadows::direct_light;
use crate::tutorial::{self, Materials};
use glam::Vec3;
use rt_runtime::{Context, Scope};
use rt_std::prelude::*;

/// Perceived brightness of a colour.
#[rt_function]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(vec3(0.3, 0.59, 0.11))
}

/// `a` and `b` in squares of side `tile_size` on the xz plane (just `a`
/// when `tile_size` is not positive), seen from `distance` away: far
/// squares, smaller than a pixel, fade to the mean of the two colours
/// instead of flickering.
#[rt_function]
pub fn checker(p: Vec3, tile_size: f32, a: Vec3, b: Vec3, distance: f32) -> Vec3 {
    let mut color = a;
    if tile_size > 0.0 {
        let cell = (vec2(p.x, p.z) / tile_size).floor().as_ivec2();
        if ((cell.x + cell.y) & 1) != 0 {
            color = b;
        }
        let fade = smoothstep(12.0 * tile_size, 45.0 * tile_size, distance);
        color = mix(color, (a + b) * 0.5, fade);
    }
    color
}

#[rt_program(closest_hit)]
pub fn reflective(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] ka: Vec3,
    #[var] kd: Vec3,
    #[var] kd2: Vec3,
    #[var] tile_size: f32,
    #[var] ks: Vec3,
    #[var] phong_exp: f32,
    #[var] reflectivity: Vec3,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
    #[var] max_depth: i32,
    #[var] importance_cutoff: f32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] top_shadower: Object,
) {
    let ray = current_ray();
    let ffnormal = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let base = checker(hit_point, tile_size, kd, kd2, t_hit());
    let mut result = ka * base * ambient_light_color
        + direct_light(hit_point, ffnormal, ray.direction, base, ks, phong_exp, lights, scene_epsilon, top_shadower);
    let importance = prd.importance * luminance(reflectivity);
    if importance > importance_cutoff && prd.depth < max_depth {
        let mut refl = Radiance { result: Vec3::ZERO, importance, depth: prd.depth + 1 };
        let r = reflect(ray.direction, ffnormal);
        rt_trace(top_object, Ray::new(hit_point, r, RADIANCE_RAY, scene_epsilon, f32::INFINITY), &mut refl);
        result += reflectivity * refl.result;
    }
    prd.result = result;
}

/// Bounces a ray may make.
pub const MAX_DEPTH: i32 = 5;

/// Checkerboard floor, chrome sphere, glossy box; the recursion limits.
pub fn set_colors(ctx: &mut Context, materials: &Materials) -> Result<(), Error> {
    phong::set_colors(ctx, materials)?;
    let floor = materials.floor;
    ctx.set_var(floor, "kd", Vec3::new(0.8, 0.78, 0.72))?;
    ctx.set_var(floor, "kd2", Vec3::new(0.22, 0.24, 0.28))?;
    ctx.set_var(floor, "ka", Vec3::ONE)?;
    ctx.set_var(floor, "tile_size", 1.0f32)?;
    ctx.set_var(floor, "reflectivity", Vec3::splat(0.25))?;
    let sphere = materials.sphere;
    ctx.set_var(sphere, "kd", Vec3::new(0.06, 0.06, 0.07))?;
    ctx.set_var(sphere, "ka", Vec3::ZERO)?;
    ctx.set_var(sphere, "ks", Vec3::splat(0.8))?;
    ctx.set_var(sphere, "phong_exp", 120.0f32)?;
    ctx.set_var(sphere, "reflectivity", Vec3::new(0.85, 0.86, 0.9))?;
    for m in [materials.sphere, materials.block] {
        ctx.set_var(m, "tile_size", 0.0f32)?;
        ctx.set_var(m, "kd2", Vec3::ZERO)?;
    }
    ctx.set_var(materials.block, "reflectivity", Vec3::ZERO)?;
    ctx.set_var(Scope::Context, "max_depth", MAX_DEPTH)?;
    ctx.set_var(Scope::Context, "importance_cutoff", 0.01f32)?;
    // Primary rays are depth 1, and a shadow ray leaves the deepest bounce.
    ctx.set_max_trace_depth(MAX_DEPTH as u32 + 2);
    Ok(())
}

/// The tutorial scene with reflections.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &reflective::PROGRAM)?;
    materials.block_shadow_rays(&mut ctx)?;
    set_colors(&mut ctx, &materials)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
