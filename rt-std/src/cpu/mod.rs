//! The CPU side of programs, in three rooms: `thunk.rs`, the contract with
//! the compiler's generated thunks (how the CPU backend calls a program's
//! Rust function and binds its variables), `execution.rs`, the per-thread
//! state that intrinsics read and write when programs run as Rust, and
//! `lanes.rs`, what a program's lane-wise form calls to run a block of
//! launch indices at once (`mask.rs`: a block's shape, which the others
//! name).

mod execution;
pub mod lanes;
mod mask;
mod thunk;

pub use crate::layout::TriangleBuiltins;
pub use execution::{
    __callable_variables, __print, __report_intersection, AnyAttributes, ExecutionContext, HIT_CUSTOM, HIT_NONE,
    HIT_TRIANGLE_BACK, HIT_TRIANGLE_FRONT, Tracer, Transforms, context, context_mut, in_context, pending_exception,
    raise, raise_here, serving, with_context, with_tracer,
};
pub(crate) use execution::{bindless_buffer, bindless_sampler, callable, calling, read, update, with_installed_tracer};
pub use thunk::{__arg, BoundVariables, CpuArgs, CpuResult, Var, VariableList, VariableMismatch};
