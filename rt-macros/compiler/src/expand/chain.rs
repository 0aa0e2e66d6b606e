//! The dependency chain: the `macro_rules!` links through which a program
//! (or a helper, struct, constant or impl) sees the items it names, and
//! `__rt_collect!`, the step between two links.
//!
//! `#[rt_struct] struct S` (likewise `#[rt_function]`, `#[rt_const]`) emits,
//! beside the item, `macro_rules! __rt_item_S` and `pub(crate) use
//! __rt_item_S as S;` — a macro named like the item, found wherever the item
//! is (macros and types live in different namespaces). Invoked as
//! `S!{ @rt_collect REST }` it expands to `::rt_std::__rt_collect!{ def {
//! <S and everything S depends on> } REST }`.
//!
//! A macro with dependencies `A, B` emits `A!{ @rt_collect todo { B } done {}
//! entry { ... } }`; `__rt_collect!` ([`collect`]) moves the definition into
//! `done` and invokes the next path in `todo`. With `todo` empty, it lowers
//! the entry. Because each item collects its own dependencies where it is
//! declared, paths always resolve in the module that wrote them.
//!
//! `#[rt_impl] impl S` is a link too, `__rt_impl_S`, and `#[rt_struct(impl)]`
//! puts it among the struct's dependencies, so `S!` hands out the impl with
//! the struct (see [`crate::methods`]); likewise `impl T for S`,
//! `__rt_impl_S__T`, with `#[rt_struct(impl T)]`, and `#[rt_trait] trait T`
//! is the link `T` (see [`crate::traits`]).

use super::descriptor::program_output;
use super::parse_kind;
use crate::error::Errors;
use crate::lower::{self, Entry};
use crate::{Item, StructRole};
use proc_macro2::{Span, TokenStream, TokenTree};
use quote::{format_ident, quote, quote_spanned};
use syn::spanned::Spanned;

/// Starts the chain for `entry` with dependency paths `deps`; with none, lowers
/// at once.
pub(super) fn start_chain(entry: TokenStream, deps: Vec<syn::Path>) -> TokenStream {
    start_chain_with(entry, deps, TokenStream::new())
}

/// As [`start_chain`], with definitions the entry brings itself (`done`:
/// the plain constants of its module, `crate::plain_consts`).
pub(super) fn start_chain_with(entry: TokenStream, deps: Vec<syn::Path>, done: TokenStream) -> TokenStream {
    match deps.split_first() {
        None => finish(&entry, done),
        Some((first, rest)) => chain_call(first, rest, done, &entry),
    }
}

