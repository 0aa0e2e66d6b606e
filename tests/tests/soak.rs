//! Soak: 2,000 launches on each backend that alternate variable, buffer,
//! transform, vertex and program changes. After warm-up the process's
//! resident memory stays flat (and, on wgpu, the device's allocations where
//! the adapter reports them), and every 100th image equals the image a
//! fresh context renders from the same state. `RT_SOAK=n` runs `n` launches
//! per backend instead, and prints the figures.

use glam::{Mat4, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;

const W: u32 = 16;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_attributes]
pub struct Bary {
    pub barycentrics: Vec2,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] tilt: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let ray = Ray::new(vec3(p.x * 1.5, p.y * 1.5, 5.0), vec3(tilt, 0.0, -1.0).normalize(), 0, 0.0, f32::INFINITY);
    let mut prd = Shade { color: Vec3::ZERO };
    rt_trace(top, ray, &mut prd);
    out[idx] = prd.color.extend(1.0);
}

#[rt_program(closest_hit)]
pub fn tinted(prd: &mut Shade, attr: &Bary, #[var] table: Buffer<Vec3>) {
    prd.color = table[primitive_index() % table.len()] * attr.barycentrics.x + vec3(0.0, 0.0, t_hit() * 0.1);
}

#[rt_program(closest_hit)]
pub fn plain(prd: &mut Shade, attr: &Bary) {
    prd.color = vec3(attr.barycentrics.y, t_hit() * 0.05, 1.0);
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.color = vec3(0.2, 0.3, 0.4);
}

/// What the loop changes; a fresh context is built from it.
#[derive(Clone)]
struct State {
    tilt: f32,
    table: Vec<Vec3>,
    transform: Mat4,
    positions: Vec<Vec3>,
    tinted: bool,
}

impl State {
    fn at(i: usize) -> State {
        let f = i as f32;
        State {
            tilt: (f * 0.37).sin() * 0.2,
            table: vec![Vec3::new((f * 0.11).fract(), 0.5, 0.25), Vec3::new(0.1, (f * 0.07).fract(), 0.9)],
            transform: Mat4::from_rotation_z(f * 0.05) * Mat4::from_scale(Vec3::splat(1.0 + 0.2 * (f * 0.13).sin())),
            positions: vec![
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(1.0, -1.0, 0.1 * (f * 0.3).sin()),
                Vec3::new(0.0, 1.0, 0.5),
                Vec3::new(1.2, 1.0, -0.2),
            ],
            tinted: (i / 3).is_multiple_of(2),
        }
    }
}

/// A context holding `s`'s scene, and the handles the loop changes.
struct Rig {
    ctx: Context,
    out: BufferId,
    table: BufferId,
    xf: NodeId,
    geom: GeometryId,
    mat: MaterialId,
    tinted: ProgramId,
    plain: ProgramId,
}

impl Rig {
    fn new(backend: Backend, device: Option<&(::wgpu::Device, ::wgpu::Queue, ::wgpu::AdapterInfo)>, s: &State) -> Rig {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        if let Some((d, q, info)) = device {
            ctx.use_wgpu_device(d.clone(), q.clone(), info.clone());
        }
        let mesh =
            TriangleMesh { positions: s.positions.clone(), indices: vec![[0, 1, 2], [1, 3, 2]], ..Default::default() };
        let geom = ctx.create_triangles(mesh).unwrap();
        let mat = ctx.create_material();
        let tinted = ctx.create_program(&tinted::PROGRAM);
        let plain = ctx.create_program(&plain::PROGRAM);
        ctx.set_closest_hit_program(mat, 0, if s.tinted { tinted } else { plain }).unwrap();
        let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
        let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        let xf = ctx.create_transform(s.transform, gg).unwrap();
        let top = ctx.create_group(&[xf], Acceleration::default()).unwrap();
        let rg = ctx.create_program(&camera::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let miss = ctx.create_program(&sky::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, W, W).unwrap();
        let table = ctx.create_buffer(BufferType::Input, s.table.clone());
        for (name, v) in [("out", out), ("table", table)] {
            ctx.set_var(Scope::Context, name, v).unwrap();
        }
        ctx.set_var(Scope::Context, "top", top).unwrap();
        ctx.set_var(Scope::Context, "tilt", s.tilt).unwrap();
        Rig { ctx, out, table, xf, geom, mat, tinted, plain }
    }

    /// Applies the `i % 5`th kind of change from `s`.
    fn change(&mut self, i: usize, s: &State) {
        let ctx = &mut self.ctx;
        match i % 5 {
            0 => ctx.set_var(Scope::Context, "tilt", s.tilt).unwrap(),
            1 => ctx.write_buffer(self.table, &s.table).unwrap(),
            2 => ctx.set_transform(self.xf, s.transform).unwrap(),
            3 => ctx.set_triangle_positions(self.geom, s.positions.clone()).unwrap(),
            _ => ctx.set_closest_hit_program(self.mat, 0, if s.tinted { self.tinted } else { self.plain }).unwrap(),
        }
    }

    fn image(&mut self) -> Vec<Vec4> {
        self.ctx.launch(0, W, W).unwrap();
        self.ctx.read_buffer::<Vec4>(self.out).unwrap()
    }
}

fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    statm.split_whitespace().nth(1).and_then(|p| p.parse::<u64>().ok()).unwrap_or(0) * 4096
}

