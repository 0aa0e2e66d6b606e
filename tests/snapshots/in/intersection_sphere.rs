//! Custom geometry: an intersection program for a buffer of spheres that
//! reports the nearer root the ray accepts (else the farther), and the
//! matching bounding-box program; one of each program kind.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(intersection)]
pub fn sphere_intersect(prim: u32, attr: &mut Normals, #[var] spheres: Buffer<Vec4>) {
    let s = spheres[prim];
    let center = s.xyz();
    let radius = s.w;
    let ray = current_ray();
    let o = ray.origin - center;
    let b = o.dot(ray.direction);
    let c = o.dot(o) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return;
    }
    let sdisc = disc.sqrt();
    let roots = [-b - sdisc, -b + sdisc];
    let mut i = 0;
    while i < 2 {
        let t = roots[i];
        if rt_potential_intersection(t) {
            let n = (o + t * ray.direction) / radius;
            attr.geometric_normal = n;
            attr.shading_normal = n;
            if rt_report_intersection(0) {
                break;
            }
        }
        i += 1;
    }
}

#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32, #[var] spheres: Buffer<Vec4>) -> Aabb {
    let s = spheres.load(prim);
    let r = Vec3::splat(s.w.abs());
    if s.w <= 0.0 {
        return Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };
    }
    Aabb::new(s.xyz() - r, s.xyz() + r)
}
