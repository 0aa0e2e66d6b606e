//! The Stanford bunny (`shared/scenes/stanford-bunny.obj`, 69,451
//! triangles) on a floor, under a key light with shadows and a sky
//! ambient term darkened by ambient occlusion.
//!
//! Any mesh renders this way ([`mesh_scene`]; the `render` binary uses it):
//! the camera and light are placed from the mesh's bounds, a floor is laid
//! under it, each `.mtl` material gets its own `kd`. Pictures are
//! progressive like the Cornell box's: each launch traces one jittered
//! camera ray per pixel and `ao_samples` occlusion rays from what it hits,
//! and the output is the running mean. Beside it the camera writes a
//! denoiser's guides ([`Aovs`]): the mean radiance, the first hit's
//! albedo, shading normal and world position, averaged over the samples
//! as the radiance is, and the variance of the mean's luminance
//! ([`crate::guides`]).

use crate::common::*;
use crate::diffuse::facing_normal;
use crate::guides::{add_luminance_sample, demodulated_luminance};
use crate::mesh::{self, LoadedMesh};
use crate::scene::{Aovs, Camera, Error, Scene, Settings, quad, shared_scene};
use crate::shadows::direct_light;
use glam::Vec3;
use rt_runtime::{Acceleration, BufferType, Builder, Scope};
use rt_std::prelude::*;

/// Per-ray data of a lit mesh's camera rays: the colour found, and the
/// albedo, shading normal and position (w 1) of what the ray hit (the
/// denoiser's guides; the background's colour, no normal and no position
/// where it hit nothing).
#[rt_payload]
pub struct GuidedRadiance {
    pub result: Vec3,
    pub albedo: Vec3,
    pub normal: Vec3,
    pub position: Vec4,
}

/// A jittered pinhole camera that accumulates one sample per launch and
/// writes the mean, gamma-corrected, the guides' running means and the
/// luminance's variance entry ([`add_luminance_sample`]).
#[rt_program(ray_generation)]
pub fn accumulating_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] frame: u32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut accum_buffer: RwBuffer2d<Vec4>,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
    #[var] mut radiance_buffer: RwBuffer2d<Vec4>,
    #[var] mut albedo_buffer: RwBuffer2d<Vec4>,
    #[var] mut normal_buffer: RwBuffer2d<Vec4>,
    #[var] mut variance_buffer: RwBuffer2d<Vec4>,
    #[var] mut position_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim();
    let mut seed = tea4(idx.y * dim.x + idx.x, frame + 0x5bd1_e995);
    let mut jitter = Vec2::splat(0.5);
    if frame > 0 {
        jitter = vec2(rnd(&mut seed), rnd(&mut seed));
    }
    let d = (idx.as_vec2() + jitter) / dim.as_vec2() * 2.0 - Vec2::ONE;
    let ray = Ray::new(eye, (d.x * u + d.y * v + w).normalize(), RADIANCE_RAY, scene_epsilon, f32::INFINITY);
    let mut prd = GuidedRadiance { result: Vec3::ZERO, albedo: Vec3::ZERO, normal: Vec3::ZERO, position: Vec4::ZERO };
    rt_trace(top_object, ray, &mut prd);
    let mut acc = Vec4::ZERO;
    let mut albedo = Vec3::ZERO;
    let mut normal = Vec3::ZERO;
    let mut moments = Vec4::ZERO;
    let mut position = Vec4::ZERO;
    if frame > 0 {
        acc = accum_buffer[idx];
        albedo = albedo_buffer[idx].xyz();
        normal = normal_buffer[idx].xyz();
        moments = variance_buffer[idx];
        position = position_buffer[idx];
    }
    acc += prd.result.extend(1.0);
    accum_buffer[idx] = acc;
    let mean = acc.xyz() / acc.w;
    output_buffer[idx] = mean.max(Vec3::ZERO).powf(1.0 / 2.2).extend(1.0);
    radiance_buffer[idx] = mean.extend(1.0);
    let keep = (acc.w - 1.0) / acc.w;
    albedo_buffer[idx] = (albedo * keep + prd.albedo / acc.w).extend(1.0);
    normal_buffer[idx] = (normal * keep + prd.normal / acc.w).extend(0.0);
    variance_buffer[idx] = add_luminance_sample(moments, demodulated_luminance(prd.result, prd.albedo), acc.w);
    // The running mean of the hits' positions (w 1) and of zero for a
    // miss: w is the fraction that hit, xyz over w the hits' mean.
    position_buffer[idx] = position * keep + prd.position / acc.w;
}

/// Camera rays that hit nothing see the background, which is also their
/// albedo (a flat colour the denoiser divides out).
#[rt_program(miss)]
pub fn guided_background(prd: &mut GuidedRadiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
    prd.albedo = bg_color;
}

