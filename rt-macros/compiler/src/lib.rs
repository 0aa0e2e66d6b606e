//! # rt-compiler: restricted Rust ray programs to validated WGSL
//!
//! This crate is the compiler behind `#[rt_program]` and its sibling
//! attributes (`rt-macros` is a thin proc-macro shell over it). It works on
//! `proc_macro2` tokens, so tests, benchmarks and fuzzers call it without
//! rustc: see [`lower_file`] and [`lower_tokens`].
//!
//! ## Pipeline
//! 1. **Dependencies** ([`deps`]): a program names user items — payload,
//!    attribute and buffer element structs, helper functions, constants. A
//!    proc macro sees one item only, so each `#[rt_struct]`, `#[rt_function]`
//!    and `#[rt_const]` also defines a `macro_rules!` of the same name that
//!    hands its tokens (and those of everything *it* depends on) to the next
//!    step. [`expand`] chains these macros: `#[rt_program]` calls the first
//!    dependency's macro, which calls `__rt_collect!`, which calls the next,
//!    until every definition is collected. Name resolution is Rust's own, so
//!    `use` and module paths work as usual.
//! 2. **Checking and lowering** ([`lower`]): one pass over the syn AST types
//!    every expression in the subset (integer literals are inferred as in
//!    Rust) and writes WGSL text, with every piece of text wrapped in markers
//!    naming the Rust span it came from ([`lower::text`]). Anything outside the
//!    subset is an [`Error`] at its span that says what to use instead.
//! 3. **Validation** ([`validate`]): naga parses and validates the module;
//!    its error spans are mapped back through the markers to the Rust
//!    expression at fault.
//! 4. **Emission** ([`expand`]): the original function (for the CPU backend),
//!    a CPU thunk and a `ProgramDescriptor` with the WGSL, payload/attribute
//!    layouts, variables, intrinsics used, and file/line.
//!
//! ## Invariants
//! - The program kinds, the intrinsics each may call and their WGSL
//!   signatures are one table, the contract crate `rt-abi` (re-exported
//!   in [`kinds`]), which rt-std and the runtime read too; the WGSL spelling
//!   and heap layout of a type are defined once, in [`types`].
//! - A lowered module has four sections (prelude of runtime stubs, generated
//!   from the contract; types; functions; program); the runtime's linker
//!   replaces the prelude and deduplicates shared types and functions by
//!   name.

pub mod aliases;
pub mod cpu_semantics;
pub mod declared;
pub mod deps;
pub mod enums;
pub mod error;
pub mod expand;
pub mod intrinsic;
pub mod kinds;
pub mod lanes;
pub mod lower;
pub mod methods;
pub mod operators;
pub mod plain_consts;
pub mod signature;
pub mod sugar;
pub mod traits;
pub mod typed;
pub mod types;
pub mod validate;

pub use error::{Error, Errors};
pub use kinds::Kind;
pub use lower::Lowered;

use proc_macro2::TokenStream;

/// Which attribute declared a struct.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StructRole {
    /// `#[rt_struct]`: plain data (buffer elements, variables, locals).
    Data,
    /// `#[rt_payload]`: per-ray data.
    Payload,
    /// `#[rt_attributes]`: intersection attributes.
    Attributes,
}

impl StructRole {
    pub fn keyword(self) -> &'static str {
        match self {
            StructRole::Data => "data",
            StructRole::Payload => "payload",
            StructRole::Attributes => "attributes",
        }
    }

    pub fn from_keyword(k: &str) -> Option<StructRole> {
        match k {
            "data" => Some(StructRole::Data),
            "payload" => Some(StructRole::Payload),
            "attributes" => Some(StructRole::Attributes),
            _ => None,
        }
    }
}

/// A user item a unit may depend on.
#[derive(Clone, Debug)]
pub enum Item {
    Struct(syn::ItemStruct, StructRole),
    Function(syn::ItemFn),
    Const(syn::ItemConst),
    /// `#[rt_enum]`: a C-like enum.
    Enum(syn::ItemEnum),
    /// `#[rt_impl]`: the methods, associated functions and constants of
    /// a struct (see [`methods`]), or its impl of an `#[rt_trait]`.
    Impl(syn::ItemImpl),
    /// `#[rt_trait]`: a trait with static dispatch (see [`traits`]).
    Trait(syn::ItemTrait),
    /// `#[rt_type]`: a type alias (see [`aliases`]).
    Alias(syn::ItemType),
}

impl Item {
    pub fn name(&self) -> String {
        match self {
            Item::Struct(s, _) => s.ident.to_string(),
            Item::Function(f) => f.sig.ident.to_string(),
            Item::Const(c) => c.ident.to_string(),
            Item::Enum(e) => e.ident.to_string(),
            // Not a name Rust code can spell: an impl never shadows an item.
            Item::Impl(i) => methods::impl_key_of(i),
            Item::Trait(t) => t.ident.to_string(),
            Item::Alias(t) => t.ident.to_string(),
        }
    }
}

/// What an `rt_*` attribute on a syn item declares.
pub enum Declared {
    Program(Kind, syn::ItemFn),
    Item(Item),
}

