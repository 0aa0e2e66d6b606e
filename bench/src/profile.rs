//! `--profile-cpu N`: the AO workload's CPU launches and nothing else, for
//! a profiler (callgrind, perf) to count what a pixel costs in the mode
//! `RT_CPU_EXEC` names. The first launch builds the tree; `N` launches
//! follow. Nothing is timed or compared: the profiler is the measurement.

use crate::programs::{Workload, scene_with};
use crate::scenes::BenchScene;
use rt_runtime::{Backend, CpuExecution};

/// `launches` launches of `scene`'s AO workload at `width` x `height` on
/// the CPU backend, after the one that builds the tree; what ran on stderr.
pub(crate) fn profile_cpu(scene: &BenchScene, (width, height): (u32, u32), launches: usize) -> Result<(), String> {
    let cam = scene.camera(width, height);
    let (mut ctx, ..) =
        scene_with(&scene.mesh, cam, Backend::Cpu, width, height, Workload::Ao).map_err(|e| e.to_string())?;
    ctx.launch(0, width, height).map_err(|e| e.to_string())?;
    let mut rays = 0;
    for _ in 0..launches {
        rays += ctx.launch(0, width, height).map_err(|e| e.to_string())?.rays;
    }
    let mode = match CpuExecution::from_env() {
        CpuExecution::Lanes => "lane-wise",
        CpuExecution::Scalar => "scalar",
    };
    eprintln!(
        "{}: {launches} launches of {width}x{height} ({} pixels, {rays} rays), {mode}",
        scene.name,
        launches as u64 * u64::from(width * height)
    );
    Ok(())
}
