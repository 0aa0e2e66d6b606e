//! Launching a context repeatedly and what that measured: medians of
//! repeated launches (as they are, under a moving transform, with moving
//! vertices), and launch settings measured against each other in
//! alternation (tiles against whole launches, exceptions off against on).

use crate::json::Json;
use crate::peers::{self, median};
use glam::Vec3;
use rt_runtime::*;
use std::time::{Duration, Instant};

/// Geometry `g` (holding `mesh`) launched `reps` times, every vertex moved
/// before each (an animated mesh); `change` is the time of setting the
/// positions.
pub(crate) fn moving_vertex_launches(
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
pub(crate) fn moving_transform_launches(
    ctx: &mut Context,
    gg: NodeId,
    width: u32,
    height: u32,
    reps: usize,
) -> Result<Repeated> {
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

/// `d` in milliseconds.
pub(crate) fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Millions of rays per second: `rays` traced in `t`.
pub(crate) fn mrays(rays: u64, t: Duration) -> f64 {
    rays as f64 / t.as_secs_f64() / 1e6
}

/// What [`repeat_launches`] measured: medians, and the rays of a launch.
pub(crate) struct Repeated {
    /// Rays of a launch.
    pub(crate) rays: u64,
    /// Median time of the change made before each launch (what the change
    /// itself measured; zero for none).
    pub(crate) change: Duration,
    /// Median time of a launch's encoding and building (refit checks),
    /// before its run.
    pub(crate) prepare: Duration,
    /// Median wall-clock run time (dispatch, wait and read-back on wgpu).
    pub(crate) run: Duration,
    /// Median device time of the kernel, where the device has timestamps.
    pub(crate) kernel: Option<Duration>,
    /// Process CPU time of the `reps` launches and changes.
    pub(crate) cpu: Duration,
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
pub(crate) fn measure_launches(
    ctx: &mut Context,
    width: u32,
    height: u32,
    reps: usize,
) -> Result<(LaunchReport, Repeated)> {
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
pub(crate) fn tiled_and_whole(
    ctx: &mut Context,
    width: u32,
    height: u32,
    reps: usize,
) -> Result<(Duration, Duration, u32)> {
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
pub(crate) fn record_exceptions_off(
    j: &mut Json,
    ctx: &mut Context,
    width: u32,
    height: u32,
    reps: usize,
) -> Option<f64> {
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
pub(crate) fn record_tiled_and_whole(j: &mut Json, measured: Result<(Duration, Duration, u32)>) -> Option<f64> {
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
