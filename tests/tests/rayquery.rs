//! The ray-query traversal's mappings, each with values known analytically
//! and checked against the CPU backend and the compute traversal: the path
//! really runs (its counters and its WGSL), an intersection program's two
//! candidates (entry rejected, exit accepted), a moved transform rebuilds
//! only the TLAS and moved vertices only their BLAS (counted), 10,000
//! instances, a selector scene falling back to the compute traversal with
//! its reason, no host tree built for ray queries (one built when a launch
//! falls back), and the errors: ray queries forced on a device without
//! them, a scene over the device's TLAS limit. (The runtime suite runs its
//! any-hit, culling, flag and mask tests on this traversal too.)
//!
//! Tests that need an adapter with ray queries pass with a note where there
//! is none (see `rt_tests::targets`).

use glam::{Mat4, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Probe {
    pub t: f32,
    pub color: Vec3,
}

#[rt_attributes]
pub struct Normal {
    pub geometric_normal: Vec3,
}

/// An orthographic camera at height `z` looking down -z over
/// `[-extent, extent]^2`; writes (color, t).
#[rt_program(ray_generation)]
pub fn down(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] extent: f32, #[var] z: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * extent, p.y * extent, z), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY);
    let mut prd = Probe { t: -1.0, color: Vec3::ZERO };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.color.extend(prd.t);
}

/// The hit's distance and its instance's origin in world space.
#[rt_program(closest_hit)]
pub fn where_hit(prd: &mut Probe) {
    prd.t = t_hit();
    prd.color = rt_transform_point(TransformKind::ObjectToWorld, Vec3::ZERO);
}

#[rt_program(miss)]
pub fn nothing(prd: &mut Probe) {
    prd.t = -1.0;
}

/// A sphere at the origin of radius `radius`: its entry, else its exit.
#[rt_program(intersection)]
pub fn ball(prim: u32, attr: &mut Normal, #[var] radius: f32) {
    let _ = prim;
    let ray = current_ray();
    let b = ray.origin.dot(ray.direction);
    let a = ray.direction.dot(ray.direction);
    let c = ray.origin.dot(ray.origin) - radius * radius;
    let disc = b * b - a * c;
    if disc > 0.0 {
        let s = disc.sqrt();
        let t0 = (-b - s) / a;
        let t1 = (-b + s) / a;
        if rt_potential_intersection(t0) {
            attr.geometric_normal = (ray.origin + t0 * ray.direction) / radius;
            rt_report_intersection(0);
        } else if rt_potential_intersection(t1) {
            attr.geometric_normal = (ray.origin + t1 * ray.direction) / radius;
            rt_report_intersection(0);
        }
    }
}

#[rt_program(bounding_box)]
pub fn ball_bounds(prim: u32, #[var] radius: f32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::splat(-radius), Vec3::splat(radius))
}

#[rt_program(visit)]
pub fn first_child(prd: &Probe) -> u32 {
    let _ = prd.t;
    0
}

/// Like `down` over `[-1, 1]^2` from height 5, tracing rays of type
/// `ray_type`.
#[rt_program(ray_generation)]
pub fn down_typed(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] ray_type: u32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x, p.y, 5.0), vec3(0.0, 0.0, -1.0), ray_type, 0.0, f32::INFINITY);
    let mut prd = Probe { t: -1.0, color: Vec3::ZERO };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.color.extend(prd.t);
}

/// Lets every candidate through.
#[rt_program(any_hit)]
pub fn see_through(prd: &mut Probe) {
    let _ = prd.t;
    rt_ignore_intersection();
}

const W: u32 = 16;

/// A context on `on` with the camera at height `z` over `[-extent,
/// extent]^2`, a miss program and the output buffer.
fn camera(on: On, extent: f32, z: f32) -> (Context, BufferId) {
    let mut ctx = on.context();
    let rg = ctx.create_program(&down::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, W).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "extent", extent).unwrap();
    ctx.set_var(Scope::Context, "z", z).unwrap();
    (ctx, out)
}

