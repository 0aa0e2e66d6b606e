//! The lane-wise form of a ray program: the program's CPU copy (its Rust,
//! with the GPU's integer semantics: `cpu_semantics`) rewritten to run a
//! block of `rt_std::cpu::lanes::LANES` launch indices at once, so the CPU
//! backend calls it once per block and a trace hands the block's rays to
//! the backend together (`rt_std::cpu::lanes`; the statement forms are in
//! `stmt.rs`, one lane's view of a statement in `rename.rs`).
//!
//! Ray-generation, closest-hit and miss programs get the form; a payload or
//! attributes parameter holds each lane's reference (`lanes::refs`), and
//! the backend runs a packet's hits lane-wise, one call per program. A
//! program of another kind, or one with a construct the rewriting does not
//! take, runs one launch index at a time as before: its descriptor's `cpu_lanes` says why
//! (`CpuLanes::Scalar`), and the CPU backend reports it
//! (`Context::cpu_execution`). A refusal is never an error: the scalar copy
//! always runs.

mod rename;
mod stmt;

use crate::declared::reroot_type;
use crate::expand::variable_tuple;
use crate::kinds::Kind;
use crate::signature::{Param, Role};
use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote, quote_spanned};
use std::collections::HashSet;
use syn::visit::Visit;

/// Why a program has no lane-wise form: the construct, where it is.
#[derive(Debug)]
pub(crate) struct Refusal {
    /// The construct's span (`None`: the program as a whole).
    pub(crate) at: Option<Span>,
    pub(crate) what: String,
}

impl Refusal {
    pub(crate) fn new(span: Span, what: String) -> Refusal {
        Refusal { at: Some(span), what }
    }
}

/// The lane-wise form of program `f` as written: its CPU copy (`#[var]`
/// attributes taken off, `cpu_semantics` applied), rewritten; emitted with
/// the descriptor, inside the program's module, where the lowering
/// succeeded.
pub fn lane_form(kind: Kind, f: &syn::ItemFn) -> TokenStream {
    let Ok(params) = crate::signature::program_params(kind, f) else {
        return quote!(
            const CPU_LANES: ::rt_std::program::CpuLanes =
                ::rt_std::program::CpuLanes::Scalar("the program has errors");
        );
    };
    let mut copy = f.clone();
    for input in copy.sig.inputs.iter_mut() {
        if let syn::FnArg::Typed(pt) = input {
            pt.attrs.retain(|a| !crate::signature::is_var_attr(a));
        }
    }
    crate::cpu_semantics::rewrite_fn(&mut copy);
    cpu_lanes(kind, &copy, &params)
}

