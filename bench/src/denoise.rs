//! The denoiser's cost: on each backend, the path-traced Cornell box
//! (the `examples` crate's, with its albedo and normal guides) at the
//! bench's resolution, one launch of one sample a pixel and one run of
//! the denoiser stage over what it wrote, each the median of `reps`
//! after a first run that links and builds. Reported: the stage's time
//! per megapixel, and `denoise_vs_launch`, the stage's time over the
//! launch's (the goal on the wgpu backend: under 0.5). Also
//! `list_vs_one_by_one`: a command list of the launch, the denoiser and
//! the tonemapper (on wgpu one submission, the launch's outputs staying
//! on the device) over the three run one by one, alternated in the same
//! run.

use crate::json::Json;
use crate::peers::median;
use examples::{Settings, cornell};
use rt_runtime::{Backend, BufferType, CommandList, Scope, StageKind};
use std::time::{Duration, Instant};

/// Measures each backend `backends` names into `json`'s children.
pub fn measure(backends: &[Backend], (width, height): (u32, u32), reps: usize, json: &mut Json) {
    eprintln!("\ndenoiser on the Cornell box at {width}x{height} (median of {reps}):");
    for &backend in backends {
        let j = json.child(backend.name());
        match measure_on(backend, width, height, reps) {
            Ok(((launch, stage), (list, one_by_one))) => {
                let megapixels = (width * height) as f64 / 1e6;
                let per_mpix = stage.as_secs_f64() * 1e3 / megapixels;
                let ratio = stage.as_secs_f64() / launch.as_secs_f64();
                eprintln!(
                    "  {:5} 1-spp launch {:8.2} ms, denoise {:8.2} ms ({per_mpix:.2} ms per megapixel), denoise_vs_launch {ratio:.3}",
                    backend.name(),
                    launch.as_secs_f64() * 1e3,
                    stage.as_secs_f64() * 1e3
                );
                j.set("launch_ms", launch.as_secs_f64() * 1e3);
                j.set("denoise_ms", stage.as_secs_f64() * 1e3);
                j.set("denoise_ms_per_megapixel", per_mpix);
                j.set("denoise_vs_launch", ratio);
                let list_ratio = list.as_secs_f64() / one_by_one.as_secs_f64();
                eprintln!(
                    "  {:5} list (launch + denoise + tonemap) {:8.2} ms, one by one {:8.2} ms, list_vs_one_by_one {list_ratio:.3}",
                    backend.name(),
                    list.as_secs_f64() * 1e3,
                    one_by_one.as_secs_f64() * 1e3
                );
                j.set("list_ms", list.as_secs_f64() * 1e3);
                j.set("one_by_one_ms", one_by_one.as_secs_f64() * 1e3);
                j.set("list_vs_one_by_one", list_ratio);
            }
            Err(e) => {
                eprintln!("  {:5} failed: {e}", backend.name());
                j.set("error", e.as_str());
            }
        }
    }
}

/// Two medians each: of a 1-spp launch and of the denoiser after it;
/// and of a command list of both and the tonemapper and of the three run
/// one by one (each to the tonemapped image on the host), alternated.
type Medians = ((Duration, Duration), (Duration, Duration));

/// [`Medians`] on `backend`.
fn measure_on(backend: Backend, width: u32, height: u32, reps: usize) -> Result<Medians, String> {
    let settings = Settings { backend, ..Settings::new(width, height).with_spp(1) };
    let mut scene = cornell::scene(&settings).map_err(|e| e.to_string())?;
    let aovs = scene.aovs.ok_or("the Cornell box writes no guides")?;
    let ctx = &mut scene.ctx;
    let e = |e: rt_runtime::RtError| e.to_string();
    ctx.set_var(Scope::Context, "frame", 0u32).map_err(e)?;
    let out = ctx.create_buffer_2d::<glam::Vec4>(BufferType::Output, width, height).map_err(e)?;
    let stage = ctx.create_postprocessing_stage(StageKind::Denoiser);
    ctx.set_stage_var(stage, "input_buffer", aovs.radiance).map_err(e)?;
    ctx.set_stage_var(stage, "input_albedo_buffer", aovs.albedo).map_err(e)?;
    ctx.set_stage_var(stage, "input_normal_buffer", aovs.normal).map_err(e)?;
    ctx.set_stage_var(stage, "input_variance_buffer", aovs.variance).map_err(e)?;
    ctx.set_stage_var(stage, "output_buffer", out).map_err(e)?;
    let mapped = ctx.create_buffer_2d::<glam::Vec4>(BufferType::Output, width, height).map_err(e)?;
    let tonemapper = ctx.create_postprocessing_stage(StageKind::Tonemapper);
    ctx.set_stage_var(tonemapper, "input_buffer", out).map_err(e)?;
    ctx.set_stage_var(tonemapper, "output_buffer", mapped).map_err(e)?;
    let mut list = CommandList::new();
    list.append_launch_2d(0, width, height).map_err(e)?;
    list.append_stage(stage, width, height).map_err(e)?;
    list.append_stage(tonemapper, width, height).map_err(e)?;
    list.finalize(ctx).map_err(e)?;
    let (mut launches, mut stages, mut lists, mut one_by_one) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for rep in 0..=reps {
        let t = Instant::now();
        ctx.launch(0, width, height).map_err(e)?;
        let launched = t.elapsed();
        let t = Instant::now();
        ctx.run_stage(stage, width, height).map_err(e)?;
        let staged = t.elapsed();
        let t = Instant::now();
        ctx.run_stage(tonemapper, width, height).map_err(e)?;
        ctx.read_buffer::<glam::Vec4>(mapped).map_err(e)?;
        let mapped_after = t.elapsed();
        let t = Instant::now();
        list.execute(ctx).map_err(e)?;
        ctx.read_buffer::<glam::Vec4>(mapped).map_err(e)?;
        let listed = t.elapsed();
        // The first of each links, builds and compiles.
        if rep > 0 {
            launches.push(launched);
            stages.push(staged);
            one_by_one.push(launched + staged + mapped_after);
            lists.push(listed);
        }
    }
    Ok(((median(launches), median(stages)), (median(lists), median(one_by_one))))
}