/// A material with `where_hit` as its closest hit.
fn material(ctx: &mut Context) -> MaterialId {
    let mat = ctx.create_material();
    let ch = ctx.create_program(&where_hit::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    mat
}

/// A unit quad in z = 0 over [-s, s]^2 as a geometry group.
fn quad(ctx: &mut Context, s: f32) -> (NodeId, GeometryId) {
    let mesh = TriangleMesh {
        positions: vec![Vec3::new(-s, -s, 0.0), Vec3::new(s, -s, 0.0), Vec3::new(s, s, 0.0), Vec3::new(-s, s, 0.0)],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Default::default()
    };
    let geom = ctx.create_triangles(mesh).unwrap();
    let mat = material(ctx);
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    (ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap(), geom)
}

fn image(ctx: &mut Context, out: BufferId) -> Vec<Vec4> {
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    ctx.read_buffer::<Vec4>(out).unwrap()
}

/// The pixel centre's world position.
fn world(x: u32, y: u32, extent: f32) -> (f32, f32) {
    let p = |i: u32| ((i as f32 + 0.5) / W as f32 * 2.0 - 1.0) * extent;
    (p(x), p(y))
}

fn assert_ray_queries_ran(ctx: &Context) {
    let (traversal, why) = ctx.traversal().expect("a wgpu launch");
    assert_eq!(traversal, Traversal::RayQuery, "{why}");
    assert!(ctx.linked_wgsl().unwrap().contains("rayQueryProceed"));
}

#[test]
fn ray_queries_run_and_hit_what_the_other_targets_hit() {
    if !On::RAY_QUERY.available() {
        return;
    }
    let mut images = Vec::new();
    for on in On::ALL {
        let (mut ctx, out) = camera(on, 1.0, 5.0);
        let (gg, _) = quad(&mut ctx, 0.5);
        let t = ctx.create_transform(Mat4::from_translation(Vec3::new(0.25, 0.0, 1.0)), gg).unwrap();
        ctx.set_var(Scope::Context, "top", t).unwrap();
        let img = image(&mut ctx, out);
        if on == On::RAY_QUERY {
            assert_ray_queries_ran(&ctx);
            assert_eq!(ctx.ray_query_builds(), (1, 1));
        }
        for y in 0..W {
            for x in 0..W {
                let (wx, wy) = world(x, y, 1.0);
                let inside = (wx - 0.25).abs() < 0.5 && wy.abs() < 0.5;
                let p = img[(y * W + x) as usize];
                if inside {
                    assert_eq!(p, Vec4::new(0.25, 0.0, 1.0, 4.0), "{} pixel {x},{y}", on.name());
                } else {
                    assert_eq!(p.w, -1.0, "{} pixel {x},{y}", on.name());
                }
            }
        }
        images.push(img);
    }
    assert_eq!(images[0], images[2]);
}

/// The ray-query traversal walks the device's structures: it builds no
/// geometry group's tree on the host (but still refuses a builder no
/// backend has). A launch that falls back to the compute traversal (a
/// selector above the group) builds the tree then, from vertices moved
/// since; both traversals then draw the same image, and going back to ray
/// queries builds nothing more on the host.
#[test]
fn ray_query_launches_build_no_host_tree_and_a_fallback_builds_it() {
    if !On::RAY_QUERY.available() {
        return;
    }
    let (mut ctx, out) = camera(On::RAY_QUERY, 1.0, 5.0);
    let (gg, geom) = quad(&mut ctx, 0.5);
    let t = ctx.create_transform(Mat4::from_translation(Vec3::new(0.25, 0.0, 1.0)), gg).unwrap();
    ctx.set_var(Scope::Context, "top", t).unwrap();
    image(&mut ctx, out);
    assert_ray_queries_ran(&ctx);
    assert_eq!((ctx.geometry_trees_built(), ctx.ray_query_builds()), (0, (1, 1)));
    // Moved vertices: the BLAS again, still no tree.
    let s = 0.25;
    let moved = vec![Vec3::new(-s, -s, 0.0), Vec3::new(s, -s, 0.0), Vec3::new(s, s, 0.0), Vec3::new(-s, s, 0.0)];
    ctx.set_triangle_positions(geom, moved).unwrap();
    let rq = image(&mut ctx, out);
    assert_eq!((ctx.geometry_trees_built(), ctx.ray_query_builds()), (0, (2, 2)));
    let covered = rq.iter().filter(|p| p.w == 4.0).count();
    assert_eq!(covered, 16, "the moved quad covers 4 x 4 pixel centres");
    // Under a selector the scene cannot be flattened: the compute
    // traversal, whose tree is built now, over the moved vertices.
    let visit = ctx.create_program(&first_child::PROGRAM);
    let sel = ctx.create_selector(visit, &[t]).unwrap();
    ctx.set_var(Scope::Context, "top", sel).unwrap();
    assert_eq!(image(&mut ctx, out), rq);
    assert_eq!(ctx.traversal().unwrap().0, Traversal::Compute);
    assert_eq!(ctx.geometry_trees_built(), 1);
    // Ray queries again: the same image, nothing more built on the host.
    ctx.set_var(Scope::Context, "top", t).unwrap();
    assert_eq!(image(&mut ctx, out), rq);
    assert_ray_queries_ran(&ctx);
    assert_eq!(ctx.geometry_trees_built(), 1);
    // A builder no backend has is refused here too.
    let m = material(&mut ctx);
    let gi = ctx.create_geometry_instance(geom, &[m]).unwrap();
    let kd = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::TriangleKdTree)).unwrap();
    ctx.set_var(Scope::Context, "top", kd).unwrap();
    let e = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(e.starts_with("acceleration builder `TriangleKdTree` cannot be honoured: obvhs builds BVHs"), "{e}");
}

