//! Example 7: procedural geometry. A convex hull given as a buffer of
//! planes (`Vec4`: outward normal, d) is intersected by clipping the ray
//! against every plane, keeping the entry `t0` and exit `t1` with their
//! normals; a bounding-box program returns its box. It is rendered as glass:
//! Fresnel-weighted (Schlick) reflection and refraction, tinted on the way
//! through, and its shadow is the light that the glass lets through (its
//! any-hit program for shadow rays attenuates and lets the search go on).

use crate::common::*;
use crate::envmap;
use crate::reflections::{self, reflective};
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use glam::{Vec3, Vec4};
use rt_runtime::{Acceleration, BufferType, Builder, Context, NodeId, Scope};
use rt_std::prelude::*;

#[rt_program(intersection)]
pub fn chull_intersect(prim: u32, attr: &mut Normals, #[var] planes: Buffer<Vec4>) {
    let _ = prim;
    let ray = current_ray();
    let mut t0 = -f32::MAX;
    let mut t1 = f32::MAX;
    let mut t0_normal = Vec3::ZERO;
    let mut t1_normal = Vec3::ZERO;
    let n = planes.len();
    let mut i = 0u32;
    while i < n && t0 < t1 {
        let plane = planes[i];
        let normal = plane.xyz();
        let d = plane.w;
        let denom = normal.dot(ray.direction);
        let t = -(d + normal.dot(ray.origin)) / denom;
        if denom < 0.0 {
            if t > t0 {
                t0 = t;
                t0_normal = normal;
            }
        } else if t < t1 {
            t1 = t;
            t1_normal = normal;
        }
        i += 1;
    }
    if t0 > t1 {
        return;
    }
    if rt_potential_intersection(t0) {
        attr.shading_normal = t0_normal;
        attr.geometric_normal = t0_normal;
        rt_report_intersection(0);
    } else if rt_potential_intersection(t1) {
        attr.shading_normal = t1_normal;
        attr.geometric_normal = t1_normal;
        rt_report_intersection(0);
    }
}

#[rt_program(bounding_box)]
pub fn chull_bounds(prim: u32, #[var] chull_bbmin: Vec3, #[var] chull_bbmax: Vec3) -> Aabb {
    let _ = prim;
    Aabb::new(chull_bbmin, chull_bbmax)
}

/// Schlick's approximation of the Fresnel reflectance.
#[rt_function]
pub fn fresnel_schlick(cos_theta: f32, f0: f32) -> f32 {
    f0 + (1.0 - f0) * (1.0 - cos_theta).clamp(0.0, 1.0).powf(5.0)
}

#[rt_program(closest_hit)]
pub fn glass(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] refraction_index: f32,
    #[var] glass_color: Vec3,
    #[var] max_depth: i32,
    #[var] importance_cutoff: f32,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
) {
    let ray = current_ray();
    let hit_point = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize();
    let entering = ray.direction.dot(n) < 0.0;
    let ffn = if entering { n } else { -n };
    let eta = if entering { 1.0 / refraction_index } else { refraction_index };
    let cos_i = -ray.direction.dot(ffn);
    let refract_dir = refract(ray.direction, ffn, eta);
    let f0 = ((1.0 - refraction_index) / (1.0 + refraction_index)).powi(2);
    // Schlick's cosine is the one on the optically thinner side.
    let mut cos_thin = cos_i;
    if !entering {
        cos_thin = -refract_dir.dot(ffn);
    }
    let mut fresnel = fresnel_schlick(cos_thin, f0);
    if refract_dir.length_squared() == 0.0 {
        fresnel = 1.0;
    }
    let mut result = Vec3::ZERO;
    if prd.depth < max_depth {
        let reflect_importance = prd.importance * fresnel;
        if reflect_importance > importance_cutoff {
            let mut refl = Radiance { result: Vec3::ZERO, importance: reflect_importance, depth: prd.depth + 1 };
            let r = reflect(ray.direction, ffn);
            rt_trace(top_object, Ray::new(hit_point, r, RADIANCE_RAY, scene_epsilon, f32::INFINITY), &mut refl);
            result += fresnel * refl.result;
        }
        let refract_importance = prd.importance * (1.0 - fresnel);
        if refract_importance > importance_cutoff {
            let mut refr = Radiance { result: Vec3::ZERO, importance: refract_importance, depth: prd.depth + 1 };
            let t = Ray::new(hit_point, refract_dir, RADIANCE_RAY, scene_epsilon, f32::INFINITY);
            rt_trace(top_object, t, &mut refr);
            result += (1.0 - fresnel) * glass_color * refr.result;
        }
    }
    prd.result = result;
}

