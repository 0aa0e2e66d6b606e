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
pub fn flat_miss(prd: &mut Radiance) {
    prd.result = Vec3::ONE;
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
pub fn flagged_camera(
    #[var] top: Object,
    #[var] mut out: RwBuffer2d<Vec4>,
    #[var] flags: u32,
    #[var] mask: u32,
    #[var] z: f32,
) {
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

/// Increments through a `&mut` to a payload field (WGSL passes pointers to
/// whole variables only: the compiler copies in and out).
#[rt_function]
pub fn bump(x: &mut i32) -> i32 {
    *x += 2;
    *x * 10
}

#[rt_program(closest_hit)]
pub fn bumps_a_payload_field(prd: &mut Radiance) {
    prd.depth = 1;
    let v = bump(&mut prd.depth);
    prd.result = vec3(v as f32, prd.depth as f32, 0.0);
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

/// Chooses a selector's child from the payload (which `parity_camera` fills
/// with the launch index's parity) plus a node-scope offset: a child index
/// past the last one enters nothing.
#[rt_program(visit)]
pub fn parity_visit(prd: &Radiance, #[var] offset: u32) -> u32 {
    prd.depth as u32 + offset
}

/// Chooses a selector's child by the side of the selector's space the ray
/// starts on.
#[rt_program(visit)]
pub fn side_visit(prd: &Radiance) -> u32 {
    let _ = prd.depth;
    if current_ray().origin.x < 0.0 { 0 } else { 1 }
}

/// A visit program for shadow rays, met by a radiance ray.
#[rt_program(visit)]
pub fn shadow_visit(prd: &ShadowPrd) -> u32 {
    let _ = prd.attenuation;
    0
}

/// The ortho camera with the launch index's x parity in the payload.
#[rt_program(ray_generation)]
pub fn parity_camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] extent: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * extent, p.y * extent, 10.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, depth: (idx.x % 2) as i32 };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.result.extend(1.0);
}

/// Column `column % 4` of the hit instance's object-to-world matrix
/// (`column < 4`) or of its world-to-object matrix, from `rt_get_transform`.
#[rt_program(closest_hit)]
pub fn transform_column(prd: &mut Radiance, #[var] column: u32) {
    let o2w = rt_get_transform(ObjectToWorld);
    let w2o = rt_get_transform(WorldToObject);
    let m = if column < 4 { o2w } else { w2o };
    prd.result = m.col((column % 4) as usize).truncate();
}

/// A mirror: traces the reflected ray and keeps `reflectance` of its colour.
#[rt_program(closest_hit)]
pub fn mirror(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let mut reflected = Radiance { result: Vec3::ZERO, depth: prd.depth + 1 };
    rt_trace(top, Ray::new(p, reflect(ray.direction, n), 0, 0.001, f32::INFINITY), &mut reflected);
    prd.result = reflected.result * reflectance;
}

/// What a reflected ray sees: a helper that traces, called from a
/// closest-hit program inside a larger expression (the resumable form takes
/// the call out of the expression and suspends in the helper).
#[rt_function]
pub fn reflected_color(top: Object, p: Vec3, d: Vec3, depth: i32) -> Vec3 {
    let mut next = Radiance { result: Vec3::ZERO, depth: depth + 1 };
    rt_trace(top, Ray::new(p, d, 0, 0.001, f32::INFINITY), &mut next);
    next.result
}

/// [`mirror`] through the [`reflected_color`] helper.
#[rt_program(closest_hit)]
pub fn mirror_through_a_helper(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    prd.result = Vec3::ZERO + reflected_color(top, p, reflect(ray.direction, n), prd.depth) * reflectance;
}

/// [`mirror`] with its trace in a `match` arm (the resumable form switches
/// over the scrutinee kept in its frame).
#[rt_program(closest_hit)]
pub fn mirror_in_a_match(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let mut reflected = Radiance { result: Vec3::ZERO, depth: prd.depth + 1 };
    match prd.depth {
        100 => {}
        _ => rt_trace(top, Ray::new(p, reflect(ray.direction, n), 0, 0.001, f32::INFINITY), &mut reflected),
    }
    prd.result = reflected.result * reflectance;
}

/// [`reflected_color`] with its trace inside a `let`'s value, where the
/// compiler makes no resumable form.
#[rt_function]
#[allow(clippy::let_and_return)] // The `let` is the point.
pub fn reflected_in_a_let(top: Object, p: Vec3, d: Vec3, depth: i32) -> Vec3 {
    let mut next = Radiance { result: Vec3::ZERO, depth: depth + 1 };
    let seen = {
        rt_trace(top, Ray::new(p, d, 0, 0.001, f32::INFINITY), &mut next);
        next.result
    };
    seen
}

/// [`mirror`] through [`reflected_in_a_let`]: no resumable form, so
/// kernels using it clone what traces per depth instead.
#[rt_program(closest_hit)]
pub fn mirror_without_a_resumable_form(prd: &mut Radiance, attr: &Hit, #[var] top: Object, #[var] reflectance: f32) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    prd.result = reflected_in_a_let(top, p, reflect(ray.direction, n), prd.depth) * reflectance;
}

