//! The wgpu side of a scene ([`crate::measure`]): the megakernel with the
//! compute traversal, then the hand-written kernel over the CWBVH and over
//! the BVH2, on one adapter, then the ray-query traversal
//! ([`crate::rayquery`]).

use crate::figures::SceneFigures;
use crate::handwritten;
use crate::json::Json;
use crate::launches::{
    Repeated, measure_launches, moving_transform_launches, moving_vertex_launches, mrays, ms, record_exceptions_off,
    record_tiled_and_whole, tiled_and_whole,
};
use crate::programs::{Workload, scene_with};
use crate::rayquery;
use crate::scenes;
use rt_runtime::*;

/// The launch settings' ratios of one backend: tiled over whole launches,
/// every exception kind off over on.
struct LaunchRatios {
    tiled: Option<f64>,
    exceptions_off: Option<f64>,
}

/// The wgpu side of [`crate::measure::measure_scene`]: the megakernel, then
/// the hand-written kernel over the CWBVH and over the BVH2, on one
/// adapter; nothing (said in `j`'s `skipped`) for a scene over
/// `wgpu_max_triangles`.
pub(crate) fn measure_gpu(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    wgpu_max_triangles: usize,
    j: &mut Json,
    fig: &mut SceneFigures,
) {
    if scene.triangles() > wgpu_max_triangles {
        let why = format!("{} triangles > --wgpu-max-triangles {wgpu_max_triangles}", scene.triangles());
        j.child("skipped").set("wgpu", why.as_str());
        j.child("skipped").set("handwritten_wgsl", why.as_str());
        return;
    }
    match megakernel(scene, cam, (width, height), reps, fig) {
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
    handwritten_cwbvh(scene, cam, (width, height), reps, j, fig);
    handwritten_bvh2(scene, cam, (width, height), reps, j, fig);
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

/// The megakernel with the compute traversal: its first launch's figures
/// and the repeated launches' (as they are, under a moving transform, with
/// moving vertices, tiled and with exceptions off) as a JSON object, the
/// repeated launches' medians, the adapter and the launch settings' ratios;
/// its setup into `fig`.
fn megakernel(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    fig: &mut SceneFigures,
) -> Result<(Json, Repeated, String, LaunchRatios)> {
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
    w.set("setup_ms", ms(first.timings.setup));
    fig.compute_setup = Some(ms(first.timings.setup));
    w.set("first_dispatch_ms", ms(first.timings.run.saturating_sub(l.run)));
    // Repeated launches, in medians: the host's preparation, the
    // run (upload, dispatch, wait, read-back), the kernel; as
    // they are, under a transform that moves before each launch,
    // and with every vertex moved before each (refit, geometry
    // encoded and uploaded again).
    for (key, r) in
        [("repeat_launch_ms", &l), ("moving_transform_launch_ms", &transform), ("moving_vertices_launch_ms", &vertices)]
    {
        let o = w.child(key);
        o.set("prepare", ms(r.prepare));
        o.set("run", ms(r.run));
        o.set("kernel", r.kernel.map(ms));
    }
    w.child("moving_vertices_launch_ms").set("set_positions", ms(vertices.change));
    let tiled = record_tiled_and_whole(&mut w, tiled_and_whole(&mut ctx, width, height, reps));
    let exceptions_off = record_exceptions_off(&mut w, &mut ctx, width, height, reps);
    Ok((w, l, device, LaunchRatios { tiled, exceptions_off }))
}

/// The hand-written kernel over the CWBVH, on the megakernel's adapter
/// (`adapters_differ` where it is not).
fn handwritten_cwbvh(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    j: &mut Json,
    fig: &mut SceneFigures,
) {
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
}

/// The same kernel over the BVH2 the CWBVH is converted from (what the
/// megakernel walks with any-hit or intersection programs).
fn handwritten_bvh2(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    j: &mut Json,
    fig: &mut SceneFigures,
) {
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
}
