//! The scene of the seed's examples 1 to 7: a large floor, an exact sphere
//! (custom geometry: OptiX's `sphere.cu`) and a turned box (triangles),
//! under a key and a fill light, seen by the pinhole camera. Each example
//! gives the three objects its own materials.

use crate::common::*;
use crate::scene::{Camera, Error, Scene, Settings, oriented_box, quad};
use glam::Vec3;
use rt_runtime::{Acceleration, BufferId, BufferType, Builder, Context, GeometryInstanceId, MaterialId, NodeId, Scope};
use rt_std::prelude::*;

/// An exact sphere `sphere.xyz`, radius `sphere.w`: reports the nearer root
/// the search accepts, else the farther (rays from inside).
#[rt_program(intersection)]
pub fn sphere_intersect(prim: u32, attr: &mut Normals, #[var] sphere: Vec4) {
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

/// The sphere's box.
#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32, #[var] sphere: Vec4) -> Aabb {
    let _ = prim;
    Aabb::new(sphere.xyz() - Vec3::splat(sphere.w), sphere.xyz() + Vec3::splat(sphere.w))
}

/// The sphere: centre and radius.
pub const SPHERE: Vec4 = Vec4::new(1.45, 1.0, 0.2, 1.0);
/// The box: corners before turning, and the turn about its vertical axis.
pub const BOX_MIN: Vec3 = Vec3::new(-2.9, 0.0, -1.1);
pub const BOX_MAX: Vec3 = Vec3::new(-0.9, 1.7, 0.9);
pub const BOX_YAW: f32 = 0.45;
/// Half the side of the square floor at y = 0.
pub const FLOOR_HALF: f32 = 400.0;
/// The seed's background blue.
pub const BG_COLOR: Vec3 = Vec3::new(0.34, 0.55, 0.85);

/// The camera of examples 1 to 7.
pub fn camera() -> Camera {
    Camera { eye: Vec3::new(0.0, 2.5, 9.0), look_at: Vec3::new(0.0, 1.0, 0.0), up: Vec3::Y, vfov_degrees: 34.0 }
}

/// A warm key light up and to the left, a dim cool fill to the right.
pub fn lights() -> Vec<BasicLight> {
    vec![
        BasicLight { pos: Vec3::new(-6.0, 9.0, 7.0), color: Vec3::new(0.9, 0.86, 0.8), casts_shadow: 1 },
        BasicLight { pos: Vec3::new(8.0, 5.0, 6.0), color: Vec3::new(0.22, 0.25, 0.3), casts_shadow: 1 },
    ]
}

/// The three objects' materials.
#[derive(Clone, Copy, Debug)]
pub struct Materials {
    pub floor: MaterialId,
    pub sphere: MaterialId,
    pub block: MaterialId,
}

impl Materials {
    /// Three new materials with closest hit `closest_hit` for radiance rays.
    pub fn with_closest_hit(
        ctx: &mut Context,
        closest_hit: &'static rt_std::program::ProgramDescriptor,
    ) -> Result<Materials, Error> {
        let program = ctx.create_program(closest_hit);
        let mut one = || -> Result<MaterialId, Error> {
            let m = ctx.create_material();
            ctx.set_closest_hit_program(m, RADIANCE_RAY, program)?;
            Ok(m)
        };
        Ok(Materials { floor: one()?, sphere: one()?, block: one()? })
    }

    pub fn all(&self) -> [MaterialId; 3] {
        [self.floor, self.sphere, self.block]
    }

    /// Gives every material the any-hit program that blocks shadow rays.
    pub fn block_shadow_rays(&self, ctx: &mut Context) -> Result<(), Error> {
        let shadow = ctx.create_program(&any_hit_shadow::PROGRAM);
        for m in self.all() {
            ctx.set_any_hit_program(m, SHADOW_RAY, shadow)?;
        }
        Ok(())
    }
}

/// The built objects.
#[derive(Clone, Copy, Debug)]
pub struct Tutorial {
    /// The geometry group of the three objects.
    pub objects: NodeId,
    pub floor: GeometryInstanceId,
    pub sphere: GeometryInstanceId,
    pub block: GeometryInstanceId,
}

/// A context with the pinhole camera, the background miss for radiance rays
/// (`bg_color`), the pass-through miss for shadow rays, and the lights
/// buffer (`lights`).
pub fn start(settings: &Settings) -> Result<(Context, BufferId), Error> {
    let (mut ctx, output) = Scene::start(settings, 1e-3)?;
    let camera = ctx.create_program(&pinhole_camera::PROGRAM);
    ctx.set_ray_generation_program(0, camera)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(RADIANCE_RAY, miss)?;
    let shadow_miss = ctx.create_program(&shadow_miss::PROGRAM);
    ctx.set_miss_program(SHADOW_RAY, shadow_miss)?;
    ctx.set_var(Scope::Context, "bg_color", BG_COLOR)?;
    self::camera().set_vars(&mut ctx, settings.aspect())?;
    let lights = ctx.create_buffer(BufferType::Input, lights());
    ctx.set_var(Scope::Context, "lights", lights)?;
    Ok((ctx, output))
}

/// Builds the floor, sphere and box with `materials`, and makes their group
/// the context's `top_object` and `top_shadower`.
pub fn build(ctx: &mut Context, materials: Materials) -> Result<Tutorial, Error> {
    let floor_mesh = quad(
        Vec3::new(-FLOOR_HALF, 0.0, -FLOOR_HALF),
        Vec3::new(0.0, 0.0, 2.0 * FLOOR_HALF),
        Vec3::new(2.0 * FLOOR_HALF, 0.0, 0.0),
    );
    let floor_geometry = ctx.create_triangles(floor_mesh)?;
    let floor = ctx.create_geometry_instance(floor_geometry, &[materials.floor])?;

    let isect = ctx.create_program(&sphere_intersect::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let sphere_geometry = ctx.create_custom_geometry(1, isect, bounds)?;
    ctx.set_var(sphere_geometry, "sphere", SPHERE)?;
    let sphere = ctx.create_geometry_instance(sphere_geometry, &[materials.sphere])?;

    let box_geometry = ctx.create_triangles(oriented_box(BOX_MIN, BOX_MAX, BOX_YAW))?;
    let block = ctx.create_geometry_instance(box_geometry, &[materials.block])?;

    let objects = ctx.create_geometry_group(&[floor, sphere, block], Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", objects)?;
    ctx.set_var(Scope::Context, "top_shadower", objects)?;
    Ok(Tutorial { objects, floor, sphere, block })
}