/// One ray per origin (1D launch), straight down -z: the closest hit's
/// colour's x, or the background's.
#[rt_program(ray_generation)]
pub fn probe_rays(#[var] top: Object, #[var] origins: Buffer<Vec3>, #[var] mut hits: RwBuffer<f32>) {
    let i = launch_index().x;
    let mut prd = Radiance { result: Vec3::ZERO, depth: 0 };
    rt_trace(top, Ray::new(origins[i], vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
    hits[i] = prd.result.x;
}

/// Writes `index + 1` at every 1D launch index.
#[rt_program(ray_generation)]
pub fn write_index(#[var] mut ids: RwBuffer<u32>) {
    let i = launch_index().x;
    ids[i] = i + 1;
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

/// `mesh` under a material with closest hit `program`, in a geometry group
/// that becomes `top`: its geometry and material.
fn mesh_scene(
    ctx: &mut Context,
    mesh: TriangleMesh,
    program: &'static rt_std::program::ProgramDescriptor,
) -> (GeometryId, MaterialId) {
    let g = ctx.create_triangles(mesh).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(program);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    (g, mat)
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

/// `rt_get_transform` gives the transform above the hit instance and its
/// inverse, column by column, as glam computes them on the host; without a
/// transform above it, the identity.
fn rt_get_transform_reads_the_instance_transform_and_its_inverse(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let geom = ctx.create_triangles(quad(0.0, 1.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&transform_column::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let m = glam::Mat4::from_scale_rotation_translation(
        Vec3::new(1.5, 1.25, 2.0),
        glam::Quat::from_rotation_z(0.5),
        Vec3::new(0.1, -0.2, 1.0),
    );
    let xf = ctx.create_transform(m, gg).unwrap();
    let transformed = ctx.create_group(&[xf], Acceleration::default()).unwrap();
    for (top, m) in [(transformed, m), (gg, glam::Mat4::IDENTITY)] {
        ctx.set_var(Scope::Context, "top", top).unwrap();
        for column in 0..8u32 {
            ctx.set_var(Scope::Context, "column", column).unwrap();
            ctx.launch(0, W, W).unwrap();
            let got = pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate();
            let of = if column < 4 { m } else { m.inverse() };
            let want = of.col((column % 4) as usize).truncate();
            assert!((got - want).abs().max_element() < 1e-5, "column {column}: {got} against {want}");
        }
    }
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
    assert_eq!(ctx.acceleration_builds(), (1, 0));
    ctx.set_triangle_positions(geom, quad(0.0, 2.0).positions).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.acceleration_builds(), (1, 1), "moved geometry is refit, not rebuilt");
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), 0, 0).truncate(), Vec3::ONE);
}

/// A deformed mesh: its refit trees (the BVH2, and the CWBVH both backends
/// walk, re-quantized in place) find what trees built for the new shape
/// find.
fn a_refit_mesh_renders_as_one_built_for_its_new_shape(backend: Backend) {
    let wave = |mesh: &TriangleMesh| -> Vec<Vec3> {
        mesh.positions.iter().map(|p| Vec3::new(p.x * 1.3, p.y, p.z + 0.4 * (3.0 * p.x).sin() * p.y)).collect()
    };
    let grid = bumpy_grid(30);
    let (mut ctx, out) = camera(1.4, backend);
    let (g, _) = mesh_scene(&mut ctx, grid.clone(), &normal_shader::PROGRAM);
    ctx.launch(0, W, W).unwrap();
    ctx.set_triangle_positions(g, wave(&grid)).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.acceleration_builds(), (1, 1), "moved geometry is refit, not rebuilt");
    let refit = ctx.read_buffer::<Vec4>(out).unwrap();
    let (mut fresh, fresh_out) = camera(1.4, backend);
    mesh_scene(&mut fresh, TriangleMesh { positions: wave(&grid), ..grid }, &normal_shader::PROGRAM);
    fresh.launch(0, W, W).unwrap();
    let built = fresh.read_buffer::<Vec4>(fresh_out).unwrap();
    let hits = built.iter().filter(|c| c.truncate() != BG).count();
    assert!(hits > (W * W / 2) as usize, "{hits} pixels hit");
    // The same closest triangles (a tie on a shared edge may go either way).
    let differ = refit.iter().zip(&built).filter(|(a, b)| (**a - **b).abs().max_element() > 1e-4).count();
    assert!(differ <= 2, "{differ} pixels differ between the refit and the built trees");
}

fn buffer_overrun_raises_the_exception_and_printf_reaches_the_host(backend: Backend) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &reads_past_the_end::PROGRAM, Vec3::ZERO, 1.0);
    let table = ctx.create_buffer(BufferType::Input, vec![0.25f32, 0.5, 0.75]);
    ctx.set_var(Scope::Context, "table", table).unwrap();
    ctx.set_print(true, Some(UVec2::new(W / 2, W / 2)));
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(
        report.exceptions,
        vec![ExceptionRecord {
            launch_index: UVec2::new(W / 2, W / 2),
            code: EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS,
            location: None
        }]
    );
    // The out-of-bounds read yields zero; the print is filtered to one index.
    assert_eq!(report.prints, vec![(UVec2::new(W / 2, W / 2), format!("pixel [{}, {}] read 0 of 3", W / 2, W / 2))]);
    ctx.set_print(true, Some(UVec2::new(W / 2 + 1, W / 2)));
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(
        report.prints,
        vec![(UVec2::new(W / 2 + 1, W / 2), format!("pixel [{}, {}] read 0.25 of 3", W / 2 + 1, W / 2))]
    );
}

fn nan_rays_raise_invalid_ray(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let rg = ctx.create_program(&nan_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, 4, 4).unwrap();
    assert_eq!(
        report.exceptions,
        vec![ExceptionRecord { launch_index: UVec2::new(1, 2), code: EXCEPTION_INVALID_RAY, location: None }]
    );
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    // Other launch indices completed: they hit the sphere head on.
    assert!((img[0].truncate() - Vec3::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-3, "{}", img[0]);
}

/// The smallest trees: a geometry group of one triangle (its CWBVH a root
/// with one leaf child) and one of none, beside each other in a group.
fn one_triangle_and_an_empty_group(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    let tri = TriangleMesh {
        positions: vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0)],
        indices: vec![[0, 1, 2]],
        ..TriangleMesh::default()
    };
    let g = ctx.create_triangles(tri).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    ctx.set_var(mat, "color", Vec3::X).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let one = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let none = ctx.create_geometry_group(&[], Acceleration::default()).unwrap();
    let top = ctx.create_group(&[one, none], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, 2.0);
            let c = pixel(&img, x, y).truncate();
            if wx > -0.95 && wy > -0.95 && wx + wy < -0.05 {
                assert_eq!(c, Vec3::X, "pixel {x},{y} inside the triangle");
            } else if wx < -1.05 || wy < -1.05 || wx + wy > 0.05 {
                assert_eq!(c, BG, "pixel {x},{y} outside the triangle");
            }
        }
    }
    if backend == Backend::Wgpu {
        assert!(ctx.linked_wgsl().unwrap().contains("const RT_CWBVH: bool = true;"));
    }
}

