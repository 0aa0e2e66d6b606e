//! Closest-hit shading: a sphere's normals, the same through methods of
//! the payload and the attributes, a triangle's attributes through a
//! transform, and `rt_get_transform` in a closest hit; the quad and the
//! mesh scene the other tests build on.

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
