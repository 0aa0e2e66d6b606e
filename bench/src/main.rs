//! `rt-bench`: issue #6's workload in the style of tray_racing, on every
//! backend and against peers measured in the same run.
//!
//! `cargo run --release -p rt-bench -- [--quick] [--json] [--plot DIR]`, or
//! `-- --from FILE.json --plot DIR` to chart an earlier `--json` run
//! without measuring (`plot.rs`).
//!
//! - Scenes: the bunny, the teapot and the Cornell box from
//!   `../shared/scenes`, and a generated wall of 30 bunnies (2,083,530
//!   triangles, one flat mesh), each with a camera framed from its bounds.
//! - Workload: per pixel one primary ray and, at each hit, one
//!   cosine-weighted ambient-occlusion ray (closest hit, unbounded);
//!   Mrays/s counts the rays actually traced.
//! - Peers: obvhs's own CWBVH traversal (rayon, same threads), Embree 3's
//!   `rtcIntersect1` (loaded at run time, see `embree.rs`), a hand-written
//!   WGSL kernel on the same adapter as the megakernel (`handwritten.rs`),
//!   obvhs's direct build against our end-to-end build.
//! - Also: primary rays on the bunny per backend, the tour's megakernel
//!   link and pipeline times (`tour.rs`), lowering time per program
//!   (`lowering.rs`).
//!
//! Every ratio compares figures measured in this run, on this machine;
//! higher is better for us.

// The runtime's errors name programs and scopes; size does not matter here.
#![allow(clippy::result_large_err)]

mod embree;
mod handwritten;
mod handwritten_rayquery;
mod json;
mod lowering;
mod peers;
mod plot;
mod rayquery;
mod scenes;
mod tour;

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
    /// A small image, fewer repetitions, and only what lavapipe does in
    /// seconds (under 3 minutes on the 2-core CI VM).
    #[arg(long)]
    quick: bool,
    /// Print one JSON object on stdout (the table goes to stderr).
    #[arg(long)]
    json: bool,
    /// Image width (default 1920, or 320 with --quick).
    #[arg(long)]
    width: Option<u32>,
    /// Image height (default 1080, or 240 with --quick).
    #[arg(long)]
    height: Option<u32>,
    /// Backends to measure.
    #[arg(long, value_delimiter = ',', default_value = "cpu,wgpu")]
    backends: Vec<String>,
    /// Scenes to measure (bunny, teapot, cornell_box, bunny_wall_2m), or
    /// `none` (the bunny's primary-ray figures run with the bunny).
    #[arg(long, value_delimiter = ',')]
    scenes: Vec<String>,
    /// Scenes with more triangles than this skip the wgpu backend and the
    /// hand-written kernel (default: no limit; the scene's sections each
    /// fit lavapipe's 128 MiB binding, so the 2M-triangle wall runs too).
    #[arg(long)]
    wgpu_max_triangles: Option<usize>,
    /// Leave the Embree peer out.
    #[arg(long)]
    no_embree: bool,
    /// Never install Embree (by default a root run without libembree3
    /// installs Debian's package, as bench/setup.sh does).
    #[arg(long)]
    no_install: bool,
    /// Tour examples whose megakernel link to time: `auto` (the default:
    /// the four that link in seconds with --quick, plus cornell and bunny
    /// without), `fast`, `all`, `none`, or names.
    #[arg(long, value_delimiter = ',', default_value = "auto")]
    tour_links: Vec<String>,
    /// Only the per-scene traversal figures: no primary-ray or build
    /// figures, no lowering times (for profiling the traversal alone).
    #[arg(long)]
    traversal_only: bool,
    /// Use Mesa's usual on-disk shader cache (by default the bench gives
    /// Mesa a fresh one, so each kernel's first compile is cold).
    #[arg(long)]
    warm_shader_cache: bool,
    /// Write SVG charts of the Mrays/s figures into this directory
    /// (mrays_by_scene.svg, mrays_vs_triangles.svg).
    #[arg(long, value_name = "DIR")]
    plot: Option<std::path::PathBuf>,
    /// Measure nothing: chart the JSON an earlier --json run printed
    /// (needs --plot).
    #[arg(long, value_name = "FILE.json", requires = "plot")]
    from: Option<std::path::PathBuf>,
}

/// The workload: primary rays only, or primary plus one AO ray per hit.
#[derive(Clone, Copy, PartialEq)]
enum Workload {
    Primary,
    Ao,
}

fn scene_with(
    mesh: &TriangleMesh,
    cam: scenes::Camera,
    backend: Backend,
    width: u32,
    height: u32,
    workload: Workload,
) -> Result<(Context, BufferId, NodeId, GeometryId)> {
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
    let (eye, u, v, w) = cam;
    for (name, value) in [("eye", eye), ("u", u), ("v", v), ("w", w), ("bg_color", Vec3::new(0.2, 0.2, 0.25))] {
        ctx.set_var(Scope::Context, name, value)?;
    }
    ctx.set_var(Scope::Context, "top_object", gg)?;
    ctx.set_var(Scope::Context, "output_buffer", out)?;
    Ok((ctx, out, gg, g))
}

/// Geometry `g` (holding `mesh`) launched `reps` times, every vertex moved
/// before each (an animated mesh); `change` is the time of setting the
/// positions.
fn moving_vertex_launches(
    ctx: &mut Context,
    g: GeometryId,
    mesh: &TriangleMesh,
    width: u32,
    height: u32,
    reps: usize,
) -> Result<Repeated> {
    repeat_launches(ctx, width, height, reps, |ctx, i| {
        let offset = Vec3::new(0.0, 0.0, 1e-4 * (i + 1) as f32);
        let positions: Vec<Vec3> = mesh.positions.iter().map(|p| *p + offset).collect();
        let t = Instant::now();
        ctx.set_triangle_positions(g, positions)?;
        Ok(t.elapsed())
    })
}