fn chain_call(next: &syn::Path, rest: &[syn::Path], done: TokenStream, entry: &TokenStream) -> TokenStream {
    // The invocation carries the span of the path, so "cannot find macro"
    // (an item not declared with an rt attribute) points at the use.
    let span = next.span();
    quote_spanned! {span=> #next!{ @rt_collect todo { #(#rest),* } done { #done } entry { #entry } } }
}

/// `__rt_collect!`: one step of the chain.
pub fn collect(input: TokenStream) -> TokenStream {
    let groups = match keyed_groups(input) {
        Ok(g) => g,
        Err(e) => return e.to_compile_error(),
    };
    let get = |k: &str| groups.iter().find(|(n, _)| n == k).map(|(_, g)| g.clone()).unwrap_or_default();
    let def = get("def");
    let mut done = get("done");
    done.extend(def);
    let entry = get("entry");
    let todo: Vec<syn::Path> = match syn::parse::Parser::parse2(
        syn::punctuated::Punctuated::<syn::Path, syn::Token![,]>::parse_terminated,
        get("todo"),
    ) {
        Ok(p) => p.into_iter().collect(),
        Err(e) => return e.to_compile_error(),
    };
    match todo.split_first() {
        Some((first, rest)) => chain_call(first, rest, done, &entry),
        None => finish(&entry, done),
    }
}

/// Splits `name { ... } name { ... }` into pairs.
fn keyed_groups(input: TokenStream) -> syn::Result<Vec<(String, TokenStream)>> {
    let mut out = Vec::new();
    let mut it = input.into_iter();
    while let Some(t) = it.next() {
        let TokenTree::Ident(name) = t else {
            return Err(syn::Error::new(t.span(), "malformed __rt_collect! input"));
        };
        match it.next() {
            Some(TokenTree::Group(g)) => out.push((name.to_string(), g.stream())),
            _ => return Err(syn::Error::new(name.span(), "malformed __rt_collect! input")),
        }
    }
    Ok(out)
}

/// Parses `role { item } role { item } ...` definitions.
pub fn parse_defs(tokens: TokenStream) -> syn::Result<Vec<Item>> {
    let mut items = Vec::new();
    let mut it = tokens.into_iter().peekable();
    while let Some(t) = it.next() {
        let TokenTree::Ident(kw) = t else { return Err(syn::Error::new(t.span(), "malformed definition")) };
        let kw = kw.to_string();
        let role = if kw == "struct" {
            match it.next() {
                Some(TokenTree::Ident(r)) => StructRole::from_keyword(&r.to_string()),
                _ => None,
            }
        } else {
            None
        };
        let Some(TokenTree::Group(g)) = it.next() else {
            return Err(syn::Error::new(Span::call_site(), "malformed definition"));
        };
        let item = match (kw.as_str(), role) {
            ("struct", Some(r)) => Item::Struct(syn::parse2(g.stream())?, r),
            ("function", _) => Item::Function(syn::parse2(g.stream())?),
            ("constant", _) => Item::Const(syn::parse2(g.stream())?),
            ("enum", _) => Item::Enum(syn::parse2(g.stream())?),
            ("impl", _) => Item::Impl(syn::parse2(g.stream())?),
            ("trait", _) => Item::Trait(syn::parse2(g.stream())?),
            ("alias", _) => Item::Alias(syn::parse2(g.stream())?),
            _ => return Err(syn::Error::new(g.span(), "malformed definition")),
        };
        if !items.iter().any(|i: &Item| i.name() == item.name()) {
            items.push(item);
        }
    }
    Ok(items)
}

/// The end of the chain: lower the entry with every collected definition.
fn finish(entry: &TokenStream, done: TokenStream) -> TokenStream {
    let deps = match parse_defs(done.clone()) {
        Ok(d) => d,
        Err(e) => return e.to_compile_error(),
    };
    let mut it = entry.clone().into_iter();
    let kw = match it.next() {
        Some(TokenTree::Ident(i)) => i.to_string(),
        _ => return quote!(compile_error!("malformed rt entry");),
    };
    match kw.as_str() {
        "program" => {
            let (Some(TokenTree::Ident(kind)), Some(TokenTree::Group(g))) = (it.next(), it.next()) else {
                return quote!(compile_error!("malformed rt entry"););
            };
            let f: syn::ItemFn = match syn::parse2(g.stream()) {
                Ok(f) => f,
                Err(e) => return e.to_compile_error(),
            };
            let kind = match parse_kind(&kind) {
                Ok(k) => k,
                Err(e) => return Errors::from(e).to_compile_errors(),
            };
            let lowered = lower::lower_own(Entry::Program(kind, &f), &deps);
            if lowered.is_ok() && asserts(&f, &deps) {
                // The module with the checks and the one without, chosen
                // by the declaring crate's `cfg(debug_assertions)`.
                let off = lower::lower_own_without_debug_assertions(Entry::Program(kind, &f), &deps);
                let on = program_output(kind, &f, lowered);
                let off = program_output(kind, &f, off);
                return quote!(if ::core::cfg!(debug_assertions) { #on } else { #off });
            }
            program_output(kind, &f, lowered)
        }
        "impl" => {
            // Checked where the struct's chain ends (see `rt_impl`).
            let Some(TokenTree::Group(g)) = it.next() else { return quote!(compile_error!("malformed rt entry");) };
            let item_tokens = g.stream();
            let i: syn::ItemImpl = match syn::parse2(item_tokens.clone()) {
                Ok(i) => i,
                Err(e) => return e.to_compile_error(),
            };
            let Some(ty) = (match &*i.self_ty {
                syn::Type::Path(p) => p.path.segments.last().map(|s| s.ident.clone()),
                _ => None,
            }) else {
                return quote!(compile_error!("malformed rt entry"););
            };
            export_macro(&crate::methods::impl_macro_ident_of(&i, &ty), quote!(impl { #item_tokens } #done))
        }
        // Its default bodies are checked in each impl that uses them.
        "trait" => export_as_written(it.next(), |t: &syn::ItemTrait| t.ident.clone(), quote!(trait), &done),
        // Checked where it is used: its type is lowered there.
        "alias" => export_as_written(it.next(), |t: &syn::ItemType| t.ident.clone(), quote!(alias), &done),
        "enum" => match it.next() {
            Some(TokenTree::Group(g)) => finish_enum(g.stream(), &deps, done),
            _ => quote!(compile_error!("malformed rt entry");),
        },
        "function" | "constant" | "struct" => {
            let role = if kw == "struct" {
                match it.next() {
                    Some(TokenTree::Ident(r)) => StructRole::from_keyword(&r.to_string()),
                    _ => None,
                }
            } else {
                None
            };
            let Some(TokenTree::Group(g)) = it.next() else { return quote!(compile_error!("malformed rt entry");) };
            let item_tokens = g.stream();
            let (name, check) = match (kw.as_str(), role) {
                ("function", _) => match syn::parse2::<syn::ItemFn>(item_tokens.clone()) {
                    Ok(f) => (f.sig.ident.clone(), lower::lower_own(Entry::Helper(&f), &deps).map(|_| ())),
                    Err(e) => return e.to_compile_error(),
                },
                ("constant", _) => match syn::parse2::<syn::ItemConst>(item_tokens.clone()) {
                    Ok(c) => (c.ident.clone(), lower::lower_own(Entry::Const(&c), &deps).map(|_| ())),
                    Err(e) => return e.to_compile_error(),
                },
                (_, Some(r)) => match syn::parse2::<syn::ItemStruct>(item_tokens.clone()) {
                    Ok(s) => {
                        let mut deps = deps.clone();
                        deps.retain(|d| s.ident != d.name());
                        deps.push(Item::Struct(s.clone(), r));
                        (s.ident.clone(), lower::lower_own(Entry::Struct(&s), &deps).map(|_| ()))
                    }
                    Err(e) => return e.to_compile_error(),
                },
                _ => return quote!(compile_error!("malformed rt entry");),
            };
            let errors = match check {
                Ok(()) => TokenStream::new(),
                Err(e) => e.to_compile_errors(),
            };
            let role_kw = role.map(|r| format_ident!("{}", r.keyword()));
            let kw_ident = format_ident!("{}", kw);
            let export = export_macro(&name, quote!(#kw_ident #role_kw { #item_tokens } #done));
            quote!(#errors #export)
        }
        _ => quote!(compile_error!("malformed rt entry");),
    }
}

/// The end of the chain of an item checked where it is used (a trait, an
/// alias): its link, handing it out as written with what it depends on.
fn export_as_written<T: syn::parse::Parse>(
    group: Option<TokenTree>,
    ident: impl Fn(&T) -> syn::Ident,
    kw: TokenStream,
    done: &TokenStream,
) -> TokenStream {
    let Some(TokenTree::Group(g)) = group else { return quote!(compile_error!("malformed rt entry");) };
    let item_tokens = g.stream();
    match syn::parse2::<T>(item_tokens.clone()) {
        Ok(t) => export_macro(&ident(&t), quote!(#kw { #item_tokens } #done)),
        Err(e) => e.to_compile_error(),
    }
}

/// The end of an enum's chain, which carries its `#[rt_impl]` blocks:
/// they are checked here, as a struct's are where its chain ends.
fn finish_enum(item_tokens: TokenStream, deps: &[Item], done: TokenStream) -> TokenStream {
    let e: syn::ItemEnum = match syn::parse2(item_tokens.clone()) {
        Ok(e) => e,
        Err(e) => return e.to_compile_error(),
    };
    let mut deps = deps.to_vec();
    deps.retain(|d| e.ident != d.name());
    deps.push(Item::Enum(e.clone()));
    let errors = match lower::lower_own(Entry::Enum(&e), &deps) {
        Ok(_) => TokenStream::new(),
        Err(err) => err.to_compile_errors(),
    };
    let export = export_macro(&e.ident, quote!(enum { #item_tokens } #done));
    quote!(#errors #export)
}

/// Whether a program or one of its dependencies has a `debug_assert!`.
fn asserts(f: &syn::ItemFn, deps: &[Item]) -> bool {
    fn walk(ts: TokenStream) -> bool {
        let mut it = ts.into_iter().peekable();
        while let Some(t) = it.next() {
            match t {
                TokenTree::Ident(i) if i == "debug_assert" => {
                    if matches!(it.peek(), Some(TokenTree::Punct(p)) if p.as_char() == '!') {
                        return true;
                    }
                }
                TokenTree::Group(g) if walk(g.stream()) => return true,
                _ => {}
            }
        }
        false
    }
    walk(quote!(#f))
        || deps.iter().any(|d| match d {
            Item::Function(f) => walk(quote!(#f)),
            Item::Impl(i) => walk(quote!(#i)),
            Item::Trait(t) => walk(quote!(#t)),
            Item::Struct(..) | Item::Const(_) | Item::Enum(_) | Item::Alias(_) => false,
        })
}

/// `macro_rules! __rt_item_NAME` handing out `defs`, re-exported as `NAME`.
pub(super) fn export_macro(name: &syn::Ident, defs: TokenStream) -> TokenStream {
    let mac = format_ident!("__rt_item_{}", name);
    quote! {
        #[doc(hidden)]
        #[allow(unused_macros)]
        macro_rules! #mac {
            (@rt_collect $($rest:tt)*) => { ::rt_std::__rt_collect!{ def { #defs } $($rest)* } };
        }
        #[doc(hidden)]
        #[allow(unused_imports)]
        pub(crate) use #mac as #name;
    }
}