/// Diffuse and a little specular light from the lights (with shadows), plus
/// `ambient_light_color` times the fraction of `ao_samples`
/// cosine-distributed rays that travel `ao_radius` unblocked.
#[rt_program(closest_hit)]
pub fn occluded_shade(
    prd: &mut GuidedRadiance,
    attr: &Normals,
    #[var] kd: Vec3,
    #[var] ks: Vec3,
    #[var] phong_exp: f32,
    #[var] ambient_light_color: Vec3,
    #[var] lights: Buffer<BasicLight>,
    #[var] ao_samples: u32,
    #[var] ao_radius: f32,
    #[var] frame: u32,
    #[var] scene_epsilon: f32,
    #[var] top_shadower: Object,
) {
    let ray = current_ray();
    let n = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    let hit_point = ray.origin + t_hit() * ray.direction;
    let idx = launch_index();
    let mut seed = tea4(idx.y * launch_dim().x + idx.x, frame);
    let mut open = 0.0;
    for _ in 0..ao_samples {
        let u1 = rnd(&mut seed);
        let u2 = rnd(&mut seed);
        let dir = cosine_sample_hemisphere(n, u1, u2);
        let mut shadow = Shadow { attenuation: Vec3::ONE };
        rt_trace(top_shadower, Ray::new(hit_point, dir, SHADOW_RAY, scene_epsilon, ao_radius), &mut shadow);
        open += shadow.attenuation.x;
    }
    let ao = open / ao_samples.max(1) as f32;
    prd.result = kd * ambient_light_color * ao
        + direct_light(hit_point, n, ray.direction, kd, ks, phong_exp, lights, scene_epsilon, top_shadower);
    prd.albedo = kd;
    prd.normal = n;
    prd.position = hit_point.extend(1.0);
}

/// How a mesh is shown.
#[derive(Clone, Copy, Debug)]
pub struct MeshView {
    /// The direction the camera looks along.
    pub view_direction: Vec3,
    pub vfov_degrees: f32,
    /// Where the key light is, from the mesh's centre (scaled by its size).
    pub key_direction: Vec3,
}

impl Default for MeshView {
    fn default() -> Self {
        MeshView {
            view_direction: Vec3::new(0.45, -0.38, -1.0),
            vfov_degrees: 30.0,
            key_direction: Vec3::new(0.87, 1.2, 0.45),
        }
    }
}

/// Occlusion rays per pixel per launch.
pub const AO_SAMPLES: u32 = 2;
/// The sky's light, reaching what occlusion leaves open.
pub const SKY: Vec3 = Vec3::new(0.16, 0.18, 0.23);
/// The floor's colour.
pub const FLOOR_KD: Vec3 = Vec3::new(0.72, 0.71, 0.68);
/// The background.
pub const BACKGROUND: Vec3 = Vec3::new(0.62, 0.68, 0.78);

/// The camera [`mesh_scene`] uses.
pub fn camera(loaded: &LoadedMesh, view: MeshView, aspect: f32) -> Camera {
    Camera::framing(loaded.min, loaded.max, view.view_direction, view.vfov_degrees, aspect)
}

/// Where [`mesh_scene`] puts the key light: eight mesh radii from its
/// centre along `view.key_direction`.
pub fn key_light_position(loaded: &LoadedMesh, view: MeshView) -> Vec3 {
    key_light_position_in((loaded.min, loaded.max), view)
}

/// [`key_light_position`] for bounds `(min, max)`.
pub fn key_light_position_in((min, max): (Vec3, Vec3), view: MeshView) -> Vec3 {
    let radius = ((max - min).length() * 0.5).max(1e-6);
    (min + max) * 0.5 + view.key_direction.normalize() * radius * 8.0
}

/// A scene of `loaded` on a floor, framed from its bounds, `settings.spp`
/// launches.
pub fn mesh_scene(loaded: &LoadedMesh, settings: &Settings, view: MeshView) -> Result<Scene, Error> {
    mesh_scene_from(loaded, settings, view, camera(loaded, view, settings.aspect()))
}