/// Rays starting inside a sphere: the entry (behind the origin) is
/// rejected by `rt_potential_intersection`, the exit is accepted and
/// generated, at t = sqrt(r^2 - x^2 - y^2).
#[test]
fn an_intersection_programs_entry_is_rejected_and_its_exit_accepted() {
    if !On::RAY_QUERY.available() {
        return;
    }
    for on in On::ALL {
        let (mut ctx, out) = camera(on, 1.0, 0.0);
        let isect = ctx.create_program(&ball::PROGRAM);
        let bounds = ctx.create_program(&ball_bounds::PROGRAM);
        let geom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
        ctx.set_var(geom, "radius", 2.0f32).unwrap();
        let mat = material(&mut ctx);
        let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
        let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", gg).unwrap();
        let img = image(&mut ctx, out);
        if on == On::RAY_QUERY {
            assert_ray_queries_ran(&ctx);
        }
        for y in 0..W {
            for x in 0..W {
                let (wx, wy) = world(x, y, 1.0);
                let exit = (4.0 - wx * wx - wy * wy).sqrt();
                let t = img[(y * W + x) as usize].w;
                assert!((t - exit).abs() < 1e-5, "{} pixel {x},{y}: t {t}, exit at {exit}", on.name());
            }
        }
    }
}