/// The scene of `ctx` moved under a transform in a group, then launched
/// `reps` times, the transform changing before each (an animated
/// instance).
fn moving_transform_launches(ctx: &mut Context, gg: NodeId, width: u32, height: u32, reps: usize) -> Result<Repeated> {
    let xf = ctx.create_transform(glam::Mat4::IDENTITY, gg)?;
    let top = ctx.create_group(&[xf], Acceleration::default())?;
    ctx.set_var(Scope::Context, "top_object", top)?;
    ctx.launch(0, width, height)?;
    repeat_launches(ctx, width, height, reps, |ctx, i| {
        let t = Instant::now();
        ctx.set_transform(xf, glam::Mat4::from_translation(Vec3::new(0.0, 0.0, 1e-4 * (i + 1) as f32)))?;
        Ok(t.elapsed())
    })
}

use peers::median;

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn mrays(rays: u64, t: Duration) -> f64 {
    rays as f64 / t.as_secs_f64() / 1e6
}

/// What [`repeat_launches`] measured: medians, and the rays of a launch.
struct Repeated {
    /// Rays of a launch.
    rays: u64,
    /// Median time of the change made before each launch (what the change
    /// itself measured; zero for none).
    change: Duration,
    /// Median time of a launch's encoding and building (refit checks),
    /// before its run.
    prepare: Duration,
    /// Median wall-clock run time (dispatch, wait and read-back on wgpu).
    run: Duration,
    /// Median device time of the kernel, where the device has timestamps.
    kernel: Option<Duration>,
    /// Process CPU time of the `reps` launches and changes.
    cpu: Duration,
}

/// Launches `ctx` `reps` times, calling `change` (with the launch's number;
/// it returns the time of what it measures) before each.
fn repeat_launches(
    ctx: &mut Context,
    width: u32,
    height: u32,
    reps: usize,
    mut change: impl FnMut(&mut Context, usize) -> Result<Duration>,
) -> Result<Repeated> {
    let (mut changes, mut prepares, mut runs, mut kernels) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut rays = 0;
    let cpu = peers::process_cpu_time();
    for i in 0..reps {
        changes.push(change(ctx, i)?);
        let r = ctx.launch(0, width, height)?;
        rays = r.rays;
        prepares.push(r.timings.build + r.timings.encode + r.timings.link);
        runs.push(r.timings.run);
        kernels.extend(r.timings.kernel);
    }
    let cpu = peers::process_cpu_time().saturating_sub(cpu);
    let kernel = (!kernels.is_empty()).then(|| median(kernels));
    Ok(Repeated { rays, change: median(changes), prepare: median(prepares), run: median(runs), kernel, cpu })
}

/// Launches `ctx` once (building and linking), then `reps` times as they
/// are: the first launch's report and the repeats' figures.
fn measure_launches(ctx: &mut Context, width: u32, height: u32, reps: usize) -> Result<(LaunchReport, Repeated)> {
    let first = ctx.launch(0, width, height)?;
    Ok((first, repeat_launches(ctx, width, height, reps, |_, _| Ok(Duration::ZERO))?))
}

/// Launches alternating between two settings, `set(ctx, false)` then
/// `set(ctx, true)`, `reps` times each, so both sides see the same machine
/// state: the medians of their whole times (build, encode, link and run),
/// false's then true's, and true's last report.
fn alternating(
    ctx: &mut Context,
    width: u32,
    height: u32,
    reps: usize,
    set: impl Fn(&mut Context, bool),
) -> Result<(Duration, Duration, Option<LaunchReport>)> {
    let (mut off, mut on, mut last) = (Vec::new(), Vec::new(), None);
    for _ in 0..reps {
        for side in [false, true] {
            set(ctx, side);
            let r = ctx.launch(0, width, height)?;
            let t = r.timings.build + r.timings.encode + r.timings.link + r.timings.run;
            if side {
                on.push(t);
                last = Some(r);
            } else {
                off.push(t);
            }
        }
    }
    Ok((median(off), median(on), last))
}

/// What cutting launches into tiles costs: `reps` launches as tiles (the
/// default budget) alternating with `reps` whole ones, the medians of
/// their whole times and the tiles of a tiled launch.
fn tiled_and_whole(ctx: &mut Context, width: u32, height: u32, reps: usize) -> Result<(Duration, Duration, u32)> {
    let budget = |tiled| if tiled { TileBudget::default() } else { TileBudget::Whole };
    let measured = alternating(ctx, width, height, reps, |c, tiled| c.set_tile_budget(budget(tiled)));
    ctx.set_tile_budget(TileBudget::default());
    let (whole, tiled, last) = measured?;
    Ok((tiled, whole, last.map_or(0, |r| r.tiles)))
}

/// What exception checks cost (OptiX's `rtContextSetExceptionEnabled`):
/// `reps` launches with every kind on (the default) alternating with `reps`
/// with every kind off, the ratio of their median times (above 1: turning
/// them off pays), into `j` as `exceptions_off_vs_on`.
fn record_exceptions_off(j: &mut json::Json, ctx: &mut Context, width: u32, height: u32, reps: usize) -> Option<f64> {
    let measured = alternating(ctx, width, height, reps, |c, on| c.set_exception_enabled(ExceptionKind::All, on));
    ctx.set_exception_enabled(ExceptionKind::All, true);
    match measured {
        Ok((off, on, _)) => {
            let r = on.as_secs_f64() / off.as_secs_f64();
            eprintln!("exceptions on {:.1} ms, off {:.1} ms: exceptions_off_vs_on {r:.3}", ms(on), ms(off));
            let o = j.child("exceptions_off_vs_on");
            o.set("on_ms", ms(on));
            o.set("off_ms", ms(off));
            Some(r)
        }
        Err(e) => {
            eprintln!("exceptions on against off: {e}");
            None
        }
    }
}