/// [`mesh_scene`] seen by `camera`.
pub fn mesh_scene_from(
    loaded: &LoadedMesh,
    settings: &Settings,
    view: MeshView,
    camera: Camera,
) -> Result<Scene, Error> {
    let (min, max) = (loaded.min, loaded.max);
    let (mut ctx, output) = Scene::start(settings, 1.0)?;
    let lit = light_and_frame(&mut ctx, settings, (min, max), view, camera)?;
    let materials =
        loaded.materials.iter().map(|m| lit.material(&mut ctx, m.diffuse)).collect::<Result<Vec<_>, _>>()?;
    let floor_material = lit.material(&mut ctx, FLOOR_KD)?;
    let model = ctx.create_triangles(loaded.mesh.clone())?;
    let model = ctx.create_geometry_instance(model, &materials)?;
    let floor = ctx.create_triangles(floor_quad(min, max))?;
    let floor = ctx.create_geometry_instance(floor, &[floor_material])?;
    let top = ctx.create_geometry_group(&[model, floor], Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.set_var(Scope::Context, "top_shadower", top)?;
    let mut scene = Scene::new(ctx, output, settings);
    scene.frames = settings.spp;
    scene.accumulation = Some(lit.accumulation);
    scene.aovs = Some(lit.aovs);
    Ok(scene)
}

/// What [`light_and_frame`] made: the programs every material of a lit
/// scene runs.
pub struct Lit {
    shade: rt_runtime::ProgramId,
    block: rt_runtime::ProgramId,
    /// The accumulation buffer.
    pub accumulation: rt_runtime::BufferId,
    /// The guide buffers the camera writes.
    pub aovs: Aovs,
}

impl Lit {
    /// A material shaded by [`occluded_shade`] in diffuse colour `kd`
    /// (blocking shadow rays).
    pub fn material(&self, ctx: &mut rt_runtime::Context, kd: Vec3) -> Result<rt_runtime::MaterialId, Error> {
        let m = ctx.create_material();
        self.attach(ctx, m, kd)?;
        Ok(m)
    }

    /// Makes an existing material (a loaded scene's) one of this scene's.
    pub fn attach(&self, ctx: &mut rt_runtime::Context, m: rt_runtime::MaterialId, kd: Vec3) -> Result<(), Error> {
        ctx.set_closest_hit_program(m, RADIANCE_RAY, self.shade)?;
        ctx.set_any_hit_program(m, SHADOW_RAY, self.block)?;
        ctx.set_var(m, "kd", kd)?;
        Ok(())
    }
}

/// Everything of [`mesh_scene`] but the geometry: its programs, the
/// background, `camera`, the accumulation buffer, the key light and sky
/// placed from `bounds`, and `scene_epsilon` from their size.
pub fn light_and_frame(
    ctx: &mut rt_runtime::Context,
    settings: &Settings,
    bounds: (Vec3, Vec3),
    view: MeshView,
    camera: Camera,
) -> Result<Lit, Error> {
    let (min, max) = bounds;
    let radius = ((max - min).length() * 0.5).max(1e-6);
    ctx.set_var(Scope::Context, "scene_epsilon", radius * 1e-4)?;
    let ray_generation = ctx.create_program(&accumulating_camera::PROGRAM);
    ctx.set_ray_generation_program(0, ray_generation)?;
    let miss = ctx.create_program(&guided_background::PROGRAM);
    ctx.set_miss_program(RADIANCE_RAY, miss)?;
    let shadow_miss = ctx.create_program(&shadow_miss::PROGRAM);
    ctx.set_miss_program(SHADOW_RAY, shadow_miss)?;
    ctx.set_var(Scope::Context, "bg_color", BACKGROUND)?;
    camera.set_vars(ctx, settings.aspect())?;
    let accum = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, settings.width, settings.height)?;
    ctx.set_var(Scope::Context, "accum_buffer", accum)?;
    let aovs = guide_buffers(ctx, (settings.width, settings.height))?;
    let key =
        BasicLight { pos: key_light_position_in(bounds, view), color: Vec3::new(0.75, 0.7, 0.62), casts_shadow: 1 };
    let lights = ctx.create_buffer(BufferType::Input, vec![key]);
    ctx.set_var(Scope::Context, "lights", lights)?;
    ctx.set_var(Scope::Context, "ambient_light_color", SKY)?;
    ctx.set_var(Scope::Context, "ao_samples", AO_SAMPLES)?;
    ctx.set_var(Scope::Context, "ao_radius", radius * 0.6)?;
    ctx.set_var(Scope::Context, "ks", Vec3::splat(0.12))?;
    ctx.set_var(Scope::Context, "phong_exp", 40.0f32)?;
    let shade = ctx.create_program(&occluded_shade::PROGRAM);
    let block = ctx.create_program(&any_hit_shadow::PROGRAM);
    Ok(Lit { shade, block, accumulation: accum, aovs })
}

/// The camera's guide buffers at `size`, set as its variables: kept on the
/// device (read back only when asked for, by a denoiser or `read_buffer`),
/// not after every launch.
pub fn guide_buffers(ctx: &mut rt_runtime::Context, (width, height): (u32, u32)) -> Result<Aovs, Error> {
    let mut guide = |name: &str| -> Result<_, Error> {
        let b = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, width, height)?;
        ctx.set_buffer_device_local(b, true)?;
        ctx.set_var(Scope::Context, name, b)?;
        Ok(b)
    };
    Ok(Aovs {
        radiance: guide("radiance_buffer")?,
        albedo: guide("albedo_buffer")?,
        normal: guide("normal_buffer")?,
        variance: guide("variance_buffer")?,
        position: Some(guide("position_buffer")?),
    })
}

/// The floor under `[min, max]`: a square 80 radii wide at `min.y`.
pub fn floor_quad(min: Vec3, max: Vec3) -> rt_runtime::TriangleMesh {
    let center = (min + max) * 0.5;
    let radius = ((max - min).length() * 0.5).max(1e-6);
    let half = radius * 40.0;
    quad(
        Vec3::new(center.x - half, min.y, center.z - half),
        Vec3::new(0.0, 0.0, 2.0 * half),
        Vec3::new(2.0 * half, 0.0, 0.0),
    )
}

/// The bunny.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let loaded = mesh::load_obj(&shared_scene("stanford-bunny.obj"))?;
    mesh_scene(&loaded, settings, MeshView::default())
}
