//! Checks, compiled by rustc, that the items a program, helper or impl
//! names were declared with their rt attribute. An item that was not is
//! rustc's "cannot find macro `X`" where the chain invokes it (see
//! `expand`), a message that names `X` but not the fix; each check here
//! adds, at the same use, an error that says which attribute `X` needs.
//!
//! - Types: `RtData`, `Payload` and `Attributes` say it
//!   (`#[diagnostic::on_unimplemented]`), asked through rt-std's hidden
//!   `__require_*` functions.
//! - Constants and functions have no type to ask, so `#[rt_const]` and
//!   `#[rt_function]` also declare a marker of the item's name in the type
//!   namespace (a braced struct, where the constant or function is in the
//!   value namespace: [`marker`]). The check imports the name explicitly
//!   (the marker, if there is one) beside a glob import of fallbacks of
//!   the same names (a non-glob name shadows a glob one in the type
//!   namespace), and requires the name to implement the marker trait: the
//!   fallback does not, and its trait's message says what to add.

use crate::deps::{Dep, DepKind};
use crate::signature::{self, Role};
use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};
use std::collections::BTreeSet;
use syn::spanned::Spanned;

/// A function that does nothing but require, at each use's span, that the
/// types the item names were declared with an rt attribute: a type that was
/// not is rustc's "cannot find macro" in the chain, and this adds the
/// message of `RtData`, `Payload` or `Attributes`
/// (`#[diagnostic::on_unimplemented]`), which says which attribute to add.
pub fn declared_checks(deps: &[Dep], params: &[signature::Param]) -> TokenStream {
    let mut checks = Vec::new();
    let mut roles = Vec::new();
    for p in params {
        let check = match p.role {
            Role::Payload { .. } => quote!(__require_payload),
            Role::Attributes { .. } => quote!(__require_attributes),
            _ => continue,
        };
        let ty = reroot_type(&p.ty);
        roles.push(quote!(#ty).to_string());
        let span = p.ty.span();
        checks.push(quote_spanned!(span=> ::rt_std::data::#check::<#ty>();));
    }
    let types: Vec<&syn::Path> = deps
        .iter()
        .filter(|d| d.kind == DepKind::Type)
        .map(|d| &d.path)
        .filter(|path| !roles.contains(&quote!(#path).to_string()))
        .collect();
    let types = type_checks(&types);
    let named = named_checks(deps);
    let checks = if checks.is_empty() {
        TokenStream::new()
    } else {
        quote! {
            #[allow(dead_code)]
            fn __rt_declared() {
                #(#checks)*
            }
        }
    };
    quote!(#checks #types #named)
}

/// The checks for the types among `deps`, in a module of their own one
/// level down. A type named `X` must be declared with an rt attribute,
/// unless it is an `#[rt_type]` alias, whose type may be one that needs
/// none (`Vec3`). The alias declares a function `__rt_type_check_X<T>`
/// that asks nothing of `T` ([`alias_marker`]); the module declares one of
/// the same name that requires `T` declared, and calls the name at `X`
/// where a block glob-imports the module that wrote `X`: the alias's
/// function, where there is one, shadows the module's (a block's names
/// come before its module's).
fn type_checks(types: &[&syn::Path]) -> TokenStream {
    let mut seen = BTreeSet::new();
    let mut fallbacks = Vec::new();
    let mut checks = Vec::new();
    for path in types {
        let Some(last) = path.segments.last() else { continue };
        let span = last.ident.span();
        let down = one_level_down(path);
        if !seen.insert(last.ident.to_string()) {
            // Another path to a type of the same name: checked as a type.
            checks.push(quote_spanned!(span=> ::rt_std::data::__require_declared::<#down>();));
            continue;
        }
        let check = alias_check_ident(&last.ident);
        let mut module = down.clone();
        module.segments.pop();
        let module = syn::Path {
            leading_colon: module.leading_colon,
            segments: module.segments.into_pairs().map(|p| p.into_value()).collect(),
        };
        fallbacks.push(quote_spanned!(span=> fn #check<T: ::rt_std::data::DeclaredData + ?Sized>() {}));
        checks.push(quote_spanned!(span=> { use #module::*; #check::<#down>(); }));
    }
    if checks.is_empty() {
        return TokenStream::new();
    }
    quote! {
        #[allow(dead_code, non_snake_case, unused_imports, clippy::all)]
        mod __rt_types {
            #(#fallbacks)*
            fn __rt_declared() {
                #(#checks)*
            }
        }
    }
}

/// The function an `#[rt_type]` alias `X` declares for [`type_checks`].
fn alias_check_ident(ident: &syn::Ident) -> syn::Ident {
    syn::Ident::new(&format!("__rt_type_check_{ident}"), ident.span())
}

/// What `#[rt_type]` declares beside its alias (see `type_checks`): a
/// function that does nothing, of the alias's visibility.
pub fn alias_marker(vis: &syn::Visibility, ident: &syn::Ident) -> TokenStream {
    let check = alias_check_ident(ident);
    quote! {
        #[doc(hidden)]
        #[allow(non_snake_case, dead_code)]
        #vis fn #check<T: ?Sized>() {}
    }
}

/// The checks for the constants and functions among `deps` (see the
/// module's doc), in a module of their own one level down.
fn named_checks(deps: &[Dep]) -> TokenStream {
    let mut seen = BTreeSet::new();
    let mut fallbacks = Vec::new();
    let mut imports = Vec::new();
    let mut checks = Vec::new();
    for d in deps {
        let Some(last) = d.path.segments.last() else { continue };
        let ident = &last.ident;
        let require = match d.kind {
            DepKind::Type | DepKind::Trait => continue,
            DepKind::Value => quote!(__require_rt_const),
            DepKind::Function => quote!(__require_rt_function),
        };
        if !seen.insert(ident.to_string()) {
            continue;
        }
        let span = ident.span();
        let path = one_level_down(&d.path);
        fallbacks.push(quote!(pub struct #ident {}));
        imports.push(quote_spanned!(span=> use #path;));
        checks.push(quote_spanned!(span=> ::rt_std::data::#require::<#ident>();));
    }
    if checks.is_empty() {
        return TokenStream::new();
    }
    quote! {
        #[allow(dead_code, non_camel_case_types, unused_imports, non_snake_case, clippy::all)]
        mod __rt_named {
            mod __rt_fallback {
                #(#fallbacks)*
            }
            use __rt_fallback::*;
            #(#imports)*
            fn __rt_declared() {
                #(#checks)*
            }
        }
    }
}

/// `p` as a module one level below the one that wrote it names it.
fn one_level_down(p: &syn::Path) -> syn::Path {
    let mut p = p.clone();
    if p.leading_colon.is_some() {
        return p;
    }
    let Some(first) = p.segments.first() else { return p };
    let span = first.ident.span();
    match first.ident.to_string().as_str() {
        "crate" => {}
        "self" => p.segments[0].ident = syn::Ident::new("super", span),
        _ => p.segments.insert(0, syn::PathSegment::from(syn::Ident::new("super", span))),
    }
    p
}

/// The marker `#[rt_const]` and `#[rt_function]` declare beside their item
/// (see the module's doc): a braced struct of the item's name and
/// visibility, in the type namespace, which the item does not use.
pub fn marker(vis: &syn::Visibility, ident: &syn::Ident, function: bool) -> TokenStream {
    let trait_ = if function { quote!(__RtFunctionMarker) } else { quote!(__RtConstMarker) };
    quote! {
        #[doc(hidden)]
        #[allow(non_camel_case_types, dead_code)]
        #vis struct #ident {}
        impl ::rt_std::data::#trait_ for #ident {}
    }
}

/// Inside the program's module, paths relative to the parent need one more
/// `super`.
pub fn reroot(p: &syn::Path) -> syn::Path {
    let mut p = p.clone();
    if p.leading_colon.is_none()
        && let Some(first) = p.segments.first()
    {
        let f = first.ident.to_string();
        if f == "super" {
            p.segments.insert(0, syn::PathSegment::from(syn::Ident::new("super", first.ident.span())));
        } else if f == "self" {
            p.segments[0].ident = syn::Ident::new("super", first.ident.span());
        }
    }
    p
}

/// Rewrites `super::` paths in a type for use one module deeper.
pub fn reroot_type(ty: &syn::Type) -> syn::Type {
    struct R;
    impl syn::visit_mut::VisitMut for R {
        fn visit_path_mut(&mut self, p: &mut syn::Path) {
            *p = reroot(p);
            syn::visit_mut::visit_path_mut(self, p);
        }
    }
    let mut t = ty.clone();
    syn::visit_mut::VisitMut::visit_type_mut(&mut R, &mut t);
    t
}