/// Reads the `rt_*` attribute of an item of a file, if it has one.
pub fn declared(item: &syn::Item) -> Option<Result<Declared, Error>> {
    let attrs = match item {
        syn::Item::Fn(f) => &f.attrs,
        syn::Item::Struct(s) => &s.attrs,
        syn::Item::Const(c) => &c.attrs,
        syn::Item::Enum(e) => &e.attrs,
        syn::Item::Impl(i) => &i.attrs,
        syn::Item::Trait(t) => &t.attrs,
        syn::Item::Type(t) => &t.attrs,
        _ => return None,
    };
    let attr = attrs.iter().find(|a| {
        let p = a.path();
        p.segments.last().is_some_and(|s| {
            matches!(
                s.ident.to_string().as_str(),
                "rt_program"
                    | "rt_function"
                    | "rt_struct"
                    | "rt_payload"
                    | "rt_attributes"
                    | "rt_const"
                    | "rt_enum"
                    | "rt_impl"
                    | "rt_trait"
                    | "rt_type"
            )
        })
    })?;
    let name = attr.path().segments.last().unwrap().ident.to_string();
    Some((|| -> Result<Declared, Error> {
        Ok(match (name.as_str(), item) {
            ("rt_program", syn::Item::Fn(f)) => {
                let kind_ident: syn::Ident = attr.parse_args()?;
                let kind = expand::parse_kind(&kind_ident)?;
                Declared::Program(kind, f.clone())
            }
            ("rt_function", syn::Item::Fn(f)) => Declared::Item(Item::Function(f.clone())),
            ("rt_struct", syn::Item::Struct(s)) => Declared::Item(Item::Struct(s.clone(), StructRole::Data)),
            ("rt_payload", syn::Item::Struct(s)) => Declared::Item(Item::Struct(s.clone(), StructRole::Payload)),
            ("rt_attributes", syn::Item::Struct(s)) => Declared::Item(Item::Struct(s.clone(), StructRole::Attributes)),
            ("rt_const", syn::Item::Const(c)) => Declared::Item(Item::Const(c.clone())),
            ("rt_enum", syn::Item::Enum(e)) => {
                enums::check(e)?;
                Declared::Item(Item::Enum(e.clone()))
            }
            ("rt_impl", syn::Item::Impl(i)) => {
                // The first of its shape errors (the attribute reports all).
                if let Err(e) = methods::check_impl(i) {
                    return Err(e.0.into_iter().next().expect("an error"));
                }
                Declared::Item(Item::Impl(i.clone()))
            }
            ("rt_trait", syn::Item::Trait(t)) => {
                if let Err(e) = traits::check_trait(t) {
                    return Err(e.0.into_iter().next().expect("an error"));
                }
                Declared::Item(Item::Trait(t.clone()))
            }
            ("rt_type", syn::Item::Type(t)) => {
                aliases::check(t)?;
                Declared::Item(Item::Alias(t.clone()))
            }
            (n, _) => {
                return Err(Error::new(
                    syn::spanned::Spanned::span(attr),
                    format!("`#[{n}]` cannot be applied to this item"),
                ));
            }
        })
    })())
}

/// Lowers every program declared in a Rust source file, each with all the
/// file's `rt_*` items as its dependencies. Returns `(program name, result)`
/// in file order. This is the entry point of the snapshot tests.
pub fn lower_file(file: &syn::File) -> Vec<(String, Result<Lowered, Errors>)> {
    let mut programs = Vec::new();
    let mut items = Vec::new();
    let mut out = Vec::new();
    for it in &file.items {
        match declared(it) {
            Some(Ok(Declared::Program(k, f))) => programs.push((k, f)),
            Some(Ok(Declared::Item(i))) => items.push(i),
            Some(Err(e)) => out.push(("<attribute>".to_string(), Err(e.into()))),
            None => {}
        }
    }
    for (k, f) in &programs {
        out.push((f.sig.ident.to_string(), lower::lower(lower::Entry::Program(*k, f), &items)));
    }
    out
}

/// Lowers the program in `source` (Rust items as text) named `name`.
pub fn lower_source(source: &str, name: &str) -> Result<Lowered, Errors> {
    let file: syn::File = syn::parse_str(source).map_err(Error::from)?;
    lower_file(&file)
        .into_iter()
        .find(|(n, _)| n == name)
        .map(|(_, r)| r)
        .unwrap_or_else(|| Err(Error::new(proc_macro2::Span::call_site(), format!("no program `{name}`")).into()))
}

/// Lowers one `#[rt_program(kind)]` function given as tokens (`attr` is the
/// `kind`), with `deps` as the items it may use.
pub fn lower_tokens(attr: TokenStream, item: TokenStream, deps: &[Item]) -> Result<Lowered, Errors> {
    let kind_ident: syn::Ident = syn::parse2(attr).map_err(Error::from)?;
    let kind = expand::parse_kind(&kind_ident)?;
    let f: syn::ItemFn = syn::parse2(item).map_err(Error::from)?;
    lower::lower(lower::Entry::Program(kind, &f), deps)
}
