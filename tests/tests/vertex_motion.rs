//! Triangle meshes with vertex motion keys (OptiX 6's
//! `rtGeometryTrianglesSetMotionVertices`) on every target: rays traced at
//! a time (`rt_trace_at`) meet each triangle with its vertices
//! interpolated between the two keys around the time, clamped outside the
//! range; the hit's distance, barycentrics, geometric normal and side are
//! the interpolated triangle's; triangles' boxes hold the whole motion (a
//! hit lies outside the first key's box); a 512-triangle grid moving
//! beside a static mesh in one geometry group; keys set between launches
//! and removed again. The ray-query target falls back to the compute
//! traversal while vertices move, and walks the scene again once they stop.

use glam::{Mat4, Vec2, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Probe {
    pub hit: f32,
    pub t: f32,
    pub normal: Vec3,
    pub bary: Vec2,
    pub front: f32,
}

#[rt_attributes]
pub struct TriangleHit {
    pub geometric_normal: Vec3,
    pub barycentrics: Vec2,
}

const WORDS: usize = 8;

/// One ray down -z per launch index at `rays[i].xy` at time `rays[i].z`.
#[rt_program(ray_generation)]
pub fn probe(#[var] top: Object, #[var] rays: Buffer<Vec4>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let r = rays[i];
    let mut prd = Probe { hit: 0.0, t: 0.0, normal: Vec3::ZERO, bary: Vec2::ZERO, front: 0.0 };
    let ray = Ray::new(vec3(r.x, r.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0);
    rt_trace_at(top, ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, r.z);
    let at = i * 8;
    out[at] = prd.hit;
    out[at + 1] = prd.t;
    out[at + 2] = prd.normal.x;
    out[at + 3] = prd.normal.y;
    out[at + 4] = prd.normal.z;
    out[at + 5] = prd.bary.x;
    out[at + 6] = prd.bary.y;
    out[at + 7] = prd.front;
}

/// The hit as the interpolated triangle gives it; `which` tells the
/// geometry groups' materials apart.
#[rt_program(closest_hit)]
pub fn hit(prd: &mut Probe, attr: &TriangleHit, #[var] which: f32) {
    prd.hit = which;
    prd.t = t_hit();
    prd.normal = attr.geometric_normal;
    prd.bary = attr.barycentrics;
    prd.front = if is_triangle_hit_front_face() { 1.0 } else { 0.0 };
}

#[rt_program(miss)]
pub fn missed(prd: &mut Probe) {
    prd.hit = -1.0;
}

/// Custom geometry, which has no vertices to move.
#[rt_program(intersection)]
pub fn nothing(prim: u32) {
    let _ = prim;
}

#[rt_program(bounding_box)]
pub fn unit_box(prim: u32) -> Aabb {
    let _ = prim;
    Aabb::new(Vec3::ZERO, Vec3::ONE)
}

/// The moving triangle's three keys over [0, 2]: at time 0 the triangle
/// (-1, -1, 0), (3, -1, 0), (-1, 3, 0); at 1 the same two units along x;
/// at 2 its second vertex raised to z = 4 as well.
fn triangle_keys() -> Vec<Vec<Vec3>> {
    let first = vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(3.0, -1.0, 0.0), Vec3::new(-1.0, 3.0, 0.0)];
    let second: Vec<Vec3> = first.iter().map(|p| *p + Vec3::new(2.0, 0.0, 0.0)).collect();
    let mut third = second.clone();
    third[1].z = 4.0;
    vec![first, second, third]
}

fn triangle() -> TriangleMesh {
    TriangleMesh { positions: triangle_keys().swap_remove(0), indices: vec![[0, 1, 2]], ..Default::default() }
}

/// A 16 x 16 grid of quads over [-2, 2]^2 at z = 0 (512 triangles).
fn grid() -> TriangleMesh {
    rt_tests::meshes::grid(16, 2.0, |_, _| 0.0)
}

/// A geometry group over `geometries` (one instance each) with the probe's
/// closest hit, its material saying `which`.
fn group_of(ctx: &mut Context, geometries: &[GeometryId], which: f32) -> NodeId {
    let m = ctx.create_material();
    let ch = ctx.create_program(&hit::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    ctx.set_var(m, "which", which).unwrap();
    let instances: Vec<GeometryInstanceId> =
        geometries.iter().map(|g| ctx.create_geometry_instance(*g, &[m]).unwrap()).collect();
    ctx.create_geometry_group(&instances, Acceleration::default()).unwrap()
}

/// `ctx` with the probe's ray generation and miss programs tracing `top`.
fn probing(ctx: &mut Context, top: NodeId) {
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let rg = ctx.create_program(&probe::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&missed::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
}

/// Launches `rays` (x, y, time): each ray's words. `moving`: whether some
/// vertices move (which keeps the ray-query target on the compute
/// traversal, as it checks).
fn launch(on: On, ctx: &mut Context, rays: &[[f32; 3]], moving: bool) -> Vec<[f32; WORDS]> {
    let rays_buffer =
        ctx.create_buffer(BufferType::Input, rays.iter().map(|r| Vec4::new(r[0], r[1], r[2], 0.0)).collect());
    ctx.set_var(Scope::Context, "rays", rays_buffer).unwrap();
    let out = ctx.create_buffer::<f32>(BufferType::Output, vec![0.0; rays.len() * WORDS]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let report = ctx.launch_1d(0, rays.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{}: {:?}", on.name(), report.exceptions);
    if on == On::RAY_QUERY {
        let (traversal, why) = ctx.traversal().unwrap();
        if moving {
            assert_eq!(traversal, Traversal::Compute, "moving vertices keep the compute traversal");
            assert!(why.contains("whose vertices move"), "{why}");
        } else {
            assert_eq!(traversal, Traversal::RayQuery, "a static scene is walked by ray queries");
        }
    }
    ctx.read_buffer::<f32>(out).unwrap().chunks(WORDS).map(|c| c.try_into().unwrap()).collect()
}

/// Asserts `got` is `want` within `tol`, naming the target, ray and word.
fn check(on: On, what: &str, got: &[[f32; WORDS]], want: &[[f32; WORDS]], tol: f32) {
    assert_eq!(got.len(), want.len());
    for (r, (g, w)) in got.iter().zip(want).enumerate() {
        for (k, (a, b)) in g.iter().zip(w).enumerate() {
            assert!((a - b).abs() <= tol, "{} ({what}): ray {r} word {k}: {a} (want {b}); all: {g:?}", on.name());
        }
    }
}

/// A front-face hit of material `which` at distance `t`, geometric normal
/// `n` (unnormalised: the cross product of the triangle's edges),
/// barycentrics `(u, v)`.
fn hit_words(which: f32, t: f32, n: [f32; 3], (u, v): (f32, f32)) -> [f32; WORDS] {
    [which, t, n[0], n[1], n[2], u, v, 1.0]
}

fn miss() -> [f32; WORDS] {
    [-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
}

/// The moving triangle beside a static quad far away (so a group's BVH
/// bounds the motion), keys over [0, 2]: distances, barycentrics, normals
/// and sides at times in each segment, before and after the range, and
/// where the triangle is at a time only (outside the first key's box).
#[test]
fn vertices_are_interpolated_at_the_ray_time_on_every_target() {
    let rays = [
        // Time 0.5: the first key moved one unit along x.
        [0.5, 0.5, 0.5],
        // There the first key's triangle is, but not the one at 0.5.
        [-0.5, 0.5, 0.5],
        // Time 1.5: the second vertex half raised, (5, -1, 2).
        [3.0, 0.0, 1.5],
        // Only the moved triangle reaches x = 4.25 (the first key's box
        // ends at 3).
        [4.25, -0.75, 1.5],
        // Clamped before and after the range.
        [0.5, 0.5, -1.0],
        [3.0, 0.0, 3.0],
        // The far quad, at any time.
        [0.5, 49.5, 0.7],
    ];
    let want = [
        hit_words(1.0, 5.0, [0.0, 0.0, 16.0], (0.125, 0.375)),
        miss(),
        hit_words(1.0, 4.0, [-8.0, 0.0, 16.0], (0.5, 0.25)),
        hit_words(1.0, 3.375, [-8.0, 0.0, 16.0], (0.8125, 0.0625)),
        hit_words(1.0, 5.0, [0.0, 0.0, 16.0], (0.375, 0.375)),
        hit_words(1.0, 3.0, [-16.0, 0.0, 16.0], (0.5, 0.25)),
        hit_words(2.0, 5.0, [0.0, 0.0, 4.0], (0.5, 0.25)),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        let g = ctx.create_triangles(triangle()).unwrap();
        ctx.set_motion_vertices(g, triangle_keys(), 0.0, 2.0).unwrap();
        let moving = group_of(&mut ctx, &[g], 1.0);
        let quad = ctx.create_triangles(rt_tests::meshes::unit_quad()).unwrap();
        let far = group_of(&mut ctx, &[quad], 2.0);
        let far = ctx.create_transform(Mat4::from_translation(Vec3::new(0.0, 50.0, 0.0)), far).unwrap();
        let top = ctx.create_group(&[moving, far], Acceleration::default()).unwrap();
        probing(&mut ctx, top);
        check(on, "one triangle", &launch(on, &mut ctx, &rays, true), &want, 1e-6);
    }
}

/// A 512-triangle grid whose vertices sink by 2 and slide by 1 along x
/// over [0, 1], in one geometry group with a static quad at z = 1 over
/// [2.5, 4.5] x [-1, 1]: the grid is found at its place at each time among
/// the static triangles (on the CPU backend, a SIMD tree without
/// triangle packets), under each acceleration; then its keys change, and
/// it stops (the ray-query target walks it again).
#[test]
fn a_moving_grid_beside_static_triangles_and_keys_changed_between_launches_on_every_target() {
    let sunk = |depth: f32, slide: f32| -> Vec<Vec3> {
        grid().positions.iter().map(|p| *p + Vec3::new(slide, 0.0, -depth)).collect()
    };
    let mut quad = rt_tests::meshes::unit_quad();
    quad.positions.iter_mut().for_each(|p| *p += Vec3::new(3.5, 0.0, 1.0));
    // Grid hits: distance 5 + 2 time; the quad: 4 (normal (0, 0, 4)).
    let at = |x: f32, time: f32| [x, 0.3, time];
    let rays = [at(-1.9, 0.0), at(-2.1, 0.5), at(-1.1, 0.5), at(2.2, 1.0), at(3.0, 0.25), at(4.0, 0.0), at(0.0, 0.75)];
    // (The grid's cells are 0.25 wide: normals (0, 0, 1/16).)
    let grid_hit = |t: f32| [1.0, t, 0.0, 0.0, 0.0625];
    let quad_hit = [1.0, 4.0, 0.0, 0.0, 4.0];
    let want =
        [grid_hit(5.0), [-1.0, 0.0, 0.0, 0.0, 0.0], grid_hit(6.0), grid_hit(7.0), quad_hit, quad_hit, grid_hit(6.5)];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        for builder in [Builder::Bvh, Builder::NoAccel] {
            let mut ctx = on.context();
            let g = ctx.create_triangles(grid()).unwrap();
            let still = ctx.create_triangles(quad.clone()).unwrap();
            let m = ctx.create_material();
            let ch = ctx.create_program(&hit::PROGRAM);
            ctx.set_closest_hit_program(m, 0, ch).unwrap();
            ctx.set_var(m, "which", 1.0f32).unwrap();
            let a = ctx.create_geometry_instance(g, &[m]).unwrap();
            let b = ctx.create_geometry_instance(still, &[m]).unwrap();
            let top = ctx.create_geometry_group(&[a, b], Acceleration::new(builder)).unwrap();
            probing(&mut ctx, top);
            ctx.set_motion_vertices(g, vec![sunk(0.0, 0.0), sunk(2.0, 1.0)], 0.0, 1.0).unwrap();
            let got = launch(on, &mut ctx, &rays, true);
            // Hit, distance and normal (the grid's barycentrics depend on
            // the cell).
            let got: Vec<[f32; 5]> = got.iter().map(|w| [w[0], w[1], w[2], w[3], w[4]]).collect();
            for (r, (g, w)) in got.iter().zip(&want).enumerate() {
                let close = g.iter().zip(w).all(|(a, b)| (a - b).abs() <= 1e-5);
                assert!(close, "{} {builder:?}: ray {r}: {g:?} (want {w:?})", on.name());
            }
            // New keys: three, over [1, 3], sinking by 1 each.
            ctx.set_motion_vertices(g, vec![sunk(0.0, 0.0), sunk(1.0, 0.0), sunk(2.0, 0.0)], 1.0, 3.0).unwrap();
            assert_eq!(ctx.motion_vertices(g).map(|m| (m.keys.len(), m.t0, m.t1)), Some((3, 1.0, 3.0)));
            let got = launch(on, &mut ctx, &[at(-1.9, 2.5), at(0.0, 0.0)], true);
            assert!((got[0][1] - 6.5).abs() <= 1e-5 && (got[1][1] - 5.0).abs() <= 1e-5, "{}: {got:?}", on.name());
            // Static again, where it was at the last key.
            ctx.set_triangle_positions(g, sunk(2.0, 0.0)).unwrap();
            assert!(ctx.motion_vertices(g).is_none());
            let got = launch(on, &mut ctx, &[at(-1.9, 0.0), at(1.0, 0.5)], false);
            assert!((got[0][1] - 7.0).abs() <= 1e-5 && (got[1][1] - 7.0).abs() <= 1e-5, "{}: {got:?}", on.name());
        }
    }
}

#[test]
fn bad_vertex_motion_is_an_error_naming_the_geometry() {
    let mut ctx = Context::new();
    let g = ctx.create_triangles(triangle()).unwrap();
    let keys = triangle_keys();
    let one = ctx.set_motion_vertices(g, keys[..1].to_vec(), 0.0, 1.0).unwrap_err().to_string();
    assert!(one.contains("geometry 0") && one.contains("at least 2 keys, found 1"), "{one}");
    let mut short = keys.clone();
    short[2].pop();
    let short = ctx.set_motion_vertices(g, short, 0.0, 1.0).unwrap_err().to_string();
    assert!(short.contains("motion key 2 has 2 positions for 3 vertices"), "{short}");
    let mut nan = keys.clone();
    nan[1][2].x = f32::INFINITY;
    let nan = ctx.set_motion_vertices(g, nan, 0.0, 1.0).unwrap_err().to_string();
    assert!(nan.contains("motion key 1: vertex 2 has a non-finite position"), "{nan}");
    let backwards = ctx.set_motion_vertices(g, keys.clone(), 2.0, 1.0).unwrap_err().to_string();
    assert!(backwards.contains("ends before it begins"), "{backwards}");
    // Nothing was kept from the refused calls.
    assert!(ctx.motion_vertices(g).is_none());
    // Custom geometry has no vertices to move.
    let isect = ctx.create_program(&nothing::PROGRAM);
    let bounds = ctx.create_program(&unit_box::PROGRAM);
    let custom = ctx.create_custom_geometry(1, isect, bounds).unwrap();
    let err = ctx.set_motion_vertices(custom, keys, 0.0, 1.0).unwrap_err().to_string();
    assert!(err.contains(&format!("geometry {}", custom.index())) && err.contains("not a triangle geometry"), "{err}");
}
