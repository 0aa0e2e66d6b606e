//! The CPU backend: programs run natively as Rust (each descriptor's `cpu`
//! entry), rays traverse the node graph as built (groups' obvhs BVH2s over
//! their children, transforms composed on the way down, selectors' visit
//! programs choosing one child, geometry groups' trees over primitives in
//! the SIMD layout of [`crate::accel::wide`], on the instruction set
//! [`crate::accel::CpuSimd::current`] picks), rayon spreads chunks of
//! launch indices over all cores.
//!
//! Semantics are OptiX's and the megakernel's: the intersection protocol
//! (`rt_potential_intersection` accepts `t` in `(tmin, closest)`,
//! `rt_report_intersection` runs any hit, which may ignore the candidate or
//! terminate the ray), ray flags and visibility masks, the trace-depth limit
//! and exceptions. Intrinsics reach this backend through rt-std's
//! thread-local execution context and the `Tracer` it installs.
//!
//! Per ray nothing is allocated and nothing is looked up by name: variables
//! are bound once per launch and program use, their types checked then
//! ([`rt_std::cpu::BoundVariables`]: a call reads them after one comparison,
//! not one downcast per variable),
//! each program call's context is built in place and installed by pointer
//! ([`rt_std::cpu::in_context`]), the tracer is installed once per chunk of
//! launch indices, and attribute values are reused from a per-thread pool.
//! Triangle hits of instances without any-hit programs commit just the
//! distance and barycentrics; the attributes are computed once, for the
//! closest hit.
//!
//! A ray generation program with a lane-wise form runs a block of launch
//! indices per call (`block`), unless the context asks for one index at a
//! time (`super::cpu_execution`: `RT_CPU_EXEC`,
//! [`crate::Context::set_cpu_execution`]).
//!
//! Files: `bind` resolves and binds every program use of a launch,
//! `lane` runs launch indices and traces rays, `block` runs a block of
//! them lane-wise, `packet` traces a block's rays together, `triangle`
//! computes a triangle hit's built-in attributes; this file is the backend
//! and its run.

mod bind;
mod block;
mod hit_block;
mod lane;
mod packet;
mod tracer;
mod traverse;
mod triangle;

use super::cpu_execution::CpuExecution;
use super::{Launch, LaunchBackend, LaunchReport};
use crate::accel::bvh::TreeForm;
use crate::accel::cache::Trees;
use crate::buffer::BufferRec;
use crate::error::{LaunchError, Result, RtError};
use crate::panics;
use crate::scene::Scene;
use bind::link_all;
use block::Band;
use glam::UVec2;
use lane::Lane;
use rayon::prelude::*;
use rt_std::program::CpuLanes;
use std::sync::atomic::{AtomicBool, Ordering};

/// The CPU backend: it keeps nothing between launches.
#[derive(Default)]
pub(crate) struct CpuBackend;

impl LaunchBackend for CpuBackend {
    fn kind(&self) -> super::Backend {
        super::Backend::Cpu
    }

    fn prepare(&mut self) -> Result<()> {
        Ok(())
    }

    /// Groups' BVH2s as the wide form's; every geometry group's tree in the
    /// SIMD layout, its triangles in its leaves.
    fn trees(&mut self, _: &Scene) -> Result<Trees> {
        Ok(Trees { groups: TreeForm::Wide, geometry: true, cwbvh: false, simd: true })
    }

    fn launch(&mut self, launch: &Launch) -> Result<LaunchReport> {
        run(launch)
    }

    fn writes_host_buffers(&self) -> bool {
        true
    }

    /// Programs wrote the host's buffers themselves.
    fn read_back_outputs(&mut self, _: &mut [BufferRec]) {}

    /// Nothing outlives a launch but the host's buffers, which the launch
    /// path puts back.
    fn recover(&mut self, _: super::Failure<'_>) {}
}

/// The error for a panic at `index`, in `program` (`None`: in the runtime,
/// between programs).
fn panicked(
    program: Option<&'static rt_std::program::ProgramDescriptor>,
    index: UVec2,
    caught: panics::Caught,
) -> RtError {
    match program {
        Some(p) => LaunchError::ProgramPanicked {
            program: p.name,
            location: format!("{}:{}", p.file, p.line),
            launch_index: index,
            message: caught.message,
            at: caught.at,
        }
        .into(),
        None => LaunchError::RuntimePanicked { backend: "cpu", message: caught.message, at: caught.at }.into(),
    }
}

/// Runs a launch over its tile's launch indices.
fn run(launch: &Launch) -> Result<LaunchReport> {
    let &Launch { scene, settings, accels, entry, width, height, depth, tile, .. } = launch;
    let t1 = web_time::Instant::now();
    let calls = link_all(scene, settings, &accels.nodes, entry, (UVec2::new(width, height / depth), depth))?;
    let linked = calls.bind()?;
    let lanes = match (settings.cpu_execution, linked.ray_generation.desc.cpu_lanes) {
        (CpuExecution::Lanes, CpuLanes::Lanes(entry)) => Some(entry),
        _ => None,
    };
    let t2 = web_time::Instant::now();
    // Chunks of launch indices in row-major order (not rows: a 1D launch
    // spreads over all cores too); reports are merged in index order.
    let total = tile.count();
    let chunk = (total / (rayon::current_num_threads() as u64 * 8)).clamp(64, 16384);
    // Lane-wise, chunks are bands of rows cut into square blocks
    // (`block::Band`).
    let (bands, chunks) = match lanes {
        Some(_) => {
            let bands = Band::cut(&tile, chunk);
            let n = bands.len() as u64;
            (bands, n)
        }
        None => (Vec::new(), total.div_ceil(chunk)),
    };
    // A panic stops its chunk, and the others at their next index.
    let stop = AtomicBool::new(false);
    let chunks: Vec<std::result::Result<LaunchReport, RtError>> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut report = LaunchReport::default();
            let lane = Lane::new(&linked);
            let checking = settings.integer_exceptions;
            rt_std::cpu::serving(&lane, || {
                rt_std::arith::checking_integers(checking, || {
                    // One catch around the chunk, not one per index: a
                    // panic ends the chunk either way, and the lane knows
                    // the index it was running (`run_index` sets it first).
                    let run = panics::catching(|| {
                        if let Some(entry) = lanes {
                            lane.run_band(entry, &bands[c as usize], &mut report, &stop);
                            return;
                        }
                        let end = ((c + 1) * chunk).min(total);
                        let mut i = c * chunk;
                        while i < end && !stop.load(Ordering::Relaxed) {
                            lane.run_index(tile.index(i), &mut report);
                            i += 1;
                        }
                    });
                    match run {
                        Ok(()) => Ok(report),
                        Err(caught) => {
                            stop.store(true, Ordering::Relaxed);
                            Err(panicked(lane.program.get(), lane.index_at_fault(), caught))
                        }
                    }
                })
            })
        })
        .collect();
    let mut report = LaunchReport::default();
    // The error of the lowest launch index that panicked.
    for r in chunks {
        let r = r?;
        report.exceptions.extend(r.exceptions);
        report.prints.extend(r.prints);
        report.rays += r.rays;
    }
    if lanes.is_some() {
        block::in_index_order(&mut report);
    }
    report.timings = super::Timings {
        build: Default::default(),
        encode: t2 - t1,
        link: Default::default(),
        run: t2.elapsed(),
        kernel: None,
        accel: Default::default(),
        setup: t2 - t1,
    };
    Ok(report)
}