/// Glass casts a tinted, lighter shadow: shadow rays lose part of their
/// light and go on.
#[rt_program(any_hit)]
pub fn glass_shadow(prd: &mut Shadow, #[var] shadow_attenuation: Vec3) {
    prd.attenuation *= shadow_attenuation;
    rt_ignore_intersection();
}

/// A gem: a hexagonal prism of circumradius `radius` from y = `y0` to `y1`
/// about the vertical line through `center`, its top edges cut by six
/// bevels that drop `bevel_height` from 60% of the way out on the top face
/// to the sides. Returns the planes and the box.
pub fn gem_planes(center: Vec3, radius: f32, y0: f32, y1: f32, bevel_height: f32) -> (Vec<Vec4>, Vec3, Vec3) {
    let apothem = radius * (std::f32::consts::PI / 6.0).cos();
    let plane = |n: Vec3, p: Vec3| n.normalize().extend(-n.normalize().dot(p));
    let mut planes = vec![plane(Vec3::NEG_Y, Vec3::new(0.0, y0, 0.0)), plane(Vec3::Y, Vec3::new(0.0, y1, 0.0))];
    let top = Vec3::new(center.x, y1, center.z);
    for k in 0..6 {
        let a = k as f32 * std::f32::consts::PI / 3.0 + 0.25;
        let out = Vec3::new(a.cos(), 0.0, a.sin());
        planes.push(plane(out, center + out * apothem));
        // Through `top + out * 0.6 apothem`, sloping down to the side face
        // `bevel_height` lower.
        let run = apothem * 0.4;
        planes.push(plane(out * bevel_height + Vec3::Y * run, top + out * apothem * 0.6));
    }
    let min = Vec3::new(center.x - radius, y0, center.z - radius);
    let max = Vec3::new(center.x + radius, y1, center.z + radius);
    (planes, min, max)
}

/// The gem stands this far above the floor: a bottom face in the floor's
/// plane would leave rays inside the glass to pick either surface at random.
pub const GEM_LIFT: f32 = 0.01;
/// The gem's place in the scene.
pub const GEM_CENTER: Vec3 = Vec3::new(-0.35, 0.0, 2.9);

/// Adds the glass gem to the scene's top group (beside `objects`), and
/// returns the new top group.
pub fn add_gem(ctx: &mut Context, objects: NodeId) -> Result<NodeId, Error> {
    let (planes, min, max) = gem_planes(GEM_CENTER, 0.8, GEM_LIFT, 2.1, 0.55);
    let isect = ctx.create_program(&chull_intersect::PROGRAM);
    let bounds = ctx.create_program(&chull_bounds::PROGRAM);
    let geometry = ctx.create_custom_geometry(1, isect, bounds)?;
    let planes = ctx.create_buffer(BufferType::Input, planes);
    ctx.set_var(geometry, "planes", planes)?;
    ctx.set_var(geometry, "chull_bbmin", min)?;
    ctx.set_var(geometry, "chull_bbmax", max)?;
    let material = ctx.create_material();
    let glass = ctx.create_program(&glass::PROGRAM);
    ctx.set_closest_hit_program(material, RADIANCE_RAY, glass)?;
    let shadow = ctx.create_program(&glass_shadow::PROGRAM);
    ctx.set_any_hit_program(material, SHADOW_RAY, shadow)?;
    ctx.set_var(material, "refraction_index", 1.5f32)?;
    ctx.set_var(material, "glass_color", Vec3::new(0.88, 0.97, 0.93))?;
    ctx.set_var(material, "shadow_attenuation", Vec3::new(0.55, 0.68, 0.62))?;
    let instance = ctx.create_geometry_instance(geometry, &[material])?;
    let gem = ctx.create_geometry_group(&[instance], Acceleration::new(Builder::NoAccel))?;
    let top = ctx.create_group(&[objects, gem], Acceleration::new(Builder::Bvh))?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.set_var(Scope::Context, "top_shadower", top)?;
    Ok(top)
}

/// Glass needs more bounces than mirrors: light crosses it twice and may
/// reflect inside.
pub const GLASS_MAX_DEPTH: i32 = 8;

/// The environment-mapped scene with a glass gem in front.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    envmap::use_envmap(&mut ctx)?;
    let materials = Materials::with_closest_hit(&mut ctx, &reflective::PROGRAM)?;
    materials.block_shadow_rays(&mut ctx)?;
    reflections::set_colors(&mut ctx, &materials)?;
    ctx.set_var(Scope::Context, "ambient_light_color", Vec3::new(0.22, 0.25, 0.32))?;
    ctx.set_var(Scope::Context, "max_depth", GLASS_MAX_DEPTH)?;
    ctx.set_max_trace_depth(GLASS_MAX_DEPTH as u32 + 2);
    let built = tutorial::build(&mut ctx, materials)?;
    add_gem(&mut ctx, built.objects)?;
    Ok(Scene::new(ctx, output, settings))
}
