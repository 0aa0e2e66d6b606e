//! Runtime behaviour on every backend (each test runs on the CPU backend and
//! on wgpu — lavapipe on machines without a GPU), with pixel values known
//! analytically: a sphere's silhouette and normals, a triangle's shadow
//! edge, any-hit termination, the trace-depth limit, variable shadowing by
//! scope, exceptions, and link errors that name what is wrong.

use glam::{UVec2, Vec2, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

mod device;
mod exceptions;
mod graphs;
mod ray_flags;
mod refits;
mod scopes;
mod selectors;
mod shading;
mod textures;
mod tracing;

use device::*;
use exceptions::*;
use graphs::*;
use ray_flags::*;
use refits::*;
use scopes::*;
use selectors::*;
use shading::*;
use textures::*;
use tracing::*;

#[rt_payload(impl)]
pub struct Radiance {
    pub result: Vec3,
    pub depth: i32,
}

#[rt_impl]
impl Radiance {
    /// The payload's result set through `&mut self`.
    pub fn shade(&mut self, color: Vec3) {
        self.result = color;
        self.depth += Self::SHADED;
    }

    pub const SHADED: i32 = 1;
}

#[rt_payload]
pub struct ShadowPrd {
    pub attenuation: f32,
}

#[rt_attributes(impl)]
pub struct Hit {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

#[rt_impl]
impl Hit {
    /// The world-space shading normal mapped into `[0, 1]`.
    pub fn normal_color(&self) -> Vec3 {
        rt_transform_normal(ObjectToWorld, self.shading_normal).normalize() * 0.5 + 0.5
    }
}

/// Orthographic camera looking down -z over `[-extent, extent]^2`.
#[rt_program(ray_generation)]
pub fn ortho(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] extent: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * extent, p.y * extent, 10.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, depth: 0 };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.result.extend(1.0);
}

#[rt_program(miss)]
pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

#[rt_program(miss)]
pub fn flat_miss(prd: &mut Radiance) {
    prd.result = Vec3::ONE;
}

#[rt_program(miss)]
pub fn shadow_miss(prd: &mut ShadowPrd) {
    prd.attenuation = 1.0;
}

#[rt_program(closest_hit)]
pub fn normal_shader(prd: &mut Radiance, attr: &Hit) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
}

/// `normal_shader` through methods of the payload and the attributes.
#[rt_program(closest_hit)]
pub fn normal_shader_by_methods(prd: &mut Radiance, attr: &Hit) {
    prd.shade(attr.normal_color());
}

#[rt_program(closest_hit)]
pub fn flat_color(prd: &mut Radiance, #[var] color: Vec3) {
    prd.result = color;
}

/// Lights the hit point if a shadow ray to `light` reaches it.
#[rt_program(closest_hit)]
pub fn shadowed(prd: &mut Radiance, #[var] light: Vec3, #[var] top: Object) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let to_light = light - p;
    let dist = to_light.length();
    let mut s = ShadowPrd { attenuation: 0.0 };
    rt_trace(top, Ray::new(p, to_light / dist, 1, 0.001, dist), &mut s);
    prd.result = Vec3::splat(s.attenuation);
}

#[rt_program(any_hit)]
pub fn ignore_all(prd: &mut Radiance) {
    let _ = prd.depth;
    rt_ignore_intersection();
}

#[rt_program(any_hit)]
pub fn shadow_blocker(prd: &mut ShadowPrd) {
    prd.attenuation = 0.0;
    rt_terminate_ray();
}

/// Traces again from every hit: recursion without end.
#[rt_program(closest_hit)]
pub fn mirror_forever(prd: &mut Radiance, #[var] top: Object) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let mut next = Radiance { result: Vec3::ZERO, depth: prd.depth + 1 };
    rt_trace(top, Ray::new(p, -ray.direction, 0, 0.001, f32::INFINITY), &mut next);
    prd.result = next.result + Vec3::splat(1.0);
}

#[rt_program(exception)]
pub fn paint_exception(#[var] mut out: RwBuffer2d<Vec4>) {
    out[launch_index()] = vec4(1.0, 0.0, 1.0, exception_code() as f32);
}

#[rt_program(closest_hit)]
pub fn throws(prd: &mut Radiance) {
    prd.result = Vec3::ONE;
    rt_throw(EXCEPTION_USER + 7);
}