/// [`tiled_and_whole`] into `j` (as `tiled_vs_whole`), and the throughput
/// ratio of tiled launches over whole ones (below 1: tiles cost time).
fn record_tiled_and_whole(j: &mut json::Json, measured: Result<(Duration, Duration, u32)>) -> Option<f64> {
    match measured {
        Ok((tiled, whole, tiles)) => {
            eprintln!(
                "tiled launches ({tiles} tiles) {:.1} ms, whole launches {:.1} ms: tiled_vs_whole {:.3}",
                ms(tiled),
                ms(whole),
                whole.as_secs_f64() / tiled.as_secs_f64()
            );
            let o = j.child("tiled_vs_whole");
            o.set("tiles", tiles);
            o.set("tiled_ms", ms(tiled));
            o.set("whole_ms", ms(whole));
            Some(whole.as_secs_f64() / tiled.as_secs_f64())
        }
        Err(e) => {
            eprintln!("tiled against whole launches: {e}");
            None
        }
    }
}

/// Primary rays (normal shader) on the bunny per backend, and the build
/// against obvhs's: the figures the bench reported before issue #6.
fn bunny_primary(args: &Args, bunny: &scenes::BenchScene, width: u32, height: u32, reps: usize, json: &mut json::Json) {
    let mesh = &bunny.mesh;
    let cam = bunny.camera(width, height);
    eprintln!("bunny: {} triangles, {width}x{height}, primary rays (normal shader)", mesh.indices.len());
    let tris = bunny.obvhs_triangles();
    // Alternating, one of each per round (more rounds than launches: a
    // build is short and noisy), so both sides see the same machine state;
    // in blocks (all of obvhs's, then ours) the ratio read 0.72-0.80 where
    // the per-scene builds of the same run read about 1.
    let obvhs_once = || {
        let t = Instant::now();
        let aabbs: Vec<obvhs::aabb::Aabb> = tris.iter().map(obvhs::Boundable::aabb).collect();
        let mut core = Duration::ZERO;
        // What the runtime builds: a BVH2 (for the GPU) and its CWBVH (for
        // the CPU); obvhs's own CWBVH build is the baseline.
        std::hint::black_box(obvhs::cwbvh::builder::build_cwbvh(
            &aabbs,
            obvhs::BvhBuildParams::medium_build(),
            &mut core,
        ));
        t.elapsed()
    };
    let ours_once = || -> Result<Duration> {
        let (mut ctx, ..) = scene_with(mesh, cam, Backend::Cpu, 1, 1, Workload::Primary)?;
        Ok(ctx.launch(0, 1, 1)?.timings.build)
    };
    let (mut obvhs_times, mut our_times) = (Vec::new(), Vec::new());
    let mut our_build: Result<()> = Ok(());
    for round in 0..reps * 6 {
        // Order alternates too (obvhs first, then ours first): whichever
        // runs second finds the other's freed memory and warm threads.
        if round % 2 == 0 {
            obvhs_times.push(obvhs_once());
        }
        match ours_once() {
            Ok(d) => our_times.push(d),
            Err(e) => {
                our_build = Err(e);
                break;
            }
        }
        if round % 2 == 1 {
            obvhs_times.push(obvhs_once());
        }
    }
    let obvhs_build = median(obvhs_times);
    let our_build = our_build.map(|()| our_times);
    match our_build {
        Ok(b) => {
            let our_build = median(b);
            let ratio = obvhs_build.as_secs_f64() / our_build.as_secs_f64();
            eprintln!(
                "build: obvhs build_cwbvh (medium) {:.1} ms, ours (bounds + BVH2 + CWBVH) {:.1} ms, build_vs_obvhs {ratio:.2}",
                ms(obvhs_build),
                ms(our_build),
            );
            json.set("build_vs_obvhs", ratio);
            json.set("build_obvhs_ms", ms(obvhs_build));
            json.set("build_ours_ms", ms(our_build));
        }
        Err(e) => {
            eprintln!("build: {e}");
            json.set("build_vs_obvhs", json::Json::Null);
        }
    }
    for b in &args.backends {
        let backend = if b == "cpu" { Backend::Cpu } else { Backend::Wgpu };
        let run = || -> Result<json::Json> {
            let (mut ctx, out, ..) = scene_with(mesh, cam, backend, width, height, Workload::Primary)?;
            // The compute traversal (the ray-query one is measured per scene).
            ctx.set_traversal(rt_runtime::Traversal::Compute);
            let device = if backend == Backend::Wgpu {
                ctx.open_wgpu()?
            } else {
                format!("cpu, {} threads", rayon::current_num_threads())
            };
            let (first, Repeated { rays, run, kernel, .. }) = measure_launches(&mut ctx, width, height, reps)?;
            let m = mrays(rays, run);
            let img = ctx.read_buffer::<Vec4>(out)?;
            let hit = img.iter().filter(|c| c.truncate() != Vec3::new(0.2, 0.2, 0.25)).count();
            eprintln!(
                "{b} [{device}]: {m:.2} Mrays/s ({rays} rays in {:.1} ms, {:.0}% of pixels hit); first launch: link {:.1} ms, encode {:.1} ms",
                ms(run),
                100.0 * hit as f64 / img.len() as f64,
                ms(first.timings.link),
                ms(first.timings.encode)
            );
            let mut j = json::Json::obj();
            j.set("device", device);
            j.set("mrays_per_s", m);
            j.set("kernel_mrays_per_s", kernel.map(|k| mrays(rays, k)));
            j.set("link_ms", ms(first.timings.link));
            Ok(j)
        };
        match run() {
            Ok(j) => json.set(b, j),
            Err(e) => {
                eprintln!("{b}: {e}");
                json.set(b, json::Json::Null);
            }
        }
    }
}

/// The launch settings' ratios of one backend: tiled over whole launches,
/// every exception kind off over on.
struct LaunchRatios {
    tiled: Option<f64>,
    exceptions_off: Option<f64>,
}

