//! Callable programs (OptiX's bindless callables): the tutorial's three
//! objects under one closest-hit program, each material's BRDF a callable
//! chosen from a buffer of ids by the material's `brdf` index: Lambert on
//! the floor, a toon shade on the sphere, Blinn-Phong on the box. Adding a
//! BRDF is a callable and an id in the buffer; the closest-hit program and
//! the kernel's other programs stay as they are.

use crate::common::*;
use crate::diffuse::{self, facing_normal};
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::Vec3;
use rt_runtime::{BufferType, Context, Scope};
use rt_std::prelude::*;

/// Lambert: the colour `kd` reflected toward any `v` from unit direction
/// `l`, at unit normal `n`, per unit of light.
#[rt_program(callable)]
pub fn lambert(n: Vec3, l: Vec3, v: Vec3, kd: Vec3) -> Vec3 {
    let _ = v;
    kd * n.dot(l).max(0.0)
}

/// Blinn-Phong: Lambert plus a white highlight around the half vector,
/// `BLINN_KS * (N.H)^BLINN_EXP`.
#[rt_program(callable)]
pub fn blinn_phong(n: Vec3, l: Vec3, v: Vec3, kd: Vec3) -> Vec3 {
    let n_dot_l = n.dot(l);
    if n_dot_l <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (l + v).normalize();
    kd * n_dot_l + Vec3::splat(BLINN_KS * n.dot(h).max(0.0).powf(BLINN_EXP))
}

/// The Blinn-Phong highlight's strength.
#[rt_const]
pub const BLINN_KS: f32 = 0.6;
/// The Blinn-Phong highlight's exponent.
#[rt_const]
pub const BLINN_EXP: f32 = 30.0;

/// Toon: Lambert cut into three flat bands (`TOON_BANDS`), and a hard white
/// highlight.
#[rt_program(callable)]
pub fn toon(n: Vec3, l: Vec3, v: Vec3, kd: Vec3) -> Vec3 {
    let h = (l + v).normalize();
    if n.dot(h) > 0.97 {
        return Vec3::ONE;
    }
    kd * ((n.dot(l).max(0.0) * 3.0).ceil() / 3.0)
}

/// The toon shade's bands: what it multiplies `kd` by where no highlight is.
pub const TOON_BANDS: [f32; 4] = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0];

/// Ambient plus every light through the material's BRDF, the callable
/// `brdfs[brdf]`.
#[allow(clippy::type_complexity)]
#[rt_program(closest_hit)]
pub fn brdf_shaded(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] kd: Vec3,
    #[var] brdf: u32,
    #[var] brdfs: Buffer<Callable<fn(Vec3, Vec3, Vec3, Vec3) -> Vec3>>,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
) {
    let ray = current_ray();
    let n = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let v = -ray.direction.normalize();
    let shade = brdfs[brdf];
    let mut color = kd * ambient_light_color;
    for i in 0..lights.len() {
        let light = lights[i];
        let l = (light.pos - hit_point).normalize();
        color += light.color * shade.call(n, l, v, kd);
    }
    prd.result = color;
}

/// The tutorial scene, each object shaded by its own callable BRDF.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &brdf_shaded::PROGRAM)?;
    diffuse::set_colors(&mut ctx, &materials)?;
    set_brdfs(&mut ctx, &materials)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}

/// The buffer of BRDF ids (`brdfs`) and each material's index into it.
pub fn set_brdfs(ctx: &mut Context, materials: &Materials) -> Result<(), Error> {
    let mut ids = Vec::new();
    for brdf in [&lambert::PROGRAM, &blinn_phong::PROGRAM, &toon::PROGRAM] {
        let p = ctx.create_program(brdf);
        ids.push(ctx.callable_id::<fn(Vec3, Vec3, Vec3, Vec3) -> Vec3>(p)?);
    }
    let brdfs = ctx.create_buffer(BufferType::Input, ids);
    ctx.set_var(Scope::Context, "brdfs", brdfs)?;
    for (m, brdf) in [(materials.floor, 0u32), (materials.sphere, 2), (materials.block, 1)] {
        ctx.set_var(m, "brdf", brdf)?;
    }
    Ok(())
}
