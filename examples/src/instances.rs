//! Instancing: a hundred teapots (`shared/scenes/teapot.obj`), each a
//! Transform node over the same geometry group, so one BVH of 6,320
//! triangles serves them all; a top-level group's BVH is built over the
//! transformed instances. Hit programs run in each instance's object
//! space; the colour comes from where the instance's origin lands in the
//! world (`rt_transform_point(ObjectToWorld, 0)`), since variables cannot
//! tell shared instances apart.

use crate::common::*;
use crate::diffuse::facing_normal;
use crate::mesh;
use crate::reflections::{self, reflective};
use crate::scene::{Camera, Error, Scene, Settings, quad, shared_scene};
use crate::shadows::direct_light;
use glam::{Mat4, Quat, Vec3};
use rt_runtime::{Acceleration, BufferType, Builder, Scope};
use rt_std::prelude::*;

/// Phong with shadows, `kd` picked from `palette` by a hash of the
/// instance's world position.
#[rt_program(closest_hit)]
pub fn instance_color(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] palette: Buffer<Vec3>,
    #[var] ks: Vec3,
    #[var] phong_exp: f32,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
    #[var] scene_epsilon: f32,
    #[var] top_shadower: Object,
) {
    let ray = current_ray();
    let n = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let origin = rt_transform_point(ObjectToWorld, Vec3::ZERO);
    let cell = (vec2(origin.x, origin.z) * 4.0).floor().as_ivec2();
    let kd = palette[tea4(cell.x as u32, cell.y as u32) % palette.len()];
    prd.result = kd * ambient_light_color
        + direct_light(hit_point, n, ray.direction, kd, ks, phong_exp, lights, scene_epsilon, top_shadower);
}

/// Instances per row and column.
pub const GRID: u32 = 10;
/// Distance between neighbouring instances (the teapot is about 6.4 wide).
pub const SPACING: f32 = 8.0;

/// The instances' transforms: a jittered grid, each turned and scaled
/// (deterministic: a small LCG).
pub fn transforms() -> Vec<Mat4> {
    let mut state = 12345u32;
    let mut next = || {
        state = state.wrapping_mul(1664525).wrapping_add(1013904223);
        (state >> 8) as f32 / 16777216.0
    };
    let mut out = Vec::new();
    let offset = (GRID as f32 - 1.0) * 0.5 * SPACING;
    for i in 0..GRID {
        for j in 0..GRID {
            let jitter = Vec3::new(next() - 0.5, 0.0, next() - 0.5) * SPACING * 0.25;
            let pos = Vec3::new(i as f32 * SPACING - offset, 0.0, j as f32 * SPACING - offset) + jitter;
            let yaw = next() * std::f32::consts::TAU;
            let scale = 0.75 + next() * 0.5;
            out.push(Mat4::from_scale_rotation_translation(Vec3::splat(scale), Quat::from_rotation_y(yaw), pos));
        }
    }
    out
}

/// High above one corner of the grid, looking across it.
pub fn camera() -> Camera {
    Camera { eye: Vec3::new(-30.0, 38.0, 62.0), look_at: Vec3::new(2.0, 0.0, 2.0), up: Vec3::Y, vfov_degrees: 42.0 }
}

