//! OptiX's semantic values of a hit and a ray: `is_triangle_hit`,
//! `is_triangle_hit_front_face` / `_back_face` (closest hit and any hit),
//! `ray_flags` and `ray_mask` (closest hit, any hit, miss, intersection),
//! on every target, with exact values: the front of a triangle, its back
//! (through a culling flag), a custom sphere, a miss, a mirrored instance
//! (the side is the object space's), and a closest hit that traces again
//! and reads its own values back afterwards.

use glam::{Mat4, Vec3};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Seen {
    pub kind: u32,
    pub flags: u32,
    pub mask: u32,
    pub any_hit: u32,
    pub after: u32,
    pub depth: u32,
}

#[rt_attributes]
pub struct SphereHit {
    pub isect_flags: u32,
    pub isect_mask: u32,
}

/// 1 for a triangle, + 2 on its front, + 4 on its back.
#[rt_function]
pub fn hit_kind() -> u32 {
    let mut k = 0u32;
    if is_triangle_hit() {
        k += 1;
    }
    if is_triangle_hit_front_face() {
        k += 2;
    }
    if is_triangle_hit_back_face() {
        k += 4;
    }
    k
}

/// Six rays, one per launch index (see the test).
#[rt_program(ray_generation)]
pub fn probe(#[var] top: Object, #[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    // Off the quad's diagonal, where its two triangles meet.
    let mut origin = vec3(0.3, -0.2, 5.0);
    let mut dir = vec3(0.0, 0.0, -1.0);
    let mut flags = RAY_FLAG_NONE;
    let mut mask = RAY_MASK_ALL;
    if i == 1 {
        origin = vec3(0.3, -0.2, -5.0);
        dir = vec3(0.0, 0.0, 1.0);
        flags = RAY_FLAG_CULL_FRONT_FACING;
        mask = 0x0f;
    } else if i == 2 {
        origin = vec3(3.0, 0.0, 5.0);
        flags = RAY_FLAG_TERMINATE_ON_FIRST_HIT;
        mask = 0x03;
    } else if i == 3 {
        origin = vec3(0.3, 10.0, 5.0);
        flags = RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_TERMINATE_ON_FIRST_HIT;
        mask = 0x181;
    } else if i == 4 {
        origin = vec3(-3.3, -0.2, 5.0);
    }
    let mut prd = Seen { kind: 0, flags: 0, mask: 0, any_hit: 0, after: 0, depth: 0 };
    rt_trace_with(top, Ray::new(origin, dir, 0, 0.0, 100.0), &mut prd, flags, mask);
    let at = i * 5;
    out[at] = prd.kind;
    out[at + 1] = prd.flags;
    out[at + 2] = prd.mask;
    out[at + 3] = prd.any_hit;
    out[at + 4] = prd.after;
}

#[rt_program(closest_hit)]
pub fn seen_triangle(prd: &mut Seen, #[var] top: Object) {
    prd.kind = hit_kind();
    prd.flags = ray_flags();
    prd.mask = ray_mask();
    if prd.depth == 0 && launch_index().x == 5 {
        // A ray that misses, with other flags and mask: its miss program
        // sees those; this program sees its own again afterwards.
        let mut inner = Seen { kind: 0, flags: 0, mask: 0, any_hit: 0, after: 0, depth: 1 };
        let ray = Ray::new(vec3(0.0, 0.0, 5.0), vec3(0.0, 1.0, 0.0), 0, 0.0, 100.0);
        rt_trace_with(top, ray, &mut inner, RAY_FLAG_DISABLE_ANYHIT, 0x42);
        prd.after = inner.kind * 1000000 + inner.flags * 1000 + inner.mask + hit_kind() * 100000000;
        prd.flags = prd.flags + ray_flags() * 100;
        prd.mask = prd.mask + ray_mask() * 1000;
    }
}

#[rt_program(any_hit)]
pub fn record_any_hit(prd: &mut Seen) {
    prd.any_hit = hit_kind() + 10 * ray_flags() + 1000 * ray_mask();
}

#[rt_program(closest_hit)]
pub fn seen_sphere(prd: &mut Seen, attr: &SphereHit) {
    prd.kind = hit_kind();
    prd.flags = ray_flags();
    prd.mask = ray_mask();
    prd.after = attr.isect_flags * 1000 + attr.isect_mask;
}

