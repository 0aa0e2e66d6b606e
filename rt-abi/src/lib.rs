//! The contract between the three sides of a ray program: the compiler
//! (`rt-compiler`, behind `#[rt_program]`), the device vocabulary
//! (`rt-std`) and the runtime (`rt-runtime`'s linker and backends).
//!
//! Everything here is stated once and read by all three:
//!
//! - [`kinds`]: the program kinds, their `#[rt_program(...)]` spellings and
//!   the parameters each may take;
//! - [`intrinsics`]: every kind-restricted intrinsic: its Rust name, its
//!   OptiX name, which kinds may call it, and its WGSL function with
//!   parameter and return types. The compiler type-checks calls and writes
//!   the stub prelude programs are validated against from it; the runtime's
//!   prelude is checked against the same rows (a test parses both with
//!   naga and compares the signatures);
//! - [`constants`]: the ray-flag, mask and exception-code values;
//! - [`records`]: the GPU records the runtime writes and the megakernel
//!   reads (the launch uniform), as Rust structs with their word layout,
//!   from which their WGSL is generated;
//! - [`wgsl`]: the WGSL text both sides share (the records a program and the
//!   megakernel exchange, the constants) and the stub generator.
//!
//! Adding an intrinsic is one row in [`intrinsics::INTRINSICS`], its CPU
//! body in rt-std and its WGSL body in the runtime's prelude: the compiler
//! lowers a plain call from the row alone.
//!
//! The crate has no dependencies, so reading it costs the proc macro
//! nothing.

pub mod constants;
pub mod intrinsics;
pub mod kinds;
pub mod records;
pub mod wgsl;

pub use constants::*;
pub use intrinsics::{AbiTy, Form, INTRINSICS, Intrinsic, intrinsic};
pub use kinds::{ALL_KINDS, Callers, Kind};
