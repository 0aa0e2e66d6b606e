//! Refits: moved geometry is refit rather than rebuilt, and a refit mesh
//! renders as one built for its new shape.

use super::*;

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
