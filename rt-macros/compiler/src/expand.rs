//! Token emission for the attribute macros, and the dependency chain.
//!
//! ## The chain
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
//! the struct (see [`crate::methods`]).
//!
//! Programs expand inside `mod <program name> { use super::*; ... }` (a
//! module and a function may share a name), which holds the CPU thunk and
//! `pub static PROGRAM: ProgramDescriptor = <chain>;`: a program's chain runs
//! in expression position and ends in the descriptor (or the errors). So
//! `PROGRAM` exists even when the chain breaks (a dependency not declared
//! with an rt attribute is rustc's "cannot find macro" at its use, and
//! nothing more), and each error is reported once: errors inside a
//! dependency are its own macro's to report ([`lower::lower_own`]).

use crate::declared::{declared_checks, reroot, reroot_type};
use crate::error::{Error, Errors};
use crate::kinds::Kind;
use crate::lower::text::Site;
use crate::lower::{self, Entry, Lowered};
use crate::signature::{self, Role};
use crate::types::Ty;
use crate::{Item, StructRole, deps};
use proc_macro2::{Span, TokenStream, TokenTree};
use quote::{format_ident, quote, quote_spanned};
use std::collections::BTreeMap;
use syn::spanned::Spanned;

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

/// The original function with `#[var]` parameter attributes removed.
fn strip_var_attrs(f: &syn::ItemFn) -> syn::ItemFn {
    let mut f = f.clone();
    for input in f.sig.inputs.iter_mut() {
        if let syn::FnArg::Typed(pt) = input {
            pt.attrs.retain(|a| !signature::is_var_attr(a));
        }
    }
    f
}

/// `#[rt_program(kind)]`.
pub fn rt_program(attr: TokenStream, item: TokenStream) -> TokenStream {
    let f: syn::ItemFn = match syn::parse2(item.clone()) {
        Ok(f) => f,
        Err(e) => {
            let err = e.to_compile_error();
            return quote!(#err #item);
        }
    };
    let mut stripped = strip_var_attrs(&f);
    let kind = match syn::parse2::<syn::Ident>(attr.clone()) {
        Ok(i) => match parse_kind(&i) {
            Ok(k) => k,
            Err(e) => return failed_program(&f, &stripped, e.into()),
        },
        Err(_) => {
            let all: Vec<&str> = crate::kinds::ALL_KINDS.iter().map(|k| k.name()).collect();
            let span = if attr.is_empty() { Span::call_site() } else { attr.span() };
            let e = Error::new(span, format!("`#[rt_program]` needs a program kind: one of {}", all.join(", ")));
            return failed_program(&f, &stripped, e.into());
        }
    };
    let params = match signature::program_params(kind, &f) {
        Ok(p) => p,
        Err(e) => return failed_program(&f, &stripped, e),
    };
    if kind == Kind::Intersection {
        pass_attributes_to_reports(&mut stripped, &params);
    }
    crate::cpu_semantics::rewrite_fn(&mut stripped);
    let name = &f.sig.ident;
    let vis = &f.vis;
    let thunk = cpu_thunk(kind, &f, &params);
    let kind_ident = format_ident!("{}", kind.name());
    let entry = quote!(program #kind_ident { #item });
    let deps: Vec<syn::Path> = deps::of_fn(&f).into_iter().map(|p| reroot(&p)).collect();
    let declared = declared_checks(&deps, &params);
    let body = start_chain(entry, deps);
    quote! {
        #stripped
        #[doc(hidden)]
        #[allow(non_snake_case, unused_imports, clippy::all)]
        #vis mod #name {
            use super::*;
            #declared
            #thunk
            /// The program's descriptor: WGSL, layouts, variables and the CPU entry.
            pub static PROGRAM: ::rt_std::program::ProgramDescriptor = #body;
        }
    }
}

/// A program whose attribute or signature is wrong: the function as written
/// and a module whose `PROGRAM` is the errors (an expression of any type), so
/// code that names `name::PROGRAM` reports nothing more.
fn failed_program(f: &syn::ItemFn, stripped: &syn::ItemFn, e: Errors) -> TokenStream {
    let name = &f.sig.ident;
    let vis = &f.vis;
    let errs = error_expr(&e);
    quote! {
        #stripped
        #[doc(hidden)]
        #[allow(non_snake_case, unused_imports, clippy::all)]
        #vis mod #name {
            pub static PROGRAM: ::rt_std::program::ProgramDescriptor = #errs;
        }
    }
}

