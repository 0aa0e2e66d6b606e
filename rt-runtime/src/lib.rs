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
//! Launches link first (`link`): every variable is resolved in
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
//!
//! ## A first program
//!
//! README.md (packaged with this crate) opens with two programs: a closest
//! hit that shades by the surface normal and a miss program that returns a
//! background colour. Here they are with a camera and the host side: a
//! square seen head-on, rendered on the CPU backend.
//!
//! ```
//! use rt_runtime::{Acceleration, BufferType, Context, Scope, TriangleMesh};
//! use rt_std::prelude::*;
//!
//! #[rt_payload]
//! pub struct Radiance { pub result: Vec3, pub importance: f32, pub depth: i32 }
//!
//! #[rt_attributes]
//! pub struct Normals { pub geometric_normal: Vec3, pub shading_normal: Vec3 }
//!
//! #[rt_program(closest_hit)]
//! pub fn normals(prd: &mut Radiance, attr: &Normals) {
//!     prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
//! }
//!
//! #[rt_program(miss)]
//! pub fn background(prd: &mut Radiance, #[var] bg_color: Vec3) {
//!     prd.result = bg_color;
//! }
//!
//! /// One ray down -z per pixel, from the pixel's centre in `[-1, 1]^2`.
//! #[rt_program(ray_generation)]
//! pub fn camera(#[var] top: Object, #[var] mut image: RwBuffer2d<Vec4>) {
//!     let idx = launch_index();
//!     let p = (idx.as_vec2() + Vec2::splat(0.5)) / launch_dim().as_vec2() * 2.0 - Vec2::ONE;
//!     let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
//!     rt_trace(top, Ray::new(vec3(p.x, p.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
//!     image[idx] = prd.result.extend(1.0);
//! }
//!
//! # fn main() -> rt_runtime::Result<()> {
//! let mut ctx = Context::new(); // the CPU backend
//! let camera = ctx.create_program(&camera::PROGRAM);
//! ctx.set_ray_generation_program(0, camera)?;
//! let miss = ctx.create_program(&background::PROGRAM);
//! ctx.set_miss_program(0, miss)?;
//! ctx.set_var(Scope::Context, "bg_color", vec3(0.25, 0.5, 0.75))?;
//! let material = ctx.create_material();
//! let hit = ctx.create_program(&normals::PROGRAM);
//! ctx.set_closest_hit_program(material, 0, hit)?;
//! // The square [-0.5, 0.5]^2 at z = 0, facing +z.
//! let square = ctx.create_triangles(TriangleMesh {
//!     positions: vec![vec3(-0.5, -0.5, 0.0), vec3(0.5, -0.5, 0.0), vec3(0.5, 0.5, 0.0), vec3(-0.5, 0.5, 0.0)],
//!     indices: vec![[0, 1, 2], [0, 2, 3]],
//!     ..Default::default()
//! })?;
//! let instance = ctx.create_geometry_instance(square, &[material])?;
//! let top = ctx.create_geometry_group(&[instance], Acceleration::default())?;
//! ctx.set_var(Scope::Context, "top", top)?;
//! let image = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 4, 4)?;
//! ctx.set_var(Scope::Context, "image", image)?;
//! ctx.launch(0, 4, 4)?;
//! let pixels = ctx.read_buffer::<Vec4>(image)?;
//! // A corner pixel misses; a centre one sees the normal (0, 0, 1).
//! assert_eq!(pixels[0], vec4(0.25, 0.5, 0.75, 1.0));
//! assert_eq!(pixels[5], vec4(0.5, 0.5, 1.0, 1.0));
//! # Ok(()) }
//! ```

// Errors carry the names, locations and scopes at fault; they are returned
// on cold paths only, so their size does not matter.
#![allow(clippy::result_large_err)]
#![warn(missing_docs)]

pub mod accel;
pub mod backend;
pub mod buffer;
pub mod command_list;
pub mod context;
mod env_settings;
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
pub use backend::cpu_execution::{CpuExecution, ProgramExecution};
pub use backend::tiles::{DEFAULT_TILE_BUDGET, LaunchControl, LaunchProgress, Tile, TileBudget};
pub use backend::wgpu::Traversal;
pub use backend::{Backend, ExceptionRecord, LaunchReport, Timings};
pub use buffer::{BufferType, generate_mip_levels, generate_mip_levels_3d};
pub use command_list::{Command, CommandList, CommandProgress};
pub use context::{Context, ExceptionKind, MipLevels, SamplerDescriptor, SamplerExtent, Scope, UsageCallback};
pub use error::{
    ConfigError, DeviceError, IoError, LaunchError, LinkError, PostProcessError, Result, RtError, SceneError,
};
pub use motion::{MotionKeys, MotionTransform, Srt};
pub use postprocess::{StageId, StageKind, StageValue};
pub use scene::{
    BufferId, GeometryId, GeometryInstanceId, GeometryKind, MaterialId, NodeId, ProgramId, SamplerId, TriangleMesh,
};
pub use texels::{ReadMode, SamplerOptions, TexelData};
pub use usage::UsageReport;
pub use vars::{IntoVariable, VarValue};
pub use vertex_motion::VertexMotion;
