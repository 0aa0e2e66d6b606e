//! `rt-bench`: primary-ray throughput of the normal-shader scene over the
//! Stanford bunny on each backend, the acceleration build against obvhs's
//! own build of the same triangles, and the megakernel link time.
//!
//! `cargo run --release -p rt-bench -- [--quick] [--json] [--width W --height H]`
//!
//! Every ratio compares figures measured in this run, on this machine.

// The runtime's errors name programs and scopes; size does not matter here.
#![allow(clippy::result_large_err)]

mod handwritten;

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

/// Occlusion of an ambient-occlusion ray.
#[rt_payload]
pub struct Occlusion {
    pub hit: u32,
}

/// PCG-style integer hash (also in `obvhs_ao`, so both trace the same rays).
#[rt_function]
pub fn hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

/// Primary hit: one cosine-weighted ambient-occlusion ray, unbounded.
#[rt_program(closest_hit)]
pub fn ambient_occlusion(prd: &mut Radiance, attr: &Normals, #[var] top_object: Object) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let n = rt_transform_normal(ObjectToWorld, attr.geometric_normal).normalize();
    let n = faceforward(n, ray.direction, n);
    let idx = launch_index();
    let h1 = hash(idx.x + idx.y * launch_dim().x);
    let h2 = hash(h1);
    let u1 = (h1 >> 8) as f32 / 16777216.0;
    let u2 = (h2 >> 8) as f32 / 16777216.0;
    let d = cosine_direction(n, u1, u2);
    let mut occ = Occlusion { hit: 0 };
    rt_trace(top_object, Ray::new(p + n * 1e-4, d, 1, 0.0, f32::INFINITY), &mut occ);
    prd.result = Vec3::splat(1.0 - occ.hit as f32);
}

/// A cosine-weighted direction around `n` from two uniform numbers.
#[rt_function]
pub fn cosine_direction(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let a = if n.x.abs() > 0.9 { Vec3::Y } else { Vec3::X };
    let t = n.cross(a).normalize();
    let b = n.cross(t);
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize()
}

#[rt_program(closest_hit)]
pub fn occluded(prd: &mut Occlusion) {
    prd.hit = 1;
}

#[rt_program(miss)]
pub fn unoccluded(prd: &mut Occlusion) {
    prd.hit = 0;
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
    let (models, _) =
        tobj::load_obj(path, &tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() })
            .unwrap_or_else(|e| panic!("{path}: {e}"));
    let m = &models[0].mesh;
    TriangleMesh {
        positions: m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])).collect(),
        indices: m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        ..TriangleMesh::default()
    }
}

/// The workload: primary rays only, or primary plus one AO ray per hit.
#[derive(Clone, Copy, PartialEq)]
enum Workload {
    Primary,
    Ao,
}

fn scene(mesh: &TriangleMesh, backend: Backend, width: u32, height: u32) -> Result<(Context, BufferId)> {
    scene_with(mesh, backend, width, height, Workload::Primary)
}

/// The camera of every workload: (eye, u, v, w).
fn camera(mesh: &TriangleMesh, width: u32, height: u32) -> (Vec3, Vec3, Vec3, Vec3) {
    let (lo, hi) =
        mesh.positions.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let eye = center + Vec3::new(0.0, 0.1, 2.2) * radius;
    let w = (center - eye).normalize();
    let u = w.cross(Vec3::Y).normalize() * (width as f32 / height as f32) * 0.45;
    let v = u.cross(w).normalize() * 0.45;
    (eye, u, v, w)
}

fn scene_with(
    mesh: &TriangleMesh,
    backend: Backend,
    width: u32,
    height: u32,
    workload: Workload,
) -> Result<(Context, BufferId)> {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    ctx.set_ray_type_count(2);
    let occ_miss = ctx.create_program(&unoccluded::PROGRAM);
    ctx.set_miss_program(1, occ_miss)?;
    let rg = ctx.create_program(&pinhole::PROGRAM);
    ctx.set_ray_generation_program(0, rg)?;
    let miss = ctx.create_program(&background::PROGRAM);
    ctx.set_miss_program(0, miss)?;
    let g = ctx.create_triangles(mesh.clone())?;
    let mat = ctx.create_material();
    let ch = match workload {
        Workload::Primary => ctx.create_program(&normal_shader::PROGRAM),
        Workload::Ao => ctx.create_program(&ambient_occlusion::PROGRAM),
    };
    ctx.set_closest_hit_program(mat, 0, ch)?;
    let occ = ctx.create_program(&occluded::PROGRAM);
    ctx.set_closest_hit_program(mat, 1, occ)?;
    let gi = ctx.create_geometry_instance(g, &[mat])?;
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh))?;
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, width, height)?;
    let (eye, u, v, w) = camera(mesh, width, height);
    for (name, value) in [("eye", eye), ("u", u), ("v", v), ("w", w), ("bg_color", Vec3::new(0.2, 0.2, 0.25))] {
        ctx.set_var(Scope::Context, name, value)?;
    }
    ctx.set_var(Scope::Context, "top_object", gg)?;
    ctx.set_var(Scope::Context, "output_buffer", out)?;
    Ok((ctx, out))
}

