//! Selectors: visit programs choosing a child from the payload, from the
//! ray in the selector's space, and checking the payload's type.

use super::*;

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
