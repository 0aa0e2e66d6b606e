//! Runtime behaviour on every backend (each test runs on the CPU backend and
//! on wgpu — lavapipe on machines without a GPU), with pixel values known
//! analytically: a sphere's silhouette and normals, a triangle's shadow
//! edge, any-hit termination, the trace-depth limit, variable shadowing by
//! scope, exceptions, and link errors that name what is wrong.

use glam::{UVec2, Vec2, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub depth: i32,
}

#[rt_payload]
pub struct ShadowPrd {
    pub attenuation: f32,
}

#[rt_attributes]
pub struct Hit {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
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
pub fn shadow_miss(prd: &mut ShadowPrd) {
    prd.attenuation = 1.0;
}

#[rt_program(closest_hit)]
pub fn normal_shader(prd: &mut Radiance, attr: &Hit) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
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
pub fn flagged_camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] flags: u32, #[var] mask: u32, #[var] z: f32) {
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

const W: u32 = 32;
const BG: Vec3 = Vec3::new(0.1, 0.2, 0.3);

/// A context with the ortho camera, a background miss and an output buffer.
fn camera(extent: f32, backend: Backend) -> (Context, BufferId) {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
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

fn sphere_silhouette_and_normals(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    let mut hits = 0;
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, extent);
            let r2 = wx * wx + wy * wy;
            let c = pixel(&img, x, y);
            if r2 < 0.98 {
                hits += 1;
                let n = Vec3::new(wx, wy, (1.0 - r2).sqrt());
                let expected = n * 0.5 + 0.5;
                assert!((c.truncate() - expected).abs().max_element() < 1e-3, "pixel {x},{y}: {c} vs {expected}");
            } else if r2 > 1.02 {
                assert_eq!(c.truncate(), BG, "pixel {x},{y} should miss");
            }
        }
    }
    assert!(hits > 100, "the sphere covers {hits} pixels");
    assert_eq!(report.rays, (W * W) as u64);
}

