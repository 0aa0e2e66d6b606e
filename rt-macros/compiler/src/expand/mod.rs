//! Token emission for the attribute macros, one job a file:
//!
//! - `attributes.rs`: what each `rt_*` attribute expands to — the item as
//!   the CPU compiles it, its checks, and its link in the chain;
//! - `chain.rs`: the `macro_rules!` links that hand a program (or a helper,
//!   struct, constant or impl) the items it names, and `__rt_collect!`,
//!   the step between two links;
//! - `descriptor.rs`: a lowered program as `ProgramDescriptor` tokens;
//! - `thunk.rs`: a program's CPU entry (`cpu`, `cpu_bind`, a callable's
//!   function pointer);
//! - `data.rs`: a struct's Rust side (`#[repr(C)]`, the derives, `RtData`
//!   and its role's marker trait).
//!
//! Programs expand inside `mod <program name> { use super::*; ... }` (a
//! module and a function may share a name), which holds the CPU thunk and
//! `pub static PROGRAM: ProgramDescriptor = <chain>;`: a program's chain runs
//! in expression position and ends in the descriptor (or the errors). So
//! `PROGRAM` exists even when the chain breaks (a dependency not declared
//! with an rt attribute is rustc's "cannot find macro" at its use, and
//! nothing more), and each error is reported once: errors inside a
//! dependency are its own macro's to report ([`crate::lower::lower_own`]).

mod attributes;
mod chain;
mod data;
mod descriptor;
mod thunk;

pub use attributes::{rt_const, rt_enum, rt_function, rt_impl, rt_program, rt_struct, rt_trait, rt_type};
pub use chain::{collect, parse_defs};
pub(crate) use thunk::variable_tuple;

use crate::error::Error;
use crate::kinds::Kind;

/// The program kind an attribute names (`closest_hit`, ...), or an error
/// that lists the kinds and guesses the one meant.
pub fn parse_kind(ident: &syn::Ident) -> Result<Kind, Error> {
    Kind::from_name(&ident.to_string()).ok_or_else(|| {
        let all: Vec<&str> = crate::kinds::ALL_KINDS.iter().map(|k| k.name()).collect();
        // `closest`, `anyhit`, `raygen`: a prefix or a spelling without `_`.
        let given = ident.to_string().to_lowercase().replace('_', "");
        let guess = all.iter().find(|k| {
            let k = k.replace('_', "");
            k == given || (given.len() >= 3 && k.starts_with(&given))
        });
        let hint = guess.map(|g| format!(" (did you mean `{g}`?)")).unwrap_or_default();
        Error::new(ident.span(), format!("unknown program kind `{ident}`{hint}: expected one of {}", all.join(", ")))
    })
}