#[rt_program(intersection)]
pub fn sphere_intersect(prim: u32, attr: &mut Hit, #[var] sphere: Vec4) {
    let _ = prim;
    let ray = current_ray();
    let center = sphere.xyz();
    let radius = sphere.w;
    let o = ray.origin - center;
    let a = ray.direction.dot(ray.direction);
    let b = o.dot(ray.direction);
    let c = o.dot(o) - radius * radius;
    let disc = b * b - a * c;
    if disc > 0.0 {
        let s = disc.sqrt();
        let t0 = (-b - s) / a;
        let t1 = (-b + s) / a;
        if rt_potential_intersection(t0) {
            let n = (o + t0 * ray.direction) / radius;
            attr.geometric_normal = n;
            attr.shading_normal = n;
            rt_report_intersection(0);
        } else if rt_potential_intersection(t1) {
            let n = (o + t1 * ray.direction) / radius;
            attr.geometric_normal = n;
            attr.shading_normal = n;
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32, #[var] sphere: Vec4) -> Aabb {
    let _ = prim;
    Aabb::new(sphere.xyz() - Vec3::splat(sphere.w), sphere.xyz() + Vec3::splat(sphere.w))
}

/// Reads a buffer past its end at the centre pixel, prints at one pixel.
#[rt_program(closest_hit)]
pub fn reads_past_the_end(prd: &mut Radiance, #[var] table: Buffer<f32>) {
    let i = launch_index();
    let mut idx = 0u32;
    if i.x == launch_dim().x / 2 && i.y == launch_dim().y / 2 {
        idx = table.len() + 3;
    }
    let v = table[idx];
    rt_printf!("pixel {} read {} of {}", i, v, table.len());
    prd.result = Vec3::splat(v);
}

/// Traces a ray with a NaN direction from the centre pixel.
#[rt_program(ray_generation)]
pub fn nan_camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let mut d = vec3(0.0, 0.0, -1.0);
    if idx.x == 1 && idx.y == 2 {
        d = vec3(f32::NAN, 0.0, -1.0);
    }
    let mut prd = Radiance { result: Vec3::ZERO, depth: 0 };
    rt_trace(top, Ray::new(vec3(0.0, 0.0, 10.0), d, 0, 0.0, f32::INFINITY), &mut prd);
    out[idx] = prd.result.extend(1.0);
}

/// Ray flags under test, from variables.
#[rt_program(ray_generation)]
pub fn flagged_camera(
    #[var] top: Object,
    #[var] mut out: RwBuffer2d<Vec4>,
    #[var] flags: u32,
    #[var] mask: u32,
    #[var] z: f32,
) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 4.0 - 2.0;
    let mut prd = Radiance { result: Vec3::ZERO, depth: 0 };
    let ray = Ray::new(vec3(p.x, p.y, z), vec3(0.0, 0.0, -z.signum()), 0, 0.0, f32::INFINITY);
    rt_trace_with(top, ray, &mut prd, flags, mask);
    out[idx] = prd.result.extend(1.0);
}

/// Traces a shadow payload on the radiance ray type: a mistake the linker
/// cannot see (the ray type is a run-time value).
#[rt_program(ray_generation)]
pub fn wrong_payload_camera(#[var] top: Object) {
    let mut s = ShadowPrd { attenuation: 0.5 };
    rt_trace(top, Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 1.0), &mut s);
}

/// Increments through a `&mut` to a payload field (WGSL passes pointers to
/// whole variables only: the compiler copies in and out).
#[rt_function]
pub fn bump(x: &mut i32) -> i32 {
    *x += 2;
    *x * 10
}

#[rt_program(closest_hit)]
pub fn bumps_a_payload_field(prd: &mut Radiance) {
    prd.depth = 1;
    let v = bump(&mut prd.depth);
    prd.result = vec3(v as f32, prd.depth as f32, 0.0);
}

/// Any hit that adds to the payload and lets the search go on.
#[rt_program(any_hit)]
pub fn count_hits(prd: &mut Radiance) {
    prd.result += vec3(0.0, 0.0, 1.0);
}

/// Closest hit that samples a texture at the hit's texture coordinate.
#[rt_attributes]
pub struct Uv {
    pub texcoord: Vec2,
}

#[rt_program(closest_hit)]
pub fn textured(prd: &mut Radiance, attr: &Uv, #[var] tex: Sampler2d) {
    prd.result = tex.sample(attr.texcoord).xyz();
}

/// Chooses a selector's child from the payload (which `parity_camera` fills
/// with the launch index's parity) plus a node-scope offset: a child index
/// past the last one enters nothing.
#[rt_program(visit)]
pub fn parity_visit(prd: &Radiance, #[var] offset: u32) -> u32 {
    prd.depth as u32 + offset
}

/// Chooses a selector's child by the side of the selector's space the ray
/// starts on.
#[rt_program(visit)]
pub fn side_visit(prd: &Radiance) -> u32 {
    let _ = prd.depth;
    if current_ray().origin.x < 0.0 { 0 } else { 1 }
}