fn quad(z: f32, half: f32) -> TriangleMesh {
    TriangleMesh {
        positions: vec![
            Vec3::new(-half, -half, z),
            Vec3::new(half, -half, z),
            Vec3::new(half, half, z),
            Vec3::new(-half, half, z),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..TriangleMesh::default()
    }
}

fn triangle_attributes_reach_closest_hit_through_a_transform(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let geom = ctx.create_triangles(quad(0.0, 1.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Sbvh)).unwrap();
    // Rotate the quad 90 degrees about x: its +z normal becomes -y... but
    // seen edge-on it would vanish, so rotate 180 about y: normal -z.
    let xf = ctx.create_transform(glam::Mat4::from_rotation_y(std::f32::consts::PI), gg).unwrap();
    let top = ctx.create_group(&[xf], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    // Inside the quad: world normal (0, 0, -1) → (0.5, 0.5, 0).
    let c = pixel(&img, W / 2, W / 2);
    assert!((c.truncate() - Vec3::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-4, "{c}");
    // Outside the quad's [-1, 1] square (extent 2): background.
    assert_eq!(pixel(&img, 0, 0).truncate(), BG);
}

fn any_hit_terminate_casts_a_shadow_with_a_sharp_edge(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    // A floor quad at z = 0 and a blocker over x in [-3, 0] at z = 1, the
    // light straight above at z = 100: floor points with x < 0 are in
    // shadow. Camera rays ignore the blocker (its any hit for ray type 0
    // ignores every intersection); shadow rays stop at it (terminate).
    let floor = ctx.create_triangles(quad(0.0, 3.0)).unwrap();
    let blocker = ctx
        .create_triangles(TriangleMesh {
            positions: vec![
                Vec3::new(-3.0, -3.0, 1.0),
                Vec3::new(0.0, -3.0, 1.0),
                Vec3::new(0.0, 3.0, 1.0),
                Vec3::new(-3.0, 3.0, 1.0),
            ],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            ..TriangleMesh::default()
        })
        .unwrap();
    let floor_mat = ctx.create_material();
    let shade = ctx.create_program(&shadowed::PROGRAM);
    ctx.set_closest_hit_program(floor_mat, 0, shade).unwrap();
    let blocker_mat = ctx.create_material();
    let see_through = ctx.create_program(&ignore_all::PROGRAM);
    ctx.set_any_hit_program(blocker_mat, 0, see_through).unwrap();
    let stop = ctx.create_program(&shadow_blocker::PROGRAM);
    ctx.set_any_hit_program(blocker_mat, 1, stop).unwrap();
    let g1 = ctx.create_geometry_instance(floor, &[floor_mat]).unwrap();
    let g2 = ctx.create_geometry_instance(blocker, &[blocker_mat]).unwrap();
    let floor_group = ctx.create_geometry_group(&[g1], Acceleration::default()).unwrap();
    let blocker_group = ctx.create_geometry_group(&[g2], Acceleration::new(Builder::Lbvh)).unwrap();
    let top = ctx.create_group(&[floor_group, blocker_group], Acceleration::new(Builder::MedianBvh)).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    ctx.set_var(Scope::Context, "light", Vec3::new(0.0, 0.0, 100.0)).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty());
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    for y in 0..W {
        for x in 0..W {
            let (wx, _) = world(x, y, extent);
            let expected = if wx < 0.0 { 0.0 } else { 1.0 };
            assert_eq!(pixel(&img, x, y).x, expected, "pixel {x},{y} (x = {wx})");
        }
    }
    // A camera ray and a shadow ray per pixel.
    assert_eq!(report.rays, 2 * (W * W) as u64);

    // With the blocker invisible to every ray (mask), nothing is shadowed.
    ctx.set_visibility_mask(blocker_group, 0).unwrap();
    ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert!(img.iter().all(|c| c.x == 1.0));
}

fn trace_depth_limit_raises_the_exception_and_the_exception_program_runs(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    ctx.set_max_trace_depth(3);
    // Two facing quads: every ray bounces between them forever.
    let g = ctx.create_triangles(quad(0.0, 3.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&mirror_forever::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let back = ctx.create_transform(glam::Mat4::from_translation(Vec3::new(0.0, 0.0, 20.0)), gg).unwrap();
    let top = ctx.create_group(&[gg, back], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let ex = ctx.create_program(&paint_exception::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(report.exceptions.len(), (W * W) as usize);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_TRACE_DEPTH_EXCEEDED));
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(pixel(&img, 3, 5), Vec4::new(1.0, 0.0, 1.0, EXCEPTION_TRACE_DEPTH_EXCEEDED as f32));
}

fn user_exception_reaches_the_exception_program_and_other_pixels_are_untouched(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    sphere_scene(&mut ctx, &throws::PROGRAM, Vec3::ZERO, 1.0);
    let ex = ctx.create_program(&paint_exception::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    let center =
        report.exceptions.iter().find(|e| e.launch_index == UVec2::new(W / 2, W / 2)).expect("center pixel threw");
    assert_eq!(center.code, EXCEPTION_USER + 7);
    assert_eq!(pixel(&img, W / 2, W / 2), Vec4::new(1.0, 0.0, 1.0, (EXCEPTION_USER + 7) as f32));
    assert_eq!(pixel(&img, 0, 0).truncate(), BG);
    assert!(report.exceptions.iter().all(|e| {
        let (x, y) = world(e.launch_index.x, e.launch_index.y, extent);
        x * x + y * y < 1.0
    }));
}

fn variables_resolve_innermost_scope_first(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let (_, mat, gi) = sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    ctx.set_var(Scope::Context, "color", Vec3::new(1.0, 0.0, 0.0)).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::X);
    // Material shadows context; geometry instance shadows material.
    ctx.set_var(mat, "color", Vec3::new(0.0, 1.0, 0.0)).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::Y);
    ctx.set_var(gi, "color", Vec3::new(0.0, 0.0, 1.0)).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::Z);
}

fn link_errors_name_the_program_the_variable_and_the_scopes(backend: Backend) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    let err = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(err.contains("variable `color`"), "{err}");
    assert!(err.contains("`flat_color`") && err.contains("runtime.rs:"), "{err}");
    assert!(err.contains("searched, innermost first: program 5, geometry instance 0, material 0, context"), "{err}");

    ctx.set_var(Scope::Context, "color", 1.0f32).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(err.contains("declared `Vec3`") && err.contains("context scope sets it to `f32`"), "{err}");

    let (mut ctx, _) = camera(2.0, backend);
    ctx.set_ray_type_count(3);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let err = ctx.launch(0, W, W).unwrap_err();
    assert!(matches!(err, RtError::NoMissProgram { ray_type: 2 }), "{err}");

    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let wrong = ctx.create_program(&normal_shader::PROGRAM);
    let err = ctx.set_miss_program(0, wrong).unwrap_err().to_string();
    assert!(err.contains("is a ClosestHit program, but ray type 0's miss takes a Miss program"), "{err}");
    assert!(matches!(ctx.launch(0, 0, 4), Err(RtError::BadLaunch { .. })));
}

fn moving_geometry_refits_instead_of_rebuilding(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let geom = ctx.create_triangles(quad(0.0, 0.5)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    ctx.set_var(mat, "color", Vec3::ONE).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), 0, 0).truncate(), BG);
    // Grow the quad to cover the corner pixel: a refit must see it.
    ctx.set_triangle_positions(geom, quad(0.0, 2.0).positions).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), 0, 0).truncate(), Vec3::ONE);
}


