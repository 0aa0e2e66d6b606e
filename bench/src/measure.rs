//! The AO workload on one scene: the builds, then the CPU backend, its walk
//! alone, obvhs and Embree traced in turn, the CPU backend's launch
//! settings, and the wgpu side ([`crate::gpu`]).

use crate::cli::Args;
use crate::embree;
use crate::figures::{SceneFigures, record_figures};
use crate::gpu::measure_gpu;
use crate::json::Json;
use crate::launches::{
    moving_transform_launches, mrays, ms, record_exceptions_off, record_tiled_and_whole, tiled_and_whole,
};
use crate::peers::{self, AoRun, median};
use crate::programs::{Workload, scene_with};
use crate::scenes;
use obvhs::triangle::Triangle;
use rt_runtime::accel::CpuSimd;
use rt_runtime::accel::wide::testing::Triangles;
use rt_runtime::*;
use std::time::Duration;

/// What every traversal of one scene traces: its triangles (as obvhs and
/// the peers take them), the camera and the image size.
#[derive(Clone, Copy)]
struct Frame<'a> {
    tris: &'a [Triangle],
    cam: scenes::Camera,
    width: u32,
    height: u32,
}

/// The interleaved traversals' times, one per repetition, and their rays.
#[derive(Default)]
struct Runs {
    /// The CPU backend: its runs, the host work before them, its rays.
    ours: Vec<Duration>,
    our_prepare: Vec<Duration>,
    our_rays: u64,
    /// The CPU backend in the other execution mode than `ours` (lane-wise
    /// where `ours` is scalar, and the reverse), on the same context.
    other_mode: Vec<Duration>,
    /// obvhs's CWBVH traversal.
    theirs: Vec<Duration>,
    obvhs_run: Option<AoRun>,
    /// Embree's `rtcIntersect1` and `rtcIntersect16`.
    emb: Vec<Duration>,
    embree_run: Option<AoRun>,
    emb16: Vec<Duration>,
    embree16_run: Option<AoRun>,
    /// The CPU backend's walk alone: single rays and packets, the whole
    /// workload and its primary rays alone.
    walks: Vec<Duration>,
    packet_walks: Vec<Duration>,
    packet_rays: u64,
    primary_walks: Vec<Duration>,
    primary_packet_walks: Vec<Duration>,
}

/// The AO workload on one scene: every backend and peer.
#[allow(clippy::too_many_arguments)]
pub(crate) fn measure_scene(
    args: &Args,
    scene: &scenes::BenchScene,
    embree: Option<&embree::Embree>,
    width: u32,
    height: u32,
    reps: usize,
    wgpu_max_triangles: usize,
    j: &mut Json,
) -> SceneFigures {
    let mut fig = SceneFigures::default();
    let cam = scene.camera(width, height);
    j.set("triangles", scene.triangles());
    j.set("source", scene.source.as_str());
    eprintln!("\n{}: {} triangles, {width}x{height}, primary + AO", scene.name, scene.triangles());
    if args.setup_only {
        crate::setup::measure(scene, cam, (width, height), j, &mut fig);
        record_figures(j, &fig);
        return fig;
    }
    let tris = scene.obvhs_triangles();

    // Builds: obvhs's CWBVH, Embree's own BVH, then ours inside the first
    // CPU launch (one sample each).
    let (bvh, obvhs_build) = peers::obvhs_cwbvh(&tris);
    let builds = j.child("build_ms");
    builds.set("obvhs_cwbvh", ms(obvhs_build));
    let embree_scene = build_embree(scene, embree, builds);
    let (mut cpu_ctx, cpu_gg) =
        if args.measures("cpu") { cpu_context(scene, cam, (width, height), j) } else { (None, None) };

    // Traversal, interleaved so load from elsewhere spreads over all sides.
    let frame = Frame { tris: &tris, cam, width, height };
    let runs = interleaved(frame, &bvh, &mut cpu_ctx, embree_scene.as_ref(), args.measures("cpu"), reps, &mut fig);
    record_runs(frame, runs, j, &mut fig);
    cpu_launch_settings(&mut cpu_ctx, cpu_gg, (width, height), reps, j, &mut fig);
    drop(cpu_ctx);
    drop(embree_scene);

    // The megakernel against the hand-written kernel, same adapter.
    if args.measures("wgpu") {
        measure_gpu(scene, cam, (width, height), reps, wgpu_max_triangles, j, &mut fig);
    }
    record_figures(j, &fig);
    fig
}