/// The flagged camera over a quad at z = 0 (counter-clockwise seen from
/// +z) under a closest hit painting red and, with `any_hit`, an any hit
/// that counts (blue += 1): the context, its output and the quad's group.
fn flagged_quad(backend: Backend, any_hit: bool) -> (Context, BufferId, NodeId) {
    let (mut ctx, out) = camera(2.0, backend);
    let rg = ctx.create_program(&flagged_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let g = ctx.create_triangles(quad(0.0, 3.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    if any_hit {
        let ah = ctx.create_program(&count_hits::PROGRAM);
        ctx.set_any_hit_program(mat, 0, ah).unwrap();
    }
    ctx.set_var(mat, "color", Vec3::X).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    (ctx, out, gg)
}

fn ray_flags_and_masks(backend: Backend) {
    // Two stacked quads at z = 0 and z = 1, both with an any hit that counts
    // and a closest hit painting red.
    let (mut ctx, out, gg) = flagged_quad(backend, true);
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
    assert_eq!(
        center(
            &mut ctx,
            RAY_FLAG_TERMINATE_ON_FIRST_HIT | RAY_FLAG_DISABLE_ANYHIT | RAY_FLAG_DISABLE_CLOSESTHIT,
            0xff,
            10.0
        ),
        Vec3::ZERO
    );
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
    // Tracing into the geometry group itself checks its mask too.
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0b01, 10.0), BG);
    assert_eq!(center(&mut ctx, RAY_FLAG_NONE, 0b10, 10.0), Vec3::X);
}

/// Culling without any-hit programs: the wgpu kernel's lean triangle search
/// (which asks a triangle's side only when a cull flag is set) culls as the
/// general search and the CPU backend do.
fn culling_in_the_lean_search(backend: Backend) {
    let (mut ctx, out, gg) = flagged_quad(backend, false);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    ctx.set_var(Scope::Context, "mask", 0xffu32).unwrap();
    let mut center = |flags: u32, z: f32| {
        ctx.set_var(Scope::Context, "flags", flags).unwrap();
        ctx.set_var(Scope::Context, "z", z).unwrap();
        ctx.launch(0, 8, 8).unwrap();
        pixel8(&ctx.read_buffer::<Vec4>(out).unwrap(), 4, 4).truncate()
    };
    let both = RAY_FLAG_CULL_FRONT_FACING | RAY_FLAG_CULL_BACK_FACING;
    for (flags, above, below) in [
        (RAY_FLAG_NONE, Vec3::X, Vec3::X),
        (RAY_FLAG_CULL_FRONT_FACING, BG, Vec3::X),
        (RAY_FLAG_CULL_BACK_FACING, Vec3::X, BG),
        (both, BG, BG),
    ] {
        assert_eq!(center(flags, 10.0), above, "flags {flags:#x} from above");
        assert_eq!(center(flags, -10.0), below, "flags {flags:#x} from below");
    }
    if backend == Backend::Wgpu {
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(
            wgsl.contains("const RT_TRIANGLES_ONLY: bool = true;") && wgsl.contains("const RT_CWBVH: bool = true;")
        );
    }
}

fn pixel8(img: &[Vec4], x: u32, y: u32) -> Vec4 {
    img[(y * 8 + x) as usize]
}

fn textures_sample_with_wrap_and_filter(backend: Backend) {
    let (mut ctx, out) = camera(1.0, backend);
    let mut mesh = quad(0.0, 1.0);
    // Texture coordinates from -1 to 2: wrapping shows.
    mesh.texcoords = Some(vec![Vec2::new(-1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(2.0, 2.0), Vec2::new(-1.0, 2.0)]);
    mesh_scene(&mut ctx, mesh, &textured::PROGRAM);
    let texels =
        vec![Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 1.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 1.0, 1.0), Vec4::ONE];
    for (wrap, filter) in [
        (WrapMode::Repeat, FilterMode::Nearest),
        (WrapMode::Clamp, FilterMode::Linear),
        (WrapMode::Mirror, FilterMode::Linear),
    ] {
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
                assert!(
                    (got - expected).abs().max_element() < 2e-3,
                    "{wrap:?} {filter:?} at {x},{y}: {got} vs {expected}"
                );
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

/// A flat-coloured sphere geometry group (custom primitives).
fn colored_sphere(ctx: &mut Context, center: Vec3, radius: f32, color: Vec3) -> NodeId {
    let isect = ctx.create_program(&sphere_intersect::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let geom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    ctx.set_var(geom, "sphere", center.extend(radius)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    ctx.set_var(mat, "color", color).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap()
}

fn selector_chooses_a_child_from_the_payload_and_launch_index_parity(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    let rg = ctx.create_program(&parity_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    // Two spheres in the same place, red and blue, modelled at x = -0.5
    // and moved to the origin by a transform above the selector.
    let red = colored_sphere(&mut ctx, Vec3::new(-0.5, 0.0, 0.0), 1.0, Vec3::X);
    let blue = colored_sphere(&mut ctx, Vec3::new(-0.5, 0.0, 0.0), 1.0, Vec3::Z);
    let visit = ctx.create_program(&parity_visit::PROGRAM);
    let sel = ctx.create_selector(visit, &[red, blue]).unwrap();
    ctx.set_var(sel, "offset", 0u32).unwrap();
    let moved = ctx.create_transform(glam::Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0)), sel).unwrap();
    let top = ctx.create_group(&[moved], Acceleration::default()).unwrap();
    let check = |ctx: &mut Context, offset: u32, origin: Vec3| {
        ctx.set_var(sel, "offset", offset).unwrap();
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        let mut seen = [0; 3];
        for y in 0..W {
            for x in 0..W {
                let (wx, wy) = world(x, y, extent);
                let r2 = (wx - origin.x).powi(2) + (wy - origin.y).powi(2);
                let c = pixel(&img, x, y).truncate();
                if r2 < 0.98 {
                    // Child (x parity + offset): red, blue, or none.
                    let expected = [Vec3::X, Vec3::Z, BG][(x % 2 + offset) as usize];
                    assert_eq!(c, expected, "pixel {x},{y} with offset {offset}");
                    seen[(x % 2 + offset) as usize] += 1;
                } else if r2 > 1.02 {
                    assert_eq!(c, BG, "pixel {x},{y} should miss");
                }
            }
        }
        seen
    };
    // The selector traced directly (in its own space: the spheres at x = -0.5).
    ctx.set_var(Scope::Context, "top", sel).unwrap();
    let seen = check(&mut ctx, 0, Vec3::new(-0.5, 0.0, 0.0));
    assert!(seen[0] > 50 && seen[1] > 50, "{seen:?}");
    // Under a group and a transform.
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let seen = check(&mut ctx, 0, Vec3::ZERO);
    assert!(seen[0] > 50 && seen[1] > 50, "{seen:?}");
    // A node-scope value change: even indices blue, odd ones enter nothing.
    let seen = check(&mut ctx, 1, Vec3::ZERO);
    assert!(seen[1] > 50 && seen[2] > 50, "{seen:?}");
}

fn visit_programs_see_the_ray_in_the_selectors_space_and_check_the_payload_type(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    let red = colored_sphere(&mut ctx, Vec3::ZERO, 1.5, Vec3::X);
    let blue = colored_sphere(&mut ctx, Vec3::ZERO, 1.5, Vec3::Z);
    let visit = ctx.create_program(&side_visit::PROGRAM);
    let sel = ctx.create_selector(visit, &[red, blue]).unwrap();
    // Moved by +0.5 in x: the selector's x = 0 is world x = 0.5.
    let moved = ctx.create_transform(glam::Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0)), sel).unwrap();
    ctx.set_var(Scope::Context, "top", moved).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, extent);
            let r2 = (wx - 0.5).powi(2) + wy * wy;
            if r2 < 1.5 * 1.5 * 0.98 {
                let expected = if wx < 0.5 { Vec3::X } else { Vec3::Z };
                assert_eq!(pixel(&img, x, y).truncate(), expected, "pixel {x},{y}");
            }
        }
    }
    // A visit program taking another payload type: invalid ray, no child
    // (the default exception program paints the image magenta).
    let visit = ctx.create_program(&shadow_visit::PROGRAM);
    let sel = ctx.create_selector(visit, &[red]).unwrap();
    ctx.set_var(Scope::Context, "top", sel).unwrap();
    let report = ctx.launch(0, 4, 4).unwrap();
    assert_eq!(report.exceptions.len(), 16);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_INVALID_RAY), "{:?}", report.exceptions);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(img[0], Vec4::new(1.0, 0.0, 1.0, 1.0));
}

fn three_level_graph_group_of_groups_of_transforms(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    // One unit sphere's geometry group, instanced twice:
    // top = group[group[T1 -> spheres], Tz -> group[T2 -> spheres]].
    let isect = ctx.create_program(&sphere_intersect::PROGRAM);
    let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
    let geom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    ctx.set_var(geom, "sphere", Vec3::ZERO.extend(1.0)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let spheres = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    use glam::Mat4;
    let t1 = ctx
        .create_transform(
            Mat4::from_translation(Vec3::new(-1.0, 0.5, 0.0)) * Mat4::from_scale(Vec3::splat(0.5)),
            spheres,
        )
        .unwrap();
    let g1 = ctx.create_group(&[t1], Acceleration::default()).unwrap();
    let t2 = ctx
        .create_transform(
            Mat4::from_translation(Vec3::new(0.8, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(0.5)),
            spheres,
        )
        .unwrap();
    let g2 = ctx.create_group(&[t2], Acceleration::new(Builder::NoAccel)).unwrap();
    let tz = ctx
        .create_transform(Mat4::from_translation(Vec3::new(0.2, -0.6, 0.0)) * Mat4::from_scale(Vec3::splat(1.2)), g2)
        .unwrap();
    let top = ctx.create_group(&[g1, tz], Acceleration::new(Builder::Lbvh)).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    if backend == Backend::Wgpu {
        // The graph traversal is linked, with one transform level below world space.
        assert!(ctx.linked_wgsl().unwrap().contains("const RT_LEVELS: u32 = 2u;"));
    }
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    // World spheres: (-1, 0.5) radius 0.5; Tz * (0.8, 0) = (1.16, -0.6), radius 0.6.
    let spheres = [(Vec2::new(-1.0, 0.5), 0.5), (Vec2::new(1.16, -0.6), 0.6)];
    let mut hits = [0; 2];
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, extent);
            let c = pixel(&img, x, y).truncate();
            let mut outside = true;
            for (i, (center, r)) in spheres.iter().enumerate() {
                let d = (Vec2::new(wx, wy) - *center) / *r;
                if d.length_squared() < 0.98 {
                    let n = d.extend((1.0 - d.length_squared()).sqrt());
                    let expected = n * 0.5 + 0.5;
                    assert!((c - expected).abs().max_element() < 1e-3, "pixel {x},{y}: {c} vs {expected}");
                    hits[i] += 1;
                }
                outside &= d.length_squared() > 1.02;
            }
            if outside {
                assert_eq!(c, BG, "pixel {x},{y} should miss");
            }
        }
    }
    assert!(hits[0] > 20 && hits[1] > 30, "{hits:?}");
    // A visibility mask on the inner group hides its sphere.
    ctx.set_visibility_mask(g2, 0).unwrap();
    ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    let (x, y) = (((1.16 / extent + 1.0) / 2.0 * W as f32) as u32, ((-0.6 / extent + 1.0) / 2.0 * W as f32) as u32);
    assert_eq!(pixel(&img, x, y).truncate(), BG);
}