fn buffer_overrun_raises_the_exception_and_printf_reaches_the_host(backend: Backend) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &reads_past_the_end::PROGRAM, Vec3::ZERO, 1.0);
    let table = ctx.create_buffer(BufferType::Input, vec![0.25f32, 0.5, 0.75]);
    ctx.set_var(Scope::Context, "table", table).unwrap();
    ctx.set_print(true, Some(UVec2::new(W / 2, W / 2)));
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(report.exceptions, vec![ExceptionRecord { launch_index: UVec2::new(W / 2, W / 2), code: EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS }]);
    // The out-of-bounds read yields zero; the print is filtered to one index.
    assert_eq!(report.prints, vec![(UVec2::new(W / 2, W / 2), format!("pixel [{}, {}] read 0 of 3", W / 2, W / 2))]);
    ctx.set_print(true, Some(UVec2::new(W / 2 + 1, W / 2)));
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(report.prints, vec![(UVec2::new(W / 2 + 1, W / 2), format!("pixel [{}, {}] read 0.25 of 3", W / 2 + 1, W / 2))]);
}

fn nan_rays_raise_invalid_ray(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let rg = ctx.create_program(&nan_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, 4, 4).unwrap();
    assert_eq!(report.exceptions, vec![ExceptionRecord { launch_index: UVec2::new(1, 2), code: EXCEPTION_INVALID_RAY }]);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    // Other launch indices completed: they hit the sphere head on.
    assert!((img[0].truncate() - Vec3::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-3, "{}", img[0]);
}

fn ray_flags_and_masks(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let rg = ctx.create_program(&flagged_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    // Two stacked quads at z = 0 and z = 1, both with an any hit that counts
    // (blue += 1) and a closest hit painting `color`.
    let g = ctx.create_triangles(quad(0.0, 3.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    let ah = ctx.create_program(&count_hits::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    ctx.set_any_hit_program(mat, 0, ah).unwrap();
    ctx.set_var(mat, "color", Vec3::new(1.0, 0.0, 0.0)).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let up = ctx.create_transform(glam::Mat4::from_translation(Vec3::Z), gg).unwrap();
    let top = ctx.create_group(&[gg, up], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let center = |ctx: &mut Context, flags: u32, mask: u32, z: f32| {
        ctx.set_var(Scope::Context, "flags", flags).unwrap();
        ctx.set_var(Scope::Context, "mask", mask).unwrap();
        ctx.set_var(Scope::Context, "z", z).unwrap();
        ctx.launch(0, 8, 8).unwrap();
        pixel8(&ctx.read_buffer::<Vec4>(out).unwrap(), 4, 4).truncate()
    };
    // Closest hit overwrites the payload: red.
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0xff, 10.0), Vec3::X);
    // No closest hit: the any hits' counts stay (one or two, order-free).
    let c = center(&mut ctx, RAY_FLAG_DISABLE_CLOSESTHIT, 0xff, 10.0);
    assert!(c.z >= 1.0 && c.x == 0.0, "{c}");
    // Terminate on first hit with no any hit and no closest hit: black.
    assert_eq!(center(&mut ctx, RAY_FLAG_TERMINATE_ON_FIRST_HIT | RAY_FLAG_DISABLE_ANYHIT | RAY_FLAG_DISABLE_CLOSESTHIT, 0xff, 10.0), Vec3::ZERO);
    // Quads wind counter-clockwise seen from +z: culling front faces from
    // above misses both (background), culling back faces keeps them.
    assert_eq!(center(&mut ctx, RAY_FLAG_CULL_FRONT_FACING, 0xff, 10.0), BG);
    assert_eq!(center(&mut ctx, RAY_FLAG_CULL_BACK_FACING, 0xff, 10.0), Vec3::X);
    // From below, the back faces are what the ray sees.
    assert_eq!(center(&mut ctx, RAY_FLAG_CULL_BACK_FACING, 0xff, -10.0), BG);
    // Masks: the group's children keep mask 0xff; a ray with mask 0 sees nothing.
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0, 10.0), BG);
    ctx.set_visibility_mask(gg, 0b10).unwrap();
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0b01, 10.0), BG);
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0b10, 10.0), Vec3::X);
}

fn pixel8(img: &[Vec4], x: u32, y: u32) -> Vec4 {
    img[(y * 8 + x) as usize]
}