/// What one scene measured, for the top-level ratios.
#[derive(Default)]
struct SceneFigures {
    cpu: Option<f64>,
    obvhs: Option<f64>,
    /// Embree's best mode: the faster of `embree1` and `embree16`.
    embree: Option<f64>,
    /// `rtcIntersect1` (single rays) and `rtcIntersect16` (4x4 tiles).
    embree1: Option<f64>,
    embree16: Option<f64>,
    /// The CPU backend's tree and walk without its programs, and its rays.
    walk: Option<f64>,
    walk_rays: u64,
    /// The same tree walked by 16-ray packets (4x4 tiles, then their AO
    /// rays), as Embree's `rtcIntersect16` is driven.
    packet_walk: Option<f64>,
    /// The primary rays alone (no AO rays traced), one by one and in
    /// packets: where packets should pay most.
    walk_primary: Option<f64>,
    packet_walk_primary: Option<f64>,
    wgpu: Option<f64>,
    handwritten: Option<f64>,
    /// Rays per CPU second of the process (lavapipe's threads), which
    /// load from other processes does not change.
    wgpu_per_cpu_s: Option<f64>,
    handwritten_per_cpu_s: Option<f64>,
    /// Rays per second of the device's own time (timestamp queries): the
    /// kernels alone, without submission, waiting and read-back.
    wgpu_kernel: Option<f64>,
    handwritten_kernel: Option<f64>,
    /// The hand-written kernel over the BVH2 instead of the CWBVH.
    handwritten_bvh2: Option<f64>,
    handwritten_bvh2_kernel: Option<f64>,
    /// The megakernel with the ray-query traversal, and the hand-written
    /// ray-query kernel (wall clock, device time).
    rayquery: Option<f64>,
    rayquery_kernel: Option<f64>,
    rayquery_handwritten: Option<f64>,
    rayquery_handwritten_kernel: Option<f64>,
    /// Throughput of launches cut into tiles (the default) over whole
    /// ones, per backend.
    cpu_tiled_vs_whole: Option<f64>,
    wgpu_tiled_vs_whole: Option<f64>,
    /// Throughput with every exception kind off over every kind on.
    cpu_exceptions_off_vs_on: Option<f64>,
    wgpu_exceptions_off_vs_on: Option<f64>,
}