/// A visit program for shadow rays, met by a radiance ray.
#[rt_program(visit)]
pub fn shadow_visit(prd: &ShadowPrd) -> u32 {
    let _ = prd.attenuation;
    0
}

/// The ortho camera with the launch index's x parity in the payload.
#[rt_program(ray_generation)]
pub fn parity_camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] extent: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * extent, p.y * extent, 10.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, depth: (idx.x % 2) as i32 };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.result.extend(1.0);
}

/// Column `column % 4` of the hit instance's object-to-world matrix
/// (`column < 4`) or of its world-to-object matrix, from `rt_get_transform`.
#[rt_program(closest_hit)]
pub fn transform_column(prd: &mut Radiance, #[var] column: u32) {
    let o2w = rt_get_transform(ObjectToWorld);
    let w2o = rt_get_transform(WorldToObject);
    let m = if column < 4 { o2w } else { w2o };
    prd.result = m.col((column % 4) as usize).truncate();
}

/// A mirror: traces the reflected ray and keeps `reflectance` of its colour.
#[rt_program(closest_hit)]
pub fn mirror(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let mut reflected = Radiance { result: Vec3::ZERO, depth: prd.depth + 1 };
    rt_trace(top, Ray::new(p, reflect(ray.direction, n), 0, 0.001, f32::INFINITY), &mut reflected);
    prd.result = reflected.result * reflectance;
}

/// What a reflected ray sees: a helper that traces, called from a
/// closest-hit program inside a larger expression (the resumable form takes
/// the call out of the expression and suspends in the helper).
#[rt_function]
pub fn reflected_color(top: Object, p: Vec3, d: Vec3, depth: i32) -> Vec3 {
    let mut next = Radiance { result: Vec3::ZERO, depth: depth + 1 };
    rt_trace(top, Ray::new(p, d, 0, 0.001, f32::INFINITY), &mut next);
    next.result
}

/// [`mirror`] through the [`reflected_color`] helper.
#[rt_program(closest_hit)]
pub fn mirror_through_a_helper(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    prd.result = Vec3::ZERO + reflected_color(top, p, reflect(ray.direction, n), prd.depth) * reflectance;
}

/// [`mirror`] with its trace in a `match` arm (the resumable form switches
/// over the scrutinee kept in its frame).
#[rt_program(closest_hit)]
pub fn mirror_in_a_match(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let mut reflected = Radiance { result: Vec3::ZERO, depth: prd.depth + 1 };
    match prd.depth {
        100 => {}
        _ => rt_trace(top, Ray::new(p, reflect(ray.direction, n), 0, 0.001, f32::INFINITY), &mut reflected),
    }
    prd.result = reflected.result * reflectance;
}

/// [`reflected_color`] with its trace inside a `let`'s value, where the
/// compiler makes no resumable form.
#[rt_function]
#[allow(clippy::let_and_return)] // The `let` is the point.
pub fn reflected_in_a_let(top: Object, p: Vec3, d: Vec3, depth: i32) -> Vec3 {
    let mut next = Radiance { result: Vec3::ZERO, depth: depth + 1 };
    let seen = {
        rt_trace(top, Ray::new(p, d, 0, 0.001, f32::INFINITY), &mut next);
        next.result
    };
    seen
}

/// A helper that traces only through another helper
/// ([`reflected_in_a_let`]).
#[rt_function]
pub fn reflected_two_helpers_down(top: Object, p: Vec3, d: Vec3, depth: i32) -> Vec3 {
    reflected_in_a_let(top, p, d, depth)
}

/// [`mirror`] through [`reflected_two_helpers_down`]: per-depth clones of a
/// helper whose trace is one helper further down.
#[rt_program(closest_hit)]
pub fn mirror_through_two_helpers(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    prd.result = reflected_two_helpers_down(top, p, reflect(ray.direction, n), prd.depth) * reflectance;
}

/// [`mirror`] through [`reflected_in_a_let`]: no resumable form, so
/// kernels using it clone what traces per depth instead.
#[rt_program(closest_hit)]
pub fn mirror_without_a_resumable_form(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    prd.result = reflected_in_a_let(top, p, reflect(ray.direction, n), prd.depth) * reflectance;
}