fn textures_sample_with_wrap_and_filter(backend: Backend) {
    let (mut ctx, out) = camera(1.0, backend);
    let mut mesh = quad(0.0, 1.0);
    // Texture coordinates from -1 to 2: wrapping shows.
    mesh.texcoords = Some(vec![Vec2::new(-1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(2.0, 2.0), Vec2::new(-1.0, 2.0)]);
    let g = ctx.create_triangles(mesh).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&textured::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let texels = vec![Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 1.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 1.0, 1.0), Vec4::ONE];
    for (wrap, filter) in [(WrapMode::Repeat, FilterMode::Nearest), (WrapMode::Clamp, FilterMode::Linear), (WrapMode::Mirror, FilterMode::Linear)] {
        let tex = ctx.create_sampler(texels.clone(), 2, 2, wrap, filter).unwrap();
        ctx.set_var(Scope::Context, "tex", tex).unwrap();
        ctx.launch(0, W, W).unwrap();
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        // Compare every pixel with rt-std's CPU sampler at the same uv.
        let reference = unsafe { Sampler2d::from_raw_parts(texels.as_ptr(), 2, 2, wrap, filter) };
        for y in 0..W {
            for x in 0..W {
                let (wx, wy) = world(x, y, 1.0);
                let uv = Vec2::new(-1.0 + 3.0 * (wx + 1.0) / 2.0, -1.0 + 3.0 * (wy + 1.0) / 2.0);
                let expected = reference.sample(uv).truncate();
                let got = pixel(&img, x, y).truncate();
                assert!((got - expected).abs().max_element() < 2e-3, "{wrap:?} {filter:?} at {x},{y}: {got} vs {expected}");
            }
        }
    }
}

fn payload_of_the_wrong_ray_type_raises_invalid_ray(backend: Backend) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::new(0.0, 0.0, 5.0), 1.0);
    let rg = ctx.create_program(&wrong_payload_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, 2, 1).unwrap();
    assert_eq!(report.exceptions.len(), 2);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_INVALID_RAY), "{:?}", report.exceptions);
}

/// Instantiates every test above once per backend.
macro_rules! on_backends {
    ($($name:ident),* $(,)?) => {
        mod cpu {
            use super::*;
            $( #[test] fn $name() { super::$name(Backend::Cpu) } )*
        }
        mod wgpu {
            use super::*;
            $( #[test] fn $name() { super::$name(Backend::Wgpu) } )*
        }
    };
}

on_backends!(
    payload_of_the_wrong_ray_type_raises_invalid_ray,
    buffer_overrun_raises_the_exception_and_printf_reaches_the_host,
    nan_rays_raise_invalid_ray,
    ray_flags_and_masks,
    textures_sample_with_wrap_and_filter,
    sphere_silhouette_and_normals,
    triangle_attributes_reach_closest_hit_through_a_transform,
    any_hit_terminate_casts_a_shadow_with_a_sharp_edge,
    trace_depth_limit_raises_the_exception_and_the_exception_program_runs,
    user_exception_reaches_the_exception_program_and_other_pixels_are_untouched,
    variables_resolve_innermost_scope_first,
    link_errors_name_the_program_the_variable_and_the_scopes,
    moving_geometry_refits_instead_of_rebuilding,
);

#[test]
fn wgpu_and_cpu_render_the_same_sphere() {
    let render = |backend| {
        let (mut ctx, out) = camera(2.0, backend);
        sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::new(0.2, -0.1, 0.0), 1.1);
        ctx.launch(0, W, W).unwrap();
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let (a, b) = (render(Backend::Cpu), render(Backend::Wgpu));
    let worst = a.iter().zip(&b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0f32, f32::max);
    assert!(worst < 2.0 / 255.0, "largest difference {worst}");
}

#[test]
fn changing_values_never_relinks_but_changing_programs_does() {
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    let (_, mat, _) = sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    ctx.set_var(Scope::Context, "color", Vec3::X).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.pipelines_created(), 1);
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::X);
    // New values and buffer contents: same pipeline.
    ctx.set_var(Scope::Context, "color", Vec3::Y).unwrap();
    ctx.set_var(Scope::Context, "bg_color", Vec3::ONE).unwrap();
    ctx.write_buffer(out, &vec![Vec4::ONE; (W * W) as usize]).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.pipelines_created(), 1);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(pixel(&img, W / 2, W / 2).truncate(), Vec3::Y);
    assert_eq!(pixel(&img, 0, 0).truncate(), Vec3::ONE);
    // Shadowing on another scope is a value change too.
    ctx.set_var(mat, "color", Vec3::Z).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.pipelines_created(), 1);
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::Z);
    // A different closest-hit program: a new link.
    let ch = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.pipelines_created(), 2);
    assert!(ctx.linked_wgsl().unwrap().contains("fn rtp_normal_shader_d1("));
}