/// A hundred teapots on a checkerboard.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let loaded = mesh::load_obj(&shared_scene("teapot.obj"))?;
    let (mut ctx, output) = Scene::start(settings, 1e-3)?;
    let ray_generation = ctx.create_program(&pinhole_camera::PROGRAM);
    ctx.set_ray_generation_program(0, ray_generation)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(RADIANCE_RAY, miss)?;
    let shadow_miss = ctx.create_program(&shadow_miss::PROGRAM);
    ctx.set_miss_program(SHADOW_RAY, shadow_miss)?;
    ctx.set_var(Scope::Context, "bg_color", Vec3::new(0.55, 0.66, 0.82))?;
    camera().set_vars(&mut ctx, settings.aspect())?;
    let lights = vec![
        BasicLight { pos: Vec3::new(-60.0, 90.0, 40.0), color: Vec3::new(0.9, 0.86, 0.8), casts_shadow: 1 },
        BasicLight { pos: Vec3::new(70.0, 40.0, 60.0), color: Vec3::new(0.2, 0.22, 0.28), casts_shadow: 0 },
    ];
    let lights = ctx.create_buffer(BufferType::Input, lights);
    ctx.set_var(Scope::Context, "lights", lights)?;
    ctx.set_var(Scope::Context, "ambient_light_color", Vec3::new(0.2, 0.21, 0.25))?;
    let palette = vec![
        Vec3::new(0.85, 0.25, 0.2),
        Vec3::new(0.95, 0.65, 0.15),
        Vec3::new(0.3, 0.7, 0.3),
        Vec3::new(0.2, 0.5, 0.85),
        Vec3::new(0.6, 0.35, 0.8),
        Vec3::new(0.9, 0.9, 0.85),
        Vec3::new(0.15, 0.7, 0.7),
    ];
    let palette = ctx.create_buffer(BufferType::Input, palette);
    ctx.set_var(Scope::Context, "palette", palette)?;
    let block = ctx.create_program(&any_hit_shadow::PROGRAM);

    // One geometry, one geometry instance, one geometry group (one BVH)...
    let teapot_material = ctx.create_material();
    let shade = ctx.create_program(&instance_color::PROGRAM);
    ctx.set_closest_hit_program(teapot_material, RADIANCE_RAY, shade)?;
    ctx.set_any_hit_program(teapot_material, SHADOW_RAY, block)?;
    ctx.set_var(teapot_material, "ks", Vec3::splat(0.45))?;
    ctx.set_var(teapot_material, "phong_exp", 50.0f32)?;
    let mut mesh = loaded.mesh;
    mesh.material_indices = None;
    let teapot = ctx.create_triangles(mesh)?;
    let teapot = ctx.create_geometry_instance(teapot, &[teapot_material])?;
    let teapot = ctx.create_geometry_group(&[teapot], Acceleration::new(Builder::Sbvh))?;
    // ... under many transforms.
    let mut children = transforms()
        .into_iter()
        .map(|m| ctx.create_transform(m, teapot).map_err(Error::from))
        .collect::<Result<Vec<_>, _>>()?;

    let floor_material = ctx.create_material();
    let checker = ctx.create_program(&reflective::PROGRAM);
    ctx.set_closest_hit_program(floor_material, RADIANCE_RAY, checker)?;
    ctx.set_any_hit_program(floor_material, SHADOW_RAY, block)?;
    for (name, value) in [
        ("ka", Vec3::ONE),
        ("kd", Vec3::new(0.78, 0.76, 0.7)),
        ("kd2", Vec3::new(0.45, 0.46, 0.5)),
        ("ks", Vec3::ZERO),
        ("reflectivity", Vec3::ZERO),
    ] {
        ctx.set_var(floor_material, name, value)?;
    }
    ctx.set_var(floor_material, "tile_size", SPACING)?;
    ctx.set_var(floor_material, "phong_exp", 1.0f32)?;
    ctx.set_var(Scope::Context, "max_depth", reflections::MAX_DEPTH)?;
    ctx.set_var(Scope::Context, "importance_cutoff", 0.01f32)?;
    let half = 200.0;
    let floor = ctx.create_triangles(quad(
        Vec3::new(-half, 0.0, -half),
        Vec3::new(0.0, 0.0, 2.0 * half),
        Vec3::new(2.0 * half, 0.0, 0.0),
    ))?;
    let floor = ctx.create_geometry_instance(floor, &[floor_material])?;
    children.push(ctx.create_geometry_group(&[floor], Acceleration::new(Builder::Bvh))?);

    let top = ctx.create_group(&children, Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.set_var(Scope::Context, "top_shadower", top)?;
    Ok(Scene::new(ctx, output, settings))
}
