//! Variables by scope: the innermost scope that sets a variable wins, and
//! a link error names the program, the variable and the scopes searched.

use super::*;

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
