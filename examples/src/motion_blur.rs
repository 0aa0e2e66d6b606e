//! Motion blur (OptiX 6's motion transforms and `rtTrace(.., time)`): the
//! tutorial's floor, its sphere sliding to the right under two matrix keys
//! and the teapot turning a quarter turn about its axis under two
//! scale-rotate-translate keys, both over the shutter interval `[0, 1]`.
//! Each launch traces every pixel at a random time (and a jittered point in
//! the pixel) and accumulates, so moving things smear over the frames.

use crate::common::*;
use crate::diffuse;
use crate::mesh;
use crate::scene::{Error, Scene, Settings, quad, shared_scene};
use crate::tutorial::{self, FLOOR_HALF, Materials, SPHERE, sphere_bounds, sphere_intersect};
use glam::{Mat4, Quat, Vec3};
use rt_runtime::{Acceleration, BufferType, Builder, MotionKeys, Scope, Srt};
use rt_std::prelude::*;

/// The pinhole camera tracing each sample at its own time in the shutter
/// interval: one jittered sample per pixel and launch, averaged in
/// `accum_buffer`.
#[rt_program(ray_generation)]
pub fn motion_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] frame: u32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut accum_buffer: RwBuffer2d<Vec4>,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim();
    let mut seed = tea4(idx.y * dim.x + idx.x, frame);
    let jitter = vec2(rnd(&mut seed), rnd(&mut seed));
    let time = rnd(&mut seed);
    let d = (idx.as_vec2() + jitter) / dim.as_vec2() * 2.0 - Vec2::ONE;
    let ray = Ray::new(eye, (d.x * u + d.y * v + w).normalize(), RADIANCE_RAY, scene_epsilon, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    rt_trace_at(top_object, ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, time);
    let mut acc = Vec4::ZERO;
    if frame > 0 {
        acc = accum_buffer[idx];
    }
    acc += prd.result.extend(1.0);
    accum_buffer[idx] = acc;
    output_buffer[idx] = (acc.xyz() / acc.w).extend(1.0);
}

/// How far the sphere slides along x over the shutter interval.
pub const SLIDE: f32 = 1.2;
/// How far the teapot turns about its vertical axis (radians).
pub const TURN: f32 = std::f32::consts::FRAC_PI_2;
/// The teapot's scale and place on the floor.
pub const TEAPOT_SCALE: f32 = 0.45;
pub const TEAPOT_AT: Vec3 = Vec3::new(-1.6, 0.0, 0.3);

/// The floor, the sliding sphere and the turning teapot, shaded diffuse.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let loaded = mesh::load_obj(&shared_scene("teapot.obj"))?;
    let (mut ctx, output) = tutorial::start(settings)?;
    let camera = ctx.create_program(&motion_camera::PROGRAM);
    ctx.set_ray_generation_program(0, camera)?;
    let accum = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, settings.width, settings.height)?;
    ctx.set_var(Scope::Context, "accum_buffer", accum)?;
    let materials = Materials::with_closest_hit(&mut ctx, &diffuse::diffuse::PROGRAM)?;
    diffuse::set_colors(&mut ctx, &materials)?;

    let floor = ctx.create_triangles(quad(
        Vec3::new(-FLOOR_HALF, 0.0, -FLOOR_HALF),
        Vec3::new(0.0, 0.0, 2.0 * FLOOR_HALF),
        Vec3::new(2.0 * FLOOR_HALF, 0.0, 0.0),
    ))?;
    let floor = ctx.create_geometry_instance(floor, &[materials.floor])?;
    let floor = ctx.create_geometry_group(&[floor], Acceleration::new(Builder::Bvh))?;

    let isect = ctx.create_program(&sphere_intersect::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let sphere = ctx.create_custom_geometry(1, isect, bounds)?;
    ctx.set_var(sphere, "sphere", SPHERE)?;
    let sphere = ctx.create_geometry_instance(sphere, &[materials.sphere])?;
    let sphere = ctx.create_geometry_group(&[sphere], Acceleration::new(Builder::Bvh))?;
    let slide = MotionKeys::Matrices(vec![Mat4::IDENTITY, Mat4::from_translation(Vec3::new(SLIDE, 0.0, 0.0))]);
    let sliding = ctx.create_motion_transform(slide, 0.0, 1.0, sphere)?;

    let mut teapot = loaded.mesh;
    teapot.material_indices = None;
    let teapot = ctx.create_triangles(teapot)?;
    let teapot = ctx.create_geometry_instance(teapot, &[materials.block])?;
    let teapot = ctx.create_geometry_group(&[teapot], Acceleration::new(Builder::Sbvh))?;
    let key = |angle: f32| Srt {
        scale: Vec3::splat(TEAPOT_SCALE),
        rotation: Quat::from_rotation_y(angle),
        translation: TEAPOT_AT,
    };
    let turning = ctx.create_motion_transform(MotionKeys::Srt(vec![key(0.0), key(TURN)]), 0.0, 1.0, teapot)?;

    let top = ctx.create_group(&[floor, sliding, turning], Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    let mut scene = Scene::new(ctx, output, settings);
    scene.frames = settings.spp;
    Ok(scene)
}