#[test]
fn a_moved_transform_rebuilds_the_tlas_only_and_moved_vertices_their_blas() {
    let on = On::RAY_QUERY;
    if !on.available() {
        return;
    }
    let (mut ctx, out) = camera(on, 1.0, 5.0);
    let (gg, geom) = quad(&mut ctx, 0.25);
    let t = ctx.create_transform(Mat4::IDENTITY, gg).unwrap();
    let (other, _) = quad(&mut ctx, 0.25);
    let t2 = ctx.create_transform(Mat4::from_translation(Vec3::new(-0.6, -0.6, 0.0)), other).unwrap();
    let top = ctx.create_group(&[t, t2], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    image(&mut ctx, out);
    assert_eq!(ctx.ray_query_builds(), (2, 1));
    // The same launch again: nothing rebuilt.
    image(&mut ctx, out);
    assert_eq!(ctx.ray_query_builds(), (2, 1));
    // A moved transform: the TLAS only.
    ctx.set_transform(t, Mat4::from_translation(Vec3::new(0.5, 0.5, 0.0))).unwrap();
    let img = image(&mut ctx, out);
    assert_eq!(ctx.ray_query_builds(), (2, 2));
    let at = |x: f32, y: f32| {
        let i = |v: f32| (((v + 1.0) / 2.0 * W as f32) as u32).min(W - 1);
        img[(i(y) * W + i(x)) as usize]
    };
    assert_eq!(at(0.5, 0.5), Vec4::new(0.5, 0.5, 0.0, 5.0));
    assert_eq!(at(0.0, 0.0).w, -1.0);
    // Moved vertices: that quad's BLAS (and the TLAS over it), not the other's.
    let raised: Vec<Vec3> = [(-0.25, -0.25), (0.25, -0.25), (0.25, 0.25), (-0.25, 0.25)]
        .iter()
        .map(|&(x, y)| Vec3::new(x, y, 1.0))
        .collect();
    ctx.set_triangle_positions(geom, raised).unwrap();
    let img = image(&mut ctx, out);
    assert_eq!(ctx.ray_query_builds(), (3, 3));
    let i = |v: f32| (((v + 1.0) / 2.0 * W as f32) as u32).min(W - 1);
    assert_eq!(img[(i(0.5) * W + i(0.5)) as usize], Vec4::new(0.5, 0.5, 0.0, 4.0));
    assert_eq!(img[(i(-0.6) * W + i(-0.6)) as usize].w, 5.0);
}

/// 10,000 transforms over one geometry group, a 100 x 100 grid of small
/// quads: every pixel centre hits the quad under it, whose origin the
/// closest hit reports.
#[test]
fn ten_thousand_instances_each_hit_where_it_is() {
    if !On::RAY_QUERY.available() {
        return;
    }
    const N: u32 = 100;
    let mut ctx = On::RAY_QUERY.context();
    let rg = ctx.create_program(&down::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, N, N).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "extent", 1.0f32).unwrap();
    ctx.set_var(Scope::Context, "z", 5.0f32).unwrap();
    let cell = 2.0 / N as f32;
    let (gg, _) = quad(&mut ctx, cell * 0.4);
    let centre = |i: u32| (i as f32 + 0.5) * cell - 1.0;
    let mut children = Vec::new();
    for y in 0..N {
        for x in 0..N {
            let m = Mat4::from_translation(Vec3::new(centre(x), centre(y), 0.0));
            children.push(ctx.create_transform(m, gg).unwrap());
        }
    }
    let top = ctx.create_group(&children, Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, N, N).unwrap();
    assert!(report.exceptions.is_empty());
    assert_ray_queries_ran(&ctx);
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    for y in 0..N {
        for x in 0..N {
            let p = img[(y * N + x) as usize];
            assert!(
                (p.x - centre(x)).abs() < 1e-5 && (p.y - centre(y)).abs() < 1e-5 && p.w == 5.0,
                "pixel {x},{y}: {p}"
            );
        }
    }
}

/// `Auto` on a software adapter (lavapipe) takes the compute traversal,
/// saying why; on an adapter without ray queries too.
#[test]
fn auto_takes_the_compute_traversal_on_a_software_adapter() {
    let Some(info) = rt_runtime::backend::wgpu::probe() else {
        eprintln!("skipped: no wgpu adapter");
        return;
    };
    if info.device_type != ::wgpu::DeviceType::Cpu {
        eprintln!("skipped: {} is not a software adapter", info.name);
        return;
    }
    let (mut ctx, out) = camera(On { traversal: Traversal::Auto, ..On::RAY_QUERY }, 1.0, 5.0);
    let (gg, _) = quad(&mut ctx, 0.5);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let img = image(&mut ctx, out);
    let (traversal, why) = ctx.traversal().unwrap();
    assert_eq!(traversal, Traversal::Compute);
    assert!(why.contains("software adapter") || why.contains("no ray queries"), "{why}");
    assert_eq!(img[(W / 2 * W + W / 2) as usize].w, 5.0);
}

#[test]
fn a_selector_scene_keeps_the_compute_traversal_and_says_why() {
    if !On::RAY_QUERY.available() {
        return;
    }
    // Asked for ray queries: the scene still cannot have them.
    let (mut ctx, out) = camera(On::RAY_QUERY, 1.0, 5.0);
    let (gg, _) = quad(&mut ctx, 0.5);
    let visit = ctx.create_program(&first_child::PROGRAM);
    let sel = ctx.create_selector(visit, &[gg]).unwrap();
    ctx.set_var(Scope::Context, "top", sel).unwrap();
    let img = image(&mut ctx, out);
    let (traversal, why) = ctx.traversal().unwrap();
    assert_eq!(traversal, Traversal::Compute);
    assert!(why.contains(&format!("node {} is a selector", sel.index())), "{why}");
    assert_eq!(img[(W / 2 * W + W / 2) as usize].w, 5.0);
}

