//! Example 6: an environment map. The miss program of radiance rays samples
//! a latitude/longitude texture by the ray's direction (`theta = atan2(d.x,
//! d.z)`, `phi = pi/2 - acos(d.y)`). The texture is made here: a sky with a
//! sun, a few bands of cloud and a darker ground below the horizon.

use crate::common::*;
use crate::reflections::{self, reflective};
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::{Vec3, Vec4};
use rt_runtime::{Context, SamplerId, Scope};
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn envmap_miss(prd: &mut Radiance, #[var] envmap: Sampler2d) {
    prd.result = envmap.sample(latlong_uv(current_ray().direction)).xyz();
}

/// Where the sun is (unit vector): where the key light is, so the chrome
/// sphere shows the sun beside its highlight.
pub fn sun_direction() -> Vec3 {
    tutorial::lights()[0].pos.normalize()
}

/// The environment's colour in direction `d` (unit): what the texture
/// stores, computed per texel.
pub fn sky(d: Vec3) -> Vec3 {
    let y = d.y;
    if y < 0.0 {
        // Ground: warm grey, darker straight down, hazy at the horizon.
        let ground = Vec3::new(0.32, 0.28, 0.24).lerp(Vec3::new(0.12, 0.11, 0.1), (-y).powf(0.5));
        return ground.lerp(Vec3::new(0.75, 0.8, 0.85), (1.0 + y * 12.0).max(0.0));
    }
    let zenith = Vec3::new(0.12, 0.3, 0.72);
    let horizon = Vec3::new(0.78, 0.86, 0.95);
    let mut c = horizon.lerp(zenith, y.powf(0.45));
    // Soft cloud bands, thinning towards the zenith.
    let theta = d.x.atan2(d.z);
    let band = ((theta * 5.0 + y * 9.0).sin() * (theta * 3.0 - y * 4.0).cos()).max(0.0).powf(3.0);
    c = c.lerp(Vec3::splat(0.97), band * 0.55 * (1.0 - y).powf(2.0));
    // The sun and its glow.
    let s = d.dot(sun_direction()).max(0.0);
    c += Vec3::new(1.0, 0.85, 0.6) * (s.powf(600.0) * 6.0 + s.powf(24.0) * 0.35);
    c
}

/// A `width` x `width / 2` lat/long texture of [`sky`], laid out as the
/// miss program reads it (row 0 at the nadir).
pub fn sky_texels(width: u32) -> (Vec<Vec4>, u32, u32) {
    let height = (width / 2).max(1);
    let mut texels = Vec::with_capacity((width * height) as usize);
    for j in 0..height {
        let v = (j as f32 + 0.5) / height as f32;
        let phi = (2.0 * v - 1.0).asin();
        for i in 0..width {
            let u = (i as f32 + 0.5) / width as f32;
            let theta = u * 2.0 * std::f32::consts::PI - std::f32::consts::PI;
            let d = Vec3::new(theta.sin() * phi.cos(), phi.sin(), theta.cos() * phi.cos());
            texels.push(sky(d).extend(1.0));
        }
    }
    (texels, width, height)
}

/// Creates the sky texture and sets radiance rays' miss program to sample
/// it.
pub fn use_envmap(ctx: &mut Context) -> Result<SamplerId, Error> {
    let (texels, w, h) = sky_texels(512);
    let sampler = ctx.create_sampler(texels, w, h, WrapMode::Repeat, FilterMode::Linear)?;
    ctx.set_var(Scope::Context, "envmap", sampler)?;
    let miss = ctx.create_program(&envmap_miss::PROGRAM);
    ctx.set_miss_program(RADIANCE_RAY, miss)?;
    Ok(sampler)
}

/// The reflections scene under the sky.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    use_envmap(&mut ctx)?;
    let materials = Materials::with_closest_hit(&mut ctx, &reflective::PROGRAM)?;
    materials.block_shadow_rays(&mut ctx)?;
    reflections::set_colors(&mut ctx, &materials)?;
    ctx.set_var(Scope::Context, "ambient_light_color", Vec3::new(0.22, 0.25, 0.32))?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
