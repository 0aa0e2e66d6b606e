//! A receiver grid, the seed's sound-propagation use: a point source above
//! a floor with three obstacles sends rays uniformly over its lower
//! hemisphere, and the floor counts, per cell of a grid, the rays that
//! reach it directly and those that reach it after one specular reflection
//! off an obstacle. Many rays land in one cell at once, so the counts are
//! atomic adds (`RwBuffer2d<u32>::atomic_add`): exact integers, the same on
//! every backend whatever order the rays ran in.
//!
//! Entry point 1 ([`emit`]) traces the source's rays, one launch per frame
//! ([`Scene::pre_launch`]); entry point 0 ([`show_field`]) then draws the
//! grid from above: the direct field in orange, the reflected one in blue,
//! each as the fraction of the source's rays reaching a cell against what a
//! uniform spread would give it, and the obstacles' tops in grey. Acoustic
//! shadows fall behind each obstacle, away from the source, where only
//! reflections reach.

use crate::common::*;
use crate::scene::{Error, Scene, Settings, oriented_box, quad};
use glam::{UVec2, Vec3};
use rt_runtime::{Acceleration, BufferType, Scope};
use rt_std::prelude::*;

/// Rays of the source; they count into the grid.
#[rt_const]
pub const SOUND_RAY: u32 = 0;
/// Rays straight down that find what lies under a pixel of the picture.
#[rt_const]
pub const LOOK_RAY: u32 = 1;

/// The source's rays per frame: a stratified grid of directions.
pub const EMITTED: UVec2 = UVec2::new(384, 256);

/// Where the source is.
pub const SOURCE: Vec3 = Vec3::new(0.2, 1.8, 0.1);

/// A sound ray: how many reflections it has made.
#[rt_payload]
pub struct SoundRay {
    pub bounces: u32,
}

/// What a look ray found: the height of the surface under it (-1: none).
#[rt_payload]
pub struct Look {
    pub height: f32,
}

/// One ray per launch index, its direction stratified over the lower
/// hemisphere (uniform in solid angle) and jittered per frame.
#[rt_program(ray_generation)]
pub fn emit(#[var] source: Vec3, #[var] frame: u32, #[var] top_object: Object, #[var] scene_epsilon: f32) {
    let i = launch_index();
    let d = launch_dim();
    let mut seed = tea4(i.y * d.x + i.x, frame);
    let u1 = (i.x as f32 + rnd(&mut seed)) / d.x as f32;
    let u2 = (i.y as f32 + rnd(&mut seed)) / d.y as f32;
    // Uniform in solid angle: the cosine to straight down is uniform.
    let down = u1;
    let r = (1.0 - down * down).max(0.0).sqrt();
    let phi = TAU * u2;
    let dir = vec3(r * phi.cos(), -down, r * phi.sin());
    let mut prd = SoundRay { bounces: 0 };
    rt_trace(top_object, Ray::new(source, dir, SOUND_RAY, scene_epsilon, 1.0e16), &mut prd);
}

/// The floor: counts the ray in its cell, direct or reflected.
#[rt_program(closest_hit)]
pub fn receive(
    prd: &mut SoundRay,
    #[var] direct: RwBuffer2d<u32>,
    #[var] reflected: RwBuffer2d<u32>,
    #[var] half_extent: Vec2,
) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let uv = vec2(p.x, p.z) / half_extent * 0.5 + 0.5;
    let size = direct.size();
    let x = ((uv.x * size.x as f32) as u32).min(size.x - 1);
    let y = ((uv.y * size.y as f32) as u32).min(size.y - 1);
    if prd.bounces == 0 {
        direct.atomic_add(uvec2(x, y), 1);
    } else {
        reflected.atomic_add(uvec2(x, y), 1);
    }
}

/// An obstacle: reflects the ray once, specularly; a reflected ray that
/// meets another obstacle is absorbed.
#[rt_program(closest_hit)]
pub fn reflect_once(prd: &mut SoundRay, attr: &Normals, #[var] top_object: Object, #[var] scene_epsilon: f32) {
    if prd.bounces == 0 {
        let ray = current_ray();
        let p = ray.origin + t_hit() * ray.direction;
        let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
        let mut next = SoundRay { bounces: 1 };
        rt_trace(top_object, Ray::new(p, reflect(ray.direction, n), SOUND_RAY, scene_epsilon, 1.0e16), &mut next);
    }
}

/// A sound ray that leaves the scene.
#[rt_program(miss)]
pub fn escape(prd: &mut SoundRay) {
    prd.bounces += 100;
}

/// A look ray's hit: the surface's height.
#[rt_program(closest_hit)]
pub fn look(prd: &mut Look) {
    let ray = current_ray();
    prd.height = (ray.origin + t_hit() * ray.direction).y;
}

/// A look ray that finds nothing.
#[rt_program(miss)]
pub fn look_miss(prd: &mut Look) {
    prd.height = -1.0;
}

