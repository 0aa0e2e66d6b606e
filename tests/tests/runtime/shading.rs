//! Shading, transforms, any-hit, exceptions, variables, refits, flags and
//! masks, textures and selectors, on both backends.

use super::*;

pub(crate) fn sphere_silhouette_and_normals(backend: On) {
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

/// A closest-hit program calling `#[rt_impl]` methods (`rt_transform_normal`
/// inside an attribute method, `&mut self` on the payload) renders the
/// image `normal_shader` renders.
pub(crate) fn methods_of_the_payload_and_attributes_shade_as_the_fields_do(backend: On) {
    let extent = 2.0;
    let render = |shader: &'static rt_std::program::ProgramDescriptor| {
        let (mut ctx, out) = camera(extent, backend);
        sphere_scene(&mut ctx, shader, Vec3::new(0.25, -0.5, 0.0), 1.0);
        let report = ctx.launch(0, W, W).unwrap();
        assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
        ctx.read_buffer::<Vec4>(out).unwrap()
    };
    let fields = render(&normal_shader::PROGRAM);
    let methods = render(&normal_shader_by_methods::PROGRAM);
    let hits = fields.iter().filter(|c| c.truncate() != BG).count();
    assert!(hits > 100, "the sphere covers {hits} pixels");
    assert_eq!(fields, methods);
}

pub(crate) fn quad(z: f32, half: f32) -> TriangleMesh {
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
pub(crate) fn mesh_scene(
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

pub(crate) fn triangle_attributes_reach_closest_hit_through_a_transform(backend: On) {
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
pub(crate) fn rt_get_transform_reads_the_instance_transform_and_its_inverse(backend: On) {
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

pub(crate) fn any_hit_terminate_casts_a_shadow_with_a_sharp_edge(backend: On) {
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

pub(crate) fn trace_depth_limit_raises_the_exception_and_the_exception_program_runs(backend: On) {
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

pub(crate) fn user_exception_reaches_the_exception_program_and_other_pixels_are_untouched(backend: On) {
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

pub(crate) fn variables_resolve_innermost_scope_first(backend: On) {
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

pub(crate) fn link_errors_name_the_program_the_variable_and_the_scopes(backend: On) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &flat_color::PROGRAM, Vec3::ZERO, 1.0);
    let err = ctx.launch(0, W, W).unwrap_err().to_string();
    assert!(err.contains("variable `color`"), "{err}");
    assert!(err.contains("`flat_color`") && err.contains("runtime/main.rs:"), "{err}");
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

pub(crate) fn moving_geometry_refits_instead_of_rebuilding(backend: On) {
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
pub(crate) fn a_refit_mesh_renders_as_one_built_for_its_new_shape(backend: On) {
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

pub(crate) fn buffer_overrun_raises_the_exception_and_printf_reaches_the_host(backend: On) {
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

pub(crate) fn nan_rays_raise_invalid_ray(backend: On) {
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
pub(crate) fn one_triangle_and_an_empty_group(backend: On) {
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
pub(crate) fn flagged_quad(backend: On, any_hit: bool) -> (Context, BufferId, NodeId) {
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

pub(crate) fn ray_flags_and_masks(backend: On) {
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
pub(crate) fn culling_in_the_lean_search(backend: On) {
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

pub(crate) fn pixel8(img: &[Vec4], x: u32, y: u32) -> Vec4 {
    img[(y * 8 + x) as usize]
}

pub(crate) fn textures_sample_with_wrap_and_filter(backend: On) {
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

pub(crate) fn payload_of_the_wrong_ray_type_raises_invalid_ray(backend: On) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::new(0.0, 0.0, 5.0), 1.0);
    let rg = ctx.create_program(&wrong_payload_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, 2, 1).unwrap();
    assert_eq!(report.exceptions.len(), 2);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_INVALID_RAY), "{:?}", report.exceptions);
}

/// A flat-coloured sphere geometry group (custom primitives).
pub(crate) fn colored_sphere(ctx: &mut Context, center: Vec3, radius: f32, color: Vec3) -> NodeId {
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

pub(crate) fn selector_chooses_a_child_from_the_payload_and_launch_index_parity(backend: On) {
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

pub(crate) fn visit_programs_see_the_ray_in_the_selectors_space_and_check_the_payload_type(backend: On) {
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

pub(crate) fn three_level_graph_group_of_groups_of_transforms(backend: On) {
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
    if backend == On::COMPUTE {
        // The graph traversal is linked, with one transform level below world space.
        assert!(ctx.linked_wgsl().unwrap().contains("const RT_LEVELS: u32 = 2u;"));
    } else if backend == On::RAY_QUERY {
        // Flattened into one TLAS: no graph traversal.
        assert_eq!(ctx.traversal().map(|t| t.0), Some(Traversal::RayQuery));
        assert!(!ctx.linked_wgsl().unwrap().contains("RT_LEVELS"));
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

pub(crate) fn default_exception_paints_magenta_and_records_the_exception(backend: On) {
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
