//! Proc macros for ray programs. Each macro is a one-line shell over
//! [`rt_compiler`], which holds the compiler so that tests, benchmarks and
//! fuzzers can call it without rustc.
//!
//! Use these through `rt_std::prelude`, not directly.

use proc_macro::TokenStream;

/// Runs an expansion with the file the attribute is in, where the macro
/// finds the plain `const`s of the item's module
/// (`rt_compiler::plain_consts`).
fn with_source(f: impl FnOnce() -> proc_macro2::TokenStream) -> proc_macro2::TokenStream {
    rt_compiler::plain_consts::with_source(proc_macro::Span::call_site().local_file(), f)
}

/// Declares a ray program: `#[rt_program(closest_hit)]`, and so on for the
/// eight kinds. The subset of Rust programs may use is listed in the
/// project's `docs/subset.md`; `rt_std` has what they may name.
#[proc_macro_attribute]
pub fn rt_program(attr: TokenStream, item: TokenStream) -> TokenStream {
    with_source(|| rt_compiler::expand::rt_program(attr.into(), item.into())).into()
}

/// Declares a helper function callable from programs and other helpers.
#[proc_macro_attribute]
pub fn rt_function(attr: TokenStream, item: TokenStream) -> TokenStream {
    with_source(|| rt_compiler::expand::rt_function(attr.into(), item.into())).into()
}

/// Declares a struct programs may use (buffer elements, variables, locals).
#[proc_macro_attribute]
pub fn rt_struct(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_struct(attr.into(), item.into(), rt_compiler::StructRole::Data).into()
}

/// Declares per-ray data passed to `rt_trace` and reaching hit/miss programs.
#[proc_macro_attribute]
pub fn rt_payload(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_struct(attr.into(), item.into(), rt_compiler::StructRole::Payload).into()
}

/// Declares attributes an intersection program passes to hit programs.
#[proc_macro_attribute]
pub fn rt_attributes(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_struct(attr.into(), item.into(), rt_compiler::StructRole::Attributes).into()
}

/// Declares a C-like enum programs may use (locals, fields, buffer elements,
/// variables, `match`): a `u32` in WGSL.
#[proc_macro_attribute]
pub fn rt_enum(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_enum(attr.into(), item.into()).into()
}

/// Declares the methods, associated functions and associated constants of
/// a `#[rt_struct(impl)]` (or `#[rt_payload(impl)]`, `#[rt_attributes(impl)]`)
/// type, callable from programs and helpers.
#[proc_macro_attribute]
pub fn rt_impl(attr: TokenStream, item: TokenStream) -> TokenStream {
    with_source(|| rt_compiler::expand::rt_impl(attr.into(), item.into())).into()
}

/// Declares a trait programs may implement (`#[rt_impl] impl Trait for
/// Type`, the type declared `(impl Trait)`) and call with static dispatch:
/// methods with or without default bodies and associated constants.
#[proc_macro_attribute]
pub fn rt_trait(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_trait(attr.into(), item.into()).into()
}

/// Declares a constant programs may use.
#[proc_macro_attribute]
pub fn rt_const(attr: TokenStream, item: TokenStream) -> TokenStream {
    with_source(|| rt_compiler::expand::rt_const(attr.into(), item.into())).into()
}

/// Declares a type alias programs may name (`#[rt_type] type Brdf =
/// Vec3;`): each use stands for the type, as in Rust.
#[proc_macro_attribute]
pub fn rt_type(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::expand::rt_type(attr.into(), item.into()).into()
}

/// Marks rt-std's CPU body of an intrinsic of the contract (`rt-abi`): adds
/// its callers' doc line and OptiX alias from its row and checks its
/// signature against the row's.
#[doc(hidden)]
#[proc_macro_attribute]
pub fn rt_intrinsic(attr: TokenStream, item: TokenStream) -> TokenStream {
    rt_compiler::intrinsic::rt_intrinsic(attr.into(), item.into()).into()
}

/// `__rt_intrinsic_names!(callback)` expands to `callback!(name, ...)` with
/// the Rust name of every intrinsic of the contract, for checks that every
/// row has its item in rt-std.
#[doc(hidden)]
#[proc_macro]
pub fn __rt_intrinsic_names(input: TokenStream) -> TokenStream {
    rt_compiler::intrinsic::names(input.into()).into()
}

/// Internal step of the dependency chain (see `rt_compiler::expand`).
#[doc(hidden)]
#[proc_macro]
pub fn __rt_collect(input: TokenStream) -> TokenStream {
    rt_compiler::expand::collect(input.into()).into()
}