/// The AO workload on one scene: every backend and peer.
#[allow(clippy::too_many_arguments)]
fn measure_scene(
    args: &Args,
    scene: &scenes::BenchScene,
    embree: Option<&embree::Embree>,
    width: u32,
    height: u32,
    reps: usize,
    wgpu_max_triangles: usize,
    j: &mut json::Json,
) -> SceneFigures {
    let mut fig = SceneFigures::default();
    let cam = scene.camera(width, height);
    let tris = scene.obvhs_triangles();
    j.set("triangles", scene.triangles());
    j.set("source", scene.source.as_str());
    eprintln!("\n{}: {} triangles, {width}x{height}, primary + AO", scene.name, scene.triangles());

    // Builds: obvhs's CWBVH, Embree's own BVH, then ours inside the first
    // CPU launch (one sample each).
    let (bvh, obvhs_build) = peers::obvhs_cwbvh(&tris);
    let builds = j.child("build_ms");
    builds.set("obvhs_cwbvh", ms(obvhs_build));
    let embree_scene = embree.map(|e| e.build(&scene.mesh.positions, &scene.mesh.indices));
    let embree_scene = match embree_scene {
        Some(Ok((s, t))) => {
            builds.set("embree", ms(t));
            Some(s)
        }
        Some(Err(e)) => {
            eprintln!("embree build: {e}");
            None
        }
        None => None,
    };
    let mut cpu_gg = None;
    let mut cpu_ctx = if args.backends.iter().any(|b| b == "cpu") {
        match scene_with(&scene.mesh, cam, Backend::Cpu, width, height, Workload::Ao)
            .and_then(|(mut c, _, gg, _)| c.launch(0, width, height).map(|r| (c, r, gg)))
        {
            Ok((c, first, gg)) => {
                j.child("build_ms").set("ours", ms(first.timings.build));
                cpu_gg = Some(gg);
                Some(c)
            }
            Err(e) => {
                eprintln!("cpu: {e}");
                None
            }
        }
    } else {
        None
    };

    // Traversal, interleaved so load from elsewhere spreads over all sides.
    let (mut ours, mut theirs, mut emb, mut our_prepare) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut emb16 = Vec::new();
    let (mut our_rays, mut obvhs_run, mut embree_run, mut embree16_run) = (0, None, None, None);
    // The CPU backend's walk alone (its tree, no programs): how much of
    // the gap to Embree is traversal and how much the programs around it.
    let walk_tree = (args.backends.iter().any(|b| b == "cpu")).then(|| {
        let flat: Vec<[glam::Vec3; 3]> = tris.iter().map(|t| [t.v0, t.v1, t.v2].map(glam::Vec3::from)).collect();
        rt_runtime::accel::wide::testing::Triangles::new(flat)
    });
    let simd = rt_runtime::accel::CpuSimd::current();
    let mut walks = Vec::new();
    let (mut packet_walks, mut packet_rays) = (Vec::new(), 0);
    let (mut primary_walks, mut primary_packet_walks) = (Vec::new(), Vec::new());
    for _ in 0..reps {
        if let Some(ctx) = cpu_ctx.as_mut() {
            match ctx.launch(0, width, height) {
                Ok(r) => {
                    our_rays = r.rays;
                    ours.push(r.timings.run);
                    our_prepare.push(r.timings.build + r.timings.encode);
                }
                Err(e) => {
                    eprintln!("cpu: {e}");
                    cpu_ctx = None;
                }
            }
        }
        if let Some(t) = &walk_tree {
            let w = peers::trace_ao(&tris, cam, width, height, |o, d, tmin| {
                t.closest(simd, o, d, tmin, f32::INFINITY).map(|h| (h.0, h.1))
            });
            walks.push(w.time);
            fig.walk_rays = w.rays;
            // A packet's closest hits, as `trace_ao16` takes them.
            let packet = |rays: &[(glam::Vec3, glam::Vec3, f32)], out: &mut [Option<(f32, u32)>]| {
                let mut hits = [None; rt_runtime::accel::wide::testing::PACKET_RAYS];
                t.closest_packet(simd, rays, &mut hits);
                for (o, h) in out.iter_mut().zip(hits) {
                    *o = h.map(|h| (h.0, h.1));
                }
            };
            let p = peers::trace_ao16(&tris, cam, width, height, |rays, _, out| packet(rays, out));
            packet_walks.push(p.time);
            packet_rays = p.rays;
            // Primary rays only: AO rays (traced with tmin 0, or not
            // coherent) are not traced.
            let w = peers::trace_ao(&tris, cam, width, height, |o, d, tmin| {
                (tmin != 0.0).then(|| t.closest(simd, o, d, tmin, f32::INFINITY).map(|h| (h.0, h.1))).flatten()
            });
            primary_walks.push(w.time);
            let p = peers::trace_ao16(&tris, cam, width, height, |rays, coherent, out| {
                out.fill(None);
                if coherent {
                    packet(rays, out);
                }
            });
            primary_packet_walks.push(p.time);
        }
        let o = peers::obvhs_ao(&bvh, &tris, cam, width, height);
        theirs.push(o.time);
        obvhs_run = Some(o);
        if let Some(s) = &embree_scene {
            let e = peers::trace_ao(&tris, cam, width, height, |o, d, tmin| s.intersect(o, d, tmin));
            emb.push(e.time);
            embree_run = Some(e);
            let e =
                peers::trace_ao16(&tris, cam, width, height, |rays, coherent, out| s.intersect16(rays, coherent, out));
            emb16.push(e.time);
            embree16_run = Some(e);
        }
    }
    let obvhs_run = obvhs_run.expect("reps >= 1");
    if !walks.is_empty() {
        fig.walk = Some(mrays(fig.walk_rays, median(walks)));
        fig.packet_walk = Some(mrays(packet_rays, median(packet_walks)));
        let primary = (width * height) as u64;
        fig.walk_primary = Some(mrays(primary, median(primary_walks)));
        fig.packet_walk_primary = Some(mrays(primary, median(primary_packet_walks)));
    }
    let rays = j.child("rays");
    rays.set("obvhs", obvhs_run.rays);
    fig.obvhs = Some(mrays(obvhs_run.rays, median(theirs)));
    if !ours.is_empty() {
        fig.cpu = Some(mrays(our_rays, median(ours)));
        // A repeated launch's host work before the rays (refit checks,
        // variables resolved, programs bound).
        j.set("cpu_repeat_prepare_ms", ms(median(our_prepare)));
        j.child("rays").set("cpu", our_rays);
    }
    if let Some(e) = &embree16_run {
        fig.embree16 = Some(mrays(e.rays, median(emb16)));
        let (p, a) = peers::mismatches(e, &obvhs_run);
        let m = j.child("embree16_vs_obvhs_mismatches");
        m.set("primary", p);
        m.set("ao", a);
    }
    if let Some(e) = &embree_run {
        fig.embree1 = Some(mrays(e.rays, median(emb)));
        fig.embree = match (fig.embree1, fig.embree16) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        j.child("rays").set("embree", e.rays);
        let (p, a) = peers::mismatches(e, &obvhs_run);
        let m = j.child("embree_vs_obvhs_mismatches");
        m.set("primary", p);
        m.set("ao", a);
        m.set("pixels", (width * height) as usize);
    }
    eprintln!(
        "cpu backend {} Mrays/s (its walk alone {}), obvhs CWBVH {:.2}, embree {} (rtcIntersect1 {}, rtcIntersect16 {})",
        fig.cpu.map_or("-".into(), |x| format!("{x:.2}")),
        fig.walk.map_or("-".into(), |x| format!("{x:.2}")),
        fig.obvhs.unwrap_or(0.0),
        fig.embree.map_or("-".into(), |x| format!("{x:.2}")),
        fig.embree1.map_or("-".into(), |x| format!("{x:.2}")),
        fig.embree16.map_or("-".into(), |x| format!("{x:.2}")),
    );
    // The same scene as an instance under a moving transform.
    if let (Some(ctx), Some(gg), Some(flat)) = (cpu_ctx.as_mut(), cpu_gg, fig.cpu) {
        match moving_transform_launches(ctx, gg, width, height, reps) {
            Ok(m) => {
                let moved = j.child("cpu_moving_transform");
                moved.set("prepare_ms", ms(m.prepare));
                moved.set("run_ms", ms(m.run));
                moved.set("mrays_per_s", mrays(m.rays, m.run));
                moved.set("vs_flat", mrays(m.rays, m.run) / flat);
            }
            Err(e) => eprintln!("cpu under a transform: {e}"),
        }
    }
    if let Some(ctx) = cpu_ctx.as_mut() {
        let measured = tiled_and_whole(ctx, width, height, reps);
        fig.cpu_tiled_vs_whole = record_tiled_and_whole(j.child("cpu"), measured);
        fig.cpu_exceptions_off_vs_on = record_exceptions_off(j.child("cpu"), ctx, width, height, reps);
    }
    drop(cpu_ctx);
    drop(embree_scene);

    // The megakernel against the hand-written kernel, same adapter.
    if args.backends.iter().any(|b| b == "wgpu") {
        measure_gpu(scene, cam, (width, height), reps, wgpu_max_triangles, j, &mut fig);
    }
    record_figures(j, &fig);
    fig
}

