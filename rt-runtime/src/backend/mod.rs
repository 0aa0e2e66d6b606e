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
}

pub(crate) fn launch(ctx: &mut Context, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
    match ctx.backend {
        Backend::Cpu => cpu::launch(ctx, entry, width, height),
        Backend::Wgpu => wgpu::launch(ctx, entry, width, height),
    }
}
