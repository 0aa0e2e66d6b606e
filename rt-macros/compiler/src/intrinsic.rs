//! `#[rt_intrinsic]`: rt-std's CPU bodies of the contract's intrinsics.
//!
//! Each intrinsic's doc line of callers (`Program kinds: ...`) and its OptiX
//! alias come from its row in `rt-abi`, not from hand-written text, and the
//! function's parameter and return types are checked against the row's at
//! rt-std's build: a CPU body that drifts from the contract is a compile
//! error at the parameter.

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, quote};
use rt_abi::{AbiTy, Form};
use syn::spanned::Spanned;

fn error(span: Span, message: String) -> TokenStream {
    syn::Error::new(span, message).to_compile_error()
}

/// The last path segment of a type, `()` for the unit type.
fn type_name(ty: &syn::Type) -> Option<String> {
    match ty {
        syn::Type::Path(p) => p.path.segments.last().map(|s| s.ident.to_string()),
        syn::Type::Tuple(t) if t.elems.is_empty() => Some("()".into()),
        _ => None,
    }
}

/// The errors of a function whose signature differs from its row's.
fn check_signature(f: &syn::ItemFn, row: &rt_abi::Intrinsic) -> TokenStream {
    let Some(w) = row.wgsl.filter(|_| row.form != Form::Special) else { return TokenStream::new() };
    let name = &row.name;
    let inputs: Vec<&syn::PatType> = f
        .sig
        .inputs
        .iter()
        .filter_map(|a| match a {
            syn::FnArg::Typed(t) => Some(t),
            syn::FnArg::Receiver(_) => None,
        })
        .collect();
    if inputs.len() != w.params.len() {
        return error(
            f.sig.inputs.span(),
            format!("`{name}` takes {} parameter(s) in the contract (rt-abi), {} here", w.params.len(), inputs.len()),
        );
    }
    let mut out = TokenStream::new();
    for (i, (p, (_, want))) in inputs.iter().zip(w.params).enumerate() {
        if type_name(&p.ty).as_deref() != Some(want.rust()) {
            out.extend(error(
                p.ty.span(),
                format!(
                    "parameter {} of `{name}` is `{}` in the contract (rt-abi), not `{}`",
                    i + 1,
                    want.rust(),
                    p.ty.to_token_stream()
                ),
            ));
        }
    }
    let ret = match &f.sig.output {
        syn::ReturnType::Default => Some("()".to_string()),
        syn::ReturnType::Type(_, t) => type_name(t),
    };
    if ret.as_deref() != Some(w.ret.rust()) {
        let shown = if w.ret == AbiTy::Unit { "nothing".to_string() } else { format!("`{}`", w.ret.rust()) };
        let at = match &f.sig.output {
            syn::ReturnType::Default => f.sig.ident.span(),
            syn::ReturnType::Type(_, t) => t.span(),
        };
        out.extend(error(at, format!("`{name}` returns {shown} in the contract (rt-abi)")));
    }
    out
}

/// Expands `#[rt_intrinsic]` on a function or a `macro_rules!`.
pub fn rt_intrinsic(attr: TokenStream, item: TokenStream) -> TokenStream {
    if !attr.is_empty() {
        return error(attr.span(), "`#[rt_intrinsic]` takes no arguments: its row is found by name".into());
    }
    let parsed: syn::Item = match syn::parse2(item.clone()) {
        Ok(i) => i,
        Err(e) => return e.to_compile_error(),
    };
    let ident = match &parsed {
        syn::Item::Fn(f) => f.sig.ident.clone(),
        syn::Item::Macro(syn::ItemMacro { ident: Some(ident), .. }) => ident.clone(),
        other => return error(other.span(), "`#[rt_intrinsic]` goes on a function or a `macro_rules!`".into()),
    };
    let name = ident.to_string();
    let Some(row) = rt_abi::intrinsic(&name) else {
        return error(
            ident.span(),
            format!("`{name}` has no row in rt-abi's intrinsic table (rt-abi/src/intrinsics.rs)"),
        );
    };
    let errors = match &parsed {
        syn::Item::Fn(f) => check_signature(f, row),
        _ => TokenStream::new(),
    };
    let callers = format!(" {}", row.callers.doc_line());
    let alias = row.optix;
    quote! {
        #errors
        #[doc = ""]
        #[doc = #callers]
        #[doc(alias = #alias)]
        #item
    }
}

/// `callback!(name, ...)` over the Rust names of every intrinsic row.
pub fn names(callback: TokenStream) -> TokenStream {
    let names = rt_abi::INTRINSICS.iter().map(|i| proc_macro2::Ident::new(i.name, Span::call_site()));
    quote! { #callback!(#(#names),*); }
}