/// The wgpu side of [`measure_scene`]: the megakernel, then the
/// hand-written kernel over the CWBVH and over the BVH2, on one adapter.
#[allow(clippy::too_many_arguments)]
fn measure_gpu(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    wgpu_max_triangles: usize,
    j: &mut json::Json,
    fig: &mut SceneFigures,
) {
    use json::Json;
    if scene.triangles() > wgpu_max_triangles {
        let why = format!("{} triangles > --wgpu-max-triangles {wgpu_max_triangles}", scene.triangles());
        j.child("skipped").set("wgpu", why.as_str());
        j.child("skipped").set("handwritten_wgsl", why.as_str());
    } else {
        let run = || -> Result<(Json, Repeated, String, LaunchRatios)> {
            let (mut ctx, _, gg, g) = scene_with(&scene.mesh, cam, Backend::Wgpu, width, height, Workload::Ao)?;
            ctx.set_traversal(rt_runtime::Traversal::Compute);
            let device = ctx.open_wgpu()?;
            let (first, l) = measure_launches(&mut ctx, width, height, reps)?;
            let cwbvh = ctx.linked_wgsl().is_some_and(|w| w.contains("const RT_CWBVH: bool = true;"));
            let transform = moving_transform_launches(&mut ctx, gg, width, height, reps)?;
            let vertices = moving_vertex_launches(&mut ctx, g, &scene.mesh, width, height, reps)?;
            let mut w = Json::obj();
            w.set("tree", if cwbvh { "cwbvh" } else { "bvh2" });
            w.set("rays", l.rays);
            w.set("build_ms", ms(first.timings.build));
            w.set("link_ms", ms(first.timings.link));
            w.set("first_dispatch_ms", ms(first.timings.run.saturating_sub(l.run)));
            // Repeated launches, in medians: the host's preparation, the
            // run (upload, dispatch, wait, read-back), the kernel; as
            // they are, under a transform that moves before each launch,
            // and with every vertex moved before each (refit, geometry
            // encoded and uploaded again).
            for (key, r) in [
                ("repeat_launch_ms", &l),
                ("moving_transform_launch_ms", &transform),
                ("moving_vertices_launch_ms", &vertices),
            ] {
                let o = w.child(key);
                o.set("prepare", ms(r.prepare));
                o.set("run", ms(r.run));
                o.set("kernel", r.kernel.map(ms));
            }
            w.child("moving_vertices_launch_ms").set("set_positions", ms(vertices.change));
            let tiled = record_tiled_and_whole(&mut w, tiled_and_whole(&mut ctx, width, height, reps));
            let exceptions_off = record_exceptions_off(&mut w, &mut ctx, width, height, reps);
            Ok((w, l, device, LaunchRatios { tiled, exceptions_off }))
        };
        match run() {
            Ok((w, l, device, ratios)) => {
                fig.wgpu_tiled_vs_whole = ratios.tiled;
                fig.wgpu_exceptions_off_vs_on = ratios.exceptions_off;
                j.set("wgpu_first_launch", w);
                j.set("wgpu_device", device);
                fig.wgpu = Some(mrays(l.rays, l.run));
                fig.wgpu_per_cpu_s = Some((l.rays * reps as u64) as f64 / l.cpu.as_secs_f64().max(1e-3));
                fig.wgpu_kernel = l.kernel.map(|k| mrays(l.rays, k));
            }
            Err(e) => {
                eprintln!("wgpu: {e}");
                j.child("skipped").set("wgpu", e.to_string());
            }
        }
        match handwritten::run(&scene.mesh, cam, width, height, reps, handwritten::Tree::Cwbvh) {
            Ok(m) => {
                fig.handwritten = Some(mrays(m.rays, m.time));
                fig.handwritten_per_cpu_s = Some((m.rays * reps as u64) as f64 / m.cpu.as_secs_f64().max(1e-3));
                fig.handwritten_kernel = m.kernel.map(|k| mrays(m.rays, k));
                j.child("rays").set("handwritten_wgsl", m.rays);
                if j.get("wgpu_device").and_then(|d| d.as_str()).is_some_and(|d| d != m.device) {
                    eprintln!("hand-written WGSL ran on {}, not on the megakernel's adapter", m.device);
                    j.set("adapters_differ", true);
                }
                j.set("handwritten_wgsl_device", m.device);
            }
            Err(e) => {
                eprintln!("hand-written WGSL: {e}");
                j.child("skipped").set("handwritten_wgsl", e);
            }
        }
        // The same kernel over the BVH2 the CWBVH is converted from
        // (what the megakernel walks with any-hit or intersection
        // programs; the baseline before it walked CWBVHs).
        match handwritten::run(&scene.mesh, cam, width, height, reps, handwritten::Tree::Bvh2) {
            Ok(m) => {
                fig.handwritten_bvh2 = Some(mrays(m.rays, m.time));
                fig.handwritten_bvh2_kernel = m.kernel.map(|k| mrays(m.rays, k));
                j.child("rays").set("handwritten_bvh2_wgsl", m.rays);
            }
            Err(e) => {
                eprintln!("hand-written BVH2 WGSL: {e}");
                j.child("skipped").set("handwritten_bvh2_wgsl", e);
            }
        }
        rayquery::measure(scene, cam, (width, height), reps, j, fig);
        let show = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.2}"));
        eprintln!(
            "compute traversal: megakernel {} Mrays/s, hand-written WGSL {} (BVH2: {}); device time alone: megakernel {}, hand-written {} (BVH2: {})",
            show(fig.wgpu),
            show(fig.handwritten),
            show(fig.handwritten_bvh2),
            show(fig.wgpu_kernel),
            show(fig.handwritten_kernel),
            show(fig.handwritten_bvh2_kernel),
        );
    }
}

