//! A progressive path tracer over the Cornell box
//! (`shared/scenes/cornell_box.obj`, its `.mtl` colours and its area light).
//!
//! Each launch adds one jittered sample per pixel to an accumulation buffer
//! and writes the running mean, exposed and gamma-corrected, to the output:
//! run more launches for less noise. A path gathers, at each diffuse hit,
//! the area light through a shadow ray to a random point on it (next-event
//! estimation), then continues in a cosine-weighted direction, so its weight
//! is just the albedo; Russian roulette ends long paths. Emitters add their
//! light only to camera rays, since every later vertex already sampled the
//! light directly.
//!
//! The file comments out the light's face (`#f -4 -3 -2 -1` under `o
//! light`): its four vertices are read from the text and made a one-sided
//! quad light facing into the box, with the emission of material `light`
//! (`Ka 20 20 20`).
//!
//! Beside the picture, the camera writes what a denoiser needs
//! ([`Aovs`]): the mean linear radiance, the albedo and shading normal of
//! each path's first hit, averaged over the samples, and the variance of
//! the mean's luminance ([`crate::guides`]).

use crate::common::*;
use crate::diffuse::facing_normal;
use crate::guides::{add_luminance_sample, demodulated_luminance};
use crate::mesh::{self, MeshError};
use crate::scene::{Aovs, Camera, Error, Scene, Settings, shared_scene};
use glam::Vec3;
use rt_runtime::{Acceleration, BufferType, Builder, Scope, TriangleMesh};
use rt_std::prelude::*;

/// Per-path state: what the path has gathered, its weight, where it goes
/// next, its RNG state, its length and whether it has ended; and the
/// albedo and shading normal of its first hit, the denoiser's guides.
#[rt_payload]
pub struct PathPrd {
    pub radiance: Vec3,
    pub albedo: Vec3,
    pub normal: Vec3,
    pub throughput: Vec3,
    pub origin: Vec3,
    pub direction: Vec3,
    pub seed: u32,
    pub depth: i32,
    pub done: bool,
}

/// A one-sided parallelogram light: `corner + s * v1 + t * v2` for `s, t`
/// in `[0, 1]`, emitting `emission` (radiance) along `normal`.
#[rt_struct]
pub struct ParallelogramLight {
    pub corner: Vec3,
    pub v1: Vec3,
    pub v2: Vec3,
    pub normal: Vec3,
    pub emission: Vec3,
}

/// Exposure, then a filmic shoulder, then display gamma.
#[rt_function]
pub fn tonemap(c: Vec3, exposure: f32) -> Vec3 {
    let mapped = Vec3::ONE - (-c * exposure).exp();
    mapped.powf(1.0 / 2.2)
}

#[rt_program(ray_generation)]
pub fn path_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] frame: u32,
    #[var] max_depth: i32,
    #[var] exposure: f32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut accum_buffer: RwBuffer2d<Vec4>,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
    #[var] mut radiance_buffer: RwBuffer2d<Vec4>,
    #[var] mut albedo_buffer: RwBuffer2d<Vec4>,
    #[var] mut normal_buffer: RwBuffer2d<Vec4>,
    #[var] mut variance_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim();
    let mut seed = tea4(idx.y * dim.x + idx.x, frame);
    let jitter = vec2(rnd(&mut seed), rnd(&mut seed));
    let d = (idx.as_vec2() + jitter) / dim.as_vec2() * 2.0 - Vec2::ONE;
    let mut prd = PathPrd {
        radiance: Vec3::ZERO,
        albedo: Vec3::ZERO,
        normal: Vec3::ZERO,
        throughput: Vec3::ONE,
        origin: eye,
        direction: (d.x * u + d.y * v + w).normalize(),
        seed,
        depth: 0,
        done: false,
    };
    while !prd.done && prd.depth < max_depth {
        rt_trace(top_object, Ray::new(prd.origin, prd.direction, RADIANCE_RAY, scene_epsilon, f32::INFINITY), &mut prd);
        prd.depth += 1;
    }
    let mut acc = Vec4::ZERO;
    if frame > 0 {
        acc = accum_buffer[idx];
    }
    acc += prd.radiance.extend(1.0);
    accum_buffer[idx] = acc;
    output_buffer[idx] = tonemap(acc.xyz() / acc.w, exposure).extend(1.0);
    // The guides (AOVs), averaged over the frames as the radiance is.
    let mean = acc.xyz() / acc.w;
    radiance_buffer[idx] = mean.extend(1.0);
    let keep = (acc.w - 1.0) / acc.w;
    albedo_buffer[idx] = (albedo_buffer[idx].xyz() * keep + prd.albedo / acc.w).extend(1.0);
    normal_buffer[idx] = (normal_buffer[idx].xyz() * keep + prd.normal / acc.w).extend(0.0);
    let l = demodulated_luminance(prd.radiance, prd.albedo);
    variance_buffer[idx] = add_luminance_sample(variance_buffer[idx], l, acc.w);
}

