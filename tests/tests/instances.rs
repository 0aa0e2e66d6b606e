//! `instance_index()` and `instance_id()` (OptiX 7's
//! `optixGetInstanceIndex`, `optixGetInstanceId`) in closest-hit, any-hit
//! and intersection programs, exact on every target: one geometry group of
//! two geometry instances under several transforms (each path its own
//! instances), a chain of two transforms (the innermost id wins), a custom
//! sphere, a node traced below the top (numbered from itself), a closest
//! hit that traces again and reads its own values back; nested groups under
//! transforms (the compute kernel's graph walk); a selector (every child
//! counts, chosen or not).

use glam::{Mat4, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Seen {
    pub ch: UVec2,
    pub ah: UVec2,
    pub isect: UVec2,
    pub after: u32,
    pub depth: u32,
}

#[rt_attributes]
pub struct SphereHit {
    pub isect: UVec2,
}

const WORDS: u32 = 7;
const MISSED: u32 = 999;

/// One ray down -z per launch index, at `rays[i].xy`, into `top` (`rays[i].z
/// == 0`) or `sub`.
#[rt_program(ray_generation)]
pub fn probe(#[var] top: Object, #[var] sub: Object, #[var] rays: Buffer<Vec4>, #[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let r = rays[i];
    let mut prd = Seen { ch: UVec2::ZERO, ah: UVec2::ZERO, isect: UVec2::ZERO, after: 0, depth: 0 };
    let ray = Ray::new(vec3(r.x, r.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0);
    if r.z == 0.0 {
        rt_trace(top, ray, &mut prd);
    } else {
        rt_trace(sub, ray, &mut prd);
    }
    let at = i * 7;
    out[at] = prd.ch.x;
    out[at + 1] = prd.ch.y;
    out[at + 2] = prd.ah.x;
    out[at + 3] = prd.ah.y;
    out[at + 4] = prd.isect.x;
    out[at + 5] = prd.isect.y;
    out[at + 6] = prd.after;
}

/// Records the hit's instance; at `again` (a launch index), traces a
/// second ray at `(again_at, -0.2)` and then reads its own instance again.
#[rt_program(closest_hit)]
pub fn seen_quad(prd: &mut Seen, #[var] top: Object, #[var] again: u32, #[var] again_at: f32) {
    prd.ch = uvec2(instance_index(), instance_id());
    if prd.depth == 0 && launch_index().x == again {
        let mut inner = Seen { ch: UVec2::ZERO, ah: UVec2::ZERO, isect: UVec2::ZERO, after: 0, depth: 1 };
        let ray = Ray::new(vec3(again_at, 2.8, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0);
        rt_trace(top, ray, &mut inner);
        prd.after = inner.ch.x * 1000 + instance_index() + 1;
    }
}

#[rt_program(any_hit)]
pub fn seen_any(prd: &mut Seen) {
    prd.ah = uvec2(instance_index(), instance_id());
}

#[rt_program(closest_hit)]
pub fn seen_sphere(prd: &mut Seen, attr: &SphereHit) {
    prd.ch = uvec2(instance_index(), instance_id());
    prd.isect = attr.isect;
}

#[rt_program(miss)]
pub fn seen_miss(prd: &mut Seen) {
    prd.ch = uvec2(999, 999);
}

#[rt_program(intersection)]
pub fn sphere(prim: u32, attr: &mut SphereHit) {
    let _ = prim;
    let ray = current_ray();
    let b = ray.origin.dot(ray.direction);
    let c = ray.origin.dot(ray.origin) - 0.64;
    let a = ray.direction.dot(ray.direction);
    let disc = b * b - a * c;
    if disc > 0.0 {
        let t = (-b - disc.sqrt()) / a;
        if rt_potential_intersection(t) {
            attr.isect = uvec2(instance_index(), instance_id());
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::splat(-0.8), Vec3::splat(0.8))
}

/// A selector's child by the side of x = 0 the ray starts on.
#[rt_program(visit)]
pub fn side(prd: &Seen) -> u32 {
    let _ = prd.depth;
    if current_ray().origin.x < 0.0 { 0 } else { 1 }
}

/// The geometry group every scene instances: quad `a` ([-1, 1]^2 at z = 0)
/// and quad `b` (the same 3 higher), with closest- and any-hit programs;
/// `b` has instance id 100.
struct Quads {
    group: NodeId,
}

fn quads(ctx: &mut Context) -> Quads {
    let m = ctx.create_material();
    let ch = ctx.create_program(&seen_quad::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let ah = ctx.create_program(&seen_any::PROGRAM);
    ctx.set_any_hit_program(m, 0, ah).unwrap();
    let qa = ctx.create_triangles(rt_tests::meshes::unit_quad()).unwrap();
    let mut higher = rt_tests::meshes::unit_quad();
    higher.positions.iter_mut().for_each(|p| p.y += 3.0);
    let qb = ctx.create_triangles(higher).unwrap();
    let a = ctx.create_geometry_instance(qa, &[m]).unwrap();
    let b = ctx.create_geometry_instance(qb, &[m]).unwrap();
    ctx.set_instance_id(b, 100).unwrap();
    let group = ctx.create_geometry_group(&[a, b], Acceleration::default()).unwrap();
    Quads { group }
}

fn at(x: f32, y: f32) -> Mat4 {
    Mat4::from_translation(Vec3::new(x, y, 0.0))
}

/// Runs `rays` (x, y, root: 0 top, 1 sub) on `ctx` (on target `on`) into
/// the scene `build` makes
/// (returning top and sub), with the closest hit at launch index `again`
/// tracing again at x `again_at` (`flat`: a scene ray queries walk): what
/// each ray saw, `[ch index, ch id, ah
/// index, ah id, intersection index, intersection id, after]`.
fn run(
    ctx: &mut Context,
    on: On,
    build: impl Fn(&mut Context) -> (NodeId, NodeId),
    rays: &[[f32; 3]],
    again: (u32, f32),
    flat: bool,
) -> Vec<[u32; 7]> {
    let (top, sub) = build(ctx);
    // A closest hit traces once: two levels, two clones of the traversal
    // in the compute kernel (the default five take minutes on lavapipe).
    ctx.set_max_trace_depth(2);
    ctx.set_var(Scope::Context, "top", top).unwrap();
    ctx.set_var(Scope::Context, "sub", sub).unwrap();
    ctx.set_var(Scope::Context, "again", again.0).unwrap();
    ctx.set_var(Scope::Context, "again_at", again.1).unwrap();
    let rays_buffer =
        ctx.create_buffer(BufferType::Input, rays.iter().map(|r| Vec4::new(r[0], r[1], r[2], 0.0)).collect());
    ctx.set_var(Scope::Context, "rays", rays_buffer).unwrap();
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; rays.len() * WORDS as usize]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&probe::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&seen_miss::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let report = ctx.launch_1d(0, rays.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{}: {:?}", on.name(), report.exceptions);
    if on == On::RAY_QUERY && flat {
        assert_eq!(ctx.traversal().map(|(t, _)| t), Some(Traversal::RayQuery), "the scene is walked by ray queries");
    }
    ctx.read_buffer::<u32>(out).unwrap().chunks(WORDS as usize).map(|c| c.try_into().unwrap()).collect()
}

const NONE: u32 = INSTANCE_ID_NONE;

/// What a quad hit sees: the same instance in closest and any hit.
fn quad(index: u32, id: u32) -> [u32; 7] {
    [index, id, index, id, 0, 0, 0]
}

/// One level of instances: T0, T1 (id 11) and T2 (id 22) over T2b (id 23)
/// over the quads, at x = 0, 4 and 8; a sphere under Ts (id 7) at x = -4.
fn two_levels(ctx: &mut Context) -> (NodeId, NodeId) {
    ctx.set_ray_type_count(1);
    let q = quads(ctx);
    let t0 = ctx.create_transform(at(0.0, 0.0), q.group).unwrap();
    let t1 = ctx.create_transform(at(4.0, 0.0), q.group).unwrap();
    ctx.set_instance_id(t1, 11).unwrap();
    let t2b = ctx.create_transform(at(4.0, 0.0), q.group).unwrap();
    ctx.set_instance_id(t2b, 23).unwrap();
    let t2 = ctx.create_transform(at(4.0, 0.0), t2b).unwrap();
    ctx.set_instance_id(t2, 22).unwrap();
    let isect = ctx.create_program(&sphere::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let sg = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    let sm = ctx.create_material();
    let sch = ctx.create_program(&seen_sphere::PROGRAM);
    ctx.set_closest_hit_program(sm, 0, sch).unwrap();
    let sgi = ctx.create_geometry_instance(sg, &[sm]).unwrap();
    let sgg = ctx.create_geometry_group(&[sgi], Acceleration::default()).unwrap();
    let ts = ctx.create_transform(at(-4.0, 0.0), sgg).unwrap();
    ctx.set_instance_id(ts, 7).unwrap();
    let top = ctx.create_group(&[t0, t1, t2, ts], Acceleration::default()).unwrap();
    (top, t1)
}

/// Rays into [`two_levels`] and what each sees.
fn two_levels_rays() -> (Vec<[f32; 3]>, Vec<[u32; 7]>) {
    let rays = vec![
        [0.3, -0.2, 0.0],
        [0.3, 2.8, 0.0],
        [4.3, -0.2, 0.0],
        [4.3, 2.8, 0.0],
        [8.3, -0.2, 0.0],
        [8.3, 2.8, 0.0],
        [-4.0, 0.1, 0.0],
        [100.0, 0.0, 0.0],
        // T1 traced itself: its instances count from 0.
        [4.3, -0.2, 1.0],
        [4.3, 2.8, 1.0],
    ];
    let expected = vec![
        quad(0, NONE),
        quad(1, 100),
        // Traces again at x = 0.3 (instance 1), then reads its own (2).
        [2, 11, 2, 11, 0, 0, 1000 + 2 + 1],
        quad(3, 100),
        quad(4, 23),
        quad(5, 100),
        // The sphere: its intersection program saw the same.
        [6, 7, 0, 0, 6, 7, 0],
        [MISSED, MISSED, 0, 0, 0, 0, 0],
        quad(0, 11),
        quad(1, 100),
    ];
    (rays, expected)
}

/// Groups in groups: TA (id 50) and TB (10 higher) over a group of T0 (id
/// 60, at x = 4) over the quads and the quads themselves.
fn nested(ctx: &mut Context) -> (NodeId, NodeId) {
    ctx.set_ray_type_count(1);
    let q = quads(ctx);
    let t0 = ctx.create_transform(at(4.0, 0.0), q.group).unwrap();
    ctx.set_instance_id(t0, 60).unwrap();
    let inner = ctx.create_group(&[t0, q.group], Acceleration::default()).unwrap();
    let ta = ctx.create_transform(at(0.0, 0.0), inner).unwrap();
    ctx.set_instance_id(ta, 50).unwrap();
    let tb = ctx.create_transform(at(0.0, 10.0), inner).unwrap();
    let top = ctx.create_group(&[ta, tb], Acceleration::default()).unwrap();
    (top, inner)
}

/// Rays into [`nested`] and what each sees.
fn nested_rays() -> (Vec<[f32; 3]>, Vec<[u32; 7]>) {
    let rays = vec![
        [4.3, -0.2, 0.0],
        [4.3, 2.8, 0.0],
        [0.3, -0.2, 0.0],
        [0.3, 2.8, 0.0],
        [4.3, 9.8, 0.0],
        [4.3, 12.8, 0.0],
        [0.3, 9.8, 0.0],
        [0.3, 12.8, 0.0],
        // The inner group traced alone: its own numbers, no id from TA.
        [0.3, -0.2, 1.0],
    ];
    let expected = vec![
        quad(0, 60),
        quad(1, 100),
        quad(2, 50),
        quad(3, 100),
        quad(4, 60),
        quad(5, 100),
        // Traces again at x = 4.3: instance 1 (y = 2.8 is under TA).
        [6, NONE, 6, NONE, 0, 0, 1000 + 6 + 1],
        quad(7, 100),
        quad(2, NONE),
    ];
    (rays, expected)
}

/// Instances under transforms ([`two_levels`]), then nested groups
/// ([`nested`]) built and launched after it in the same context, the
/// second's programs created again (each program two cases of the kernel's
/// switches): each launch sees what its graph alone gives. (The compute
/// kernel once inlined a tracing closest hit once per case at every depth,
/// 31 traversals, and lavapipe ran out of memory compiling them; one test
/// for both scenes, as each wgpu launch compiles a kernel.)
#[test]
fn instances_under_transforms_then_nested_groups_are_numbered_in_one_context_on_every_target() {
    let (rays_a, expected_a) = two_levels_rays();
    let (rays_b, expected_b) = nested_rays();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        assert_eq!(run(&mut ctx, on, two_levels, &rays_a, (2, 0.3), true), expected_a, "{}", on.name());
        assert_eq!(run(&mut ctx, on, nested, &rays_b, (6, 4.3), true), expected_b, "{}", on.name());
    }
}

/// A group of TF (at y = -10) over the quads and a selector choosing
/// between TL (x = -4) and TR (x = 4, id 9) over them.
fn selected(ctx: &mut Context) -> (NodeId, NodeId) {
    ctx.set_ray_type_count(1);
    let q = quads(ctx);
    let tf = ctx.create_transform(at(0.0, -10.0), q.group).unwrap();
    let tl = ctx.create_transform(at(-4.0, 0.0), q.group).unwrap();
    let tr = ctx.create_transform(at(4.0, 0.0), q.group).unwrap();
    ctx.set_instance_id(tr, 9).unwrap();
    let visit = ctx.create_program(&side::PROGRAM);
    let sel = ctx.create_selector(visit, &[tl, tr]).unwrap();
    let top = ctx.create_group(&[tf, sel], Acceleration::default()).unwrap();
    (top, sel)
}

#[test]
fn a_selectors_children_are_all_numbered_on_every_target() {
    let rays = [[0.3, -10.2, 0.0], [-3.7, -0.2, 0.0], [-3.7, 2.8, 0.0], [4.3, -0.2, 0.0], [4.3, 2.8, 0.0]];
    let expected = vec![quad(0, NONE), quad(2, NONE), quad(3, 100), quad(4, 9), quad(5, 100)];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(run(&mut on.context(), on, selected, &rays, (99, 0.0), false), expected, "{}", on.name());
    }
}

#[test]
fn instance_ids_are_set_on_geometry_instances_and_transforms_only() {
    let mut ctx = Context::new();
    let q = quads(&mut ctx);
    let t = ctx.create_transform(Mat4::IDENTITY, q.group).unwrap();
    assert_eq!(ctx.instance_id(t).unwrap(), INSTANCE_ID_NONE);
    ctx.set_instance_id(t, 5).unwrap();
    assert_eq!(ctx.instance_id(t).unwrap(), 5);
    let e = ctx.set_instance_id(q.group, 1).unwrap_err().to_string();
    assert!(e.contains("not a transform"), "{e}");
    let m = ctx.create_material();
    let e = ctx.set_instance_id(m, 1).unwrap_err().to_string();
    assert!(e.contains("instance ids are set on geometry instances and transforms"), "{e}");
}