/// A scene's figures into its JSON object.
fn record_figures(j: &mut json::Json, fig: &SceneFigures) {
    for (k, v) in [
        ("cpu", fig.cpu),
        ("wgpu", fig.wgpu),
        ("obvhs", fig.obvhs),
        ("embree", fig.embree),
        ("embree_intersect1", fig.embree1),
        ("embree_intersect16", fig.embree16),
        ("cpu_walk_only", fig.walk),
        ("cpu_packet_walk_only", fig.packet_walk),
        ("cpu_walk_only_primary", fig.walk_primary),
        ("cpu_packet_walk_only_primary", fig.packet_walk_primary),
        ("handwritten_wgsl", fig.handwritten),
        ("handwritten_bvh2_wgsl", fig.handwritten_bvh2),
        ("rayquery", fig.rayquery),
        ("handwritten_rayquery", fig.rayquery_handwritten),
    ] {
        j.child("mrays_per_s").set(k, v);
    }
    // The kernels alone (device timestamps), and the megakernel's Grays/s
    // by them: the figure a GPU is judged by.
    for (k, v) in [
        ("wgpu", fig.wgpu_kernel),
        ("handwritten_wgsl", fig.handwritten_kernel),
        ("handwritten_bvh2_wgsl", fig.handwritten_bvh2_kernel),
        ("rayquery", fig.rayquery_kernel),
        ("handwritten_rayquery", fig.rayquery_handwritten_kernel),
    ] {
        j.child("kernel_mrays_per_s").set(k, v);
    }
    j.set("wgpu_grays_per_s", fig.wgpu_kernel.or(fig.wgpu).map(|m| m / 1e3));
    if fig.wgpu.is_some() {
        j.set("wgpu_grays_timed_by", if fig.wgpu_kernel.is_some() { "device timestamps" } else { "wall clock" });
    }
}

/// One of the headline ratios, from one scene's figures.
type RatioOf = fn(&SceneFigures) -> Option<f64>;

/// `a / b` where both were measured.
fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    Some(a? / b?)
}

/// Geometric mean of the ratios that exist, with how many there were.
fn geomean(rs: &[Option<f64>]) -> Option<f64> {
    let v: Vec<f64> = rs.iter().flatten().copied().collect();
    (!v.is_empty()).then(|| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp())
}

/// Writes the charts of `figures` into `dir`, or says why not and exits
/// with status 2.
fn plot_or_exit(figures: std::result::Result<plot::Figures, String>, dir: &std::path::Path) {
    match figures.and_then(|f| plot::write(&f, dir)) {
        Ok(paths) => paths.iter().for_each(|p| eprintln!("plot: {}", p.display())),
        Err(e) => {
            eprintln!("rt-bench: {e}");
            std::process::exit(2);
        }
    }
}