/// Paths that leave the box end in the dark.
#[rt_program(miss)]
pub fn path_miss(prd: &mut PathPrd) {
    prd.done = true;
}

/// A diffuse surface, maybe emissive.
#[rt_program(closest_hit)]
pub fn path_diffuse(
    prd: &mut PathPrd,
    attr: &Normals,
    #[var] kd: Vec3,
    #[var] emission: Vec3,
    #[var] light: ParallelogramLight,
    #[var] scene_epsilon: f32,
    #[var] top_shadower: Object,
) {
    let ray = current_ray();
    let hit_point = ray.origin + t_hit() * ray.direction;
    let n = facing_normal(attr.shading_normal, attr.geometric_normal, ray.direction);
    if prd.depth == 0 {
        prd.radiance += prd.throughput * emission;
        prd.albedo = kd;
        prd.normal = n;
    }
    if emission.max_element() > 0.0 {
        prd.done = true;
        return;
    }
    // Next-event estimation: a shadow ray to a random point of the light.
    let z1 = rnd(&mut prd.seed);
    let z2 = rnd(&mut prd.seed);
    let light_pos = light.corner + light.v1 * z1 + light.v2 * z2;
    let to_light = light_pos - hit_point;
    let dist = to_light.length();
    let l = to_light / dist;
    let n_dot_l = n.dot(l);
    let ln_dot_l = -light.normal.dot(l);
    if n_dot_l > 0.0 && ln_dot_l > 0.0 {
        let mut shadow = Shadow { attenuation: Vec3::ONE };
        let shadow_ray = Ray::new(hit_point, l, SHADOW_RAY, scene_epsilon, dist - scene_epsilon);
        rt_trace(top_shadower, shadow_ray, &mut shadow);
        let area = light.v1.cross(light.v2).length();
        let geometry = n_dot_l * ln_dot_l * area / (dist * dist);
        prd.radiance += prd.throughput * kd * FRAC_1_PI * light.emission * shadow.attenuation * geometry;
    }
    // A cosine-weighted bounce: BRDF * cos / pdf is the albedo.
    prd.throughput *= kd;
    if prd.depth >= 3 {
        let survive = prd.throughput.max_element().min(0.95);
        if rnd(&mut prd.seed) >= survive {
            prd.done = true;
            return;
        }
        prd.throughput /= survive;
    }
    let u1 = rnd(&mut prd.seed);
    let u2 = rnd(&mut prd.seed);
    prd.origin = hit_point;
    prd.direction = cosine_sample_hemisphere(n, u1, u2);
}

/// Path vertices at most (Russian roulette usually ends paths sooner).
pub const MAX_DEPTH: i32 = 8;
/// The `.mtl` albedos are 1 (white) and pure primaries; real paint
/// reflects less, and paths that never lose energy only end at
/// `MAX_DEPTH`. Every `Kd` is scaled by this.
pub const ALBEDO_SCALE: f32 = 0.75;
/// Exposure of the tone map.
pub const EXPOSURE: f32 = 1.6;

/// The camera of the classic view through the open front, which it fits
/// into the frame whole (floor and ceiling in view; a wide frame shows the
/// dark outside of the box at its sides).
pub fn camera(aspect: f32) -> Camera {
    let eye = Vec3::new(278.0, 273.0, -800.0);
    let (half_w, half_h) = (278.0 / 800.0, 274.4 / 800.0f32);
    let tan_v = half_h.max(half_w / aspect);
    Camera { eye, look_at: Vec3::new(278.0, 273.0, 0.0), up: Vec3::Y, vfov_degrees: 2.0 * tan_v.atan().to_degrees() }
}

/// The path-traced Cornell box, `settings.spp` launches of one sample per
/// pixel each.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let path = shared_scene("cornell_box.obj");
    let loaded = mesh::load_obj(&path)?;
    let text = std::fs::read_to_string(&path)
        .map_err(|e| Error::Io { path: path.display().to_string(), problem: e.to_string() })?;
    build(settings, loaded, &text, path.display().to_string())
}

/// [`scene`] from the text of the Cornell box's OBJ and MTL files
/// (`shared/scenes/cornell_box.obj` and `.mtl`): where there are no files
/// to read, as in a browser page.
pub fn scene_from_text(settings: &Settings, obj: &str, mtl: &str) -> Result<Scene, Error> {
    let file = "cornell_box.obj";
    let loaded = mesh::parse_obj_with_mtl(obj, file, &|_| Ok(mtl.to_string()))?;
    build(settings, loaded, obj, file.to_string())
}

