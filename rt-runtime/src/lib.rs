//! # rt-runtime: contexts, scenes and launches
//!
//! The host side of the framework, shaped like OptiX's API: a [`Context`]
//! holds programs (from the descriptors `#[rt_program]` emits), the scene
//! graph (geometry, materials, geometry instances, geometry groups, groups,
//! transforms, selectors), acceleration structures ([`accel`]: OptiX's builder
//! names over obvhs), variables set by name on scopes ([`vars`]), buffers and
//! texture samplers, and launches them over a 1D or 2D index space.
//!
//! ```text
//! let mut ctx = Context::new();
//! let camera = ctx.create_program(&pinhole_camera::PROGRAM);
//! ctx.set_ray_generation_program(0, camera)?;
//! ctx.set_var(Scope::Context, "eye", Vec3::new(0.0, 0.0, 5.0))?;
//! ctx.launch(0, 640, 480)?;
//! ```
//!
//! Launches link first ([`link`]): every variable is resolved in
//! OptiX's scope order for its program kind, and payload and attribute types
//! are checked to agree; errors name the program with its Rust file and line.
//! Backends: the CPU backend ([`backend::cpu`]) runs programs natively; the
//! wgpu backend ([`backend::wgpu`]) links them into one WGSL megakernel.
//! Both trace the same graphs (nested groups, transforms, selectors) with
//! the same semantics, exceptions included: an entry point without an
//! exception program gets the default one ([`Context::set_exception_program`]).
//! After its launches a renderer runs post-processing stages
//! ([`postprocess`]: a denoiser, a tonemapper), alone or with the launches
//! in a command list ([`command_list`]).

// Errors carry the names, locations and scopes at fault; they are returned
// on cold paths only, so their size does not matter.
#![allow(clippy::result_large_err)]

pub mod accel;
pub mod backend;
pub mod buffer;
pub mod command_list;
pub mod context;
pub mod error;
mod handles;
pub mod image_out;
pub(crate) mod link;
pub mod motion;
mod panics;
pub mod postprocess;
pub mod scene;
pub mod texels;
pub mod usage;
pub mod vars;
pub mod vertex_motion;

pub use accel::{Acceleration, Builder};
pub use backend::tiles::{DEFAULT_TILE_BUDGET, LaunchControl, LaunchProgress, Tile, TileBudget};
pub use backend::wgpu::Traversal;
pub use backend::{Backend, ExceptionRecord, LaunchReport, Timings};
pub use buffer::{BufferType, generate_mip_levels, generate_mip_levels_3d};
pub use command_list::{Command, CommandList, CommandProgress};
pub use context::{Context, ExceptionKind, MipLevels, SamplerDescriptor, SamplerExtent, Scope, UsageCallback};
pub use error::{Result, RtError};
pub use motion::{MotionKeys, MotionTransform, Srt};
pub use postprocess::{StageId, StageKind, StageValue};
pub use scene::{
    BufferId, GeometryId, GeometryInstanceId, GeometryKind, MaterialId, NodeId, ProgramId, SamplerId, TriangleMesh,
};
pub use texels::{ReadMode, SamplerOptions, TexelData};
pub use usage::UsageReport;
pub use vars::{IntoVariable, VarValue};
pub use vertex_motion::VertexMotion;
