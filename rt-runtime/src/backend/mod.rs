//! Backends: where launches run. The link step (variable resolution by
//! scope, payload and attribute agreement) is shared; see `link`.

pub mod cpu;
pub mod link;
pub mod wgpu;

use crate::Context;
use crate::error::Result;
use glam::UVec2;

/// Where a context's launches run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Backend {
    /// Programs run natively as Rust over obvhs BVHs, on all cores (rayon).
    Cpu,
    /// Programs linked into one WGSL megakernel on a wgpu adapter (a GPU,
    /// or Mesa's lavapipe on machines without one).
    Wgpu,
}

impl Backend {
    /// The backend to use by default, and why: `RT_BACKEND=cpu|wgpu` when
    /// set; otherwise a discrete or integrated GPU when wgpu finds one;
    /// otherwise the CPU backend, which outruns Mesa's lavapipe on CPU-only
    /// machines (3.7 vs 0.9 Mrays/s for the bunny's primary rays on a 2-core
    /// VM, BENCHMARKS.md).
    pub fn choose() -> Result<(Backend, String), crate::RtError> {
        if let Ok(v) = std::env::var("RT_BACKEND") {
            return match v.as_str() {
                "cpu" => Ok((Backend::Cpu, "RT_BACKEND=cpu".into())),
                "wgpu" => Ok((Backend::Wgpu, "RT_BACKEND=wgpu".into())),
                other => Err(crate::RtError::Gpu(format!("RT_BACKEND is `{other}`; expected `cpu` or `wgpu`"))),
            };
        }
        match wgpu::probe() {
            Some(info)
                if matches!(info.device_type, ::wgpu::DeviceType::DiscreteGpu | ::wgpu::DeviceType::IntegratedGpu) =>
            {
                Ok((Backend::Wgpu, format!("GPU adapter {} ({:?})", info.name, info.device_type)))
            }
            Some(info) => Ok((
                Backend::Cpu,
                format!(
                    "no GPU adapter (only {}, {:?}); the CPU backend is faster than it",
                    info.name, info.device_type
                ),
            )),
            None => Ok((Backend::Cpu, "no wgpu adapter".into())),
        }
    }

    /// Parses `cpu` or `wgpu`.
    pub fn from_name(name: &str) -> Option<Backend> {
        match name {
            "cpu" => Some(Backend::Cpu),
            "wgpu" => Some(Backend::Wgpu),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => "cpu",
            Backend::Wgpu => "wgpu",
        }
    }
}

/// An exception raised during a launch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExceptionRecord {
    pub launch_index: UVec2,
    /// `EXCEPTION_*` code, or a user code from `rt_throw`.
    pub code: u32,
}

/// What a launch did besides writing its buffers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaunchReport {
    /// Exceptions, in launch-index order.
    pub exceptions: Vec<ExceptionRecord>,
    /// `rt_printf!` output with its launch index, in launch-index order.
    pub prints: Vec<(UVec2, String)>,
    /// Rays traced (calls of `rt_trace` that reached traversal).
    pub rays: u64,
    /// Where the launch's time went.
    pub timings: Timings,
}

/// Wall-clock time of the phases of a launch.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Building or refitting acceleration structures.
    pub build: std::time::Duration,
    /// Resolving variables and encoding records and the scene.
    pub encode: std::time::Duration,
    /// Generating the megakernel and creating its pipeline (zero when the
    /// cached pipeline was reused, and on the CPU backend).
    pub link: std::time::Duration,
    /// Running the launch and reading results back.
    pub run: std::time::Duration,
    /// The device's own time for the launch's dispatches, from timestamp
    /// queries: what the kernel took, without submission, waiting and
    /// read-back. `None` on the CPU backend and on devices without
    /// `wgpu::Features::TIMESTAMP_QUERY`.
    pub kernel: Option<std::time::Duration>,
}

pub(crate) fn launch(ctx: &mut Context, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
    match ctx.backend {
        Backend::Cpu => cpu::launch(ctx, entry, width, height),
        Backend::Wgpu => wgpu::launch(ctx, entry, width, height),
    }
}