fn default_exception_paints_magenta_and_records_the_exception(backend: Backend) {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    sphere_scene(&mut ctx, &throws::PROGRAM, Vec3::ZERO, 1.0);
    let report = ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    let mut painted = 0;
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, extent);
            let r2 = wx * wx + wy * wy;
            let thrown = report.exceptions.iter().any(|e| e.launch_index == UVec2::new(x, y));
            if r2 < 0.98 {
                assert!(thrown, "pixel {x},{y} hit the sphere");
                assert_eq!(pixel(&img, x, y), Vec4::new(1.0, 0.0, 1.0, 1.0), "pixel {x},{y}");
                painted += 1;
            } else if r2 > 1.02 {
                assert!(!thrown);
                assert_eq!(pixel(&img, x, y), BG.extend(1.0), "pixel {x},{y}");
            }
        }
    }
    assert!(painted > 100);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_USER + 7));
}

fn mirror_shows_the_reflected_object_and_the_reflected_background(backend: Backend) {
    mirror_scene(backend, &mirror::PROGRAM, 20);
}

fn a_helper_that_traces_works_from_a_closest_hit(backend: Backend) {
    let ctx = mirror_scene(backend, &mirror_through_a_helper::PROGRAM, 20);
    if backend == Backend::Wgpu {
        // One loop runs the resumable forms: no per-depth clones.
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(wgsl.contains("fn rtf_reflected_color_rs(") && !wgsl.contains("_d1("));
    }
}

fn a_trace_in_a_match_arm_resumes_in_that_arm(backend: Backend) {
    assert!(mirror_in_a_match::PROGRAM.wgsl_resumable.is_some());
    let ctx = mirror_scene(backend, &mirror_in_a_match::PROGRAM, 20);
    if backend == Backend::Wgpu {
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(wgsl.contains("fn rtp_mirror_in_a_match(") && !wgsl.contains("_d1("));
    }
}

fn a_program_without_a_resumable_form_links_per_depth_clones(backend: Backend) {
    assert!(mirror_without_a_resumable_form::PROGRAM.wgsl_resumable.is_none());
    assert_eq!(
        mirror_without_a_resumable_form::PROGRAM.not_resumable,
        Some(
            "not resumable: `reflected_in_a_let` has no resumable form (`reflected_in_a_let`: a site inside a `let` or a macro)"
        )
    );
    // Shallow: clones grow with the depth (20 took minutes to link).
    let ctx = mirror_scene(backend, &mirror_without_a_resumable_form::PROGRAM, 3);
    if backend == Backend::Wgpu {
        assert!(ctx.linked_wgsl().unwrap().contains("fn rtp_mirror_without_a_resumable_form_d1("));
    }
}