/// The same AO workload traced by obvhs's own CWBVH traversal (rayon over
/// rows, like the CPU backend): returns (rays, time).
fn obvhs_ao(mesh: &TriangleMesh, width: u32, height: u32) -> (u64, Duration) {
    use obvhs::ray::{Ray as ORay, RayHit};
    use rayon::prelude::*;
    let tris: Vec<obvhs::triangle::Triangle> = mesh
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].into());
            obvhs::triangle::Triangle { v0: a, v1: b, v2: c }
        })
        .collect();
    let mut core = Duration::ZERO;
    let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(&tris, obvhs::BvhBuildParams::medium_build(), &mut core);
    let (eye, u, v, w) = camera(mesh, width, height);
    let closest = |o: Vec3, d: Vec3, tmin: f32| -> Option<(f32, usize)> {
        let mut hit = RayHit::none();
        let ray = ORay::new(o.into(), d.into(), tmin, f32::INFINITY);
        bvh.ray_traverse(ray, &mut hit, |r, id| tris[bvh.primitive_indices[id] as usize].intersect(r))
            .then(|| (hit.t, bvh.primitive_indices[hit.primitive_id as usize] as usize))
    };
    let start = Instant::now();
    let rays: u64 = (0..height)
        .into_par_iter()
        .map(|y| {
            let mut rays = 0u64;
            for x in 0..width {
                let d = (glam::Vec2::new(x as f32, y as f32) + 0.5) / glam::Vec2::new(width as f32, height as f32)
                    * 2.0
                    - 1.0;
                let dir = (d.x * u + d.y * v + w).normalize();
                rays += 1;
                if let Some((t, prim)) = closest(eye, dir, 1e-4) {
                    let p = eye + t * dir;
                    let tri = &tris[prim];
                    let n = Vec3::from(tri.compute_normal()).normalize();
                    let n = faceforward(n, dir, n);
                    let h1 = hash(x + y * width);
                    let h2 = hash(h1);
                    let ao = cosine_direction(n, (h1 >> 8) as f32 / 16777216.0, (h2 >> 8) as f32 / 16777216.0);
                    rays += 1;
                    std::hint::black_box(closest(p + n * 1e-4, ao, 0.0));
                }
            }
            rays
        })
        .sum();
    (rays, start.elapsed())
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
                let aabbs: Vec<obvhs::aabb::Aabb> = tris.iter().map(obvhs::Boundable::aabb).collect();
                let mut core = Duration::ZERO;
                // What the runtime builds: a BVH2 (for the GPU) and its CWBVH
                // (for the CPU); obvhs's own CWBVH build is the baseline.
                std::hint::black_box(obvhs::cwbvh::builder::build_cwbvh(
                    &aabbs,
                    obvhs::BvhBuildParams::medium_build(),
                    &mut core,
                ));
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
        "build: obvhs build_cwbvh (medium) {:.1} ms, ours (bounds + BVH2 + CWBVH) {:.1} ms, build_vs_obvhs {:.2}",
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
    // Primary + ambient occlusion on the CPU backend against obvhs's CWBVH.
    let (mut ctx, _) = scene_with(&mesh, Backend::Cpu, width, height, Workload::Ao).expect("scene");
    ctx.launch(0, width, height).expect("launch");
    let mut ours = Vec::new();
    let mut our_rays = 0;
    let mut theirs = Vec::new();
    let mut their_rays = 0;
    for _ in 0..reps {
        let r = ctx.launch(0, width, height).expect("launch");
        our_rays = r.rays;
        ours.push(r.timings.run);
        let (n, t) = obvhs_ao(&mesh, width, height);
        their_rays = n;
        theirs.push(t);
    }
    let ours_mrays = our_rays as f64 / median(ours).as_secs_f64() / 1e6;
    let theirs_mrays = their_rays as f64 / median(theirs).as_secs_f64() / 1e6;
    eprintln!(
        "primary + AO: cpu backend {ours_mrays:.2} Mrays/s ({our_rays} rays), obvhs CWBVH {theirs_mrays:.2} Mrays/s ({their_rays} rays), cpu_vs_obvhs {:.2}",
        ours_mrays / theirs_mrays
    );
    json.push(format!(
        "\"cpu_vs_obvhs\": {:.3}, \"ao_cpu_mrays_per_s\": {ours_mrays:.3}, \"ao_obvhs_mrays_per_s\": {theirs_mrays:.3}",
        ours_mrays / theirs_mrays
    ));

    // The megakernel against a hand-written kernel, same adapter, same rays.
    if args.backends.iter().any(|b| b == "wgpu") {
        match scene_with(&mesh, Backend::Wgpu, width, height, Workload::Ao) {
            Ok((mut ctx, _)) => match ctx.launch(0, width, height) {
                Ok(_) => {
                    let mut runs = Vec::new();
                    let mut rays = 0;
                    for _ in 0..reps {
                        let r = ctx.launch(0, width, height).expect("launch");
                        rays = r.rays;
                        runs.push(r.timings.run);
                    }
                    let ours = rays as f64 / median(runs).as_secs_f64() / 1e6;
                    if let Some((hrays, htime, adapter)) =
                        handwritten::run(&mesh, camera(&mesh, width, height), width, height, reps)
                    {
                        let theirs = hrays as f64 / htime.as_secs_f64() / 1e6;
                        eprintln!(
                            "primary + AO on {adapter}: megakernel {ours:.2} Mrays/s ({rays} rays), hand-written WGSL {theirs:.2} Mrays/s ({hrays} rays), megakernel_vs_handwritten {:.2}",
                            ours / theirs
                        );
                        json.push(format!(
                            "\"megakernel_vs_handwritten\": {:.3}, \"ao_megakernel_mrays_per_s\": {ours:.3}, \"ao_handwritten_mrays_per_s\": {theirs:.3}",
                            ours / theirs
                        ));
                    }
                }
                Err(e) => eprintln!("wgpu AO: {e}"),
            },
            Err(e) => eprintln!("wgpu AO: {e}"),
        }
    }

    if args.json {
        println!("{{{}}}", json.join(", "));
    }
}