fn largest_difference(a: &[Vec4], b: &[Vec4]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f32::max)
}

/// Runs `n` launches; returns (resident growth after warm-up, device
/// allocation growth if reported).
fn soak(backend: Backend, n: usize) -> (i64, Option<i64>) {
    let device = (backend == Backend::Wgpu).then(|| {
        let instance = rt_runtime::backend::wgpu::instance();
        let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect("an adapter");
        let limits = ::wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits());
        let (d, q) = pollster::block_on(
            adapter.request_device(&::wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
        )
        .unwrap();
        (d, q, adapter.get_info())
    });
    let allocated =
        || device.as_ref().and_then(|(d, ..)| d.generate_allocator_report()).map(|r| r.total_reserved_bytes as i64);
    let mut rig = Rig::new(backend, device.as_ref(), &State::at(0));
    let warm_up = n.min(200);
    let (mut rss0, mut alloc0) = (0, None);
    let mut state = State::at(0);
    for i in 0..n {
        let next = State::at(i);
        rig.change(i, &next);
        match i % 5 {
            0 => state.tilt = next.tilt,
            1 => state.table = next.table,
            2 => state.transform = next.transform,
            3 => state.positions = next.positions,
            _ => state.tinted = next.tinted,
        }
        let img = rig.image();
        if i + 1 == warm_up {
            (rss0, alloc0) = (resident_bytes(), allocated());
        }
        if i % 100 == 99 {
            // The CPU backend against a fresh CPU context, exactly; wgpu
            // against a fresh CPU context within the suite's tolerance, and
            // every 500th against a fresh wgpu context on the same device,
            // exactly.
            let fresh = Rig::new(Backend::Cpu, None, &state).image();
            match backend {
                Backend::Cpu => assert_eq!(img, fresh, "launch {i}: against a fresh context"),
                _ => {
                    let d = largest_difference(&img, &fresh);
                    assert!(d < 2.0 / 255.0, "launch {i}: {d} from a fresh CPU context");
                    if i % 500 == 499 {
                        let fresh = Rig::new(backend, device.as_ref(), &state).image();
                        assert_eq!(img, fresh, "launch {i}: against a fresh wgpu context");
                    }
                }
            }
        }
    }
    let rss = resident_bytes() as i64 - rss0 as i64;
    let alloc = allocated().zip(alloc0).map(|(a, b)| a - b);
    (rss, alloc)
}

/// The process's resident memory is what the soak measures: the other test
/// of this binary (wgpu pipelines compiled by lavapipe's LLVM) must not run
/// beside it. Each test holds this while it runs.
static ALONE: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn two_thousand_changing_launches_keep_memory_flat_and_images_fresh() {
    let _alone = ALONE.lock().unwrap_or_else(|e| e.into_inner());
    let n: usize = std::env::var("RT_SOAK").ok().and_then(|v| v.parse().ok()).unwrap_or(2000);
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let t = std::time::Instant::now();
        let (rss, alloc) = soak(backend, n);
        eprintln!(
            "soak {backend:?}: {n} launches in {:.1} s; resident memory after warm-up {:+.2} MiB; device allocations {}",
            t.elapsed().as_secs_f64(),
            rss as f64 / (1 << 20) as f64,
            alloc.map_or("not reported by the adapter".into(), |a| format!("{:+.2} MiB", a as f64 / (1 << 20) as f64)),
        );
        assert!(rss < 16 << 20, "{backend:?}: resident memory grew {rss} bytes after warm-up");
        if let Some(a) = alloc {
            assert!(a <= 0, "{backend:?}: device allocations grew {a} bytes after warm-up");
        }
    }
}

/// Rays with a zero direction component (here straight down, `(0, 0, -1)`
/// after `normalize`) under a group: `1.0 / 0.0` in the slab test is an
/// infinity WGSL lets the compiler assume away (on lavapipe such rays miss
/// everything), so the kernel takes a finite reciprocal (`rt_safe_inv`).
#[test]
fn axis_aligned_rays_through_a_group_hit_on_wgpu_as_on_the_cpu() {
    let _alone = ALONE.lock().unwrap_or_else(|e| e.into_inner());
    let state = State { tilt: 0.0, transform: Mat4::IDENTITY, ..State::at(0) };
    let cpu = Rig::new(Backend::Cpu, None, &state).image();
    let gpu = Rig::new(Backend::Wgpu, None, &state).image();
    let hits = |img: &[Vec4]| img.iter().filter(|c| c.z != 0.4).count();
    assert!(hits(&cpu) > 60, "{} hits on the CPU", hits(&cpu));
    assert_eq!(hits(&gpu), hits(&cpu));
    assert!(largest_difference(&cpu, &gpu) < 2.0 / 255.0);
}
