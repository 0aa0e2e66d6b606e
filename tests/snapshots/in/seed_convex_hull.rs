//! Example 7: a convex hull of planes as custom geometry, rendered as glass.
use super::seed_common::*;
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
    let reflect_dir = reflect(ray.direction, ffn);
    let refract_dir = refract(ray.direction, ffn, eta);
    let f0 = ((1.0 - refraction_index) / (1.0 + refraction_index)).powi(2);
    let mut fresnel = fresnel_schlick(cos_i, f0);
    if refract_dir.length_squared() == 0.0 {
        fresnel = 1.0;
    }
    let mut result = Vec3::ZERO;
    if prd.depth < max_depth {
        let mut refl = Radiance { result: Vec3::ZERO, importance: prd.importance * fresnel, depth: prd.depth + 1 };
        rt_trace(top_object, Ray::new(hit_point, reflect_dir, RADIANCE_RAY, scene_epsilon, f32::INFINITY), &mut refl);
        result += fresnel * refl.result;
        if fresnel < 1.0 {
            let mut refr =
                Radiance { result: Vec3::ZERO, importance: prd.importance * (1.0 - fresnel), depth: prd.depth + 1 };
            rt_trace(
                top_object,
                Ray::new(hit_point, refract_dir, RADIANCE_RAY, scene_epsilon, f32::INFINITY),
                &mut refr,
            );
            result += (1.0 - fresnel) * glass_color * refr.result;
        }
    }
    prd.result = result;
}
