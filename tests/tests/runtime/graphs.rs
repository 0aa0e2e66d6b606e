//! The shapes of the scene graph: three levels of groups of transforms
//! (with a visibility mask inside), and the smallest trees (one triangle,
//! an empty geometry group).

use super::*;

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
    // (The compute traversal's tree; ray queries walk the device's.)
    if ctx.traversal().is_some_and(|(t, _)| t == Traversal::Compute) {
        assert!(ctx.linked_wgsl().unwrap().contains("const RT_CWBVH: bool = true;"));
    }
}
