//! Megakernel link and pipeline-creation time for the tour's program sets:
//! each example's scene (from the `examples` crate) on the wgpu backend,
//! launched twice at a tiny size.
//!
//! Three figures per example, because on lavapipe the shader's real
//! compilation happens at its first dispatch, not at pipeline creation:
//! - `link_ms`: the runtime's link phase of the first launch (WGSL
//!   generation + shader module + `create_compute_pipeline`);
//! - `pipeline_ms`: shader module + pipeline creation alone, for the same
//!   WGSL on a separate device (so `link_ms - pipeline_ms` is generation);
//! - `first_dispatch_ms`: how much longer the first launch's run phase is
//!   than the second's: the driver compiling the kernel.

use crate::json::Json;
use rt_runtime::{Backend, Scope};
use std::time::{Duration, Instant};

/// Examples whose megakernel compiles in a few seconds on lavapipe:
/// `--quick` measures these.
pub const FAST: [&str; 4] = ["normal", "diffuse", "phong", "shadows"];

/// Examples whose megakernel takes tens of seconds on lavapipe (more
/// programs, trace loops): measured by the full run, left out of `--quick`
/// (which must finish in 3 minutes). Before programs that trace ran from
/// one loop in their resumable form, reflections took 217 s and
/// convex_hull ran out of memory.
pub const MEDIUM: [&str; 6] = ["cornell", "bunny", "reflections", "envmap", "convex_hull", "instances"];

/// Examples a run leaves out, with why.
pub fn slow_reason(name: &str) -> &'static str {
    if MEDIUM.contains(&name) {
        "tens of seconds to compile on lavapipe: measured by the full run (or --tour-links NAME)"
    } else {
        "not in the fast set (pass --tour-links NAME)"
    }
}

/// A device of its own for `pipeline_ms`.
struct Probe {
    device: wgpu::Device,
}

impl Probe {
    fn new() -> Option<Probe> {
        let adapter = crate::handwritten::adapter().ok()?;
        let (device, _queue) = pollster::block_on(
            adapter.request_device(&wgpu::DeviceDescriptor { required_limits: adapter.limits(), ..Default::default() }),
        )
        .ok()?;
        Some(Probe { device })
    }

    fn pipeline_time(&self, wgsl: &str) -> Result<Duration, String> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let t = Instant::now();
        let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("probe"),
            source: wgpu::ShaderSource::Wgsl(wgsl.into()),
        });
        let _pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("probe"),
            layout: None,
            module: &module,
            entry_point: Some("rt_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let elapsed = t.elapsed();
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(e.to_string()),
            None => Ok(elapsed),
        }
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Measures the examples named in `names` into `out` (one object each),
/// and lists the others under `skipped` with a reason.
pub fn measure(names: &[String], out: &mut Json) {
    let probe = Probe::new();
    let (w, h) = (64, 48);
    for ex in examples::EXAMPLES.iter() {
        if !names.iter().any(|n| n == ex.name) {
            out.child("skipped").set(ex.name, slow_reason(ex.name));
            continue;
        }
        let settings = examples::Settings { spp: 1, backend: Backend::Wgpu, ..examples::Settings::new(w, h) };
        let run = || -> Result<Json, String> {
            let mut scene = (ex.build)(&settings).map_err(|e| e.to_string())?;
            if ex.progressive {
                scene.ctx.set_var(Scope::Context, "frame", 0u32).map_err(|e| e.to_string())?;
            }
            let t = Instant::now();
            let first = scene.ctx.launch(0, w, h).map_err(|e| e.to_string())?;
            let first_total = t.elapsed();
            let second = scene.ctx.launch(0, w, h).map_err(|e| e.to_string())?;
            let wgsl = scene.ctx.linked_wgsl().unwrap_or_default().to_string();
            let mut j = Json::obj();
            j.set("link_ms", ms(first.timings.link));
            match probe.as_ref().map(|p| p.pipeline_time(&wgsl)) {
                Some(Ok(d)) => j.set("pipeline_ms", ms(d)),
                Some(Err(e)) => j.set("pipeline_ms_error", e),
                None => j.set("pipeline_ms_error", "no second wgpu device"),
            }
            j.set("first_dispatch_ms", ms(first.timings.run.saturating_sub(second.timings.run)));
            j.set("first_launch_ms", ms(first_total));
            j.set("wgsl_bytes", wgsl.len());
            j.set("pipelines_created", scene.ctx.pipelines_created());
            Ok(j)
        };
        eprint!("tour link: {} ... ", ex.name);
        match run() {
            Ok(j) => {
                eprintln!(
                    "link {:.1} ms (pipeline {:.1} ms), first dispatch +{:.0} ms, {} bytes of WGSL",
                    j.get("link_ms").and_then(Json::as_f64).unwrap_or(f64::NAN),
                    j.get("pipeline_ms").and_then(Json::as_f64).unwrap_or(f64::NAN),
                    j.get("first_dispatch_ms").and_then(Json::as_f64).unwrap_or(f64::NAN),
                    j.get("wgsl_bytes").and_then(Json::as_f64).unwrap_or(0.0)
                );
                out.set(ex.name, j);
            }
            Err(e) => {
                eprintln!("failed: {e}");
                out.child("failed").set(ex.name, e);
            }
        }
    }
}
