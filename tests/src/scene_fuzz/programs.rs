//! The one set of programs every generated graph runs: the wgpu megakernel
//! depends on the program set and the graph's shape only, so graphs of one
//! shape class share a pipeline.

use rt_std::prelude::*;

/// What a ray found: `hit` 0 (closest hit disabled), 1 (hit) or 2 (miss);
/// the hit's id (`instance_id * 64 + primitive_index`), distance and the
/// hit instance's object-to-world origin; `lane`, the launch index as one
/// number (for the any-hit and visit rules).
#[rt_payload]
pub struct Probe {
    pub hit: u32,
    pub id: u32,
    pub t: f32,
    pub lane: u32,
    pub origin: Vec3,
}

#[rt_attributes]
pub struct FuzzHit {
    pub geometric_normal: Vec3,
}

/// A pinhole camera at `eye` (`forward`, `right`, `up` span the image);
/// writes `(hit, id, t, 0)` and the hit instance's origin per launch index.
#[rt_program(ray_generation)]
pub fn fuzz_camera(
    #[var] top: Object,
    #[var] mut out: RwBuffer2d<Vec4>,
    #[var] mut origins: RwBuffer2d<Vec4>,
    #[var] eye: Vec3,
    #[var] forward: Vec3,
    #[var] right: Vec3,
    #[var] up: Vec3,
    #[var] flags: u32,
    #[var] mask: u32,
) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let d = (forward + right * p.x + up * p.y).normalize();
    let mut prd = Probe { hit: 0, id: 0, t: -1.0, lane: idx.x + idx.y * launch_dim().x, origin: Vec3::ZERO };
    rt_trace_with(top, Ray::new(eye, d, 0, 0.0, f32::INFINITY), &mut prd, flags, mask);
    out[idx] = vec4(prd.hit as f32, prd.id as f32, prd.t, 0.0);
    origins[idx] = prd.origin.extend(1.0);
}

#[rt_program(miss)]
pub fn fuzz_miss(prd: &mut Probe) {
    prd.hit = 2;
}

#[rt_program(closest_hit)]
pub fn fuzz_hit(prd: &mut Probe, attr: &FuzzHit, #[var] instance_id: u32) {
    let _ = attr.geometric_normal;
    prd.hit = 1;
    prd.id = instance_id * 64 + primitive_index();
    prd.t = t_hit();
    prd.origin = rt_transform_point(ObjectToWorld, Vec3::ZERO);
}

/// Ignores the candidates whose `primitive_index * 7 + lane` is a multiple
/// of `ignore_every` (1: all of them): a rule of the candidate alone, so
/// the closest accepted hit is the same in any traversal order.
#[rt_program(any_hit)]
pub fn fuzz_ignore(prd: &mut Probe, #[var] ignore_every: u32) {
    if (primitive_index() * 7 + prd.lane) % ignore_every == 0 {
        rt_ignore_intersection();
    }
}

#[rt_program(any_hit)]
pub fn fuzz_terminate(prd: &mut Probe) {
    let _ = prd.lane;
    rt_terminate_ray();
}

/// Sphere `spheres[prim]` (centre, radius), solved about the point of
/// closest approach (stable far from the sphere, where `b^2 - ac` is not).
#[rt_program(intersection)]
pub fn fuzz_sphere(prim: u32, attr: &mut FuzzHit, #[var] spheres: Buffer<Vec4>) {
    let s = spheres[prim];
    let ray = current_ray();
    let a = ray.direction.dot(ray.direction);
    let l = s.xyz() - ray.origin;
    let b = l.dot(ray.direction) / a;
    let f = l - b * ray.direction;
    let disc = s.w * s.w - f.dot(f);
    if disc > 0.0 {
        let h = (disc / a).sqrt();
        let t0 = b - h;
        let t1 = b + h;
        if rt_potential_intersection(t0) {
            attr.geometric_normal = (ray.origin + t0 * ray.direction - s.xyz()) / s.w;
            rt_report_intersection(0);
        } else if rt_potential_intersection(t1) {
            attr.geometric_normal = (ray.origin + t1 * ray.direction - s.xyz()) / s.w;
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn fuzz_sphere_bounds(prim: u32, #[var] spheres: Buffer<Vec4>) -> Aabb {
    let s = spheres[prim];
    Aabb::new(s.xyz() - Vec3::splat(s.w), s.xyz() + Vec3::splat(s.w))
}

/// Rule 0: child `lane % (children + 1)` (the last choice enters nothing);
/// rule 1: child 0 or 1 by the sign of the ray direction's x in the
/// selector's space.
#[rt_program(visit)]
pub fn fuzz_visit(prd: &Probe, #[var] visit_rule: u32, #[var] visit_children: u32) -> u32 {
    if visit_rule == 0 {
        prd.lane % (visit_children + 1)
    } else if current_ray().direction.x < 0.0 {
        0
    } else {
        1
    }
}