#[rt_program(miss)]
pub fn seen_miss(prd: &mut Seen) {
    prd.kind = 99;
    prd.flags = ray_flags();
    prd.mask = ray_mask();
}

#[rt_program(intersection)]
pub fn sphere(prim: u32, attr: &mut SphereHit, #[var] sphere: Vec4) {
    let _ = prim;
    let ray = current_ray();
    let o = ray.origin - sphere.xyz();
    let b = o.dot(ray.direction);
    let c = o.dot(o) - sphere.w * sphere.w;
    let disc = b * b - ray.direction.dot(ray.direction) * c;
    if disc > 0.0 {
        let t = (-b - disc.sqrt()) / ray.direction.dot(ray.direction);
        if rt_potential_intersection(t) {
            attr.isect_flags = ray_flags();
            attr.isect_mask = ray_mask();
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32, #[var] sphere: Vec4) -> Aabb {
    let _ = prim;
    Aabb::new(sphere.xyz() - Vec3::splat(sphere.w), sphere.xyz() + Vec3::splat(sphere.w))
}

/// What each launch index saw: `[kind, flags, mask, any_hit, after]`.
fn run(on: On) -> Vec<[u32; 5]> {
    let mut ctx = on.context();
    ctx.set_ray_type_count(1);
    // A quad at z = 0, counter-clockwise seen from +z (its front).
    let quad = rt_tests::meshes::unit_quad();
    let g = ctx.create_triangles(quad).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&seen_triangle::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let ah = ctx.create_program(&record_any_hit::PROGRAM);
    ctx.set_any_hit_program(m, 0, ah).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let quad_group = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    // The same quad mirrored in x, at x = -3.
    let mirror = Mat4::from_translation(Vec3::new(-3.0, 0.0, 0.0)) * Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    let mirrored = ctx.create_transform(mirror, quad_group).unwrap();
    // A custom sphere at x = 3.
    let isect = ctx.create_program(&sphere::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let sg = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    ctx.set_var(sg, "sphere", Vec4::new(3.0, 0.0, 0.0, 0.8)).unwrap();
    let sm = ctx.create_material();
    let sch = ctx.create_program(&seen_sphere::PROGRAM);
    ctx.set_closest_hit_program(sm, 0, sch).unwrap();
    let sgi = ctx.create_geometry_instance(sg, &[sm]).unwrap();
    let sphere_group = ctx.create_geometry_group(&[sgi], Acceleration::default()).unwrap();
    let top = ctx.create_group(&[quad_group, mirrored, sphere_group], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 30]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&probe::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&seen_miss::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let report = ctx.launch_1d(0, 6).unwrap();
    assert!(report.exceptions.is_empty(), "{}: {:?}", on.name(), report.exceptions);
    let words = ctx.read_buffer::<u32>(out).unwrap();
    words.chunks(5).map(|c| c.try_into().unwrap()).collect()
}

#[test]
fn hit_and_ray_semantic_values_are_exact_on_every_target() {
    let (cull_front, first_hit) = (RAY_FLAG_CULL_FRONT_FACING, RAY_FLAG_TERMINATE_ON_FIRST_HIT);
    let front = 1 + 2;
    let back = 1 + 4;
    let expected: Vec<[u32; 5]> = vec![
        // The quad's front, plain rt_trace: no flags, mask 0xff; any hit saw the same.
        [front, 0, 0xff, front + 1000 * 0xff, 0],
        // Its back, from below, culling front faces.
        [back, cull_front, 0x0f, back + 10 * cull_front + 1000 * 0x0f, 0],
        // The custom sphere: not a triangle; its intersection program saw the flags and mask.
        [0, first_hit, 0x03, 0, first_hit * 1000 + 0x03],
        // A miss: the mask's low 8 bits.
        [99, cull_front | first_hit, 0x81, 0, 0],
        // The mirrored quad, met from +z: its front in object space.
        [front, 0, 0xff, front + 1000 * 0xff, 0],
        // A closest hit that traced a missing ray (flags DISABLE_ANYHIT,
        // mask 0x42) and read its own values again afterwards.
        [
            front,
            0,
            0xff + 0xff * 1000,
            front + 1000 * 0xff,
            99 * 1000000 + RAY_FLAG_DISABLE_ANYHIT * 1000 + 0x42 + front * 100000000,
        ],
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(run(on), expected, "{}", on.name());
    }
}
