//! Exceptions: the trace-depth limit, user exceptions, the default
//! exception program, buffer overruns (with `rt_printf!` reaching the
//! host), NaN rays and payloads of the wrong ray type.

use super::*;

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

pub(crate) fn payload_of_the_wrong_ray_type_raises_invalid_ray(backend: On) {
    let (mut ctx, _) = camera(2.0, backend);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::new(0.0, 0.0, 5.0), 1.0);
    let rg = ctx.create_program(&wrong_payload_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, 2, 1).unwrap();
    assert_eq!(report.exceptions.len(), 2);
    assert!(report.exceptions.iter().all(|e| e.code == EXCEPTION_INVALID_RAY), "{:?}", report.exceptions);
}
