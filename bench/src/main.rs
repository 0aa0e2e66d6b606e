//! `rt-bench`: primary-ray throughput of the normal-shader scene over the
//! Stanford bunny on each backend, the acceleration build against obvhs's
//! own build of the same triangles, and the megakernel link time.
//!
//! `cargo run --release -p rt-bench -- [--quick] [--json] [--width W --height H]`
//!
//! Every ratio compares figures measured in this run, on this machine.

use clap::Parser;
use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use std::time::{Duration, Instant};

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
}

/// The seed's pinhole camera.
#[rt_program(ray_generation)]
pub fn pinhole(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let d = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Radiance { result: Vec3::ZERO };
    rt_trace(top_object, Ray::new(eye, (d.x * u + d.y * v + w).normalize(), 0, 1e-4, f32::INFINITY), &mut prd);
    output_buffer[idx] = prd.result.extend(1.0);
}

/// The seed's normal shader.
#[rt_program(closest_hit)]
pub fn normal_shader(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize() * 0.5 + 0.5;
}

#[rt_program(miss)]
pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

#[derive(Parser)]
struct Args {
    /// Fewer repetitions and a smaller image.
    #[arg(long)]
    quick: bool,
    /// Print one JSON object on stdout (the table goes to stderr).
    #[arg(long)]
    json: bool,
    #[arg(long)]
    width: Option<u32>,
    #[arg(long)]
    height: Option<u32>,
    /// Backends to measure.
    #[arg(long, value_delimiter = ',', default_value = "cpu,wgpu")]
    backends: Vec<String>,
}

fn load_bunny() -> TriangleMesh {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/scenes/stanford-bunny.obj");
    let (models, _) = tobj::load_obj(path, &tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() })
        .unwrap_or_else(|e| panic!("{path}: {e}"));
    let m = &models[0].mesh;
    TriangleMesh {
        positions: m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])).collect(),
        indices: m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        ..TriangleMesh::default()
    }
}

fn scene(mesh: &TriangleMesh, backend: Backend, width: u32, height: u32) -> Result<(Context, BufferId)> {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    let rg = ctx.create_program(&pinhole::PROGRAM);
    ctx.set_ray_generation_program(0, rg)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(0, miss)?;
    let g = ctx.create_triangles(mesh.clone())?;
    let mat = ctx.create_material();
    let ch = ctx.create_program(&normal_shader::PROGRAM);
    ctx.set_closest_hit_program(mat, 0, ch)?;
    let gi = ctx.create_geometry_instance(g, &[mat])?;
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh))?;
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, width, height)?;
    // Frame the bunny from its bounds.
    let (lo, hi) = mesh.positions.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let eye = center + Vec3::new(0.0, 0.1, 2.2) * radius;
    let w = (center - eye).normalize();
    let u = w.cross(Vec3::Y).normalize() * (width as f32 / height as f32) * 0.45;
    let v = u.cross(w).normalize() * 0.45;
    for (name, value) in [("eye", eye), ("u", u), ("v", v), ("w", w), ("bg_color", Vec3::new(0.2, 0.2, 0.25))] {
        ctx.set_var(Scope::Context, name, value)?;
    }
    ctx.set_var(Scope::Context, "top_object", gg)?;
    ctx.set_var(Scope::Context, "output_buffer", out)?;
    Ok((ctx, out))
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn main() {
    let args = Args::parse();
    let (width, height) = match (args.width, args.height) {
        (Some(w), Some(h)) => (w, h),
        _ if args.quick => (512, 384),
        _ => (1024, 768),
    };
    let reps = if args.quick { 3 } else { 7 };
    let mesh = load_bunny();
    let mut json = Vec::new();
    eprintln!("bunny: {} triangles, {width}x{height}, primary rays (normal shader)", mesh.indices.len());

    // Acceleration build: obvhs directly against our end-to-end build.
    let tris: Vec<obvhs::triangle::Triangle> = mesh
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].into());
            obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
        })
        .collect();
    let obvhs_build = median(
        (0..reps)
            .map(|_| {
                let t = Instant::now();
                let aabbs: Vec<obvhs::aabb::Aabb> = tris.iter().map(|t| obvhs::Boundable::aabb(t)).collect();
                let mut core = Duration::ZERO;
                std::hint::black_box(obvhs::bvh2::builder::build_bvh2(&aabbs, obvhs::BvhBuildParams::medium_build(), &mut core));
                t.elapsed()
            })
            .collect(),
    );
    let our_build = median(
        (0..reps)
            .map(|_| {
                let (mut ctx, _) = scene(&mesh, Backend::Cpu, 1, 1).expect("scene");
                let r = ctx.launch(0, 1, 1).expect("launch");
                r.timings.build
            })
            .collect(),
    );
    let build_ratio = obvhs_build.as_secs_f64() / our_build.as_secs_f64();
    eprintln!(
        "build: obvhs medium_build {:.1} ms, ours (bounds + build) {:.1} ms, build_vs_obvhs {:.2}",
        obvhs_build.as_secs_f64() * 1e3,
        our_build.as_secs_f64() * 1e3,
        build_ratio
    );
    json.push(format!("\"build_vs_obvhs\": {build_ratio:.3}"));

    for b in &args.backends {
        let backend = match b.as_str() {
            "cpu" => Backend::Cpu,
            "wgpu" => Backend::Wgpu,
            other => {
                eprintln!("unknown backend `{other}` (cpu or wgpu)");
                std::process::exit(2);
            }
        };
        let (mut ctx, out) = match scene(&mesh, backend, width, height) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{b}: {e}");
                continue;
            }
        };
        let device = if backend == Backend::Wgpu {
            match ctx.open_wgpu() {
                Ok(d) => d,
                Err(e) => {
                    eprintln!("{b}: {e}");
                    continue;
                }
            }
        } else {
            format!("cpu, {} threads", std::thread::available_parallelism().map_or(1, |n| n.get()))
        };
        let first = ctx.launch(0, width, height).expect("launch");
        let mut runs = Vec::new();
        let mut rays = 0;
        for _ in 0..reps {
            let r = ctx.launch(0, width, height).expect("launch");
            rays = r.rays;
            runs.push(r.timings.run);
        }
        let run = median(runs);
        let mrays = rays as f64 / run.as_secs_f64() / 1e6;
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        let hit = img.iter().filter(|c| c.truncate() != Vec3::new(0.2, 0.2, 0.25)).count();
        eprintln!(
            "{b} [{device}]: {mrays:.2} Mrays/s ({rays} rays in {:.1} ms, {:.0}% of pixels hit); first launch: link {:.1} ms, encode {:.1} ms",
            run.as_secs_f64() * 1e3,
            100.0 * hit as f64 / img.len() as f64,
            first.timings.link.as_secs_f64() * 1e3,
            first.timings.encode.as_secs_f64() * 1e3
        );
        json.push(format!(
            "\"{b}\": {{\"device\": \"{}\", \"mrays_per_s\": {mrays:.3}, \"link_ms\": {:.2}}}",
            device.replace('"', "'"),
            first.timings.link.as_secs_f64() * 1e3
        ));
    }
    if args.json {
        println!("{{{}}}", json.join(", "));
    }
}
