//! Motion blur (OptiX 6's `rtTrace(.., time)`, `rtCurrentTime`,
//! `rtTransformSetMotionKeys`) on every target: rays traced at a time
//! (`rt_trace_at`) against motion transforms with matrix keys (three, over
//! `[0, 2]`) and scale-rotate-translate keys (160 degrees over `[0, 1]`),
//! each under a group with a second child so that the group's BVH bounds
//! the motion; clamped outside the range; `current_time()` in intersection,
//! any-hit, closest-hit and miss programs, and a nested trace without a time
//! at 0. The ray-query target falls back to the compute traversal (motion
//! transforms have no single instance matrix), which the test checks.

use glam::{Mat4, Quat, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Probe {
    pub hit: u32,
    /// The object point `(2, 0, 0)` in world space at the hit.
    pub center: Vec3,
    /// The hit point in object space.
    pub local: Vec3,
    pub t: f32,
    /// `current_time()` in closest hit, any hit, intersection, miss.
    pub times: Vec4,
    /// The miss time of a trace from the closest hit without a time, and
    /// the closest hit's own time after it.
    pub inner: f32,
    pub after: f32,
    pub depth: u32,
}

#[rt_attributes]
pub struct SphereHit {
    pub time: f32,
}

const WORDS: usize = 12;

/// One ray down -z per launch index at `rays[i].xy` at time `rays[i].z`.
#[rt_program(ray_generation)]
pub fn probe(#[var] top: Object, #[var] rays: Buffer<Vec4>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let r = rays[i];
    let mut prd = Probe {
        hit: 0,
        center: Vec3::ZERO,
        local: Vec3::ZERO,
        t: 0.0,
        times: Vec4::splat(-1.0),
        inner: -1.0,
        after: -1.0,
        depth: 0,
    };
    let ray = Ray::new(vec3(r.x, r.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0);
    rt_trace_at(top, ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, r.z);
    let at = i * 12;
    out[at] = prd.hit as f32;
    out[at + 1] = prd.center.x;
    out[at + 2] = prd.center.y;
    out[at + 3] = prd.local.x;
    out[at + 4] = prd.local.y;
    out[at + 5] = prd.t;
    out[at + 6] = prd.times.x;
    out[at + 7] = prd.times.y;
    out[at + 8] = prd.times.z;
    out[at + 9] = prd.times.w;
    out[at + 10] = prd.inner;
    out[at + 11] = prd.after;
}

/// The hit, where it is; then a trace without a time that misses (its miss
/// sees time 0), and the closest hit's own time again after it.
#[rt_program(closest_hit)]
pub fn hit(prd: &mut Probe, #[var] top: Object) {
    prd.hit = 1;
    prd.t = t_hit();
    prd.times.x = current_time();
    prd.center = rt_transform_point(ObjectToWorld, vec3(2.0, 0.0, 0.0));
    let r = current_ray();
    prd.local = rt_transform_point(WorldToObject, r.origin + r.direction * t_hit());
    if prd.depth == 0 {
        let mut inner = Probe {
            hit: 0,
            center: Vec3::ZERO,
            local: Vec3::ZERO,
            t: 0.0,
            times: Vec4::splat(-1.0),
            inner: -1.0,
            after: -1.0,
            depth: 1,
        };
        let away = Ray::new(vec3(0.0, 0.0, 5.0), vec3(0.0, 0.0, 1.0), 0, 0.0, 100.0);
        rt_trace(top, away, &mut inner);
        prd.inner = inner.times.w;
        prd.after = current_time();
    }
}

#[rt_program(closest_hit)]
pub fn hit_sphere(prd: &mut Probe, attr: &SphereHit, #[var] top: Object) {
    let _ = top;
    prd.hit = 2;
    prd.t = t_hit();
    prd.times.x = current_time();
    prd.times.z = attr.time;
    prd.center = rt_transform_point(ObjectToWorld, vec3(2.0, 0.0, 0.0));
}

#[rt_program(any_hit)]
pub fn seen(prd: &mut Probe) {
    prd.times.y = current_time();
}

#[rt_program(miss)]
pub fn missed(prd: &mut Probe) {
    prd.times.w = current_time();
}

/// A sphere of radius 0.5 about the object origin.
#[rt_program(intersection)]
pub fn sphere(prim: u32, attr: &mut SphereHit) {
    let _ = prim;
    let ray = current_ray();
    let b = ray.origin.dot(ray.direction);
    let c = ray.origin.dot(ray.origin) - 0.25;
    let a = ray.direction.dot(ray.direction);
    let disc = b * b - a * c;
    if disc > 0.0 {
        let t = (-b - disc.sqrt()) / a;
        if rt_potential_intersection(t) {
            attr.time = current_time();
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn sphere_bounds(prim: u32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::splat(-0.5), Vec3::splat(0.5))
}

fn shift(x: f32) -> Mat4 {
    Mat4::from_translation(Vec3::new(x, 0.0, 0.0))
}

/// A geometry group of `mesh` with the probe's programs.
fn group_of(ctx: &mut Context, mesh: TriangleMesh) -> NodeId {
    let m = ctx.create_material();
    let ch = ctx.create_program(&hit::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let ah = ctx.create_program(&seen::PROGRAM);
    ctx.set_any_hit_program(m, 0, ah).unwrap();
    let g = ctx.create_triangles(mesh).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap()
}

/// `moving` beside a static quad far away, under one group (whose BVH
/// bounds the motion).
fn beside_a_far_quad(ctx: &mut Context, moving: NodeId) -> NodeId {
    let far = group_of(ctx, rt_tests::meshes::unit_quad());
    let far = ctx.create_transform(Mat4::from_translation(Vec3::new(0.0, 50.0, 0.0)), far).unwrap();
    ctx.create_group(&[moving, far], Acceleration::default()).unwrap()
}

/// The unit quad ([-1, 1]^2 at z = 0) under matrix keys moving it along x
/// through 0, 4 and 2 over times [0, 2].
fn sliding(ctx: &mut Context) -> NodeId {
    let quad = group_of(ctx, rt_tests::meshes::unit_quad());
    let keys = MotionKeys::Matrices(vec![shift(0.0), shift(4.0), shift(2.0)]);
    let moving = ctx.create_motion_transform(keys, 0.0, 2.0, quad).unwrap();
    beside_a_far_quad(ctx, moving)
}

/// A quad of side 1 about (2, 0, 0) under SRT keys turning it 160 degrees
/// about z over [0, 1] (not a half turn, whose shorter arc is either way).
fn spinning(ctx: &mut Context) -> NodeId {
    let mut mesh = rt_tests::meshes::unit_quad();
    mesh.positions.iter_mut().for_each(|p| *p = *p * 0.5 + Vec3::new(2.0, 0.0, 0.0));
    let quad = group_of(ctx, mesh);
    let key = |angle: f32| Srt { scale: Vec3::ONE, rotation: Quat::from_rotation_z(angle), translation: Vec3::ZERO };
    let keys = MotionKeys::Srt(vec![key(0.0), key(160f32.to_radians())]);
    let moving = ctx.create_motion_transform(keys, 0.0, 1.0, quad).unwrap();
    beside_a_far_quad(ctx, moving)
}

/// A sphere of radius 0.5 under matrix keys moving it from x = -2 to 2
/// (its point (2, 0, 0) from 0 to 4) over [0, 1].
fn rolling(ctx: &mut Context) -> NodeId {
    let isect = ctx.create_program(&sphere::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let g = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&hit_sphere::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let ah = ctx.create_program(&seen::PROGRAM);
    ctx.set_any_hit_program(m, 0, ah).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let keys = MotionKeys::Matrices(vec![shift(-2.0), shift(2.0)]);
    let moving = ctx.create_motion_transform(keys, 0.0, 1.0, gg).unwrap();
    beside_a_far_quad(ctx, moving)
}

/// Runs `rays` (x, y, time) into the scene `build` makes: each ray's words.
fn run(on: On, build: impl Fn(&mut Context) -> NodeId, rays: &[[f32; 3]]) -> Vec<[f32; WORDS]> {
    run_on(on, build, rays, true)
}

/// [`run`]; `motion`: whether the scene has motion transforms (which keep
/// the ray-query target on the compute traversal).
fn run_on(on: On, build: impl Fn(&mut Context) -> NodeId, rays: &[[f32; 3]], motion: bool) -> Vec<[f32; WORDS]> {
    let mut ctx = on.context();
    let top = build(&mut ctx);
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let rg = ctx.create_program(&probe::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&missed::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    launch(on, &mut ctx, rays, motion)
}

/// Launches `rays` in `ctx` (set up by [`run_on`]).
fn launch(on: On, ctx: &mut Context, rays: &[[f32; 3]], motion: bool) -> Vec<[f32; WORDS]> {
    let rays_buffer =
        ctx.create_buffer(BufferType::Input, rays.iter().map(|r| Vec4::new(r[0], r[1], r[2], 0.0)).collect());
    ctx.set_var(Scope::Context, "rays", rays_buffer).unwrap();
    let out = ctx.create_buffer::<f32>(BufferType::Output, vec![0.0; rays.len() * WORDS]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let report = ctx.launch_1d(0, rays.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{}: {:?}", on.name(), report.exceptions);
    if on == On::RAY_QUERY && !motion {
        assert_eq!(
            ctx.traversal().map(|(t, _)| t),
            Some(Traversal::RayQuery),
            "a static scene is walked by ray queries"
        );
    }
    if on == On::RAY_QUERY && motion {
        let (traversal, why) = ctx.traversal().unwrap();
        assert_eq!(traversal, Traversal::Compute, "a scene with motion keeps the compute traversal");
        assert!(why.contains("motion transform"), "{why}");
    }
    ctx.read_buffer::<f32>(out).unwrap().chunks(WORDS).map(|c| c.try_into().unwrap()).collect()
}

/// Asserts `got` is `want` within `tol`, naming the target, ray and word.
fn check(on: On, got: &[[f32; WORDS]], want: &[[f32; WORDS]], tol: f32) {
    for (r, (g, w)) in got.iter().zip(want).enumerate() {
        for (k, (a, b)) in g.iter().zip(w).enumerate() {
            assert!((a - b).abs() <= tol, "{}: ray {r} word {k}: {a} (want {b}); all: {g:?}", on.name());
        }
    }
}

/// A hit's words: the probe point's world (x, y), the hit's object (x, y),
/// distance 5, `time` seen by closest and any hit, the nested trace's miss
/// at 0 and the closest hit's time after it.
fn quad_hit(center: (f32, f32), local: (f32, f32), time: f32) -> [f32; WORDS] {
    [1.0, center.0, center.1, local.0, local.1, 5.0, time, time, -1.0, -1.0, 0.0, time]
}

/// A miss's words: the miss program saw `time`.
fn miss(time: f32) -> [f32; WORDS] {
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, -1.0, -1.0, time, -1.0, -1.0]
}

#[test]
fn matrix_keys_move_a_quad_to_the_lerp_of_the_keys_at_the_ray_time_on_every_target() {
    let rays = [
        [0.0, 0.0, 0.0],
        [2.5, 0.25, 0.5],
        [4.0, 0.0, 1.0],
        [3.25, -0.5, 1.5],
        [0.0, 0.0, 0.5],
        [0.5, 0.0, -1.0],
        [2.0, 0.0, 5.0],
        [4.0, 0.0, 0.25],
        [1.75, 0.0, 1.75],
    ];
    let want = [
        quad_hit((2.0, 0.0), (0.0, 0.0), 0.0),
        // At 0.5: halfway from 0 to 4.
        quad_hit((4.0, 0.0), (0.5, 0.25), 0.5),
        quad_hit((6.0, 0.0), (0.0, 0.0), 1.0),
        // At 1.5: halfway from 4 to 2.
        quad_hit((5.0, 0.0), (0.25, -0.5), 1.5),
        // The quad spans [1, 3] then.
        miss(0.5),
        // Before the range: the first key; after it: the last.
        quad_hit((2.0, 0.0), (0.5, 0.0), -1.0),
        quad_hit((4.0, 0.0), (0.0, 0.0), 5.0),
        miss(0.25),
        // At 1.75: three quarters from 4 to 2.
        quad_hit((4.5, 0.0), (-0.75, 0.0), 1.75),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        check(on, &run(on, sliding, &rays), &want, 0.0);
    }
}

#[test]
fn srt_keys_turn_a_quad_by_the_slerped_rotation_on_every_target() {
    // The probe point (2, 0, 0) turned by `deg` degrees about z.
    let turned = |deg: f32| {
        let (s, c) = deg.to_radians().sin_cos();
        (2.0 * c, 2.0 * s)
    };
    let (q, e) = (turned(90.0), turned(160.0));
    let eighth = turned(40.0);
    // A lerp of the two keys' matrices at 0.25 would put it here.
    let lerped = (0.75 * 2.0 + 0.25 * e.0, 0.25 * e.1);
    let rays = [
        [2.0, 0.0, 0.0],
        // A quarter turn at 90/160: the quad is about (0, 2), outside both
        // keys' boxes (the group's bounds must hold the arc between them).
        [q.0, q.1, 0.5625],
        [2.0, 0.0, 0.5625],
        [e.0, e.1, 1.0],
        [eighth.0, eighth.1, 0.25],
        [lerped.0, lerped.1, 0.25],
        [q.0, q.1, 3.0],
        [2.0, 0.0, -3.0],
    ];
    let want = [
        quad_hit((2.0, 0.0), (2.0, 0.0), 0.0),
        quad_hit(q, (2.0, 0.0), 0.5625),
        miss(0.5625),
        quad_hit(e, (2.0, 0.0), 1.0),
        quad_hit(eighth, (2.0, 0.0), 0.25),
        miss(0.25),
        miss(3.0),
        quad_hit((2.0, 0.0), (2.0, 0.0), -3.0),
    ];
    // WGSL's `acos` and `sin` are not correctly rounded (lavapipe's are off
    // by about 1e-5 here).
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        check(on, &run(on, spinning, &rays), &want, 5e-5);
    }
}

#[test]
fn current_time_reaches_intersection_any_hit_closest_hit_and_miss_on_every_target() {
    let rays = [[0.0, 0.0, 0.5], [0.0, 0.0, 0.3], [-2.0, 0.0, -4.0], [0.0, 0.25, 0.5]];
    // The sphere's centre is at 4t - 2: ray x = 0 hits it at 0.5, not at
    // 0.3 (0.8 away); before the range it stays at -2.
    let sphere = |center: f32, time: f32, t: f32| [2.0, center, 0.0, 0.0, 0.0, t, time, time, time, -1.0, -1.0, -1.0];
    let dist = 5.0 - (0.25f32 - 0.0625).sqrt();
    let want = [sphere(2.0, 0.5, 4.5), miss(0.3), sphere(0.0, -4.0, 4.5), sphere(2.0, 0.5, dist)];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        check(on, &run(on, rolling, &rays), &want, 1e-5);
    }
}

#[test]
fn bad_motion_keys_are_errors_naming_the_transform() {
    let mut ctx = Context::new();
    let quad = group_of(&mut ctx, rt_tests::meshes::unit_quad());
    let one = ctx.create_motion_transform(MotionKeys::Matrices(vec![shift(0.0)]), 0.0, 1.0, quad).unwrap_err();
    assert!(one.to_string().contains("transform 1") && one.to_string().contains("at least 2 keys"), "{one}");
    let two = || MotionKeys::Matrices(vec![shift(0.0), shift(1.0)]);
    let backwards = ctx.create_motion_transform(two(), 1.0, 0.5, quad).unwrap_err();
    assert!(backwards.to_string().contains("ends before it begins"), "{backwards}");
    let t = ctx.create_transform(Mat4::IDENTITY, quad).unwrap();
    let nan = ctx.set_motion_keys(t, MotionKeys::Matrices(vec![shift(0.0), shift(f32::NAN)]), 0.0, 1.0).unwrap_err();
    assert!(nan.to_string().contains(&format!("transform {}", t.index())) && nan.to_string().contains("not finite"));
    let mut projective = Mat4::IDENTITY;
    projective.x_axis.w = 1.0;
    let p = ctx.set_motion_keys(t, MotionKeys::Matrices(vec![shift(0.0), projective]), 0.0, 1.0).unwrap_err();
    assert!(p.to_string().contains("not affine"), "{p}");
    // A good one is kept until `set_transform` makes the node static.
    ctx.set_motion_keys(t, two(), 0.0, 1.0).unwrap();
    assert_eq!(ctx.motion_keys(t).map(|m| m.t1), Some(1.0));
    ctx.set_transform(t, Mat4::IDENTITY).unwrap();
    assert!(ctx.motion_keys(t).is_none());
}

/// The ray time on the ray-query traversal too (a scene without motion,
/// which ray queries walk): the hit and miss programs read it.
#[test]
fn current_time_is_the_traced_time_in_a_static_scene_on_every_target() {
    let still = |ctx: &mut Context| {
        let quad = group_of(ctx, rt_tests::meshes::unit_quad());
        let placed = ctx.create_transform(shift(1.0), quad).unwrap();
        beside_a_far_quad(ctx, placed)
    };
    // A time that is not finite traces at 0.
    let rays = [[1.25, 0.5, 0.75], [1.0, 0.0, -2.5], [5.0, 0.0, 3.0], [1.0, 0.0, f32::NAN], [5.0, 0.0, f32::INFINITY]];
    let want = [
        quad_hit((3.0, 0.0), (0.25, 0.5), 0.75),
        quad_hit((3.0, 0.0), (0.0, 0.0), -2.5),
        miss(3.0),
        quad_hit((3.0, 0.0), (0.0, 0.0), 0.0),
        miss(0.0),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        check(on, &run_on(on, still, &rays, false), &want, 0.0);
    }
}

/// A transform given motion keys after a launch, then made static again,
/// under a static transform (which the compute traversal does not fold
/// into the motion) and nesting a second motion transform: each launch
/// sees the scene as it is.
#[test]
fn motion_keys_set_between_launches_and_nested_under_transforms_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        let quad = group_of(&mut ctx, rt_tests::meshes::unit_quad());
        // Static for now: `inner` will move up by 0 -> 1, `m` along x by
        // 0 -> 4, both over [0, 1].
        let inner = ctx.create_transform(Mat4::IDENTITY, quad).unwrap();
        let m = ctx.create_transform(Mat4::IDENTITY, inner).unwrap();
        let lifted = ctx.create_transform(Mat4::from_translation(Vec3::new(0.0, 3.0, 0.0)), m).unwrap();
        let top = beside_a_far_quad(&mut ctx, lifted);
        ctx.set_var(Scope::Context, "top", top).unwrap();
        let rg = ctx.create_program(&probe::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let miss_program = ctx.create_program(&missed::PROGRAM);
        ctx.set_miss_program(0, miss_program).unwrap();
        let still = launch(on, &mut ctx, &[[0.5, 3.0, 0.5]], false);
        check(on, &still, &[quad_hit((2.0, 3.0), (0.5, 0.0), 0.5)], 0.0);
        ctx.set_motion_keys(m, MotionKeys::Matrices(vec![shift(0.0), shift(4.0)]), 0.0, 1.0).unwrap();
        let keys = vec![Mat4::IDENTITY, Mat4::from_translation(Vec3::new(0.0, 1.0, 0.0))];
        ctx.set_motion_keys(inner, MotionKeys::Matrices(keys), 0.0, 1.0).unwrap();
        // At 0.5: x by 2, y by 3 + 0.5.
        let moved = launch(on, &mut ctx, &[[2.5, 3.5, 0.5], [0.5, 3.0, 0.5], [4.0, 4.0, 1.0]], true);
        check(
            on,
            &moved,
            &[quad_hit((4.0, 3.5), (0.5, 0.0), 0.5), miss(0.5), quad_hit((6.0, 4.0), (0.0, 0.0), 1.0)],
            0.0,
        );
        ctx.set_transform(m, shift(1.0)).unwrap();
        ctx.set_transform(inner, Mat4::IDENTITY).unwrap();
        let again = launch(on, &mut ctx, &[[1.5, 3.0, 0.9], [4.0, 4.0, 1.0]], false);
        check(on, &again, &[quad_hit((3.0, 3.0), (0.5, 0.0), 0.9), miss(1.0)], 0.0);
    }
}
