//! The context: the root of everything, as in OptiX. Its `impl` is spread
//! over this folder, one concern a file: this file holds the struct, its
//! construction, the backend launches run on and the launch settings;
//! `programs.rs` programs and entry points; `geometry.rs` meshes and custom
//! primitives; `graph.rs` materials, instances, groups, transforms and
//! selectors; `variables.rs` variables on scopes; `buffers.rs`,
//! `samplers.rs` and `bindless.rs` data and its ids; `launch.rs` launches;
//! `stages.rs` post-processing stages;
//! `wgpu.rs` and `device_buffers.rs` what only the wgpu backend has.

use crate::accel::cache::AccelCache;
use crate::backend::tiles::Pace;
use crate::backend::wgpu::WgpuBackend;
use crate::backend::{Backend, LaunchBackend, Settings};
use crate::scene::*;
use crate::usage::UsageReport;
use std::any::Any;

pub use crate::scene::Scope;

mod bindless;
mod buffers;
mod device_buffers;
mod geometry;
mod graph;
mod launch;
mod programs;
mod samplers;
mod stages;
mod variables;
mod wgpu;
pub use device_buffers::{DeviceBuffer, WgpuDevice};
pub use samplers::{MipLevels, SamplerDescriptor, SamplerExtent};

/// A ray-tracing context: the root of everything, as in OptiX.
///
/// It holds the scene it edits (`Scene`), the launch settings, the
/// acceleration structures built for the scene, and the backend launches
/// run on, behind `LaunchBackend`. A backend it ran on before (or opened
/// ahead, [`Context::open_wgpu`]) is kept, with its device and its
/// statistics, for when the context switches back.
///
/// A context is `Send` and `Sync`: it may move to another thread, and
/// `&Context` (reading buffers, statistics) may be shared; launches and
/// edits take `&mut`. Contexts on several threads run at once, each CPU
/// launch on rayon's shared pool, and wgpu contexts with a device each or
/// sharing one ([`Context::use_wgpu_device`] with clones of one device and
/// queue): `tests/tests/concurrency.rs` checks that they render what a
/// serial run does.
pub struct Context {
    pub(crate) scene: Scene,
    pub(crate) settings: Settings,
    pub(crate) accels: AccelCache,
    backend: Box<dyn LaunchBackend>,
    parked: Vec<Box<dyn LaunchBackend>>,
    /// How long an index of each entry point took, for sizing tiles.
    pace: Pace,
    /// Called after every launch ([`Context::set_usage_report`]).
    usage_report: Option<UsageCallback>,
    /// Post-processing stages, by [`StageId`](crate::postprocess::StageId).
    pub(crate) stages: Vec<crate::postprocess::Stage>,
    /// The stages' pipelines on the wgpu device, once a stage ran there.
    pub(crate) stage_pipelines: Option<crate::postprocess::gpu::Pipelines>,
    /// Stage inputs the wgpu backend took from its heap on the device.
    pub(crate) stage_device_inputs: u64,
    /// Queue submissions of stages on the wgpu device.
    pub(crate) stage_submits: u64,
    /// Bytes stages' runs sent to the wgpu device, and read back from it.
    pub(crate) stage_uploaded: u64,
    pub(crate) stage_read_back: u64,
}

/// A kind of exception whose checks [`Context::set_exception_enabled`]
/// turns on or off (OptiX 6's `RT_EXCEPTION_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExceptionKind {
    /// `rt_trace` at the maximum trace depth (`EXCEPTION_TRACE_DEPTH_EXCEEDED`).
    TraceDepthExceeded,
    /// A buffer index out of bounds (`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`).
    BufferIndexOutOfBounds,
    /// A NaN or infinite ray, or a payload its ray type's programs do not
    /// take (`EXCEPTION_INVALID_RAY`).
    InvalidRay,
    /// Integer overflow (CPU backend, with integer exceptions on).
    IntegerOverflow,
    /// Integer division by zero (CPU backend, with integer exceptions on).
    IntegerDivideByZero,
    /// A callable program called through an id that names none of its
    /// signature (OptiX `RT_EXCEPTION_PROGRAM_ID_INVALID`).
    ProgramIdInvalid,
    /// A buffer read or written through a bindless id that names no buffer
    /// of its element type (OptiX `RT_EXCEPTION_BUFFER_ID_INVALID`).
    BufferIdInvalid,
    /// A texture sampled through a bindless sampler id that names no
    /// sampler of its shape (OptiX `RT_EXCEPTION_TEXTURE_ID_INVALID`).
    TextureIdInvalid,
    /// `rt_throw`'s codes.
    User,
    /// Every kind.
    All,
}

