//! What only the wgpu backend has: agreement with the CPU backend, relinks,
//! uploads, binding limits, timestamps and scene residency.

use super::*;

#[test]
pub(crate) fn wgpu_and_cpu_render_the_same_sphere() {
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
pub(crate) fn wgpu_and_cpu_render_the_same_deep_graph() {
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
pub(crate) fn changing_values_never_relinks_but_changing_programs_does() {
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
pub(crate) fn launches_upload_only_what_changed_and_host_writes_reach_the_device() {
    let (mut ctx, out) = camera(2.0, Backend::Wgpu);
    let (_, mat, _) = sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    ctx.set_var(Scope::Context, "color", Vec3::X).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert!(ctx.last_upload_bytes() > (W * W * 16) as u64, "the first launch uploads everything");
    // Nothing changed: the log's counters and the launch uniform only.
    let uniform = (rt_abi::records::LaunchUniform::WORDS * 4) as u64;
    ctx.launch(0, W, W).unwrap();
    assert_eq!(ctx.last_upload_bytes(), 16 + uniform);
    // A new value: the page of records holding it.
    ctx.set_var(mat, "color", Vec3::Z).unwrap();
    ctx.launch(0, W, W).unwrap();
    assert!(ctx.last_upload_bytes() <= 16 + uniform + 4096, "{} bytes", ctx.last_upload_bytes());
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
pub(crate) fn an_unchanged_scene_is_encoded_once_and_every_change_reaches_the_device() {
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
pub(crate) fn an_any_hit_program_added_later_switches_the_kernel_to_bvh2s_and_the_image_stays() {
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
pub(crate) fn a_scene_over_the_adapters_binding_limit_is_a_clear_error() {
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
pub(crate) fn the_device_times_the_kernel_where_it_has_timestamps() {
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
pub(crate) fn device_with(
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

pub(crate) use rt_tests::meshes::bumpy_grid;

/// A geometry group over the `n` x `n` bumpy grid under the normal shader.
pub(crate) fn grid_group(ctx: &mut Context, n: u32) -> NodeId {
    grid_group_with(ctx, n, false)
}

/// The same, with an any-hit program (the wgpu kernel walks BVH2s then).
pub(crate) fn grid_group_with(ctx: &mut Context, n: u32, any_hit: bool) -> NodeId {
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
pub(crate) fn render_grid(ctx: &mut Context, out: BufferId) -> Vec<Vec4> {
    let gg = grid_group(ctx, 100);
    let xf = ctx.create_transform(glam::Mat4::from_rotation_x(0.5), gg).unwrap();
    let top = ctx.create_group(&[xf], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    ctx.read_buffer::<Vec4>(out).unwrap()
}

#[test]
pub(crate) fn a_scene_larger_than_one_binding_renders_from_one_binding_per_section() {
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
pub(crate) fn moving_a_transform_keeps_the_geometry_on_the_device_and_renders_as_a_fresh_context() {
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
pub(crate) fn triangles_with_a_material_index_past_the_materials_are_never_hit() {
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
pub(crate) fn a_scene_section_over_the_binding_limit_is_a_clear_error() {
    // The grid's BVH2 nodes (about 1.2 MiB: with an any-hit program the
    // kernel walks BVH2s) cannot fit a 1 MiB binding.
    let (mut ctx, out) = camera(1.2, Backend::Wgpu);
    let (device, queue, info) = device_with(|l| ::wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..l });
    ctx.use_wgpu_device(device, queue, info);
    let gg = grid_group_with(&mut ctx, 100, true);
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let err = ctx.launch(0, W, W).unwrap_err();
    assert!(matches!(err, RtError::Device(DeviceError::BindingLimit { .. })), "{err:?}");
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
pub(crate) fn a_heap_over_the_binding_limit_is_a_clear_error() {
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
    assert!(matches!(err, RtError::Device(DeviceError::BindingLimit { .. })), "{err:?}");
    let err = err.to_string();
    assert!(
        err.contains("the heap (variables, buffers, textures) needs 4.0 MiB")
            && err.contains("binds at most 1 MiB per storage buffer"),
        "{err}"
    );
    // Nothing was written: the buffer holds what the host put there.
    assert!(ctx.read_buffer::<Vec4>(big).unwrap().iter().all(|p| *p == Vec4::ONE));
}