fn main() {
    use json::Json;
    let args = Args::parse();
    if let (Some(file), Some(dir)) = (&args.from, &args.plot) {
        plot_or_exit(plot::read(file), dir);
        return;
    }
    if let Some(b) = args.backends.iter().find(|b| *b != "cpu" && *b != "wgpu") {
        eprintln!("unknown backend `{b}` (cpu or wgpu)");
        std::process::exit(2);
    }
    // A fresh Mesa shader cache for this run: the first compile of each
    // kernel is cold (what the link figures report), and the same kernel
    // over the next scene is not compiled again.
    let shader_cache = std::env::temp_dir().join(format!("rt-bench-mesa-cache-{}", std::process::id()));
    // Before any thread exists (rayon and wgpu start later).
    if !args.warm_shader_cache {
        // SAFETY: set before any thread exists (rayon and wgpu start later).
        unsafe { std::env::set_var("MESA_SHADER_CACHE_DIR", &shader_cache) };
    }
    let (width, height) = match (args.width, args.height) {
        (Some(w), Some(h)) => (w, h),
        _ if args.quick => (320, 240),
        _ => (1920, 1080),
    };
    let reps = if args.quick { 3 } else { 5 };
    let wgpu_max_triangles = args.wgpu_max_triangles.unwrap_or(usize::MAX);
    let dir = scenes::scenes_dir().unwrap_or_else(|e| {
        eprintln!("rt-bench: {e}");
        std::process::exit(2);
    });
    let all = scenes::load_all(&dir).unwrap_or_else(|e| {
        eprintln!("rt-bench: {e}");
        std::process::exit(2);
    });
    let start = Instant::now();
    let mut json = Json::obj();
    let machine = json.child("machine");
    machine.set("threads", rayon::current_num_threads());
    machine.set("resolution", format!("{width}x{height}"));
    machine.set("reps", reps);
    machine.set(
        "mesa_shader_cache",
        if args.warm_shader_cache {
            "the user's (link times may be warm)"
        } else {
            "fresh for this run (first compile of each kernel cold)"
        },
    );

    let embree = if args.no_embree { Err("--no-embree".to_string()) } else { embree::Embree::load(!args.no_install) };
    match &embree {
        Ok(e) => {
            eprintln!(
                "embree {} ({}): rtcIntersect1 and rtcIntersect16, its own BVH (medium build quality)",
                e.version, e.library
            );
            let j = json.child("embree");
            j.set("version", e.version.as_str());
            j.set("library", e.library.as_str());
            j.set(
                "api",
                "the faster of rtcIntersect1 (single rays) and rtcIntersect16 (4x4 tiles: primary rays, then their AO rays), its own BVH (RTC_BUILD_QUALITY_MEDIUM), rayon threads",
            );
        }
        Err(why) => {
            eprintln!("embree: absent: {why}");
            json.set("embree", Json::Null);
            json.set("embree_absent_reason", why.as_str());
        }
    }

    let no_scenes = args.scenes.iter().any(|s| s == "none");
    if !no_scenes && !args.traversal_only && (args.scenes.is_empty() || args.scenes.iter().any(|s| s == "bunny")) {
        bunny_primary(&args, &all[0], width, height, reps, &mut json);
    }

    let mut figures = Vec::new();
    for scene in &all {
        if no_scenes || (!args.scenes.is_empty() && !args.scenes.iter().any(|s| s == scene.name)) {
            continue;
        }
        let j = json.child("scenes").child(scene.name);
        let f = measure_scene(&args, scene, embree.as_ref().ok(), width, height, reps, wgpu_max_triangles, j);
        figures.push((scene.name, f));
    }
    // The headline ratios on the bunny (as before issue #6), and their
    // geometric means over the scenes where both sides were measured.
    let pick = |name: &str| figures.iter().find(|(n, _)| *n == name).map(|(_, f)| f);
    let ratios: [(&str, RatioOf); 19] = [
        ("cpu_vs_obvhs", |f| ratio(f.cpu, f.obvhs)),
        // Against Embree's best mode (the faster of rtcIntersect1 and
        // rtcIntersect16), and against its single rays alone (the key of
        // the sessions before rtcIntersect16 was measured).
        ("cpu_vs_embree", |f| ratio(f.cpu, f.embree)),
        ("cpu_vs_embree_intersect1", |f| ratio(f.cpu, f.embree1)),
        // The CPU backend's walk without programs against Embree's best.
        ("cpu_walk_only_vs_embree", |f| ratio(f.walk, f.embree)),
        // What 16-ray packets give the same walk (above 1: packets pay),
        // and the packet walk against Embree's own packets.
        ("cpu_packet_walk_vs_walk", |f| ratio(f.packet_walk, f.walk)),
        ("cpu_packet_walk_vs_walk_primary", |f| ratio(f.packet_walk_primary, f.walk_primary)),
        ("cpu_packet_walk_vs_embree16", |f| ratio(f.packet_walk, f.embree16)),
        ("megakernel_vs_handwritten", |f| ratio(f.wgpu, f.handwritten)),
        // The same, as rays per CPU second of this process: steady under
        // load from other processes, which the wall-clock ratio is not.
        ("megakernel_vs_handwritten_cpu_time", |f| ratio(f.wgpu_per_cpu_s, f.handwritten_per_cpu_s)),
        // The kernels alone, by the device's timestamps (on a GPU, where
        // submission and read-back are a large part of a short launch).
        ("megakernel_vs_handwritten_kernel", |f| ratio(f.wgpu_kernel, f.handwritten_kernel)),
        // What 8-wide nodes give a kernel on this adapter (device time;
        // above 1: the CWBVH kernel is faster).
        ("handwritten_cwbvh_vs_bvh2_kernel", |f| ratio(f.handwritten_kernel, f.handwritten_bvh2_kernel)),
        // The megakernel's two traversals on one adapter (above 1: ray
        // queries are faster), and the ray-query megakernel against the
        // hand-written ray-query kernel (goal >= 0.9).
        ("rayquery_vs_compute", |f| ratio(f.rayquery, f.wgpu)),
        ("rayquery_vs_compute_kernel", |f| ratio(f.rayquery_kernel, f.wgpu_kernel)),
        ("megakernel_rayquery_vs_handwritten", |f| ratio(f.rayquery, f.rayquery_handwritten)),
        ("megakernel_rayquery_vs_handwritten_kernel", |f| ratio(f.rayquery_kernel, f.rayquery_handwritten_kernel)),
        // Launches cut into tiles (the default budget) against whole ones
        // (above 1: tiles are faster).
        ("cpu_tiled_vs_whole_launch", |f| f.cpu_tiled_vs_whole),
        ("wgpu_tiled_vs_whole_launch", |f| f.wgpu_tiled_vs_whole),
        ("cpu_exceptions_off_vs_on", |f| f.cpu_exceptions_off_vs_on),
        ("wgpu_exceptions_off_vs_on", |f| f.wgpu_exceptions_off_vs_on),
    ];
    for (key, r) in ratios {
        json.set(key, pick("bunny").and_then(r));
        let all: Vec<Option<f64>> = figures.iter().map(|(_, f)| r(f)).collect();
        json.set(&format!("{key}_geomean"), geomean(&all));
    }
    // How each side's speed holds from the bunny (69k triangles) to the
    // wall (2M): Mrays/s on the wall over Mrays/s on the bunny.
    let scaling = |side: fn(&SceneFigures) -> Option<f64>| {
        ratio(pick("bunny_wall_2m").and_then(side), pick("bunny").and_then(side))
    };
    json.set("cpu_scaling", scaling(|f| f.cpu));
    json.set("embree_scaling", scaling(|f| f.embree));
    json.set("cpu_simd", rt_runtime::accel::CpuSimd::current().name());
    json.set(
        "obvhs_vs_embree_geomean",
        geomean(&figures.iter().map(|(_, f)| ratio(f.obvhs, f.embree)).collect::<Vec<_>>()),
    );

    if !args.traversal_only {
        lowering::measure(if args.quick { 5 } else { 20 }, json.child("lowering"));
    }

    // The tour's program sets on the wgpu backend.
    if args.backends.iter().any(|b| b == "wgpu") {
        let names: Vec<String> = match args.tour_links.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
            ["none"] => Vec::new(),
            ["auto"] if args.quick => tour::FAST.iter().map(|s| s.to_string()).collect(),
            ["auto"] => tour::FAST.iter().chain(&tour::MEDIUM).map(|s| s.to_string()).collect(),
            ["fast"] => tour::FAST.iter().map(|s| s.to_string()).collect(),
            ["all"] => examples::EXAMPLES.iter().map(|e| e.name.to_string()).collect(),
            _ => args.tour_links.clone(),
        };
        eprintln!();
        tour::measure(&names, json.child("tour_links"));
    }
    if !args.warm_shader_cache {
        let _ = std::fs::remove_dir_all(&shader_cache);
    }
    json.set("seconds", start.elapsed().as_secs_f64());
    eprintln!("\ndone in {:.1} s", start.elapsed().as_secs_f64());
    if args.json {
        println!("{json}");
    }
    if let Some(dir) = &args.plot {
        let run = serde_json::from_str(&json.to_string()).expect("the bench's JSON reads back");
        plot_or_exit(plot::figures(&run), dir);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_without_plot_is_an_argument_error() {
        let e = Args::try_parse_from(["rt-bench", "--from", "run.json"]).err().expect("--from needs --plot");
        assert_eq!(e.kind(), clap::error::ErrorKind::MissingRequiredArgument);
        assert!(Args::try_parse_from(["rt-bench", "--from", "run.json", "--plot", "plots"]).is_ok());
    }
}