/// A tilted mirror (closest hit `program`) reflecting a green wall and the
/// background, checked pixel by pixel, with a maximum trace depth of
/// `depth` (20: deep enough that per-depth clones would be many, so the
/// wgpu kernel runs resumable programs from its loop).
fn mirror_scene(backend: Backend, program: &'static rt_std::program::ProgramDescriptor, depth: u32) -> Context {
    let extent = 2.0;
    let (mut ctx, out) = camera(extent, backend);
    ctx.set_max_trace_depth(depth);
    // A mirror quad through the origin with normal (1, 0, 1) / sqrt(2): the
    // camera's -z rays reflect to +x. A green wall at x = 5 over y in [0, 3]
    // (parallel to the camera rays, so they never see it directly).
    let mirror_geom = ctx.create_triangles(quad(0.0, 1.0)).unwrap();
    let mirror_mat = ctx.create_material();
    let ch = ctx.create_program(program);
    ctx.set_closest_hit_program(mirror_mat, 0, ch).unwrap();
    ctx.set_var(mirror_mat, "reflectance", 0.8f32).unwrap();
    let mirror_gi = ctx.create_geometry_instance(mirror_geom, &[mirror_mat]).unwrap();
    let mirror_gg = ctx.create_geometry_group(&[mirror_gi], Acceleration::default()).unwrap();
    let tilt = ctx.create_transform(glam::Mat4::from_rotation_y(std::f32::consts::FRAC_PI_4), mirror_gg).unwrap();
    let wall = ctx
        .create_triangles(TriangleMesh {
            positions: vec![
                Vec3::new(5.0, 0.0, -3.0),
                Vec3::new(5.0, 3.0, -3.0),
                Vec3::new(5.0, 3.0, 3.0),
                Vec3::new(5.0, 0.0, 3.0),
            ],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            ..TriangleMesh::default()
        })
        .unwrap();
    let wall_mat = ctx.create_material();
    let flat = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(wall_mat, 0, flat).unwrap();
    ctx.set_var(wall_mat, "color", Vec3::new(0.0, 1.0, 0.0)).unwrap();
    let wall_gi = ctx.create_geometry_instance(wall, &[wall_mat]).unwrap();
    let wall_gg = ctx.create_geometry_group(&[wall_gi], Acceleration::default()).unwrap();
    let top = ctx.create_group(&[tilt, wall_gg], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    // The mirror covers |x| < cos(45°) = 0.707 and |y| < 1 seen from above.
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let (mut green, mut sky) = (0, 0);
    for y in 0..W {
        for x in 0..W {
            let (wx, wy) = world(x, y, extent);
            let c = pixel(&img, x, y).truncate();
            if wx.abs() < half - 0.05 && wy.abs() < 0.95 && wy.abs() > 0.05 {
                // The reflected ray leaves (wx, wy, -wx) along +x: the wall
                // above y = 0, the background below.
                let expected = if wy > 0.0 { Vec3::new(0.0, 0.8, 0.0) } else { BG * 0.8 };
                assert!((c - expected).abs().max_element() < 1e-5, "pixel {x},{y}: {c} vs {expected}");
                if wy > 0.0 { green += 1 } else { sky += 1 }
            } else if wx.abs() > half + 0.05 || wy.abs() > 1.05 {
                assert_eq!(c, BG, "pixel {x},{y} misses the mirror");
            }
        }
    }
    assert!(green > 50 && sky > 50, "{green} {sky}");
    // A primary ray and a reflected one for each pixel on the mirror.
    assert!(report.rays > (W * W) as u64 + 100);
    ctx
}

/// The resumable kernel's size does not depend on the maximum trace depth
/// (per-depth clones grow with it, and with every trace call; they are
/// used only while they stay few, `kernel::MAX_CLONES`).
#[test]
fn wgpu_kernel_size_does_not_grow_with_the_trace_depth() {
    let link = |depth: u32| {
        let (mut ctx, _) = camera(1.0, Backend::Wgpu);
        ctx.set_max_trace_depth(depth);
        sphere_scene(&mut ctx, &mirror_forever::PROGRAM, Vec3::ZERO, 1.0);
        ctx.launch(0, W, W).unwrap();
        ctx.linked_wgsl().unwrap().to_string()
    };
    let size = |depth: u32| {
        let wgsl = link(depth);
        assert!(wgsl.contains("fn rt_run(") && wgsl.contains(&format!("const RT_DEPTHS: u32 = {}u;", depth + 1)));
        wgsl.replace(&format!("const RT_DEPTHS: u32 = {}u;", depth + 1), "").len()
    };
    assert_eq!(size(20), size(31));
    // At depth 2 per-depth clones are few (two copies of the traversal):
    // no trace loop.
    let shallow = link(2);
    assert!(!shallow.contains("fn rt_run(") && shallow.contains("fn rtp_mirror_forever_d2("));
}

fn launches_wider_than_the_dispatch_limit_write_every_index(backend: Backend) {
    // 600,000 indices in 8x8 workgroups are 75,000 groups across: more than
    // wgpu's 65,535 per dimension, so the wgpu backend tiles the launch in x.
    const N: u32 = 600_000;
    let (mut ctx, _) = camera(1.0, backend);
    let rg = ctx.create_program(&write_index::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let ids = ctx.create_buffer(BufferType::Output, vec![0u32; N as usize]);
    ctx.set_var(Scope::Context, "ids", ids).unwrap();
    let report = ctx.launch_1d(0, N).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", &report.exceptions[..report.exceptions.len().min(4)]);
    let got = ctx.read_buffer::<u32>(ids).unwrap();
    if let Some(i) = (0..N).find(|&i| got[i as usize] != i + 1) {
        panic!("index {i} holds {}", got[i as usize]);
    }
}

/// Nested triangles of geometrically growing size (each a level deeper)
/// make a BVH2 that is a chain about 300 levels deep (its CWBVH, with up to
/// seven leaves a node, over 32). The wgpu kernel's traversal stacks used
/// to be a fixed 64 entries, dropping entries when full; they are now sized
/// from the deepest BVH2 and CWBVH (a near-first traversal keeps at most
/// one pending entry per level), checked here, and every ray still finds
/// its triangle on both backends.
fn a_bvh_deeper_than_64_levels_loses_no_hit(backend: Backend) {
    // Without an any-hit program the wgpu kernel walks the CWBVH (about a
    // third as deep, still past 32 levels); with one, the BVH2.
    for any_hit in [false, true] {
        deep_bvh_probe(backend, any_hit);
    }
}

fn deep_bvh_probe(backend: Backend, any_hit: bool) {
    const N: u32 = 300;
    let (mut ctx, _) = camera(1.0, backend);
    let rg = ctx.create_program(&probe_rays::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let mut origins = Vec::new();
    for i in 0..N {
        // Triangle i covers x, y >= -s, x + y <= 2s at z = -i; the point
        // (s, 0.9 s) is inside it and outside every smaller one.
        let s = 1.1f32.powi(i as i32);
        let z = -(i as f32);
        let b = positions.len() as u32;
        positions.extend([Vec3::new(-s, -s, z), Vec3::new(3.0 * s, -s, z), Vec3::new(-s, 3.0 * s, z)]);
        indices.push([b, b + 1, b + 2]);
        origins.push(Vec3::new(s, 0.9 * s, 1.0));
    }
    let mesh = ctx.create_triangles(TriangleMesh { positions, indices, ..TriangleMesh::default() }).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    if any_hit {
        let ah = ctx.create_program(&count_hits::PROGRAM);
        ctx.set_any_hit_program(mat, 0, ah).unwrap();
    }
    ctx.set_var(mat, "color", Vec3::X).unwrap();
    let gi = ctx.create_geometry_instance(mesh, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let origins = ctx.create_buffer(BufferType::Input, origins);
    ctx.set_var(Scope::Context, "origins", origins).unwrap();
    let hits = ctx.create_buffer(BufferType::Output, vec![0.0f32; N as usize]);
    ctx.set_var(Scope::Context, "hits", hits).unwrap();
    let report = ctx.launch_1d(0, N).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let got = ctx.read_buffer::<f32>(hits).unwrap();
    let missed: Vec<u32> = (0..N).filter(|&i| got[i as usize] != 1.0).collect();
    assert!(missed.is_empty(), "rays that missed their triangle (any hit: {any_hit}): {missed:?}");
    if backend == Backend::Wgpu {
        let wgsl = ctx.linked_wgsl().unwrap();
        let constant = |name: &str| -> u32 {
            wgsl.split(&format!("const {name}: u32 = "))
                .nth(1)
                .and_then(|t| t.split('u').next())
                .and_then(|n| n.parse().ok())
                .expect(name)
        };
        assert_eq!(wgsl.contains("const RT_CWBVH: bool = true;"), !any_hit);
        let (stack, levels) = if any_hit { (constant("RT_BVH_STACK"), 64) } else { (constant("RT_CW_STACK"), 32) };
        assert!(stack > levels, "the BVH is not deeper than {levels} levels (stack {stack}): the test proves nothing");
    }
}

fn mut_references_to_payload_fields_reach_helpers(backend: Backend) {
    let (mut ctx, out) = camera(2.0, backend);
    sphere_scene(&mut ctx, &bumps_a_payload_field::PROGRAM, Vec3::ZERO, 1.0);
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::new(30.0, 3.0, 0.0));
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
    mut_references_to_payload_fields_reach_helpers,
    payload_of_the_wrong_ray_type_raises_invalid_ray,
    buffer_overrun_raises_the_exception_and_printf_reaches_the_host,
    nan_rays_raise_invalid_ray,
    ray_flags_and_masks,
    culling_in_the_lean_search,
    one_triangle_and_an_empty_group,
    a_refit_mesh_renders_as_one_built_for_its_new_shape,
    textures_sample_with_wrap_and_filter,
    sphere_silhouette_and_normals,
    triangle_attributes_reach_closest_hit_through_a_transform,
    rt_get_transform_reads_the_instance_transform_and_its_inverse,
    any_hit_terminate_casts_a_shadow_with_a_sharp_edge,
    trace_depth_limit_raises_the_exception_and_the_exception_program_runs,
    user_exception_reaches_the_exception_program_and_other_pixels_are_untouched,
    variables_resolve_innermost_scope_first,
    link_errors_name_the_program_the_variable_and_the_scopes,
    moving_geometry_refits_instead_of_rebuilding,
    selector_chooses_a_child_from_the_payload_and_launch_index_parity,
    visit_programs_see_the_ray_in_the_selectors_space_and_check_the_payload_type,
    three_level_graph_group_of_groups_of_transforms,
    default_exception_paints_magenta_and_records_the_exception,
    mirror_shows_the_reflected_object_and_the_reflected_background,
    a_helper_that_traces_works_from_a_closest_hit,
    a_bvh_deeper_than_64_levels_loses_no_hit,
    a_trace_in_a_match_arm_resumes_in_that_arm,
    a_program_without_a_resumable_form_links_per_depth_clones,
    launches_wider_than_the_dispatch_limit_write_every_index,
);

/// The largest difference of any channel between two images.
fn largest_difference(a: &[Vec4], b: &[Vec4]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0f32, f32::max)
}

#[test]
fn wgpu_and_cpu_render_the_same_sphere() {
    let render = |backend| {
        let (mut ctx, out) = camera(2.0, backend);
        sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::new(0.2, -0.1, 0.0), 1.1);
        ctx.launch(0, W, W).unwrap();
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let (a, b) = (render(Backend::Cpu), render(Backend::Wgpu));
    let worst = largest_difference(&a, &b);
    assert!(worst < 2.0 / 255.0, "largest difference {worst}");
}

#[test]
fn wgpu_and_cpu_render_the_same_deep_graph() {
    use glam::Mat4;
    let render = |backend| {
        let (mut ctx, out) = camera(2.0, backend);
        let isect = ctx.create_program(&sphere_intersect::PROGRAM);
        let bounds = ctx.create_program(&sphere_bounds::PROGRAM);
        let geom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
        ctx.set_var(geom, "sphere", Vec3::ZERO.extend(0.4)).unwrap();
        let mat = ctx.create_material();
        let ch = ctx.create_program(&normal_shader::PROGRAM);
        ctx.set_closest_hit_program(mat, 0, ch).unwrap();
        let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
        let sphere = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        let q = ctx.create_triangles(quad(0.0, 0.3)).unwrap();
        let qi = ctx.create_geometry_instance(q, &[mat]).unwrap();
        let quad_gg = ctx.create_geometry_group(&[qi], Acceleration::default()).unwrap();
        let xf = |ctx: &mut Context, m: Mat4, child: NodeId| ctx.create_transform(m, child).unwrap();
        // inner: a group of instances; mid: a group with a transform chain
        // above a group; sel: a selector over mid and a moved mid; top: a
        // transform above a group holding the selector.
        let a = xf(&mut ctx, Mat4::from_translation(Vec3::new(-0.6, 0.0, 0.0)), sphere);
        let b = xf(&mut ctx, Mat4::from_translation(Vec3::new(0.6, 0.0, 0.0)) * Mat4::from_rotation_x(0.4), quad_gg);
        let inner = ctx.create_group(&[a, b], Acceleration::default()).unwrap();
        let rot = xf(&mut ctx, Mat4::from_rotation_z(0.5), inner);
        let scaled = xf(&mut ctx, Mat4::from_scale(Vec3::splat(0.7)), rot);
        let mid = ctx.create_group(&[scaled, sphere], Acceleration::new(Builder::MedianBvh)).unwrap();
        let up = xf(&mut ctx, Mat4::from_translation(Vec3::new(0.0, 1.0, 0.0)), mid);
        let visit = ctx.create_program(&side_visit::PROGRAM);
        let sel = ctx.create_selector(visit, &[mid, up]).unwrap();
        let corner = xf(&mut ctx, Mat4::from_translation(Vec3::new(-1.0, 1.0, 0.0)), quad_gg);
        let group = ctx.create_group(&[sel, corner], Acceleration::default()).unwrap();
        let top = xf(
            &mut ctx,
            Mat4::from_translation(Vec3::new(0.2, -0.3, -1.0)) * Mat4::from_scale(Vec3::splat(1.3)),
            group,
        );
        ctx.set_var(Scope::Context, "top", top).unwrap();
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        if backend == Backend::Wgpu {
            assert!(ctx.linked_wgsl().unwrap().contains("const RT_LEVELS: u32 = 4u;"));
        }
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let (a, b) = (render(Backend::Cpu), render(Backend::Wgpu));
    let hits = a.iter().filter(|c| c.truncate() != BG).count();
    assert!(hits > 100, "{hits} pixels hit");
    let worst = largest_difference(&a, &b);
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
    // A two-level scene links no graph traversal.
    assert!(!ctx.linked_wgsl().unwrap().contains("RT_LEVELS"));
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

#[test]
fn launches_upload_only_what_changed_and_host_writes_reach_the_device() {
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    let (_, mat, _) = sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    ctx.set_var(Scope::Context, "color", Vec3::X).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert!(ctx.last_upload_bytes() > (W * W * 16) as u64, "the first launch uploads everything");
    // Nothing changed: the log's counters and the launch uniform only.
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.last_upload_bytes(), 16 + 48);
    // A new value: the page of records holding it.
    ctx.set_var(mat, "color", Vec3::Z).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert!(ctx.last_upload_bytes() <= 16 + 48 + 4096, "{} bytes", ctx.last_upload_bytes());
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::Z);
    // Host writes reach the device: a launch over a quarter of the image
    // leaves the rest as the host wrote it.
    ctx.write_buffer(out, &vec![Vec4::ONE; (W * W) as usize]).unwrap();
    ctx.launch(0, W / 2, W / 2).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(pixel(&img, W - 1, W - 1), Vec4::ONE);
    assert_eq!(pixel(&img, 0, 0).truncate(), BG);
    // And the launch's writes reach the host after every launch.
    ctx.set_var(mat, "color", Vec3::Y).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::Y);
}

#[test]
fn an_unchanged_scene_is_encoded_once_and_every_change_reaches_the_device() {
    use glam::Mat4;
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    let (sphere, mat, _) = sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::new(-1.0, 0.0, 0.0), 0.5);
    ctx.set_var(Scope::Context, "color", Vec3::X).unwrap();
    // The colours at the sphere's centre and at (0.94, 0.06), right of it.
    let render = |ctx: &mut Context| {
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        (pixel(&img, W / 4, W / 2).truncate(), pixel(&img, 3 * W / 4 - 1, W / 2).truncate())
    };
    assert_eq!(render(&mut ctx), (Vec3::X, BG));
    assert_eq!(ctx.scene_encodes(), 1);
    // Values and buffers: the scene stays on the device as it is.
    ctx.set_var(mat, "color", Vec3::Y).unwrap();
    ctx.write_buffer(out, &vec![Vec4::ONE; (W * W) as usize]).unwrap();
    let extra = ctx.create_buffer(BufferType::Input, vec![1.0f32; 64]);
    ctx.set_var(Scope::Context, "unused", extra).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, BG));
    assert_eq!(render(&mut ctx), (Vec3::Y, BG));
    assert_eq!(ctx.scene_encodes(), 1);
    // Every structural change is encoded again and shows in the image.
    let normals = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, normals).unwrap();
    let (centre, _) = render(&mut ctx);
    assert!((centre - Vec3::new(0.5, 0.5, 1.0)).abs().max_element() < 0.1, "{centre}");
    assert_eq!(ctx.scene_encodes(), 2);
    let flat = ctx.create_program(&flat_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, flat).unwrap();
    // A quad under a transform, beside the sphere and out of view.
    let g = ctx.create_triangles(quad(0.0, 0.25)).unwrap();
    let qi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let qg = ctx.create_geometry_group(&[qi], Acceleration::default()).unwrap();
    let xf = ctx.create_transform(Mat4::from_translation(Vec3::new(0.0, 1.5, 0.0)), qg).unwrap();
    let top = ctx.create_group(&[sphere, xf], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, BG));
    assert_eq!(ctx.scene_encodes(), 3);
    // Moved onto the right-hand point.
    ctx.set_transform(xf, Mat4::from_translation(Vec3::new(0.9, 0.0, 0.0))).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, Vec3::Y));
    assert_eq!(ctx.scene_encodes(), 4);
    // Hidden by its visibility mask, then shown again.
    ctx.set_visibility_mask(xf, 0).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, BG));
    ctx.set_visibility_mask(xf, 0xff).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, Vec3::Y));
    assert_eq!(ctx.scene_encodes(), 6);
    // Its vertices moved back by the transform's offset.
    let moved: Vec<Vec3> = quad(0.0, 0.25).positions.iter().map(|p| *p - Vec3::new(0.9, 0.0, 0.0)).collect();
    ctx.set_triangle_positions(g, moved).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, BG));
    assert_eq!(ctx.scene_encodes(), 7);
    // The geometry went up with the first launch, the new quad, and its
    // moved vertices; every other change encoded only the rest around it.
    assert_eq!(ctx.geometry_encodes(), 3);
    // A new miss program.
    let miss = ctx.create_program(&flat_miss::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    assert_eq!(render(&mut ctx), (Vec3::Y, Vec3::ONE));
    assert_eq!(ctx.scene_encodes(), 8);
    // And nothing changed: nothing encoded.
    assert_eq!(render(&mut ctx), (Vec3::Y, Vec3::ONE));
    assert_eq!(ctx.scene_encodes(), 8);
}

