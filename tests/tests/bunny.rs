//! The seed's normal-shader scene (pinhole camera, closest hit writing
//! normals, miss writing `bg_color`) over the Stanford bunny, through the
//! public API only, on both backends, saved as PNG.

use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub importance: f32,
    pub depth: i32,
}

#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

#[rt_program(ray_generation)]
pub fn pinhole_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let d = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(eye, (d.x * u + d.y * v + w).normalize(), 0, scene_epsilon, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    rt_trace(top_object, ray, &mut prd);
    output_buffer[idx] = prd.result.extend(1.0);
}

#[rt_program(closest_hit)]
pub fn closest_hit_radiance(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize() * 0.5 + 0.5;
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

const BG: Vec3 = Vec3::new(0.2, 0.2, 0.3);

fn bunny() -> TriangleMesh {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/scenes/stanford-bunny.obj");
    let (models, _) =
        tobj::load_obj(path, &tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() })
            .unwrap();
    let m = &models[0].mesh;
    TriangleMesh {
        positions: m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])).collect(),
        indices: m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        ..TriangleMesh::default()
    }
}

fn render(on: On, mesh: &TriangleMesh, w: u32, h: u32) -> (Context, BufferId) {
    let mut ctx = on.context();
    let rg = ctx.create_program(&pinhole_camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let ms = ctx.create_program(&miss::PROGRAM);
    ctx.set_miss_program(0, ms).unwrap();
    let g = ctx.create_triangles(mesh.clone()).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&closest_hit_radiance::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Sbvh)).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h).unwrap();
    let (lo, hi) =
        mesh.positions.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
    let center = (lo + hi) * 0.5;
    let eye = center + Vec3::new(0.0, 0.0, 1.6) * (hi - lo).length();
    let wv = center - eye;
    let u = wv.cross(Vec3::Y).normalize() * wv.length() * 0.35 * (w as f32 / h as f32);
    let v = u.cross(wv).normalize() * wv.length() * 0.35;
    for (n, val) in [("eye", eye), ("u", u), ("v", v), ("w", wv), ("bg_color", BG)] {
        ctx.set_var(Scope::Context, n, val).unwrap();
    }
    ctx.set_var(Scope::Context, "scene_epsilon", 1e-4f32).unwrap();
    ctx.set_var(Scope::Context, "top_object", gg).unwrap();
    ctx.set_var(Scope::Context, "output_buffer", out).unwrap();
    let report = ctx.launch(0, w, h).unwrap();
    assert!(report.exceptions.is_empty());
    assert_eq!(report.rays, (w * h) as u64);
    (ctx, out)
}

#[test]
fn the_bunny_renders_to_png_on_every_target_and_they_agree() {
    let mesh = bunny();
    let (w, h) = (96, 72);
    let dir = std::env::temp_dir().join(format!("rt-bunny-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut images = Vec::new();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (ctx, out) = render(on, &mesh, w, h);
        let path = dir.join(format!("bunny-{}.png", on.name()));
        ctx.save_png(out, &path).unwrap();
        let png = image::open(&path).unwrap().to_rgba8();
        assert_eq!(png.dimensions(), (w, h));
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        // The bunny covers the centre; the corners see the background.
        assert_ne!(img[(h / 2 * w + w / 2) as usize].truncate(), BG);
        for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
            assert_eq!(img[(y * w + x) as usize].truncate(), BG, "corner {x},{y}");
        }
        let hits = img.iter().filter(|c| c.truncate() != BG).count();
        assert!(hits > (w * h / 8) as usize, "only {hits} pixels hit the bunny");
        images.push(png);
    }
    // The differential rule: 99.9% of channels within 2/255, none beyond
    // 16/255, for each wgpu traversal against the CPU backend.
    for b in &images[1..] {
        let a = &images[0];
        let diffs: Vec<i32> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| (*x as i32 - *y as i32).abs()).collect();
        let close = diffs.iter().filter(|d| **d <= 2).count();
        assert!(close * 1000 >= diffs.len() * 999, "{close} of {} channels within 2/255", diffs.len());
        assert!(diffs.iter().all(|d| *d <= 16), "largest difference {}", diffs.iter().max().unwrap());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