impl ExceptionKind {
    fn bits(self) -> u32 {
        use rt_abi::constants::*;
        match self {
            ExceptionKind::TraceDepthExceeded => exception_kind_bit(EXCEPTION_TRACE_DEPTH_EXCEEDED),
            ExceptionKind::BufferIndexOutOfBounds => exception_kind_bit(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
            ExceptionKind::InvalidRay => exception_kind_bit(EXCEPTION_INVALID_RAY),
            ExceptionKind::IntegerOverflow => exception_kind_bit(EXCEPTION_INTEGER_OVERFLOW),
            ExceptionKind::IntegerDivideByZero => exception_kind_bit(EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
            ExceptionKind::ProgramIdInvalid => exception_kind_bit(EXCEPTION_PROGRAM_ID_INVALID),
            ExceptionKind::BufferIdInvalid => exception_kind_bit(EXCEPTION_BUFFER_ID_INVALID),
            ExceptionKind::TextureIdInvalid => exception_kind_bit(EXCEPTION_TEXTURE_ID_INVALID),
            ExceptionKind::User => exception_kind_bit(EXCEPTION_USER),
            ExceptionKind::All => ALL_EXCEPTION_KINDS,
        }
    }
}

/// What [`Context::set_usage_report`] calls.
pub type UsageCallback = Box<dyn FnMut(&UsageReport) + Send + Sync>;

impl Default for Context {
    fn default() -> Self {
        Context::new()
    }
}

impl Context {
    /// An empty context with one entry point and one ray type, a maximum
    /// trace depth of 5, on the CPU backend.
    pub fn new() -> Self {
        Context {
            scene: Scene::default(),
            settings: Settings::default(),
            accels: Default::default(),
            backend: Backend::Cpu.create(),
            parked: Vec::new(),
            pace: Pace::default(),
            usage_report: None,
            stages: Vec::new(),
            stage_pipelines: None,
            stage_device_inputs: 0,
            stage_submits: 0,
            stage_uploaded: 0,
            stage_read_back: 0,
        }
    }

    /// The backend launches run on.
    pub fn backend(&self) -> Backend {
        self.backend.kind()
    }

    /// Chooses the backend launches run on.
    pub fn set_backend(&mut self, backend: Backend) {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.run_on(backend);
    }

    /// Makes `kind` the backend launches run on: the one kept from before,
    /// else a new one.
    pub(super) fn run_on(&mut self, kind: Backend) {
        if self.backend.kind() == kind {
            return;
        }
        let next = match self.parked.iter().position(|b| b.kind() == kind) {
            Some(i) => self.parked.swap_remove(i),
            None => kind.create(),
        };
        let previous = std::mem::replace(&mut self.backend, next);
        self.parked.push(previous);
    }

    /// The active backend, then the parked ones.
    pub(super) fn backends(&self) -> impl Iterator<Item = &dyn LaunchBackend> {
        std::iter::once(&*self.backend).chain(self.parked.iter().map(|b| &**b))
    }

    /// The wgpu backend, active or parked, if the context has one.
    pub(super) fn wgpu_backend_ref(&self) -> Option<&WgpuBackend> {
        self.backends().find_map(|b| (b as &dyn Any).downcast_ref::<WgpuBackend>())
    }

    /// The wgpu backend, active or parked (a new one parked if there is
    /// none yet).
    pub(super) fn wgpu_backend(&mut self) -> &mut WgpuBackend {
        if !self.backends().any(|b| b.kind() == Backend::Wgpu) {
            self.parked.push(Backend::Wgpu.create());
        }
        std::iter::once(&mut self.backend)
            .chain(self.parked.iter_mut())
            .find_map(|b| (&mut **b as &mut dyn Any).downcast_mut::<WgpuBackend>())
            .expect("added above")
    }

    /// How many full acceleration builds and refits launches have done.
    pub fn acceleration_builds(&self) -> (u64, u64) {
        (self.accels.builds, self.accels.refits)
    }

    /// How many geometry groups' BVHs launches have built on the host. The
    /// CPU backend and the wgpu backend's compute traversal walk them; the
    /// ray-query traversal walks the device's acceleration structures and
    /// builds none (a later launch that walks them builds them then).
    pub fn geometry_trees_built(&self) -> u64 {
        self.accels.geometry_trees
    }

    /// Sets how many entry points (ray-generation programs launches choose by
    /// index) the context has; new ones have no programs yet.
    pub fn set_entry_point_count(&mut self, n: u32) {
        self.scene.structure_version += 1;
        self.scene.entry_points.resize(n as usize, EntryPoint::default());
    }

    /// How many entry points the context has (1 to start with).
    pub fn entry_point_count(&self) -> u32 {
        self.scene.entry_points.len() as u32
    }

    /// Sets how many ray types (a trace's `ray_type`, each with its own miss
    /// program and its own closest- and any-hit program per material) the
    /// context has; new ones have no programs yet.
    pub fn set_ray_type_count(&mut self, n: u32) {
        self.scene.structure_version += 1;
        self.scene.miss.resize(n as usize, None);
        for m in &mut self.scene.materials {
            m.closest_hit.resize(n as usize, None);
            m.any_hit.resize(n as usize, None);
        }
    }

    /// How many ray types the context has (1 to start with).
    pub fn ray_type_count(&self) -> u32 {
        self.scene.ray_type_count()
    }

    /// Rays may nest this deep (primary rays are depth 1); a trace beyond it
    /// raises the trace-depth-exceeded exception instead.
    pub fn set_max_trace_depth(&mut self, depth: u32) {
        self.scene.structure_version += 1;
        self.settings.max_trace_depth = depth.max(1);
    }

    /// A debugging mode beyond OptiX, off by default: on the CPU backend,
    /// integer overflow (`+ - *`, negation, `abs`, shifts by 32 or more,
    /// `i32::MIN / -1`) raises [`EXCEPTION_INTEGER_OVERFLOW`](rt_std::EXCEPTION_INTEGER_OVERFLOW)
    /// and division or remainder by zero
    /// [`EXCEPTION_INTEGER_DIVIDE_BY_ZERO`](rt_std::EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
    /// reported through the exception program and in the launch report's
    /// [`ExceptionRecord`](crate::ExceptionRecord) with the operator's file
    /// and line; the value is the wrapped one either way, and the program
    /// goes on. The wgpu backend computes the same values and raises
    /// nothing (off, both backends agree, as with Rust's release builds).
    pub fn set_integer_exceptions(&mut self, on: bool) {
        self.settings.integer_exceptions = on;
    }

    /// Turns the checks of exception kind `kind` on or off (all are on by
    /// default; OptiX 6's `rtContextSetExceptionEnabled`). A check that is
    /// off still guards its operation (a buffer index out of bounds still
    /// reads a default value and writes nothing; an invalid ray, or one past
    /// the trace depth, is still not traced: `tests/tests/exception_kinds.rs`
    /// asserts it on every backend) but raises nothing: the exception
    /// program does not run and the launch reports no record. The integer
    /// kinds also need [`Context::set_integer_exceptions`].
    #[doc(alias = "rtContextSetExceptionEnabled")]
    pub fn set_exception_enabled(&mut self, kind: ExceptionKind, on: bool) {
        let bits = kind.bits();
        if on {
            self.settings.exceptions |= bits;
        } else {
            self.settings.exceptions &= !bits;
        }
    }

    /// Whether every check of `kind` is on ([`Context::set_exception_enabled`]).
    pub fn exception_enabled(&self, kind: ExceptionKind) -> bool {
        self.settings.exceptions & kind.bits() == kind.bits()
    }

    /// Turns `rt_printf!` output on or off, and optionally limits it to one
    /// launch index (as OptiX's `rtContextSetPrintLaunchIndex`).
    pub fn set_print(&mut self, enabled: bool, launch_index: Option<glam::UVec2>) {
        self.settings.print_enabled = enabled;
        self.settings.print_launch_index = launch_index;
    }
}