#[test]
fn an_any_hit_program_added_later_switches_the_kernel_to_bvh2s_and_the_image_stays() {
    // The grid shifted off the pixel diagonal: no ray meets a shared edge,
    // where either triangle may win.
    let mut grid = bumpy_grid(30);
    for p in &mut grid.positions {
        p.x += 0.0137;
    }
    let render = |backend, any_hit: bool| {
        let (mut ctx, out) = camera(1.2, backend);
        let (_, mat) = mesh_scene(&mut ctx, grid.clone(), &normal_shader::PROGRAM);
        ctx.launch(0, W, W).unwrap();
        if backend == Backend::Wgpu {
            assert!(ctx.linked_wgsl().unwrap().contains("const RT_CWBVH: bool = true;"));
        }
        let first = ctx.read_buffer::<Vec4>(out).unwrap();
        if !any_hit {
            return (first, None, ctx);
        }
        // The closest hit overwrites what the any hit adds: the same image.
        let ah = ctx.create_program(&count_hits::PROGRAM);
        ctx.set_any_hit_program(mat, 0, ah).unwrap();
        ctx.launch(0, W, W).unwrap();
        let second = ctx.read_buffer::<Vec4>(out).unwrap();
        (first, Some(second), ctx)
    };
    let (walked_wide, walked_binary, ctx) = render(Backend::Wgpu, true);
    let wgsl = ctx.linked_wgsl().unwrap();
    assert!(wgsl.contains("const RT_TRIANGLES_ONLY: bool = false;") && wgsl.contains("const RT_CWBVH: bool = false;"));
    let (cpu, ..) = render(Backend::Cpu, false);
    let hits = cpu.iter().filter(|c| c.truncate() != BG).count();
    assert!(hits > (W * W / 2) as usize, "{hits} pixels hit");
    assert!(largest_difference(&walked_wide, &cpu) < 2.0 / 255.0, "CWBVH search against the CPU backend");
    let walked_binary = walked_binary.expect("rendered with the any hit");
    assert!(largest_difference(&walked_binary, &cpu) < 2.0 / 255.0, "BVH2 search against the CPU backend");
}