/// Embree's own BVH of `scene` where Embree is loaded, its build time into
/// `builds`.
fn build_embree<'e>(
    scene: &scenes::BenchScene,
    embree: Option<&'e embree::Embree>,
    builds: &mut Json,
) -> Option<embree::Scene<'e>> {
    let embree_scene = embree.map(|e| e.build(&scene.mesh.positions, &scene.mesh.indices));
    match embree_scene {
        Some(Ok((s, t))) => {
            builds.set("embree", ms(t));
            Some(s)
        }
        Some(Err(e)) => {
            eprintln!("embree build: {e}");
            None
        }
        None => None,
    }
}

/// The CPU backend's context of the scene after its first launch (which
/// builds our tree: its time into `j`'s `build_ms`), and its geometry
/// group; neither where it fails.
fn cpu_context(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    j: &mut Json,
) -> (Option<Context>, Option<NodeId>) {
    match scene_with(&scene.mesh, cam, Backend::Cpu, width, height, Workload::Ao)
        .and_then(|(mut c, _, gg, _)| c.launch(0, width, height).map(|r| (c, r, gg)))
    {
        Ok((c, first, gg)) => {
            j.child("build_ms").set("ours", ms(first.timings.build));
            (Some(c), Some(gg))
        }
        Err(e) => {
            eprintln!("cpu: {e}");
            (None, None)
        }
    }
}

/// `reps` rounds of every CPU side in turn: the CPU backend (dropped on
/// an error), its walk alone (where `cpu` is measured), obvhs, Embree.
fn interleaved(
    frame: Frame,
    bvh: &obvhs::cwbvh::CwBvh,
    cpu_ctx: &mut Option<Context>,
    embree_scene: Option<&embree::Scene>,
    cpu: bool,
    reps: usize,
    fig: &mut SceneFigures,
) -> Runs {
    let mut runs = Runs::default();
    // The CPU backend's walk alone (its tree, no programs): how much of
    // the gap to Embree is traversal and how much the programs around it.
    let walk_tree = cpu.then(|| {
        let flat: Vec<[glam::Vec3; 3]> = frame.tris.iter().map(|t| [t.v0, t.v1, t.v2].map(glam::Vec3::from)).collect();
        Triangles::new(flat)
    });
    let simd = CpuSimd::current();
    for _ in 0..reps {
        if let Some(ctx) = cpu_ctx.as_mut() {
            match ctx.launch(0, frame.width, frame.height) {
                Ok(r) => {
                    runs.our_rays = r.rays;
                    runs.ours.push(r.timings.run);
                    runs.our_prepare.push(r.timings.build + r.timings.encode);
                    // The same launch in the other execution mode.
                    let mode = CpuExecution::from_env();
                    ctx.set_cpu_execution(other_mode(mode));
                    if let Ok(o) = ctx.launch(0, frame.width, frame.height) {
                        runs.other_mode.push(o.timings.run);
                    }
                    ctx.set_cpu_execution(mode);
                }
                Err(e) => {
                    eprintln!("cpu: {e}");
                    *cpu_ctx = None;
                }
            }
        }
        if let Some(t) = &walk_tree {
            walk(frame, t, simd, &mut runs, fig);
        }
        peers_once(frame, bvh, embree_scene, &mut runs);
    }
    runs
}

/// One round of the CPU backend's walk alone over `t`: single rays and
/// 16-ray packets, over the whole workload and over its primary rays.
fn walk(frame: Frame, t: &Triangles, simd: CpuSimd, runs: &mut Runs, fig: &mut SceneFigures) {
    let Frame { tris, cam, width, height } = frame;
    let w = peers::trace_ao(tris, cam, width, height, |o, d, tmin| {
        t.closest(simd, o, d, tmin, f32::INFINITY).map(|h| (h.0, h.1))
    });
    runs.walks.push(w.time);
    fig.walk_rays = w.rays;
    // A packet's closest hits, as `trace_ao16` takes them.
    let packet = |rays: &[(glam::Vec3, glam::Vec3, f32)], out: &mut [Option<(f32, u32)>]| {
        let mut hits = [None; rt_runtime::accel::wide::testing::PACKET_RAYS];
        t.closest_packet(simd, rays, &mut hits);
        for (o, h) in out.iter_mut().zip(hits) {
            *o = h.map(|h| (h.0, h.1));
        }
    };
    let p = peers::trace_ao16(tris, cam, width, height, |rays, _, out| packet(rays, out));
    runs.packet_walks.push(p.time);
    runs.packet_rays = p.rays;
    // Primary rays only: AO rays (traced with tmin 0, or not
    // coherent) are not traced.
    let w = peers::trace_ao(tris, cam, width, height, |o, d, tmin| {
        (tmin != 0.0).then(|| t.closest(simd, o, d, tmin, f32::INFINITY).map(|h| (h.0, h.1))).flatten()
    });
    runs.primary_walks.push(w.time);
    let p = peers::trace_ao16(tris, cam, width, height, |rays, coherent, out| {
        out.fill(None);
        if coherent {
            packet(rays, out);
        }
    });
    runs.primary_packet_walks.push(p.time);
}