/// A device opened without ray queries (as an application's may be): a
/// launch that asks for them fails naming the adapter and the feature.
#[test]
fn ray_queries_forced_on_a_device_without_them_fail_naming_the_adapter() {
    let instance = rt_runtime::backend::wgpu::instance();
    let Ok(adapter) = pollster::block_on(instance.request_adapter(&Default::default())) else {
        eprintln!("skipped: no wgpu adapter");
        return;
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&Default::default())).unwrap();
    let (mut ctx, _) = camera(On::RAY_QUERY, 1.0, 5.0);
    ctx.use_wgpu_device(device, queue, adapter.get_info());
    ctx.set_traversal(Traversal::RayQuery);
    let (gg, _) = quad(&mut ctx, 0.5);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(
        err.contains("the ray-query traversal was asked for")
            && err.contains(&adapter.get_info().name)
            && err.contains("EXPERIMENTAL_RAY_QUERY"),
        "{err}"
    );
    assert_eq!(ctx.geometry_trees_built(), 0);
    // Auto falls back to the compute traversal there, whose tree is built
    // then.
    ctx.set_traversal(Traversal::Auto);
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.traversal().unwrap().0, Traversal::Compute);
    assert_eq!(ctx.geometry_trees_built(), 1);
}

/// A device whose TLAS may hold 4 instances, and a scene of 5: a typed
/// error naming the root node and the limit, and the context still works
/// with the compute traversal.
#[test]
fn a_scene_over_the_devices_tlas_limit_is_an_error_naming_the_root() {
    if !On::RAY_QUERY.available() {
        return;
    }
    let instance = rt_runtime::backend::wgpu::instance();
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).unwrap();
    let limits = ::wgpu::Limits {
        max_tlas_instance_count: 4,
        max_blas_geometry_count: adapter.limits().max_blas_geometry_count,
        max_blas_primitive_count: adapter.limits().max_blas_primitive_count,
        max_acceleration_structures_per_shader_stage: adapter.limits().max_acceleration_structures_per_shader_stage,
        max_storage_buffers_per_shader_stage: adapter.limits().max_storage_buffers_per_shader_stage.min(6),
        max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
        ..::wgpu::Limits::downlevel_defaults()
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&::wgpu::DeviceDescriptor {
        required_features: ::wgpu::Features::EXPERIMENTAL_RAY_QUERY,
        required_limits: limits,
        // SAFETY: as the runtime opens its own devices (ray queries are
        // experimental in wgpu).
        experimental_features: unsafe { ::wgpu::ExperimentalFeatures::enabled() },
        ..Default::default()
    }))
    .unwrap();
    let (mut ctx, out) = camera(On::RAY_QUERY, 1.0, 5.0);
    ctx.use_wgpu_device(device, queue, adapter.get_info());
    let (gg, _) = quad(&mut ctx, 0.1);
    let children: Vec<NodeId> = (0..5)
        .map(|i| ctx.create_transform(Mat4::from_translation(Vec3::new(i as f32 * 0.3 - 0.6, 0.0, 0.0)), gg).unwrap())
        .collect();
    let top = ctx.create_group(&children, Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    match ctx.launch(0, W, W) {
        Err(RtError::Device(DeviceError::AccelerationLimit { node, count: 5, limit: 4, .. })) => {
            assert_eq!(node, top.index())
        }
        other => panic!("expected the TLAS limit error, got {other:?}"),
    }
    ctx.set_traversal(Traversal::Compute);
    let img = image(&mut ctx, out);
    assert!(img.iter().any(|p| p.w == 5.0));
}