#[test]
fn a_scene_over_the_adapters_binding_limit_is_a_clear_error() {
    // A device whose storage bindings hold at most 1 MiB.
    let instance = rt_runtime::backend::wgpu::instance();
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect("an adapter (lavapipe)");
    let limits = ::wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..::wgpu::Limits::downlevel_defaults() };
    let (device, queue) = pollster::block_on(
        adapter.request_device(&::wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
    )
    .unwrap();
    let (mut ctx, _) = camera(2.0, Backend::Wgpu);
    ctx.use_wgpu_device(device, queue, adapter.get_info());
    sphere_scene(&mut ctx, &reads_past_the_end::PROGRAM, Vec3::ZERO, 1.0);
    let table = ctx.create_buffer(BufferType::Input, vec![0.5f32; 1 << 19]);
    ctx.set_var(Scope::Context, "table", table).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(
        err.contains("the heap (variables, buffers, textures) needs 2.0 MiB") && err.contains("binds at most 1 MiB"),
        "{err}"
    );
}

#[test]
fn the_device_times_the_kernel_where_it_has_timestamps() {
    let instance = rt_runtime::backend::wgpu::instance();
    let adapter = pollster::block_on(instance.request_adapter(&::wgpu::RequestAdapterOptions {
        power_preference: ::wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .expect("an adapter (lavapipe)");
    let timestamps = adapter.features().contains(::wgpu::Features::TIMESTAMP_QUERY);
    // The runtime's own device asks for timestamps where the adapter has them.
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    ctx.launch(0, W, W).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(report.timings.kernel.is_some(), timestamps, "{:?} on {}", report.timings, adapter.get_info().name);
    if let Some(kernel) = report.timings.kernel {
        assert!(kernel > std::time::Duration::ZERO && kernel <= report.timings.run, "{:?}", report.timings);
    }
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), 0, 0).truncate(), BG);
    // A device the application opened without them: no kernel time, same
    // image.
    let (device, queue, info) = device_with(|l| l);
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    ctx.use_wgpu_device(device, queue, info);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let report = ctx.launch(0, W, W).unwrap();
    assert_eq!(report.timings.kernel, None);
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), 0, 0).truncate(), BG);
}

/// A device on the adapter with `limits` over the downlevel defaults (the
/// knob for the binding tests below: the runtime takes a device's own
/// limits as they are).
fn device_with(
    limits: impl FnOnce(::wgpu::Limits) -> ::wgpu::Limits,
) -> (::wgpu::Device, ::wgpu::Queue, ::wgpu::AdapterInfo) {
    let instance = rt_runtime::backend::wgpu::instance();
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect("an adapter (lavapipe)");
    // As the runtime asks: a storage buffer per scene section, heap and log.
    let limits = limits(::wgpu::Limits {
        max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
        max_storage_buffers_per_shader_stage: adapter.limits().max_storage_buffers_per_shader_stage.min(5),
        ..::wgpu::Limits::downlevel_defaults()
    });
    let (device, queue) = pollster::block_on(
        adapter.request_device(&::wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
    )
    .unwrap();
    (device, queue, adapter.get_info())
}

/// A bumpy `n` x `n` grid of quads over [-1, 1]^2 (2 n^2 triangles).
fn bumpy_grid(n: u32) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for y in 0..=n {
        for x in 0..=n {
            let (u, v) = (x as f32 / n as f32 * 2.0 - 1.0, y as f32 / n as f32 * 2.0 - 1.0);
            mesh.positions.push(Vec3::new(u, v, 0.2 * (5.0 * u).sin() * (4.0 * v).cos()));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            mesh.indices.push([i, i + 1, i + n + 2]);
            mesh.indices.push([i, i + n + 2, i + n + 1]);
        }
    }
    mesh
}

/// A geometry group over the `n` x `n` bumpy grid under the normal shader.
fn grid_group(ctx: &mut Context, n: u32) -> NodeId {
    grid_group_with(ctx, n, false)
}

/// The same, with an any-hit program (the wgpu kernel walks BVH2s then).
fn grid_group_with(ctx: &mut Context, n: u32, any_hit: bool) -> NodeId {
    let g = ctx.create_triangles(bumpy_grid(n)).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    if any_hit {
        let ah = ctx.create_program(&count_hits::PROGRAM);
        ctx.set_any_hit_program(mat, 0, ah).unwrap();
    }
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap()
}