/// `CPU_LANES`, the descriptor's `cpu_lanes`: the lane-wise entry of `f`
/// (the CPU copy, after `cpu_semantics`), or why there is none.
pub fn cpu_lanes(kind: Kind, f: &syn::ItemFn, params: &[Param]) -> TokenStream {
    let form = if matches!(kind, Kind::RayGeneration | Kind::ClosestHit | Kind::Miss) {
        entry(f, params)
    } else {
        Err(Refusal { at: None, what: format!("{} programs run one launch index at a time", kind.name()) })
    };
    match form {
        Ok(entry) => quote! {
            #entry
            /// The program's lane-wise form (`rt_std::cpu::lanes`).
            const CPU_LANES: ::rt_std::program::CpuLanes = ::rt_std::program::CpuLanes::Lanes(cpu_lanes);
        },
        Err(r) => {
            // `line!()` at the construct's span: its line in the user's file.
            let what = r.what;
            let why = match r.at {
                Some(span) => quote_spanned!(span=> concat!(#what, " (line ", line!(), ")")),
                None => quote!(#what),
            };
            quote! {
                /// Why the program has no lane-wise form.
                const CPU_LANES: ::rt_std::program::CpuLanes = ::rt_std::program::CpuLanes::Scalar(#why);
            }
        }
    }
}

/// `fn cpu_lanes(mask, args, variables)`: the variables bound as `cpu`
/// binds them, the payload and attributes taken from `args` lane by lane,
/// then the body lane-wise.
fn entry(f: &syn::ItemFn, params: &[Param]) -> Result<TokenStream, Refusal> {
    if let Some(span) = module_relative_path(&f.block) {
        return Err(Refusal::new(span, "a path through `self::` or `super::`".into()));
    }
    let mut writer = stmt::Writer { varying: HashSet::new(), next: 0 };
    let mut types = Vec::new();
    let mut locals = Vec::new();
    let mut binds = Vec::new();
    let mut takes = Vec::new();
    for (i, (p, input)) in params.iter().zip(&f.sig.inputs).enumerate() {
        let syn::FnArg::Typed(pt) = input else {
            return Err(Refusal::new(p.span, "a `self` parameter".into()));
        };
        let syn::Pat::Ident(pi) = &*pt.pat else {
            return Err(Refusal::new(p.span, "a parameter pattern".into()));
        };
        let ty = reroot_type(&p.ty);
        let name = &pi.ident;
        let slots = match p.role {
            Role::Variable => None,
            Role::Payload { .. } => Some(quote!(payloads)),
            Role::Attributes { .. } => Some(quote!(attributes)),
            Role::Primitive | Role::Argument => {
                return Err(Refusal::new(p.span, "a parameter that is not a variable, payload or attributes".into()));
            }
        };
        if let Some(slots) = slots {
            // Each lane's `&mut T` (a lane that does not run: a spare).
            let spare = format_ident!("__rt_spare{}", i);
            writer.varying.insert(name.to_string());
            takes.push(quote! {
                let mut #spare = ::rt_std::cpu::lanes::spares::<#ty>();
                #[allow(unused_mut)]
                let mut #name = ::rt_std::cpu::lanes::refs::<#ty>(&mut __mask, &mut __rt_args.#slots, &mut #spare);
            });
            continue;
        }
        let local = format_ident!("__rt_arg{}", i);
        types.push(quote!(::rt_std::cpu::Var<#ty>));
        locals.push(quote!(::rt_std::cpu::Var(#local)));
        // A `mut` variable the program assigns holds a value per lane; a
        // buffer is written through, never assigned.
        if pi.mutability.is_some() && !is_buffer(&p.ty) {
            writer.varying.insert(name.to_string());
            binds.push(quote!(#[allow(unused_mut)] let mut #name = [#local; ::rt_std::cpu::lanes::LANES];));
        } else {
            let m = &pi.mutability;
            binds.push(quote!(#[allow(unused_mut)] let #m #name: #ty = #local;));
        }
    }
    let body = writer.block(&f.block.stmts)?;
    let list = variable_tuple(&types);
    let pattern = variable_tuple(&locals);
    let read = (!types.is_empty()).then(|| quote!(let #pattern = __rt_variables.get::<#list>();));
    Ok(quote! {
        /// Runs the program lane-wise over `mask`'s lanes (the CPU backend's
        /// lane-wise entry).
        #[allow(unused, clippy::all)]
        fn cpu_lanes(
            __rt_mask: &::rt_std::cpu::lanes::Mask,
            __rt_args: &mut ::rt_std::cpu::lanes::LaneArgs<'_>,
            __rt_variables: &::rt_std::cpu::BoundVariables<'_>,
        ) {
            let _ = (&__rt_args, __rt_variables);
            #read
            let mut __mask = *__rt_mask;
            #(#binds)*
            #(#takes)*
            if ::rt_std::cpu::lanes::any(&__mask) {
                #body
            }
        }
    })
}

/// Whether `ty` is a buffer handle (`RwBuffer2d<T>`, ...).
fn is_buffer(ty: &syn::Type) -> bool {
    matches!(ty, syn::Type::Path(p) if p.path.segments.last().is_some_and(|s| s.ident.to_string().contains("Buffer")))
}

/// Where the body names a path through `self::` or `super::`, which means
/// another module inside the entry's.
fn module_relative_path(b: &syn::Block) -> Option<Span> {
    struct P(Option<Span>);
    impl<'a> Visit<'a> for P {
        fn visit_path(&mut self, p: &'a syn::Path) {
            if let Some(s) = p.segments.first()
                && (s.ident == "self" || s.ident == "super")
                && p.segments.len() > 1
            {
                self.0.get_or_insert(s.ident.span());
            }
            syn::visit::visit_path(self, p);
        }
    }
    let mut v = P(None);
    v.visit_block(b);
    v.0
}
