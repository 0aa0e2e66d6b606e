//! A program's CPU side, beside the function itself: `cpu`, the entry the
//! CPU backend calls with `CpuArgs` (the payload, attributes, primitive and
//! variables unpacked into the function's parameters), `cpu_bind`, which
//! binds variable values to the parameter types once per launch, and for a
//! callable its function pointer `CALLABLE`. An intersection program's
//! CPU copy hands its attributes to each report.

use crate::declared::reroot_type;
use crate::kinds::Kind;
use crate::signature::{self, Role};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::spanned::Spanned;

/// In the CPU copy of an intersection program, `rt_report_intersection(m)`
/// becomes `__report_intersection(m, &*attr)`: the backend needs the
/// attributes as they are at the report, and reading them behind the
/// program's `&mut` would be unsound.
pub(super) fn pass_attributes_to_reports(f: &mut syn::ItemFn, params: &[signature::Param]) {
    let Some(attr) = params.iter().find(|p| matches!(p.role, Role::Attributes { .. })).map(|p| p.name.clone()) else {
        return;
    };
    struct R(syn::Ident);
    impl syn::visit_mut::VisitMut for R {
        fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
            syn::visit_mut::visit_expr_mut(self, e);
            if let syn::Expr::Call(c) = e
                && let syn::Expr::Path(p) = &*c.func
                && p.path.segments.last().is_some_and(|s| s.ident == "rt_report_intersection")
                && c.args.len() == 1
            {
                let m = &c.args[0];
                let a = &self.0;
                let span = c.span();
                *e = syn::parse_quote_spanned!(span=> ::rt_std::cpu::__report_intersection(#m, &*#a));
            }
        }
    }
    syn::visit_mut::VisitMut::visit_block_mut(&mut R(attr), &mut f.block);
}

/// The CPU entry: unpacks `CpuArgs` and calls the original function.
pub(super) fn cpu_thunk(kind: Kind, f: &syn::ItemFn, params: &[signature::Param]) -> TokenStream {
    let name = &f.sig.ident;
    if kind == Kind::Callable {
        return callable_thunk(f, params);
    }
    let mut var_types = Vec::new();
    let mut var_locals = Vec::new();
    let mut bindings = Vec::new();
    let args: Vec<TokenStream> = params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let ty = reroot_type(&p.ty);
            let local = format_ident!("__rt_arg{}", i);
            let source = match p.role {
                Role::Payload { .. } => quote!(payload),
                Role::Attributes { .. } => quote!(attributes),
                Role::Primitive => return quote!(*primitive),
                Role::Argument => unreachable!("callables have their own thunk"),
                Role::Variable => {
                    var_types.push(quote!(::rt_std::cpu::Var<#ty>));
                    var_locals.push(quote!(::rt_std::cpu::Var(#local)));
                    return quote!(#local);
                }
            };
            bindings.push(quote! {
                let Some(#local) = ::rt_std::cpu::__arg::<#ty>(#source.as_deref_mut()) else {
                    ::rt_std::cpu::raise(::rt_std::EXCEPTION_INVALID_RAY);
                    return ::rt_std::cpu::CpuResult::Unit;
                };
            });
            match p.role {
                Role::Payload { mutable: true } | Role::Attributes { mutable: true } => quote!(#local),
                _ => quote!(&*#local),
            }
        })
        .collect();
    let _ = kind;
    // The variables' types as one `VariableList` (tuples of at most eight,
    // nested), and the pattern that takes it apart.
    let list = variable_tuple(&var_types);
    let pattern = variable_tuple(&var_locals);
    let read_variables = (!var_types.is_empty()).then(|| quote!(let #pattern = variables.get::<#list>();));
    let attributes_from_words = params.iter().find(|p| matches!(p.role, Role::Attributes { .. })).map(|p| {
        let ty = reroot_type(&p.ty);
        quote! {
            /// Makes the program's attribute type from heap words.
            pub fn attributes_from_words(words: &[u32]) -> Box<dyn ::rt_std::cpu::AnyAttributes> {
                Box::new(<#ty as ::rt_std::RtData>::read_words(words))
            }
        }
    });
    quote! {
        #attributes_from_words
        /// Binds variable values to the program's parameter types (the CPU
        /// backend, once per launch).
        pub fn cpu_bind<'a>(
            values: &[&'a (dyn ::core::any::Any + ::core::marker::Send + ::core::marker::Sync)],
        ) -> ::core::result::Result<::rt_std::cpu::BoundVariables<'a>, ::rt_std::cpu::VariableMismatch> {
            ::rt_std::cpu::BoundVariables::bind::<#list>(values)
        }
        /// Runs the program natively (the CPU backend's entry).
        pub fn cpu(args: &mut ::rt_std::cpu::CpuArgs<'_>) -> ::rt_std::cpu::CpuResult {
            let ::rt_std::cpu::CpuArgs { payload, attributes, primitive, variables } = args;
            let _ = (&payload, &attributes, &primitive, &variables);
            #read_variables
            #(#bindings)*
            ::rt_std::cpu::CpuResult::from(super::#name(#(#args),*))
        }
    }
}

/// A callable program's CPU side: its Rust function as a `fn` pointer of
/// its arguments (what `Callable::call` downcasts to), and the entries every
/// descriptor has. A callable with `#[var]` variables is reached through a
/// shim that reads them from the launch (bound once per launch, as a
/// program's are, by `cpu_bind`) and calls the function with every
/// parameter in the Rust order. The backends never call `cpu`.
fn callable_thunk(f: &syn::ItemFn, params: &[signature::Param]) -> TokenStream {
    let name = &f.sig.ident;
    let ret = match &f.sig.output {
        syn::ReturnType::Default => quote!(),
        syn::ReturnType::Type(_, t) => {
            let t = reroot_type(t);
            quote!(-> #t)
        }
    };
    let (mut arg_decls, mut arg_tys, mut var_types, mut var_locals, mut call) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (i, p) in params.iter().enumerate() {
        let ty = reroot_type(&p.ty);
        let local = format_ident!("__rt_arg{}", i);
        if matches!(p.role, Role::Variable) {
            var_types.push(quote!(::rt_std::cpu::Var<#ty>));
            var_locals.push(quote!(::rt_std::cpu::Var(#local)));
        } else {
            arg_decls.push(quote!(#local: #ty));
            arg_tys.push(ty);
        }
        call.push(quote!(#local));
    }
    let list = variable_tuple(&var_types);
    let function = if var_types.is_empty() {
        quote!(super::#name)
    } else {
        let pattern = variable_tuple(&var_locals);
        quote! {{
            /// Reads the callable's variables and calls it.
            fn __rt_with_variables(#(#arg_decls),*) #ret {
                ::rt_std::cpu::__callable_variables(|#pattern: #list| super::#name(#(#call),*))
            }
            __rt_with_variables
        }}
    };
    quote! {
        /// The callable's Rust function, as `Callable::call` finds it.
        pub static CALLABLE: fn(#(#arg_tys),*) #ret = #function;
        /// Binds variable values to the callable's `#[var]` parameter types
        /// (the CPU backend, once per launch).
        pub fn cpu_bind<'a>(
            values: &[&'a (dyn ::core::any::Any + ::core::marker::Send + ::core::marker::Sync)],
        ) -> ::core::result::Result<::rt_std::cpu::BoundVariables<'a>, ::rt_std::cpu::VariableMismatch> {
            ::rt_std::cpu::BoundVariables::bind::<#list>(values)
        }
        /// Never called: a callable runs through `Callable::call`.
        pub fn cpu(_: &mut ::rt_std::cpu::CpuArgs<'_>) -> ::rt_std::cpu::CpuResult {
            ::rt_std::cpu::CpuResult::Unit
        }
    }
}

/// `(a, b, ...)` of `items`, as tuples of at most eight nested as deep as
/// needed (rt-std implements `VariableList` for tuples up to eight).
pub(crate) fn variable_tuple(items: &[TokenStream]) -> TokenStream {
    if items.len() <= 8 {
        return quote!((#(#items,)*));
    }
    let groups: Vec<TokenStream> = items.chunks(8).map(variable_tuple).collect();
    variable_tuple(&groups)
}