/// The bumpy grid (20,000 triangles: about 0.5 MiB of tables, 1.2 MiB of
/// BVH nodes, 0.8 MiB of leaf-ordered triangles) under the normal shader.
fn render_grid(ctx: &mut Context, out: BufferId) -> Vec<Vec4> {
    let gg = grid_group(ctx, 100);
    let xf = ctx.create_transform(glam::Mat4::from_rotation_x(0.5), gg).unwrap();
    let top = ctx.create_group(&[xf], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    ctx.read_buffer::<Vec4>(out).unwrap()
}

#[test]
fn a_scene_larger_than_one_binding_renders_from_one_binding_per_section() {
    // The whole scene (about 1.5 MiB) exceeds a 1 MiB binding; its
    // tables, BVH nodes and leaf-ordered triangles each fit.
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let (device, queue, info) = device_with(|l| ::wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..l });
    ctx.use_wgpu_device(device, queue, info);
    let split = render_grid(&mut ctx, out);
    assert!(ctx.linked_wgsl().unwrap().contains("var<storage, read> rt_bvh: array<u32>;"));
    // A device with room for the scene in one binding but too few storage
    // buffers for one per section: every section in rt_scene's binding.
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let (device, queue, info) = device_with(|l| ::wgpu::Limits { max_storage_buffers_per_shader_stage: 3, ..l });
    ctx.use_wgpu_device(device, queue, info);
    let merged = render_grid(&mut ctx, out);
    let wgsl = ctx.linked_wgsl().unwrap();
    assert!(!wgsl.contains("rt_bvh") && wgsl.contains("rt_scene[rt_scene[9u] + w]"), "merged BVH section");
    // Triangles, no any-hit program, a group: the lean triangle search
    // under the group's loop.
    assert!(wgsl.contains("const RT_TRIANGLES_ONLY: bool = true;") && wgsl.contains("const RT_GROUPS: bool = true;"));
    // The default device, and the CPU backend.
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let default = render_grid(&mut ctx, out);
    let (mut ctx, out) = camera(1.2, Backend::Cpu);
    let cpu = render_grid(&mut ctx, out);
    let hits = cpu.iter().filter(|c| c.truncate() != BG).count();
    assert!(hits > (W * W / 2) as usize, "{hits} pixels hit");
    assert_eq!(split, merged, "one binding per section and all in one binding differ");
    assert_eq!(split, default);
    let worst = largest_difference(&cpu, &split);
    assert!(worst < 2.0 / 255.0, "largest difference from the CPU backend {worst}");
}

#[test]
fn moving_a_transform_keeps_the_geometry_on_the_device_and_renders_as_a_fresh_context() {
    use glam::Mat4;
    // The grid (about 1.5 MiB of geometry) under a transform in a group.
    let scene = |ctx: &mut Context, angle: f32| {
        let gg = grid_group(ctx, 100);
        let xf = ctx.create_transform(Mat4::from_rotation_x(angle), gg).unwrap();
        let top = ctx.create_group(&[xf], Acceleration::new(Builder::Bvh)).unwrap();
        ctx.set_var(Scope::Context, "top", top).unwrap();
        xf
    };
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let xf = scene(&mut ctx, 0.5);
    ctx.launch(0, W, W).unwrap();
    assert!(ctx.last_upload_bytes() > 1 << 20, "the first launch uploads the grid");
    for angle in [0.3, -0.4] {
        ctx.set_transform(xf, Mat4::from_rotation_x(angle)).unwrap();
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        // The tables' header, the instance's matrices and the group's BVH:
        // a few pages, not the grid.
        assert!(ctx.last_upload_bytes() < 32 << 10, "{} bytes uploaded", ctx.last_upload_bytes());
        assert_eq!((ctx.scene_encodes(), ctx.geometry_encodes()), (2 + (angle < 0.0) as u64, 1));
        let moved = ctx.read_buffer::<Vec4>(out).unwrap();
        let (mut fresh, fresh_out) = camera(1.2, Backend::Wgpu);
        scene(&mut fresh, angle);
        fresh.launch(0, W, W).unwrap();
        let expected = fresh.read_buffer::<Vec4>(fresh_out).unwrap();
        let hits = expected.iter().filter(|c| c.truncate() != BG).count();
        assert!(hits > (W * W / 4) as usize, "{hits} pixels hit at angle {angle}");
        assert_eq!(largest_difference(&moved, &expected), 0.0, "angle {angle}");
    }
}

#[test]
fn triangles_with_a_material_index_past_the_materials_are_never_hit() {
    // Every third triangle names material 2 of an instance with two: the
    // lean triangle search (no any-hit program, no group) skips them, as
    // the CPU backend does.
    let render = |backend| {
        let (mut ctx, out) = camera(1.2, backend);
        let mut mesh = bumpy_grid(6);
        mesh.material_indices = Some((0..mesh.indices.len() as u32).map(|i| i % 3).collect());
        let g = ctx.create_triangles(mesh).unwrap();
        let (a, b) = (ctx.create_material(), ctx.create_material());
        let ch = ctx.create_program(&normal_shader::PROGRAM);
        ctx.set_closest_hit_program(a, 0, ch).unwrap();
        ctx.set_closest_hit_program(b, 0, ch).unwrap();
        let gi = ctx.create_geometry_instance(g, &[a, b]).unwrap();
        let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", gg).unwrap();
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        if backend == Backend::Wgpu {
            let wgsl = ctx.linked_wgsl().unwrap();
            assert!(
                wgsl.contains("const RT_TRIANGLES_ONLY: bool = true;")
                    && wgsl.contains("const RT_GROUPS: bool = false;")
            );
        }
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let (cpu, gpu) = (render(Backend::Cpu), render(Backend::Wgpu));
    let holes = cpu.iter().filter(|c| c.truncate() == BG).count();
    assert!(holes > 100 && holes < (W * W - 100) as usize, "{holes} background pixels");
    let worst = largest_difference(&cpu, &gpu);
    assert!(worst < 2.0 / 255.0, "largest difference from the CPU backend {worst}");
}

#[test]
fn a_scene_section_over_the_binding_limit_is_a_clear_error() {
    // The grid's BVH2 nodes (about 1.2 MiB: with an any-hit program the
    // kernel walks BVH2s) cannot fit a 1 MiB binding.
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let (device, queue, info) = device_with(|l| ::wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..l });
    ctx.use_wgpu_device(device, queue, info);
    let gg = grid_group_with(&mut ctx, 100, true);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err();
    assert!(matches!(err, RtError::Gpu(_)), "{err:?}");
    let err = err.to_string();
    assert!(
        err.contains("the scene's BVH nodes needs 1.2 MiB")
            && err.contains("llvmpipe")
            && err.contains("binds at most 1 MiB per storage buffer"),
        "{err}"
    );
    let _ = out;
}

#[test]
fn a_heap_over_the_binding_limit_is_a_clear_error() {
    // A 512x512 output of Vec4 (4 MiB) cannot fit a 1 MiB binding; the
    // scene can.
    let (mut ctx, _) = camera(1.2, Backend::Wgpu);
    let (device, queue, info) = device_with(|l| ::wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..l });
    ctx.use_wgpu_device(device, queue, info);
    let big = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 512, 512).unwrap();
    ctx.write_buffer(big, &vec![Vec4::ONE; 512 * 512]).unwrap();
    ctx.set_var(Scope::Context, "out", big).unwrap();
    let gg = grid_group(&mut ctx, 4);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err();
    assert!(matches!(err, RtError::Gpu(_)), "{err:?}");
    let err = err.to_string();
    assert!(
        err.contains("the heap (variables, buffers, textures) needs 4.0 MiB")
            && err.contains("binds at most 1 MiB per storage buffer"),
        "{err}"
    );
    // Nothing was written: the buffer holds what the host put there.
    assert!(ctx.read_buffer::<Vec4>(big).unwrap().iter().all(|p| *p == Vec4::ONE));
}
