//! Any-hit programs, ray flags and visibility masks: a shadow cast by an
//! any hit that terminates, every flag and mask on stacked quads, and
//! culling in the wgpu kernel's lean triangle search.

use super::*;

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
    // The compute traversal's lean search over the CWBVH (ray queries walk
    // the device's structures).
    if ctx.traversal().is_some_and(|(t, _)| t == Traversal::Compute) {
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(
            wgsl.contains("const RT_TRIANGLES_ONLY: bool = true;") && wgsl.contains("const RT_CWBVH: bool = true;")
        );
    }
}

pub(crate) fn pixel8(img: &[Vec4], x: u32, y: u32) -> Vec4 {
    img[(y * 8 + x) as usize]
}