/// One ray per origin (1D launch), straight down -z: the closest hit's
/// colour's x, or the background's.
#[rt_program(ray_generation)]
pub fn probe_rays(#[var] top: Object, #[var] origins: Buffer<Vec3>, #[var] mut hits: RwBuffer<f32>) {
    let i = launch_index().x;
    let mut prd = Radiance { result: Vec3::ZERO, depth: 0 };
    rt_trace(top, Ray::new(origins[i], vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
    hits[i] = prd.result.x;
}

/// Writes `index + 1` at every 1D launch index.
#[rt_program(ray_generation)]
pub fn write_index(#[var] mut ids: RwBuffer<u32>) {
    let i = launch_index().x;
    ids[i] = i + 1;
}

const W: u32 = 32;
const BG: Vec3 = Vec3::new(0.1, 0.2, 0.3);

/// A context with the ortho camera, a background miss and an output buffer.
fn camera(extent: f32, on: impl Into<On>) -> (Context, BufferId) {
    let mut ctx = on.into().context();
    ctx.set_ray_type_count(2);
    let rg = ctx.create_program(&ortho::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let smiss = ctx.create_program(&shadow_miss::PROGRAM);
    ctx.set_miss_program(1, smiss).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, W).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "extent", extent).unwrap();
    ctx.set_var(Scope::Context, "bg_color", BG).unwrap();
    (ctx, out)
}

fn sphere_scene(
    ctx: &mut Context,
    closest_hit: &'static rt_std::program::ProgramDescriptor,
    center: Vec3,
    radius: f32,
) -> (NodeId, MaterialId, GeometryInstanceId) {
    let isect = ctx.create_program(&sphere_intersect::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let geom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    ctx.set_var(geom, "sphere", center.extend(radius)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(closest_hit);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    (gg, mat, gi)
}

fn pixel(img: &[Vec4], x: u32, y: u32) -> Vec4 {
    img[(y * W + x) as usize]
}

/// World position of pixel (x, y) for the ortho camera.
fn world(x: u32, y: u32, extent: f32) -> (f32, f32) {
    let p = |i: u32| ((i as f32 + 0.5) / W as f32 * 2.0 - 1.0) * extent;
    (p(x), p(y))
}

/// Instantiates the tests that take a target (`fn(On)`, from every module
/// but `device`) once per target: the CPU backend, the compute traversal,
/// the ray-query traversal.
macro_rules! on_backends {
    ($($name:ident),* $(,)?) => {
        mod cpu {
            use super::*;
            $( #[test] fn $name() { super::$name(On::CPU) } )*
        }
        mod wgpu {
            use super::*;
            $( #[test] fn $name() { super::$name(On::COMPUTE) } )*
        }
        mod rayquery {
            use super::*;
            $( #[test] fn $name() { if On::RAY_QUERY.available() { super::$name(On::RAY_QUERY) } } )*
        }
    };
}

on_backends!(
    mut_references_to_payload_fields_reach_helpers,
    payload_of_the_wrong_ray_type_raises_invalid_ray,
    buffer_overrun_raises_the_exception_and_printf_reaches_the_host,
    nan_rays_raise_invalid_ray,
    ray_flags_and_masks,
    culling_in_the_lean_search,
    one_triangle_and_an_empty_group,
    a_refit_mesh_renders_as_one_built_for_its_new_shape,
    textures_sample_with_wrap_and_filter,
    sphere_silhouette_and_normals,
    methods_of_the_payload_and_attributes_shade_as_the_fields_do,
    triangle_attributes_reach_closest_hit_through_a_transform,
    rt_get_transform_reads_the_instance_transform_and_its_inverse,
    any_hit_terminate_casts_a_shadow_with_a_sharp_edge,
    trace_depth_limit_raises_the_exception_and_the_exception_program_runs,
    user_exception_reaches_the_exception_program_and_other_pixels_are_untouched,
    variables_resolve_innermost_scope_first,
    link_errors_name_the_program_the_variable_and_the_scopes,
    a_ray_type_without_a_miss_program_leaves_the_payload,
    moving_geometry_refits_instead_of_rebuilding,
    selector_chooses_a_child_from_the_payload_and_launch_index_parity,
    visit_programs_see_the_ray_in_the_selectors_space_and_check_the_payload_type,
    three_level_graph_group_of_groups_of_transforms,
    default_exception_paints_magenta_and_records_the_exception,
    mirror_shows_the_reflected_object_and_the_reflected_background,
    a_helper_that_traces_works_from_a_closest_hit,
    a_bvh_deeper_than_64_levels_loses_no_hit,
    a_trace_in_a_match_arm_resumes_in_that_arm,
    a_program_without_a_resumable_form_links_per_depth_clones,
    a_helper_tracing_through_another_helper_links_per_depth_clones,
    launches_wider_than_the_dispatch_limit_write_every_index,
);

/// The largest difference of any channel between two images.
fn largest_difference(a: &[Vec4], b: &[Vec4]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0f32, f32::max)
}