/// The scene over the loaded box, whose OBJ text `text` (file `file`)
/// names the light's quad.
fn build(settings: &Settings, loaded: mesh::LoadedMesh, text: &str, file: String) -> Result<Scene, Error> {
    let quad = mesh::object_vertices(text, "light");
    let [p0, p1, _, p3] = quad[..] else {
        return Err(MeshError {
            file,
            line: None,
            problem: format!("object `light` has {} vertices, not 4", quad.len()),
        }
        .into());
    };
    let emission = loaded.materials.iter().find(|m| m.emission.max_element() > 0.0).map(|m| m.emission);
    let Some(emission) = emission else {
        return Err(MeshError { file, line: None, problem: "no material emits light".into() }.into());
    };
    let (v1, v2) = (p1 - p0, p3 - p0);
    let center = (loaded.min + loaded.max) * 0.5;
    let mut normal = v1.cross(v2).normalize();
    if normal.dot(center - p0) < 0.0 {
        normal = -normal;
    }
    let light = ParallelogramLight { corner: p0, v1, v2, normal, emission };

    let (mut ctx, output) = Scene::start(settings, 0.05)?;
    let camera_program = ctx.create_program(&path_camera::PROGRAM);
    ctx.set_ray_generation_program(0, camera_program)?;
    let miss = ctx.create_program(&path_miss::PROGRAM);
    ctx.set_miss_program(RADIANCE_RAY, miss)?;
    let shadow_miss = ctx.create_program(&shadow_miss::PROGRAM);
    ctx.set_miss_program(SHADOW_RAY, shadow_miss)?;
    camera(settings.aspect()).set_vars(&mut ctx, settings.aspect())?;
    let accum = ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, settings.width, settings.height)?;
    ctx.set_var(Scope::Context, "accum_buffer", accum)?;
    let mut aov = || -> Result<_, Error> {
        Ok(ctx.create_buffer_2d::<Vec4>(BufferType::InputOutput, settings.width, settings.height)?)
    };
    let aovs = Aovs { radiance: aov()?, albedo: aov()?, normal: aov()?, variance: aov()?, position: None };
    // Read back only when asked for (a denoiser, `read_buffer`), not after
    // every launch.
    for b in [aovs.radiance, aovs.albedo, aovs.normal, aovs.variance] {
        ctx.set_buffer_device_local(b, true)?;
    }
    ctx.set_var(Scope::Context, "radiance_buffer", aovs.radiance)?;
    ctx.set_var(Scope::Context, "albedo_buffer", aovs.albedo)?;
    ctx.set_var(Scope::Context, "normal_buffer", aovs.normal)?;
    ctx.set_var(Scope::Context, "variance_buffer", aovs.variance)?;
    ctx.set_var(Scope::Context, "max_depth", MAX_DEPTH)?;
    ctx.set_var(Scope::Context, "exposure", EXPOSURE)?;
    ctx.set_var(Scope::Context, "light", light)?;
    ctx.set_max_trace_depth(2);

    let shade = ctx.create_program(&path_diffuse::PROGRAM);
    let block = ctx.create_program(&any_hit_shadow::PROGRAM);
    let mut material = |kd: Vec3, emission: Vec3| -> Result<_, Error> {
        let m = ctx.create_material();
        ctx.set_closest_hit_program(m, RADIANCE_RAY, shade)?;
        ctx.set_any_hit_program(m, SHADOW_RAY, block)?;
        ctx.set_var(m, "kd", kd * ALBEDO_SCALE)?;
        ctx.set_var(m, "emission", emission)?;
        Ok(m)
    };
    let materials = loaded.materials.iter().map(|m| material(m.diffuse, m.emission)).collect::<Result<Vec<_>, _>>()?;
    let light_material = material(Vec3::ZERO, emission)?;
    let room = ctx.create_triangles(loaded.mesh.clone())?;
    let room = ctx.create_geometry_instance(room, &materials)?;
    let lamp = ctx.create_triangles(TriangleMesh {
        positions: vec![p0, p0 + v1, p0 + v1 + v2, p0 + v2],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..TriangleMesh::default()
    })?;
    let lamp = ctx.create_geometry_instance(lamp, &[light_material])?;
    let top = ctx.create_geometry_group(&[room, lamp], Acceleration::new(Builder::Sbvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.set_var(Scope::Context, "top_shadower", top)?;
    let mut scene = Scene::new(ctx, output, settings);
    scene.frames = settings.spp;
    scene.aovs = Some(aovs);
    Ok(scene)
}
