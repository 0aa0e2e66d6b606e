//! # rt-std: the vocabulary of ray programs
//!
//! A ray program is a plain Rust function marked `#[rt_program(kind)]`. It
//! is compiled twice: by rustc, as ordinary Rust that the CPU backend calls
//! and that you can step through in a debugger, and by the `rt-macros`
//! compiler, to WGSL that the runtime links into one megakernel. This crate
//! is everything such a function may name besides its own helpers
//! (`#[rt_function]`), types (`#[rt_struct]`, `#[rt_payload]`,
//! `#[rt_attributes]`, `#[rt_enum]`) and their methods (`#[rt_impl]`): glam's vectors and matrices, shading math
//! ([`reflect`], [`refract`], [`mix`], ...), [`Ray`] and [`Aabb`], handles to
//! buffers, textures and scene nodes, and the intrinsics that read semantic
//! values and talk to the ray tracer ([`rt_trace`],
//! [`rt_potential_intersection`], ...). Programs import it whole:
//!
//! ```
//! use rt_std::prelude::*;
//! ```
//!
//! README.md (packaged with this crate) opens with a first program: a
//! closest hit that shades by the surface normal and a miss program that
//! returns a background colour. rt-runtime's crate documentation renders
//! it, host side included, on the CPU backend (its section "A first
//! program", a doc test).
//!
//! Two rules hold for every item:
//!
//! - **It has a real CPU implementation**, here, with the semantics the GPU
//!   version has. Where GPU and CPU could differ (texture filtering, NaN in
//!   [`saturate`], out-of-bounds buffer accesses) the CPU version is the
//!   reference and its documentation says what the GPU one must do.
//! - **The compiler maps it to WGSL by name.** Renaming an item here breaks
//!   the mapping; an item the compiler does not know is rejected at the
//!   call site with a compile error. The doc comment of each intrinsic,
//!   semantic value and handle method carries a line
//!   `Program kinds: ...` listing the kinds that may call it (or `all`);
//!   a test checks those lines against the compiler's own table, which is
//!   what enforces them.
//!
//! ## Program kinds
//! As in OptiX (see [`program::ProgramKind`]):
//!
//! | kind | attribute | runs | typically takes / returns |
//! | --- | --- | --- | --- |
//! | ray generation | `ray_generation` | once per launch index | variables; writes output buffers |
//! | exception | `exception` | when a launch index raised an exception | reads [`exception_code`] |
//! | closest hit | `closest_hit` | for the committed intersection | `&mut` payload, `&` attributes |
//! | any hit | `any_hit` | for each reported intersection | `&mut` payload, `&` attributes |
//! | miss | `miss` | when a ray hits nothing | `&mut` payload |
//! | intersection | `intersection` | per custom primitive a ray reaches | primitive index, `&mut` attributes |
//! | bounding box | `bounding_box` | per custom primitive, at build time | primitive index; returns [`Aabb`] |
//! | visit | `visit` | at a selector node | returns the chosen child (`u32`) |
//! | callable | `callable` | when a program calls its id ([`Callable`]) | arguments by value; returns a value |
//!
//! What a program reads is visible in its signature: the payload, the
//! attributes, and `#[var]` parameters resolved by OptiX's scope rules.
//! Semantic values (launch index, current ray, hit distance, primitive
//! index) come from intrinsics, not parameters.
//!
//! ## Layout: packed 32-bit words
//! Every value that crosses between host and programs (buffer elements,
//! variables, payloads, attributes) implements [`RtData`], and has one
//! layout on both sides: fields in declaration order, each scalar one
//! 32-bit word (`f32`, `i32`, `u32`, and `bool` as 0 or 1), an `n`-vector `n`
//! words, an `n`x`n` matrix `n * n` words column by column, no padding
//! anywhere. A [`Ray`] is 9 words, an [`Aabb`] 6. WGSL's own struct layout
//! would pad a `vec3` to 16 bytes; the runtime's buffer heap is an array of
//! words instead, and the compiler generates loads and stores that assemble
//! values from words, so the host writes the same bytes for either backend.
//! [`program::TypeLayout`] carries each type's size and field offsets.
//!
//! On the CPU, buffers hold ordinary Rust values of their element type (so
//! `buffer[i]` can return a reference); the words are the exchange format.
//!
//! ## Handles
//! [`Buffer`], [`RwBuffer`], [`Buffer2d`], [`RwBuffer2d`], [`Sampler2d`],
//! [`Sampler3d`], [`SamplerCube`] and [`Object`] are small `Copy` values that a program receives as variables.
//! The runtime owns the storage behind them and creates them with `unsafe`
//! `from_raw_parts` constructors whose contracts say what it must keep
//! valid. Buffer accesses are bounds-checked: out of bounds, a load reads
//! zero, a store is dropped, and the exception
//! [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] is raised (see [`buffer`]).
//!
//! Bindless ids are values rather than handles: [`BindlessBuffer`],
//! [`RwBindlessBuffer`] (see [`bindless`]), [`BindlessSampler`] (see
//! [`bindless_sampler`]) and [`Callable`] are one `u32` word that a program
//! may keep anywhere a value goes (a buffer of ids, a struct or payload
//! field) and reads through; an id that names nothing of its type raises
//! its own exception ([`EXCEPTION_BUFFER_ID_INVALID`],
//! [`EXCEPTION_TEXTURE_ID_INVALID`], [`EXCEPTION_PROGRAM_ID_INVALID`]) and
//! reads zero.
//!
//! ## The CPU execution context
//! On the GPU, intrinsics read the megakernel's state. On the CPU they read
//! a thread-local [`cpu::ExecutionContext`]: launch index and size, the
//! current ray, the hit distance, the primitive index, the exception code,
//! the instance's transforms (borrowed: a [`cpu::Transforms`] where the
//! backend's traversal holds it, so a call copies no matrices), and the
//! flags a program sets for whoever called it (`ignored`, `terminated`,
//! `pending_exception`).
//!
//! The CPU backend installs a [`cpu::Tracer`] with [`cpu::serving`] (its
//! implementation of [`rt_trace`], of the intersection protocol and of
//! [`rt_printf!`] output) and calls each program inside [`cpu::in_context`],
//! which makes the backend's context for that call the current one, in
//! place. After the call it reads that context to see what the program did:
//! an any-hit program's `ignored`/`terminated`, any program's first
//! `pending_exception`. Calls nest: a closest-hit program calls `rt_trace`,
//! the tracer runs the inner ray's programs, each inside its own
//! `in_context`, and the outer context is restored when each returns (also
//! on panic). [`cpu::with_tracer`] does both for one call.
//!
//! Outside the backend (a program called directly from a unit test) the
//! context has [default values](cpu::ExecutionContext::DEFAULT), and
//! [`cpu::with_context`] sets others. With no tracer, `rt_trace` leaves the
//! payload unchanged, `rt_potential_intersection(t)` checks `t` against the
//! current ray, `rt_report_intersection` returns `true`, and `rt_printf!`
//! prints to stdout:
//!
//! ```
//! use rt_std::cpu::{ExecutionContext, with_context};
//! use rt_std::prelude::*;
//!
//! // An intersection program for the plane z = 0, called as plain Rust.
//! fn plane(normal: &mut Vec3) {
//!     let ray = current_ray();
//!     let t = -ray.origin.z / ray.direction.z;
//!     if rt_potential_intersection(t) {
//!         *normal = Vec3::Z;
//!         rt_report_intersection(0);
//!     }
//! }
//!
//! let ray = Ray::new(vec3(0.0, 0.0, 2.0), -Vec3::Z, 0, 1e-3, 10.0);
//! let ctx = ExecutionContext { current_ray: ray, ..Default::default() };
//! let mut normal = Vec3::ZERO;
//! let ((), after) = with_context(ctx, || plane(&mut normal));
//! assert_eq!((normal, after.t_hit), (Vec3::Z, 2.0));
//! ```
//!
//! Unlike OptiX, [`rt_ignore_intersection`], [`rt_terminate_ray`] and
//! [`rt_throw`] return to the program: they set flags that take effect when
//! it returns, on both backends. An exception is recorded, not unwound: the
//! first one of a program invocation is kept, and the exception program
//! runs after the program returns.

