//! The ray programs of the workload (a pinhole camera, the normal shader,
//! the ambient-occlusion closest hit and its occlusion ray's programs) and
//! [`scene_with`], a context that runs them over one mesh.

use crate::scenes;
use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

/// The seed's pinhole camera.
#[rt_program(ray_generation)]
pub fn pinhole(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let d = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Radiance { result: Vec3::ZERO };
    rt_trace(top_object, Ray::new(eye, (d.x * u + d.y * v + w).normalize(), 0, 1e-4, f32::INFINITY), &mut prd);
    output_buffer[idx] = prd.result.extend(1.0);
}

/// The seed's normal shader.
#[rt_program(closest_hit)]
pub fn normal_shader(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize() * 0.5 + 0.5;
}

#[rt_program(miss)]
pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

/// Occlusion of an ambient-occlusion ray.
#[rt_payload]
pub struct Occlusion {
    pub hit: u32,
}

/// PCG-style integer hash (also in `obvhs_ao`, so both trace the same rays).
#[rt_function]
pub fn hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

/// Primary hit: one cosine-weighted ambient-occlusion ray, unbounded.
#[rt_program(closest_hit)]
pub fn ambient_occlusion(prd: &mut Radiance, attr: &Normals, #[var] top_object: Object) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let n = faceforward(n, ray.direction, n);
    let idx = launch_index();
    let h1 = hash(idx.x + idx.y * launch_dim().x);
    let h2 = hash(h1);
    let u1 = (h1 >> 8) as f32 / 16777216.0;
    let u2 = (h2 >> 8) as f32 / 16777216.0;
    let d = cosine_direction(n, u1, u2);
    let mut occ = Occlusion { hit: 0 };
    rt_trace(top_object, Ray::new(p + n * 1e-4, d, 1, 0.0, f32::INFINITY), &mut occ);
    prd.result = Vec3::splat(1.0 - occ.hit as f32);
}

/// A cosine-weighted direction around `n` from two uniform numbers.
#[rt_function]
pub fn cosine_direction(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let a = if n.x.abs() > 0.9 { Vec3::Y } else { Vec3::X };
    let t = n.cross(a).normalize();
    let b = n.cross(t);
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize()
}

#[rt_program(closest_hit)]
pub fn occluded(prd: &mut Occlusion) {
    prd.hit = 1;
}

#[rt_program(miss)]
pub fn unoccluded(prd: &mut Occlusion) {
    prd.hit = 0;
}

/// The workload: primary rays only, or primary plus one AO ray per hit.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Workload {
    Primary,
    Ao,
}

/// A context of `backend` tracing `mesh` (one geometry group, BVH) with
/// `workload`'s programs from `cam` into a `width` x `height` output: the
/// context, its output buffer, the geometry group and the geometry.
pub(crate) fn scene_with(
    mesh: &TriangleMesh,
    cam: scenes::Camera,
    backend: Backend,
    width: u32,
    height: u32,
    workload: Workload,
) -> Result<(Context, BufferId, NodeId, GeometryId)> {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    ctx.set_ray_type_count(2);
    let occ_miss = ctx.create_program(&unoccluded::PROGRAM);
    ctx.set_miss_program(1, occ_miss)?;
    let rg = ctx.create_program(&pinhole::PROGRAM);
    ctx.set_ray_generation_program(0, rg)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(0, miss)?;
    let g = ctx.create_triangles(mesh.clone())?;
    let mat = ctx.create_material();
    let ch = match workload {
        Workload::Primary => ctx.create_program(&normal_shader::PROGRAM),
        Workload::Ao => ctx.create_program(&ambient_occlusion::PROGRAM),
    };
    ctx.set_closest_hit_program(mat, 0, ch)?;
    let occ = ctx.create_program(&occluded::PROGRAM);
    ctx.set_closest_hit_program(mat, 1, occ)?;
    let gi = ctx.create_geometry_instance(g, &[mat])?;
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh))?;
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, width, height)?;
    let (eye, u, v, w) = cam;
    for (name, value) in [("eye", eye), ("u", u), ("v", v), ("w", w), ("bg_color", Vec3::new(0.2, 0.2, 0.25))] {
        ctx.set_var(Scope::Context, name, value)?;
    }
    ctx.set_var(Scope::Context, "top_object", gg)?;
    ctx.set_var(Scope::Context, "output_buffer", out)?;
    Ok((ctx, out, gg, g))
}