/// Which ray types take the opaque path follows the materials: a ray type
/// without any-hit programs commits triangles in the hardware (the query
/// forced opaque), one with them sees its candidates; an any-hit program
/// set after a launch runs at the next (the BLAS's opacity follows), and a
/// material index out of range keeps every ray type on candidates, so that
/// its triangle is never hit. The hits agree on every target.
#[test]
fn any_hit_programs_decide_which_ray_types_take_the_opaque_path() {
    if !On::RAY_QUERY.available() {
        return;
    }
    for on in On::ALL {
        let name = on.name();
        let (mut ctx, out) = typed_camera(on, 2);
        let ch = ctx.create_program(&where_hit::PROGRAM);
        let through = ctx.create_program(&see_through::PROGRAM);
        let [solid, glass] = [(); 2].map(|_| {
            let m = ctx.create_material();
            for ray_type in 0..2 {
                ctx.set_closest_hit_program(m, ray_type, ch).unwrap();
            }
            m
        });
        let below = quad_of(&mut ctx, None, solid);
        let above = quad_of(&mut ctx, None, glass);
        let above = ctx.create_transform(Mat4::from_translation(Vec3::new(0.0, 0.0, 1.0)), above).unwrap();
        let top = ctx.create_group(&[below, above], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", top).unwrap();
        // No any-hit program: both types hit the upper quad, in the hardware.
        assert_eq!(centre_t(&mut ctx, out, 0), 4.0, "{name}");
        assert_eq!(centre_t(&mut ctx, out, 1), 4.0, "{name}");
        if on == On::RAY_QUERY {
            assert_ray_queries_ran(&ctx);
            assert_eq!(ctx.ray_query_opaque_ray_types(), Some(vec![true, true]), "{name}");
        }
        // An any-hit program for type 1, set after launches: type 1 sees
        // through the glass quad to the one below; type 0 still hits it.
        ctx.set_any_hit_program(glass, 1, through).unwrap();
        assert_eq!(centre_t(&mut ctx, out, 0), 4.0, "{name}");
        assert_eq!(centre_t(&mut ctx, out, 1), 5.0, "{name}");
        if on == On::RAY_QUERY {
            assert_eq!(ctx.ray_query_opaque_ray_types(), Some(vec![true, false]), "{name}");
        }
        // An any-hit program for type 0 too, set after launches: both see
        // through.
        ctx.set_any_hit_program(glass, 0, through).unwrap();
        assert_eq!(centre_t(&mut ctx, out, 0), 5.0, "{name}");
        assert_eq!(centre_t(&mut ctx, out, 1), 5.0, "{name}");
        if on == On::RAY_QUERY {
            assert_eq!(ctx.ray_query_opaque_ray_types(), Some(vec![false, false]), "{name}");
        }

        // No any-hit program anywhere, and a quad whose second triangle
        // ([0, 2, 3], above the diagonal) has a material index past its
        // one material: that triangle is never hit.
        let (mut ctx, out) = typed_camera(on, 1);
        let solid = ctx.create_material();
        let ch = ctx.create_program(&where_hit::PROGRAM);
        ctx.set_closest_hit_program(solid, 0, ch).unwrap();
        let gg = quad_of(&mut ctx, Some(vec![0, 1]), solid);
        ctx.set_var(Scope::Context, "top", gg).unwrap();
        ctx.set_var(Scope::Context, "ray_type", 0u32).unwrap();
        let img = image(&mut ctx, out);
        for y in 0..W {
            for x in 0..W {
                if x == y {
                    // On the edge the two triangles share.
                    continue;
                }
                let (wx, wy) = world(x, y, 1.0);
                let inside = wx.abs() < 0.5 && wy.abs() < 0.5;
                let expected = if inside && wy < wx { 5.0 } else { -1.0 };
                assert_eq!(img[(y * W + x) as usize].w, expected, "{name} pixel {x},{y}");
            }
        }
        if on == On::RAY_QUERY {
            assert_eq!(ctx.ray_query_opaque_ray_types(), Some(vec![false]), "{name}");
        }
    }
}

/// A context on `on` with `ray_types` ray types, `down_typed` as its ray
/// generation program, a miss program for each type and the output
/// buffer.
fn typed_camera(on: On, ray_types: u32) -> (Context, BufferId) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(ray_types);
    let rg = ctx.create_program(&down_typed::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    for ray_type in 0..ray_types {
        ctx.set_miss_program(ray_type, miss).unwrap();
    }
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, W).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    (ctx, out)
}

/// A quad over [-0.5, 0.5]^2 in z = 0 with material `mat` (and material
/// indices `indices`), as a geometry group.
fn quad_of(ctx: &mut Context, indices: Option<Vec<u32>>, mat: MaterialId) -> NodeId {
    let mesh = TriangleMesh {
        positions: vec![
            Vec3::new(-0.5, -0.5, 0.0),
            Vec3::new(0.5, -0.5, 0.0),
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(-0.5, 0.5, 0.0),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        material_indices: indices,
        ..Default::default()
    };
    let geom = ctx.create_triangles(mesh).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap()
}

/// The t the centre pixel's ray of type `ray_type` reports.
fn centre_t(ctx: &mut Context, out: BufferId, ray_type: u32) -> f32 {
    ctx.set_var(Scope::Context, "ray_type", ray_type).unwrap();
    image(ctx, out)[(W / 2 * W + W / 2) as usize].w
}