/// The grid seen from above, one cell per pixel: counts over the frames so
/// far, against `rays_per_cell` (the source's rays per frame over the cells).
#[rt_program(ray_generation)]
pub fn show_field(
    #[var] direct: RwBuffer2d<u32>,
    #[var] reflected: RwBuffer2d<u32>,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
    #[var] top_object: Object,
    #[var] half_extent: Vec2,
    #[var] frame: u32,
    #[var] rays_per_cell: f32,
) {
    let i = launch_index();
    let d = launch_dim();
    let uv = (vec2(i.x as f32, i.y as f32) + 0.5) / vec2(d.x as f32, d.y as f32);
    let xz = (uv * 2.0 - 1.0) * half_extent;
    let mut seen = Look { height: -1.0 };
    rt_trace(top_object, Ray::new(vec3(xz.x, 10.0, xz.y), vec3(0.0, -1.0, 0.0), LOOK_RAY, 0.0, 1.0e16), &mut seen);
    let scale = 1.0 / (rays_per_cell * (frame + 1) as f32);
    let a = direct.load(i) as f32 * scale;
    let b = reflected.load(i) as f32 * scale;
    let mut c = (1.0 - (-1.2 * a).exp()) * vec3(1.0, 0.55, 0.15) + (1.0 - (-1.5 * b).exp()) * vec3(0.15, 0.45, 1.0);
    if seen.height > 0.01 {
        c = Vec3::splat(0.3 + 0.25 * seen.height);
    }
    output_buffer[i] = vec4(c.x, c.y, c.z, 1.0);
}

/// The floor's half width and depth: the picture's aspect, 2 deep.
fn half_extent(settings: &Settings) -> glam::Vec2 {
    glam::Vec2::new(2.0 * settings.aspect(), 2.0)
}

/// The floor, three obstacles, the source; entry 1 emits, entry 0 shows.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = Scene::start(settings, 1e-3)?;
    ctx.set_entry_point_count(2);
    let show = ctx.create_program(&show_field::PROGRAM);
    ctx.set_ray_generation_program(0, show)?;
    let emitter = ctx.create_program(&emit::PROGRAM);
    ctx.set_ray_generation_program(1, emitter)?;
    let escape = ctx.create_program(&escape::PROGRAM);
    ctx.set_miss_program(SOUND_RAY, escape)?;
    let look_miss = ctx.create_program(&look_miss::PROGRAM);
    ctx.set_miss_program(LOOK_RAY, look_miss)?;
    let look = ctx.create_program(&look::PROGRAM);

    let half = half_extent(settings);
    let (w, h) = (settings.width, settings.height);
    let direct = ctx.create_buffer_2d::<u32>(BufferType::InputOutput, w, h)?;
    let reflected = ctx.create_buffer_2d::<u32>(BufferType::InputOutput, w, h)?;
    ctx.set_var(Scope::Context, "direct", direct)?;
    ctx.set_var(Scope::Context, "reflected", reflected)?;
    ctx.set_var(Scope::Context, "half_extent", half)?;
    ctx.set_var(Scope::Context, "source", SOURCE)?;
    ctx.set_var(Scope::Context, "frame", 0u32)?;
    ctx.set_var(Scope::Context, "rays_per_cell", (EMITTED.x * EMITTED.y) as f32 / (w * h) as f32)?;

    let floor_material = ctx.create_material();
    let receive = ctx.create_program(&receive::PROGRAM);
    ctx.set_closest_hit_program(floor_material, SOUND_RAY, receive)?;
    ctx.set_closest_hit_program(floor_material, LOOK_RAY, look)?;
    let floor =
        quad(Vec3::new(-half.x, 0.0, -half.y), Vec3::new(0.0, 0.0, 2.0 * half.y), Vec3::new(2.0 * half.x, 0.0, 0.0));
    let floor = ctx.create_triangles(floor)?;
    let floor = ctx.create_geometry_instance(floor, &[floor_material])?;

    let obstacle_material = ctx.create_material();
    let reflect = ctx.create_program(&reflect_once::PROGRAM);
    ctx.set_closest_hit_program(obstacle_material, SOUND_RAY, reflect)?;
    ctx.set_closest_hit_program(obstacle_material, LOOK_RAY, look)?;
    let mut children = vec![floor];
    for (min, max, yaw) in [
        (Vec3::new(-1.7, 0.0, -0.7), Vec3::new(-0.9, 1.0, 0.2), 0.3),
        (Vec3::new(0.7, 0.0, 0.5), Vec3::new(1.5, 0.8, 1.1), -0.5),
        (Vec3::new(-0.6, 0.0, -1.5), Vec3::new(1.6, 1.2, -1.3), 0.1),
    ] {
        let b = ctx.create_triangles(oriented_box(min, max, yaw))?;
        children.push(ctx.create_geometry_instance(b, &[obstacle_material])?);
    }
    let top = ctx.create_geometry_group(&children, Acceleration::default())?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    let mut scene = Scene::new(ctx, output, settings);
    scene.frames = settings.spp;
    scene.pre_launch = Some((1, EMITTED));
    Ok(scene)
}
