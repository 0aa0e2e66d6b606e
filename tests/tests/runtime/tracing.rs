//! Recursive tracing (mirrors through helpers, match arms, per-depth
//! clones), wide launches and deep BVHs, on both backends.

use super::*;

pub(crate) fn mirror_shows_the_reflected_object_and_the_reflected_background(backend: On) {
    mirror_scene(backend, &mirror::PROGRAM, 20);
}

pub(crate) fn a_helper_that_traces_works_from_a_closest_hit(backend: On) {
    let ctx = mirror_scene(backend, &mirror_through_a_helper::PROGRAM, 20);
    if backend == Backend::Wgpu {
        // One loop runs the resumable forms: no per-depth clones.
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(wgsl.contains("fn rtf_reflected_color_rs(") && !wgsl.contains("_d1("));
    }
}

pub(crate) fn a_trace_in_a_match_arm_resumes_in_that_arm(backend: On) {
    assert!(mirror_in_a_match::PROGRAM.wgsl_resumable.is_some());
    let ctx = mirror_scene(backend, &mirror_in_a_match::PROGRAM, 20);
    if backend == Backend::Wgpu {
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(wgsl.contains("fn rtp_mirror_in_a_match(") && !wgsl.contains("_d1("));
    }
}

pub(crate) fn a_program_without_a_resumable_form_links_per_depth_clones(backend: On) {
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

pub(crate) fn a_helper_tracing_through_another_helper_links_per_depth_clones(backend: On) {
    assert!(mirror_through_two_helpers::PROGRAM.wgsl_resumable.is_none());
    let ctx = mirror_scene(backend, &mirror_through_two_helpers::PROGRAM, 3);
    if backend == Backend::Wgpu {
        let wgsl = ctx.linked_wgsl().unwrap();
        assert!(wgsl.contains("fn rtf_reflected_two_helpers_down_d1("), "the outer helper is cloned per depth too");
    }
}

/// A tilted mirror (closest hit `program`) reflecting a green wall and the
/// background, checked pixel by pixel, with a maximum trace depth of
/// `depth` (20: deep enough that per-depth clones would be many, so the
/// wgpu kernel runs resumable programs from its loop).
pub(crate) fn mirror_scene(backend: On, program: &'static rt_std::program::ProgramDescriptor, depth: u32) -> Context {
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
pub(crate) fn wgpu_kernel_size_does_not_grow_with_the_trace_depth() {
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

/// The same tracing program created twice (two cases of the closest-hit
/// switch) is called from one arm at each depth: a driver inlines every
/// call, so with per-depth clones two arms would double the traversal's
/// copies at every depth (31 at depth 5, more than lavapipe's memory).
#[test]
pub(crate) fn wgpu_kernel_calls_a_program_created_twice_from_one_arm() {
    let (mut ctx, _) = camera(1.0, Backend::Wgpu);
    ctx.set_max_trace_depth(3);
    sphere_scene(&mut ctx, &mirror_forever::PROGRAM, Vec3::ZERO, 1.0);
    sphere_scene(&mut ctx, &mirror_forever::PROGRAM, Vec3::ZERO, 1.0);
    let report = ctx.launch(0, W, W).unwrap();
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    let wgsl = ctx.linked_wgsl().unwrap();
    assert!(!wgsl.contains("fn rt_run("), "per-depth clones");
    // Its definition and one call, from an arm of two cases.
    assert_eq!(wgsl.matches("rtp_mirror_forever_d2(").count(), 2, "{wgsl}");
    let arm = wgsl.find("rtp_mirror_forever_d2(prd").map(|at| &wgsl[..at]).unwrap();
    let case = &arm[arm.rfind("case ").unwrap()..];
    assert!(case.starts_with("case ") && case.lines().next().unwrap().contains(", "), "{case}");
}

pub(crate) fn launches_wider_than_the_dispatch_limit_write_every_index(backend: On) {
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
/// seven leaves a node, over 32). The wgpu kernel's traversal stacks are
/// sized from the deepest BVH2 and CWBVH (a near-first traversal keeps at
/// most one pending entry per level), not a fixed 64 entries that would
/// drop entries when full: checked here, and every ray finds its triangle
/// on both backends.
pub(crate) fn a_bvh_deeper_than_64_levels_loses_no_hit(backend: On) {
    // Without an any-hit program the wgpu kernel walks the CWBVH (about a
    // third as deep, still past 32 levels); with one, the BVH2.
    for any_hit in [false, true] {
        deep_bvh_probe(backend, any_hit);
    }
}

pub(crate) fn deep_bvh_probe(backend: On, any_hit: bool) {
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
    // The compute traversal's stacks (ray queries walk the device's
    // structures: their kernel has none).
    if ctx.traversal().is_some_and(|(t, _)| t == Traversal::Compute) {
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

pub(crate) fn mut_references_to_payload_fields_reach_helpers(backend: On) {
    let (mut ctx, out) = camera(2.0, backend);
    sphere_scene(&mut ctx, &bumps_a_payload_field::PROGRAM, Vec3::ZERO, 1.0);
    ctx.launch(0, W, W).unwrap();
    assert_eq!(pixel(&ctx.read_buffer::<Vec4>(out).unwrap(), W / 2, W / 2).truncate(), Vec3::new(30.0, 3.0, 0.0));
}
