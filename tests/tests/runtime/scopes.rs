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
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    let wrong = ctx.create_program(&normal_shader::PROGRAM);
    let err = ctx.set_miss_program(0, wrong).unwrap_err().to_string();
    assert!(err.contains("is a ClosestHit program, but ray type 0's miss takes a Miss program"), "{err}");
    assert!(matches!(ctx.launch(0, 0, 4), Err(RtError::Launch(LaunchError::BadLaunch { .. }))));
}

/// The ortho camera's rays of ray type 2, their payload starting at `start`.
#[rt_program(ray_generation)]
pub fn ortho_ray_type_2(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] extent: f32, #[var] start: Vec3) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * extent, p.y * extent, 10.0), vec3(0.0, 0.0, -1.0), 2, 0.0, f32::INFINITY);
    let mut prd = Radiance { result: start, depth: 0 };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.result.extend(1.0);
}

/// A miss program is optional, as in OptiX: a ray type without one links,
/// and its rays that miss leave the payload as it was (as do its rays that
/// hit a material without a closest hit for it); the other ray types keep
/// theirs.
pub(crate) fn a_ray_type_without_a_miss_program_leaves_the_payload(backend: On) {
    let (mut ctx, out) = camera(2.0, backend);
    ctx.set_ray_type_count(3);
    sphere_scene(&mut ctx, &normal_shader::PROGRAM, Vec3::ZERO, 1.0);
    ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(pixel(&img, 0, 0).truncate(), BG);
    assert!((pixel(&img, W / 2, W / 2).truncate() - Vec3::new(0.5, 0.5, 1.0)).abs().max_element() < 0.1);

    let start = Vec3::new(0.25, 0.5, 0.75);
    let rg = ctx.create_program(&ortho_ray_type_2::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    ctx.set_var(Scope::Context, "start", start).unwrap();
    ctx.launch(0, W, W).unwrap();
    let img = ctx.read_buffer::<Vec4>(out).unwrap();
    assert_eq!(pixel(&img, 0, 0).truncate(), start, "a miss of ray type 2");
    assert_eq!(pixel(&img, W / 2, W / 2).truncate(), start, "a hit of ray type 2");
}
