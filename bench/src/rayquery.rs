//! The ray-query traversal in the benchmark: the megakernel over hardware
//! ray queries beside its compute traversal (same scene, AO workload and
//! adapter), its acceleration structures' device build beside our BVH
//! build, the moving-transform (TLAS rebuild) and moving-vertex (BLAS
//! rebuild) launches, and the hand-written ray-query kernel
//! ([`crate::handwritten_rayquery`]) as its baseline. On lavapipe these are
//! software traversal figures (Mesa's own BVH and traversal in LLVM code),
//! not hardware ones.

use crate::figures::SceneFigures;
use crate::json::Json;
use crate::launches::{Repeated, measure_launches, moving_transform_launches, moving_vertex_launches, mrays, ms};
use crate::programs::{Workload, scene_with};
use crate::{handwritten_rayquery, scenes};
use rt_runtime::{Backend, Result, Traversal};

/// Measures the megakernel with ray queries and the hand-written ray-query
/// kernel on `scene`, into `j` and `fig`; says why where it cannot (an
/// adapter without ray queries).
pub(crate) fn measure(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    reps: usize,
    j: &mut Json,
    fig: &mut SceneFigures,
) {
    if !rt_runtime::backend::wgpu::probe_ray_queries() {
        let why = "the adapter has no ray queries (wgpu::Features::EXPERIMENTAL_RAY_QUERY)";
        j.child("skipped").set("rayquery", why);
        j.child("skipped").set("handwritten_rayquery", why);
        return;
    }
    let run = || -> Result<(Json, Repeated, f64)> {
        let (mut ctx, _, gg, g) = scene_with(&scene.mesh, cam, Backend::Wgpu, width, height, Workload::Ao)?;
        ctx.set_traversal(Traversal::RayQuery);
        // Open before the first launch, as the compute traversal's is: its
        // setup is the scene's, not the device's.
        ctx.open_wgpu()?;
        let (first, l) = measure_launches(&mut ctx, width, height, reps)?;
        let built_first = ctx.ray_query_builds();
        let transform = moving_transform_launches(&mut ctx, gg, width, height, reps)?;
        let after_transform = ctx.ray_query_builds();
        let vertices = moving_vertex_launches(&mut ctx, g, &scene.mesh, width, height, reps)?;
        let after_vertices = ctx.ray_query_builds();
        let mut w = Json::obj();
        w.set("rays", l.rays);
        // The host's part (the geometry group's primitives and bounds; no
        // tree) and the device's BLAS and TLAS of the first launch.
        w.set("build_ms", ms(first.timings.build));
        w.set("accel_build_ms", ms(first.timings.accel));
        w.set("link_ms", ms(first.timings.link));
        w.set("setup_ms", ms(first.timings.setup));
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
        // What each phase rebuilt: (BLASes, TLASes).
        let delta = |a: (u64, u64), b: (u64, u64)| format!("{} BLAS, {} TLAS", b.0 - a.0, b.1 - a.1);
        w.set("builds_first_and_repeats", delta((0, 0), built_first));
        w.set("builds_moving_transform", delta(built_first, after_transform));
        w.set("builds_moving_vertices", delta(after_transform, after_vertices));
        Ok((w, l, ms(first.timings.setup)))
    };
    match run() {
        Ok((w, l, setup)) => {
            fig.rayquery_setup = Some(setup);
            j.set("rayquery_first_launch", w);
            fig.rayquery = Some(mrays(l.rays, l.run));
            fig.rayquery_kernel = l.kernel.map(|k| mrays(l.rays, k));
        }
        Err(e) => {
            eprintln!("ray queries: {e}");
            j.child("skipped").set("rayquery", e.to_string());
        }
    }
    match handwritten_rayquery::run(&scene.mesh, cam, width, height, reps) {
        Ok((m, build)) => {
            fig.rayquery_handwritten = Some(mrays(m.rays, m.time));
            fig.rayquery_handwritten_kernel = m.kernel.map(|k| mrays(m.rays, k));
            j.child("rays").set("handwritten_rayquery", m.rays);
            j.set("handwritten_rayquery_accel_build_ms", ms(build));
        }
        Err(e) => {
            eprintln!("hand-written ray-query WGSL: {e}");
            j.child("skipped").set("handwritten_rayquery", e);
        }
    }
    let show = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.2}"));
    eprintln!(
        "ray queries: megakernel {} Mrays/s, hand-written {}; device time alone: megakernel {}, hand-written {}",
        show(fig.rayquery),
        show(fig.rayquery_handwritten),
        show(fig.rayquery_kernel),
        show(fig.rayquery_handwritten_kernel),
    );
}