/// One round of the peers: obvhs's CWBVH traversal, then Embree's
/// `rtcIntersect1` and `rtcIntersect16` where its scene was built.
fn peers_once(frame: Frame, bvh: &obvhs::cwbvh::CwBvh, embree_scene: Option<&embree::Scene>, runs: &mut Runs) {
    let Frame { tris, cam, width, height } = frame;
    let o = peers::obvhs_ao(bvh, tris, cam, width, height);
    runs.theirs.push(o.time);
    runs.obvhs_run = Some(o);
    if let Some(s) = embree_scene {
        let e = peers::trace_ao(tris, cam, width, height, |o, d, tmin| s.intersect(o, d, tmin));
        runs.emb.push(e.time);
        runs.embree_run = Some(e);
        let e = peers::trace_ao16(tris, cam, width, height, |rays, coherent, out| s.intersect16(rays, coherent, out));
        runs.emb16.push(e.time);
        runs.embree16_run = Some(e);
    }
}

/// The interleaved runs' medians into `fig` and `j` (with Embree's hits
/// against obvhs's), and a line of them on stderr.
fn record_runs(frame: Frame, runs: Runs, j: &mut Json, fig: &mut SceneFigures) {
    let (width, height) = (frame.width, frame.height);
    let obvhs_run = runs.obvhs_run.expect("reps >= 1");
    if !runs.walks.is_empty() {
        fig.walk = Some(mrays(fig.walk_rays, median(runs.walks)));
        fig.packet_walk = Some(mrays(runs.packet_rays, median(runs.packet_walks)));
        let primary = (width * height) as u64;
        fig.walk_primary = Some(mrays(primary, median(runs.primary_walks)));
        fig.packet_walk_primary = Some(mrays(primary, median(runs.primary_packet_walks)));
    }
    let rays = j.child("rays");
    rays.set("obvhs", obvhs_run.rays);
    fig.obvhs = Some(mrays(obvhs_run.rays, median(runs.theirs)));
    if !runs.ours.is_empty() {
        fig.cpu = Some(mrays(runs.our_rays, median(runs.ours)));
        // A repeated launch's host work before the rays (refit checks,
        // variables resolved, programs bound).
        j.set("cpu_repeat_prepare_ms", ms(median(runs.our_prepare)));
        j.child("rays").set("cpu", runs.our_rays);
        if !runs.other_mode.is_empty() {
            let other = mrays(runs.our_rays, median(runs.other_mode));
            (fig.cpu_lanes, fig.cpu_scalar) = match CpuExecution::from_env() {
                CpuExecution::Lanes => (fig.cpu, Some(other)),
                CpuExecution::Scalar => (Some(other), fig.cpu),
            };
        }
    }
    if let Some(e) = &runs.embree16_run {
        fig.embree16 = Some(mrays(e.rays, median(runs.emb16)));
        let (p, a) = peers::mismatches(e, &obvhs_run);
        let m = j.child("embree16_vs_obvhs_mismatches");
        m.set("primary", p);
        m.set("ao", a);
    }
    if let Some(e) = &runs.embree_run {
        fig.embree1 = Some(mrays(e.rays, median(runs.emb)));
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
}

/// The CPU backend's launch settings: the scene as an instance under a
/// moving transform (against the flat scene's Mrays/s), tiles against
/// whole launches, exceptions off against on.
fn cpu_launch_settings(
    cpu_ctx: &mut Option<Context>,
    cpu_gg: Option<NodeId>,
    (width, height): (u32, u32),
    reps: usize,
    j: &mut Json,
    fig: &mut SceneFigures,
) {
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
}

/// The execution mode the bench measures beside `mode`.
fn other_mode(mode: CpuExecution) -> CpuExecution {
    match mode {
        CpuExecution::Lanes => CpuExecution::Scalar,
        CpuExecution::Scalar => CpuExecution::Lanes,
    }
}
