//! Contexts on several threads at once give the images a serial run gives:
//! CPU contexts side by side (each launch on rayon's shared pool), wgpu
//! contexts with a device each, and wgpu contexts sharing one device
//! through `use_wgpu_device`. `Context` is `Send` and `Sync`.

use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

const W: u32 = 24;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_attributes]
pub struct Bary {
    pub barycentrics: Vec2,
}

#[rt_program(ray_generation)]
pub fn look_down(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] tilt: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * 1.5, p.y * 1.5, 5.0), vec3(tilt, 0.0, -1.0).normalize(), 0, 0.0, f32::INFINITY);
    let mut prd = Shade { color: Vec3::ZERO };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.color.extend(1.0);
}

#[rt_program(closest_hit)]
pub fn bary_color(prd: &mut Shade, attr: &Bary) {
    prd.color = vec3(attr.barycentrics.x, attr.barycentrics.y, t_hit() * 0.1);
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.color = vec3(0.0, 0.0, 1.0);
}

/// The image of the scene at `tilt` on `ctx` (built fresh on it).
fn render(ctx: &mut Context, tilt: f32) -> Vec<Vec4> {
    let mesh = TriangleMesh {
        positions: vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.5)],
        indices: vec![[0, 1, 2]],
        ..TriangleMesh::default()
    };
    let geom = ctx.create_triangles(mesh).unwrap();
    let mat = ctx.create_material();
    let ch = ctx.create_program(&bary_color::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let rg = ctx.create_program(&look_down::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&sky::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, W).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    ctx.set_var(Scope::Context, "tilt", tilt).unwrap();
    ctx.launch(0, W, W).unwrap();
    ctx.read_buffer::<Vec4>(out).unwrap()
}

fn fresh(backend: Backend) -> Context {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    ctx
}

/// Renders `tilts` serially, then each on its own thread with a context
/// from `make`, three times over, and compares.
fn agree(make: impl Fn() -> Context + Sync, tilts: &[f32]) {
    let serial: Vec<Vec<Vec4>> = tilts.iter().map(|&t| render(&mut make(), t)).collect();
    assert!(serial.iter().all(|img| img.iter().any(|c| c.z < 1.0)), "every image hits the triangle");
    std::thread::scope(|s| {
        let threads: Vec<_> = tilts
            .iter()
            .map(|&t| {
                let make = &make;
                s.spawn(move || (0..3).map(|_| render(&mut make(), t)).collect::<Vec<_>>())
            })
            .collect();
        for (i, th) in threads.into_iter().enumerate() {
            for img in th.join().unwrap() {
                assert_eq!(img, serial[i], "tilt {} on its own thread", tilts[i]);
            }
        }
    });
}

#[test]
fn context_is_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<Context>();
}

#[test]
fn cpu_contexts_on_four_threads_render_what_a_serial_run_does() {
    agree(|| fresh(Backend::Cpu), &[0.0, 0.1, -0.2, 0.3]);
}

#[test]
fn wgpu_contexts_with_a_device_each_render_what_a_serial_run_does() {
    agree(|| fresh(Backend::Wgpu), &[0.0, 0.15]);
}

#[test]
fn wgpu_contexts_sharing_one_device_render_what_a_serial_run_does() {
    let instance = rt_runtime::backend::wgpu::instance();
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect("an adapter (lavapipe)");
    let limits = ::wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits());
    let (device, queue) = pollster::block_on(
        adapter.request_device(&::wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
    )
    .unwrap();
    let info = adapter.get_info();
    agree(
        || {
            let mut ctx = Context::new();
            ctx.use_wgpu_device(device.clone(), queue.clone(), info.clone());
            ctx
        },
        &[0.0, 0.2, -0.1],
    );
    // A moved context keeps working on the other thread.
    let mut ctx = fresh(Backend::Cpu);
    let before = render(&mut ctx, 0.05);
    let after = std::thread::spawn(move || render(&mut ctx, 0.05)).join().unwrap();
    assert_eq!(before, after);
}