/// `#[rt_function]`.
pub fn rt_function(attr: TokenStream, item: TokenStream) -> TokenStream {
    let f: syn::ItemFn = match syn::parse2(item.clone()) {
        Ok(f) => f,
        Err(e) => {
            let err = e.to_compile_error();
            return quote!(#err #item);
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_function]` takes no arguments").into(), item);
    }
    let deps = deps::of_fn(&f);
    let declared = declared_checks(&deps, &[]);
    let body = start_chain(quote!(function { #item }), deps);
    let marker = crate::declared::marker(&f.vis, &f.sig.ident, true);
    let mut cpu = f;
    crate::cpu_semantics::rewrite_fn(&mut cpu);
    quote!(#cpu #marker const _: () = { #declared }; #body)
}

/// `#[rt_struct]`, `#[rt_payload]`, `#[rt_attributes]`.
pub fn rt_struct(attr: TokenStream, item: TokenStream, role: StructRole) -> TokenStream {
    let s: syn::ItemStruct = match syn::parse2(item.clone()) {
        Ok(s) => s,
        Err(e) => {
            if let Ok(en) = syn::parse2::<syn::ItemEnum>(item.clone()) {
                let msg = format!("`{}` is an enum: declare it with #[rt_enum]", en.ident);
                return with_errors(Error::new(en.enum_token.span, msg).into(), item);
            }
            let err = e.to_compile_error();
            return quote!(#err #item);
        }
    };
    let with_impl = match struct_args(attr) {
        Ok(w) => w,
        Err(e) => return with_errors(e.into(), item),
    };
    let decorated = decorate_struct(&s);
    let data_impl = rt_data_impl(&s, role);
    let role_kw = format_ident!("{}", role.keyword());
    let mut deps = deps::of_struct(&s);
    let mut impl_checks = TokenStream::new();
    if let Some(span) = with_impl {
        // The impl's link: its macro where the struct is (see `methods`),
        // at `impl`, so a missing block is reported there.
        let mac = syn::Ident::new(&crate::methods::macro_ident(&s.ident).to_string(), span);
        deps.push(syn::Path::from(mac));
        let name = &s.ident;
        impl_checks = quote_spanned! {span=>
            impl ::rt_std::data::__DeclaresRtImpl for #name {}
            const _: () = {
                #[allow(dead_code)]
                fn __rt_impl_block() { ::rt_std::data::__require_impl_block::<#name>(); }
            };
        };
    }
    let body = start_chain(quote!(struct #role_kw { #item }), deps);
    quote!(#decorated #data_impl #impl_checks #body)
}

/// A struct attribute's arguments: none, or `impl` (its span), which says
/// the type has an `#[rt_impl]` block.
fn struct_args(attr: TokenStream) -> Result<Option<Span>, Error> {
    let mut it = attr.clone().into_iter();
    match (it.next(), it.next()) {
        (None, _) => Ok(None),
        (Some(TokenTree::Ident(i)), None) if i == "impl" => Ok(Some(i.span())),
        _ => Err(Error::new(
            attr.span(),
            "this attribute takes no arguments, or `impl` for a type with an #[rt_impl] block",
        )),
    }
}

/// `#[rt_impl]`: the impl as the CPU compiles it, the marker that says the
/// type has one, and its link in the chain, `__rt_impl_<Type>` (what its
/// methods name, collected here; see `methods`). Its bodies are checked
/// where the struct's chain ends, which has the struct.
pub fn rt_impl(attr: TokenStream, item: TokenStream) -> TokenStream {
    let i: syn::ItemImpl = match syn::parse2(item.clone()) {
        Ok(i) => i,
        Err(_) => {
            let span = syn::parse2::<syn::Item>(item.clone()).map(|i| i.span()).unwrap_or_else(|_| Span::call_site());
            return with_errors(Error::new(span, "`#[rt_impl]` goes on an `impl` block").into(), item);
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_impl]` takes no arguments").into(), item);
    }
    let ty_ident = match &*i.self_ty {
        syn::Type::Path(p) if p.qself.is_none() && !p.path.segments.is_empty() => {
            p.path.segments.last().unwrap().ident.clone()
        }
        _ => {
            let errs = crate::methods::check_impl(&i).err().unwrap_or_default();
            return with_errors(errs, item);
        }
    };
    let mac = crate::methods::macro_ident(&ty_ident);
    let self_ty = &i.self_ty;
    let span = crate::methods::span(&i);
    let markers = quote_spanned! {span=>
        impl ::rt_std::data::__HasRtImplBlock for #self_ty {}
        const _: () = {
            #[allow(dead_code)]
            fn __rt_impl_declared() { ::rt_std::data::__require_impl_declared::<#self_ty>(); }
        };
    };
    if let Err(e) = crate::methods::check_impl(&i) {
        // Exported all the same, so the struct's chain closes and says
        // nothing more; the lowering leaves a rejected impl out.
        let errs = e.to_compile_errors();
        let export = export_macro(&mac, quote!(impl { #item }));
        return quote!(#errs #item #markers #export);
    }
    let deps = deps::of_impl(&i);
    let declared = declared_checks(&deps, &[]);
    let cpu = crate::methods::cpu_impl(&i);
    let body = start_chain(quote!(impl { #item }), deps);
    quote!(#cpu const _: () = { #declared }; #markers #body)
}

/// `#[rt_enum]`: the enum with its `RtData`, and its link in the chain
/// (an enum depends on nothing). A shape the subset rejects is an error at
/// the enum, and the enum as written.
pub fn rt_enum(attr: TokenStream, item: TokenStream) -> TokenStream {
    let e: syn::ItemEnum = match syn::parse2(item.clone()) {
        Ok(e) => e,
        Err(_) => {
            let span = syn::parse2::<syn::Item>(item.clone()).map(|i| i.span()).unwrap_or_else(|_| Span::call_site());
            return with_errors(
                Error::new(span, "`#[rt_enum]` declares an enum: use #[rt_struct] for a struct").into(),
                item,
            );
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_enum]` takes no arguments").into(), item);
    }
    // Exported even when the shape is wrong: programs that name the enum
    // then stay silent (the lowering sees it failed) rather than add
    // "cannot find macro" to the one error.
    let export = export_macro(&e.ident, quote!(enum { #item }));
    let def = match crate::enums::check(&e) {
        Ok(d) => d,
        Err(err) => {
            let errs = Errors::from(err).to_compile_errors();
            return quote!(#errs #item #export);
        }
    };
    let rust = crate::enums::rust_side(&e, &def);
    quote!(#rust #export)
}

/// `#[rt_const]`.
pub fn rt_const(attr: TokenStream, item: TokenStream) -> TokenStream {
    let c: syn::ItemConst = match syn::parse2(item.clone()) {
        Ok(c) => c,
        Err(e) => {
            let err = e.to_compile_error();
            return quote!(#err #item);
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_const]` takes no arguments").into(), item);
    }
    let deps = deps::of_const(&c);
    let declared = declared_checks(&deps, &[]);
    let marker = crate::declared::marker(&c.vis, &c.ident, false);
    let body = start_chain(quote!(constant { #item }), deps);
    quote!(#item #marker const _: () = { #declared }; #body)
}

fn with_errors(e: Errors, item: TokenStream) -> TokenStream {
    let errs = e.to_compile_errors();
    quote!(#errs #item)
}

/// The errors as one expression, of whatever type the context wants:
/// `{ compile_error!(a); compile_error!(b) }`.
fn error_expr(e: &Errors) -> TokenStream {
    let errs: Vec<TokenStream> =
        e.0.iter()
            .filter(|e| !e.is_silent())
            .map(|e| {
                let msg = &e.message;
                quote_spanned!(e.span=> ::core::compile_error!(#msg))
            })
            .collect();
    match errs.split_last() {
        Some((last, rest)) => quote!({ #(#rest;)* #last }),
        None => quote!(::core::compile_error!("rt_program failed")),
    }
}

/// Starts the chain for `entry` with dependency paths `deps`; with none, lowers
/// at once.
fn start_chain(entry: TokenStream, deps: Vec<syn::Path>) -> TokenStream {
    match deps.split_first() {
        None => finish(&entry, TokenStream::new()),
        Some((first, rest)) => chain_call(first, rest, TokenStream::new(), &entry),
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
            export_macro(&crate::methods::macro_ident(&ty), quote!(impl { #item_tokens } #done))
        }
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

/// `macro_rules! __rt_item_NAME` handing out `defs`, re-exported as `NAME`.
fn export_macro(name: &syn::Ident, defs: TokenStream) -> TokenStream {
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

fn str_slice(items: &[String]) -> TokenStream {
    quote!(&[#(#items),*])
}

/// `TypeLayout` tokens for a type.
fn layout(ty: &Ty) -> TokenStream {
    let rust = ty.rust();
    let wgsl = ty.wgsl();
    let words = ty.words();
    let mut offset = 0u32;
    let fields: Vec<TokenStream> = ty
        .fields()
        .into_iter()
        .map(|(n, t)| {
            let tr = t.rust();
            let o = offset;
            offset += t.words();
            quote!(::rt_std::program::FieldLayout { name: #n, ty: #tr, offset_words: #o })
        })
        .collect();
    quote!(::rt_std::program::TypeLayout { rust: #rust, wgsl: #wgsl, words: #words, fields: &[#(#fields),*] })
}

fn option_layout(ty: &Option<Ty>) -> TokenStream {
    match ty {
        Some(t) => {
            let l = layout(t);
            quote!(Some(#l))
        }
        None => quote!(None),
    }
}

/// `WgslItem` tokens, with the sites the lowering recorded for each (none
/// for types and resumable forms).
fn wgsl_items(items: &[(String, String)], sites: &BTreeMap<String, Vec<(Site, usize)>>) -> TokenStream {
    let items = items.iter().map(|(n, t)| {
        let s = wgsl_sites(sites.get(n).map_or(&[], Vec::as_slice));
        quote!(::rt_std::program::WgslItem { name: #n, text: #t, sites: #s })
    });
    quote!(&[#(#items),*])
}

/// `CallableSignature` tokens.
fn signature_tokens(sig: &crate::types::CallSig) -> TokenStream {
    let rust = sig.rust();
    let dispatch = sig.dispatch();
    let params: Vec<String> = sig.params.iter().map(Ty::wgsl).collect();
    let params = str_slice(&params);
    let ret = match &sig.ret {
        Ty::Unit => quote!(None),
        r => {
            let w = r.wgsl();
            quote!(Some(#w))
        }
    };
    quote!(::rt_std::program::CallableSignature { rust: #rust, dispatch: #dispatch, params: #params, ret: #ret })
}

/// `WgslSite` tokens.
fn wgsl_sites(sites: &[(Site, usize)]) -> TokenStream {
    let sites = sites.iter().map(|(s, end)| {
        let end = *end as u32;
        let name = match s {
            Site::Definition => quote!(Definition),
            Site::Trace(p) => quote!(Trace(#p)),
            Site::Call(h) => quote!(Call(#h)),
        };
        quote!(::rt_std::program::WgslSite { end: #end, name: ::rt_std::program::WgslName::#name })
    });
    quote!(&[#(#sites),*])
}

fn program_output(kind: Kind, f: &syn::ItemFn, lowered: Result<Lowered, Errors>) -> TokenStream {
    let (errors, l) = match lowered {
        Ok(l) => (TokenStream::new(), l),
        Err(e) => (e.to_compile_errors(), Lowered { name: f.sig.ident.to_string(), ..Lowered::default() }),
    };
    let variant = format_ident!("{}", kind.variant());
    let name = f.sig.ident.to_string();
    let wgsl_entry = format!("rtp_{name}");
    let wgsl = &l.wgsl;
    let prelude = &l.prelude;
    let no_sites = BTreeMap::new();
    let types = wgsl_items(&l.types, &no_sites);
    let functions = wgsl_items(&l.functions, &l.sites);
    let resumable_functions = wgsl_items(&l.resumable_functions, &no_sites);
    let program = &l.program;
    let program_sites = wgsl_sites(l.sites.get(&l.wgsl_entry).map_or(&[], Vec::as_slice));
    let resumable = match &l.resumable {
        Some(r) => quote!(Some(#r)),
        None => quote!(None),
    };
    let not_resumable = match &l.not_resumable {
        Some(why) => quote!(Some(#why)),
        None => quote!(None),
    };
    let payload = option_layout(&l.payload);
    let attributes = option_layout(&l.attributes);
    let variables = l.variables.iter().map(|(n, t)| {
        let lay = layout(t);
        let vkind = match t {
            Ty::Buffer(k, e) => {
                let el = layout(e);
                let dims = k.dims as u32;
                let w = k.writable;
                quote!(::rt_std::program::VariableKind::Buffer { element: #el, dimensions: #dims, writable: #w })
            }
            Ty::Sampler => quote!(::rt_std::program::VariableKind::Sampler),
            Ty::Sampler3d => quote!(::rt_std::program::VariableKind::Sampler3d),
            Ty::SamplerCube => quote!(::rt_std::program::VariableKind::SamplerCube),
            Ty::Object => quote!(::rt_std::program::VariableKind::Object),
            _ => quote!(::rt_std::program::VariableKind::Value),
        };
        let loader = match t {
            Ty::Buffer(..) => "rt_load_RtBuffer".to_string(),
            Ty::Sampler | Ty::SamplerCube => "rt_load_RtSampler".to_string(),
            Ty::Sampler3d => "rt_load_RtSampler3d".to_string(),
            Ty::Object => "rt_load_object".to_string(),
            other => format!("rt_load_{}", other.mangle()),
        };
        quote!(::rt_std::program::VariableDescriptor { name: #n, ty: #lay, kind: #vkind, wgsl_load: #loader })
    });
    let intrinsics = str_slice(&l.intrinsics);
    let traced = l.traced.iter().map(layout);
    let printf = l.printf.iter().map(|(id, fmt, args)| {
        let args = str_slice(args);
        quote!(::rt_std::program::PrintfFormat { id: #id, format: #fmt, args: #args })
    });
    let has_attributes = f.sig.inputs.iter().any(|i| {
        matches!(i, syn::FnArg::Typed(pt) if matches!(&*pt.ty, syn::Type::Reference(_))
            && matches!(kind, Kind::ClosestHit | Kind::AnyHit | Kind::Intersection)
            && (kind == Kind::Intersection || matches!(&*pt.ty, syn::Type::Reference(r) if r.mutability.is_none())))
    });
    let cpu_attributes = if has_attributes { quote!(Some(attributes_from_words)) } else { quote!(None) };
    let calls = l.calls.values().map(|s| signature_tokens(s));
    let callable = match &l.callable {
        Some(sig) => {
            let sig = signature_tokens(sig);
            quote!(Some(::rt_std::program::CallableDescriptor { signature: #sig, cpu: &CALLABLE }))
        }
        None => quote!(None),
    };
    let span = f.sig.ident.span();
    let file = quote_spanned!(span=> file!());
    let line = quote_spanned!(span=> line!());
    quote! {
        {
        #errors
        ::rt_std::program::ProgramDescriptor {
            kind: ::rt_std::program::ProgramKind::#variant,
            name: #name,
            wgsl_entry: #wgsl_entry,
            wgsl: #wgsl,
            wgsl_prelude: #prelude,
            wgsl_types: #types,
            wgsl_functions: #functions,
            wgsl_program: #program,
            wgsl_program_sites: #program_sites,
            wgsl_resumable: #resumable,
            wgsl_resumable_functions: #resumable_functions,
            not_resumable: #not_resumable,
            payload: #payload,
            attributes: #attributes,
            variables: &[#(#variables),*],
            intrinsics: #intrinsics,
            traced_payloads: &[#(#traced),*],
            printf: &[#(#printf),*],
            calls: &[#(#calls),*],
            callable: #callable,
            file: #file,
            line: #line,
            cpu: cpu,
            cpu_bind: cpu_bind,
            cpu_attributes: #cpu_attributes,
        }
        }
    }
}

/// In the CPU copy of an intersection program, `rt_report_intersection(m)`
/// becomes `__report_intersection(m, &*attr)`: the backend needs the
/// attributes as they are at the report, and reading them behind the
/// program's `&mut` would be unsound.
fn pass_attributes_to_reports(f: &mut syn::ItemFn, params: &[signature::Param]) {
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
fn cpu_thunk(kind: Kind, f: &syn::ItemFn, params: &[signature::Param]) -> TokenStream {
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
fn variable_tuple(items: &[TokenStream]) -> TokenStream {
    if items.len() <= 8 {
        return quote!((#(#items,)*));
    }
    let groups: Vec<TokenStream> = items.chunks(8).map(variable_tuple).collect();
    variable_tuple(&groups)
}

/// The struct with `#[repr(C)]` and the derives programs rely on.
fn decorate_struct(s: &syn::ItemStruct) -> TokenStream {
    let derived = crate::enums::derived_traits(&s.attrs);
    let wanted = ["Clone", "Copy", "Debug", "Default", "PartialEq"];
    let missing: Vec<syn::Ident> =
        wanted.iter().filter(|w| !derived.iter().any(|d| d == *w)).map(|w| format_ident!("{}", w)).collect();
    let has_repr = s.attrs.iter().any(|a| a.path().is_ident("repr"));
    let repr = if has_repr { quote!() } else { quote!(#[repr(C)]) };
    let derive = if missing.is_empty() { quote!() } else { quote!(#[derive(#(#missing),*)]) };
    quote!(#derive #repr #s)
}

/// `impl RtData` (and the role's marker trait) for a user struct.
fn rt_data_impl(s: &syn::ItemStruct, role: StructRole) -> TokenStream {
    let name = &s.ident;
    let name_str = name.to_string();
    let wgsl = lower::wgsl_ident(&name_str);
    let syn::Fields::Named(fields) = &s.fields else {
        return TokenStream::new();
    };
    let mut offset = quote!(0u32);
    let mut field_layouts = Vec::new();
    let mut writes = Vec::new();
    let mut reads = Vec::new();
    let mut reads_into = Vec::new();
    // `Attributes::set_triangle`: the built-in triangle attributes into the
    // fields of their names and types (as the runtime's layout matches
    // them), zero into the rest.
    let mut triangle_sets = Vec::new();
    for f in &fields.named {
        let ident = f.ident.as_ref().unwrap();
        let fname = ident.to_string();
        let (words, write, read, read_into, zero, tyname) = match &f.ty {
            syn::Type::Array(a) => {
                let elem = &a.elem;
                let len = &a.len;
                let words = quote!(((#len) as u32 * <#elem as ::rt_std::RtData>::LAYOUT.words));
                let write = quote! {
                    for (i, e) in self.#ident.iter().enumerate() {
                        let w = <#elem as ::rt_std::RtData>::LAYOUT.words as usize;
                        ::rt_std::RtData::write_words(e, &mut out[(#offset) as usize + i * w..]);
                    }
                };
                let read = quote! {
                    #ident: core::array::from_fn(|i| {
                        let w = <#elem as ::rt_std::RtData>::LAYOUT.words as usize;
                        <#elem as ::rt_std::RtData>::read_words(&words[(#offset) as usize + i * w..])
                    })
                };
                let read_into = quote! {
                    for (i, e) in self.#ident.iter_mut().enumerate() {
                        let w = <#elem as ::rt_std::RtData>::LAYOUT.words as usize;
                        ::rt_std::RtData::read_words_into(e, &words[(#offset) as usize + i * w..]);
                    }
                };
                let zero = quote!(self.#ident.fill(::rt_std::data::zeroed::<#elem>()););
                let tyname = signature::type_text(&f.ty);
                (words, write, read, read_into, zero, tyname)
            }
            syn::Type::Path(p)
                if p.path
                    .segments
                    .last()
                    .is_some_and(|s| crate::types::unsupported_type_advice(&s.ident.to_string()).is_some()) =>
            {
                // The lowering rejects this field and says why: leave it out of
                // the layout rather than add rustc's `RtData` errors to it.
                (
                    quote!(0u32),
                    quote!(),
                    quote!(#ident: ::core::unreachable!()),
                    quote!(::core::unreachable!();),
                    quote!(::core::unreachable!();),
                    signature::type_text(&f.ty),
                )
            }
            ty => {
                let words = quote!(<#ty as ::rt_std::RtData>::LAYOUT.words);
                let write = quote!(::rt_std::RtData::write_words(&self.#ident, &mut out[(#offset) as usize..]););
                let read = quote!(#ident: <#ty as ::rt_std::RtData>::read_words(&words[(#offset) as usize..]));
                let read_into =
                    quote!(::rt_std::RtData::read_words_into(&mut self.#ident, &words[(#offset) as usize..]););
                let zero = quote!(self.#ident = ::rt_std::data::zeroed::<#ty>(););
                (words, write, read, read_into, zero, signature::type_text(ty))
            }
        };
        field_layouts.push(quote!(::rt_std::program::FieldLayout { name: #fname, ty: #tyname, offset_words: #offset }));
        // As `rt_std::program::TriangleBuiltin::of_field` matches the
        // layout: the type as written, or a path ending in it.
        let ty_name = tyname.rsplit("::").next().unwrap_or(&tyname).trim();
        let builtin = matches!(
            (fname.as_str(), ty_name),
            ("geometric_normal" | "shading_normal", "Vec3") | ("texcoord" | "barycentrics", "Vec2")
        );
        triangle_sets.push(if builtin { quote!(self.#ident = t.#ident;) } else { zero });
        writes.push(write);
        reads.push(read);
        reads_into.push(read_into);
        offset = quote!(#offset + #words);
    }
    let marker = match role {
        StructRole::Data => quote!(),
        StructRole::Payload => quote!(impl ::rt_std::Payload for #name {}),
        StructRole::Attributes => quote! {
            impl ::rt_std::Attributes for #name {
                #[allow(unreachable_code)]
                fn set_triangle(&mut self, t: &::rt_std::cpu::TriangleBuiltins) {
                    #(#triangle_sets)*
                }
            }
        },
    };
    quote! {
        impl ::rt_std::RtData for #name {
            const LAYOUT: ::rt_std::program::TypeLayout = ::rt_std::program::TypeLayout {
                rust: #name_str,
                wgsl: #wgsl,
                words: #offset,
                fields: &[#(#field_layouts),*],
            };
            fn write_words(&self, out: &mut [u32]) {
                #(#writes)*
            }
            #[allow(unreachable_code)]
            fn read_words(words: &[u32]) -> Self {
                Self { #(#reads),* }
            }
            #[allow(unreachable_code)]
            fn read_words_into(&mut self, words: &[u32]) {
                #(#reads_into)*
            }
        }
        #marker
    }
}