#![warn(missing_docs)]

pub mod arith;
pub mod atomic;
pub mod bindless;
pub mod bindless_sampler;
pub mod buffer;
pub mod callable;
pub mod cpu;
pub mod data;
pub mod geometry;
pub mod intrinsics;
pub mod layout;
pub mod math;
pub mod prelude;
pub mod program;
pub mod ray;
pub mod scene;
pub mod texture;

pub use atomic::{AtomicElement, AtomicInteger};
pub use bindless::{BindlessBuffer, RwBindlessBuffer};
pub use bindless_sampler::BindlessSampler;
pub use buffer::{Buffer, Buffer2d, Buffer3d, RwBuffer, RwBuffer2d, RwBuffer3d};
pub use callable::Callable;
pub use data::{Attributes, Payload, RtData};
pub use geometry::Aabb;
pub use intrinsics::*;
pub use math::{faceforward, mix, reflect, refract, saturate, smoothstep, step};
pub use ray::*;
pub use rt_macros::{
    __rt_collect, rt_attributes, rt_const, rt_enum, rt_function, rt_impl, rt_payload, rt_program, rt_struct, rt_trait,
    rt_type,
};
pub use scene::{Object, TransformKind};
pub use texture::{
    FilterMode, IndexMode, MipFilter, Sampler2d, Sampler3d, SamplerCube, SamplerModes, WrapMode, mip_level_count,
    mip_level_count_3d, mip_level_size, mip_level_size_3d,
};
