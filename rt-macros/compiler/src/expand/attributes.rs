//! What each `rt_*` attribute expands to: `#[rt_program]`,
//! `#[rt_function]`, `#[rt_struct]` (and `#[rt_payload]`,
//! `#[rt_attributes]`), `#[rt_impl]`, `#[rt_enum]` and `#[rt_const]`. Each
//! parses its item and arguments, emits the item as the CPU compiles it
//! with the checks rustc runs for it, and starts the item's chain (see
//! `chain.rs`); an item that does not parse, or a wrong argument, is the
//! item as written with the error beside it.

use super::chain::{export_macro, start_chain, start_chain_with};
use super::data::{decorate_struct, near_triangle_builtins, rt_data_impl};
use super::parse_kind;
use super::thunk::{cpu_thunk, pass_attributes_to_reports};
use crate::declared::{declared_checks, reroot};
use crate::error::{Error, Errors};
use crate::kinds::Kind;
use crate::plain_consts::{self, Owner};
use crate::signature;
use crate::{StructRole, deps};
use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote, quote_spanned};
use syn::spanned::Spanned;

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
    let (consts, deps) = plain_consts::take(Owner::Named(&name.to_string()), deps::of_fn(&f));
    let deps: Vec<deps::Dep> = deps.into_iter().map(|d| deps::Dep { path: reroot(&d.path), ..d }).collect();
    let declared = declared_checks(&deps, &params);
    let body = start_chain_with(entry, deps::paths(&deps), consts);
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
    let (consts, deps) = plain_consts::take(Owner::Named(&f.sig.ident.to_string()), deps::of_fn(&f));
    let declared = declared_checks(&deps, &[]);
    let body = start_chain_with(quote!(function { #item }), deps::paths(&deps), consts);
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
    let (with_impl, trait_impls) = match struct_args(attr) {
        Ok(w) => w,
        Err(e) => return with_errors(e.into(), item),
    };
    if let Err(errs) = crate::lower::generic_structs::check_shape(&s, role) {
        // Refused here, once: the struct as written, and its link, so that
        // programs that name it say nothing more.
        let errs = errs.to_compile_errors();
        let export = export_macro(&s.ident, quote!(struct data { #item }));
        return quote!(#errs #item #export);
    }
    // A near miss of a built-in is reported beside the struct's expansion,
    // which goes on (its programs compile as they are).
    let near = if role == StructRole::Attributes { near_triangle_builtins(&s).to_compile_errors() } else { quote!() };
    let decorated = decorate_struct(&s);
    let data_impl = rt_data_impl(&s, role);
    let role_kw = format_ident!("{}", role.keyword());
    let mut deps = deps::of_struct(&s);
    let (links, impl_checks) = impl_links(&s.ident, &s.generics, with_impl, &trait_impls);
    deps.extend(links);
    let body = start_chain(quote!(struct #role_kw { #item }), deps::paths(&deps));
    quote!(#near #decorated #data_impl #impl_checks #body)
}

/// A struct attribute's arguments: none, or a list of `impl` (its span),
/// which says the type has an inherent `#[rt_impl]` block, and `impl
/// Trait`, which says it has an `#[rt_impl]` of the `#[rt_trait]` or
/// operator trait `Trait` (`impl Mul<f32>`).
fn struct_args(attr: TokenStream) -> Result<(Option<Span>, Vec<syn::Path>), Error> {
    let wrong = || {
        Error::new(
            attr.span(),
            "this attribute takes no arguments, or `impl` for a type with an #[rt_impl] block and \
             `impl Trait` for each #[rt_impl] of an #[rt_trait] or operator trait (as in `impl, impl Bsdf, \
             impl Mul<f32>`)",
        )
    };
    let mut inherent = None;
    let mut traits = Vec::new();
    let parser = |input: syn::parse::ParseStream| -> syn::Result<()> {
        while !input.is_empty() {
            let kw: syn::Token![impl] = input.parse()?;
            if input.is_empty() || input.peek(syn::Token![,]) {
                inherent = Some(kw.span);
            } else {
                traits.push(input.parse::<syn::Path>()?);
            }
            if !input.is_empty() {
                input.parse::<syn::Token![,]>()?;
            }
        }
        Ok(())
    };
    syn::parse::Parser::parse2(parser, attr.clone()).map_err(|_| wrong())?;
    Ok((inherent, traits))
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
    let mac = crate::methods::impl_macro_ident_of(&i, &ty_ident);
    let self_ty = &i.self_ty;
    let span = crate::methods::span(&i);
    // The inherent block's markers (a type has one; its trait impls are
    // found by their links, see `traits`).
    // A generic impl's (`impl<T: Copy> Pair<T>`) are generic over its
    // parameters, without its bounds: the struct asks them of every
    // instance (its parameters have none).
    let mut unbounded = i.generics.clone();
    unbounded.where_clause = None;
    for p in unbounded.type_params_mut() {
        p.colon_token = None;
        p.bounds.clear();
    }
    let (impl_generics, _, where_clause) = unbounded.split_for_impl();
    let markers = if i.trait_.is_some() {
        TokenStream::new()
    } else {
        quote_spanned! {span=>
            impl #impl_generics ::rt_std::data::__HasRtImplBlock for #self_ty #where_clause {}
            const _: () = {
                #[allow(dead_code)]
                fn __rt_impl_declared #impl_generics () #where_clause {
                    ::rt_std::data::__require_impl_declared::<#self_ty>();
                }
            };
        }
    };
    if let Err(e) = crate::methods::check_impl(&i) {
        // Exported all the same, so the struct's chain closes and says
        // nothing more; the lowering leaves a rejected impl out.
        let errs = e.to_compile_errors();
        let export = export_macro(&mac, quote!(impl { #item }));
        return quote!(#errs #item #markers #export);
    }
    let self_name = crate::methods::self_name(&i).unwrap_or_default();
    let (consts, deps) = plain_consts::take(Owner::Impl(&self_name), deps::of_impl(&i));
    let declared = declared_checks(&deps, &[]);
    let cpu = crate::methods::cpu_impl(&i);
    let glue = crate::operators::cpu_glue(&i);
    let body = start_chain_with(quote!(impl { #item }), deps::paths(&deps), consts);
    quote!(#cpu #glue const _: () = { #declared }; #markers #body)
}

/// `#[rt_trait]`: the trait as the CPU compiles it (its default bodies
/// rewritten to the GPU's integer semantics) and its link, `Trait!`, which
/// hands out its tokens to the impls (see `traits`). A shape the subset
/// rejects is an error at the part at fault, beside the trait as written.
pub fn rt_trait(attr: TokenStream, item: TokenStream) -> TokenStream {
    let t: syn::ItemTrait = match syn::parse2(item.clone()) {
        Ok(t) => t,
        Err(_) => {
            let span = syn::parse2::<syn::Item>(item.clone()).map(|i| i.span()).unwrap_or_else(|_| Span::call_site());
            return with_errors(Error::new(span, "`#[rt_trait]` goes on a trait declaration").into(), item);
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_trait]` takes no arguments").into(), item);
    }
    if let Err(e) = crate::traits::check_trait(&t) {
        // Exported all the same, so its impls' chains close and say
        // nothing more.
        let errs = e.to_compile_errors();
        let export = export_macro(&t.ident, quote!(trait { #item }));
        return quote!(#errs #item #export);
    }
    let deps = deps::of_trait(&t);
    let declared = declared_checks(&deps, &[]);
    let mut cpu = t.clone();
    for it in cpu.items.iter_mut() {
        if let syn::TraitItem::Fn(m) = it
            && let Some(block) = &m.default
        {
            let mut f = syn::ItemFn {
                attrs: std::mem::take(&mut m.attrs),
                vis: syn::Visibility::Inherited,
                sig: m.sig.clone(),
                block: Box::new(block.clone()),
            };
            crate::cpu_semantics::rewrite_fn(&mut f);
            m.attrs = f.attrs;
            m.default = Some(*f.block);
        }
    }
    let body = start_chain(quote!(trait { #item }), deps::paths(&deps));
    quote!(#cpu const _: () = { #declared }; #body)
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
    let (with_impl, trait_impls) = match struct_args(attr) {
        Ok(w) => w,
        Err(e) => return with_errors(e.into(), item),
    };
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
    let (deps, impl_checks) = impl_links(&e.ident, &e.generics, with_impl, &trait_impls);
    if deps.is_empty() {
        return quote!(#rust #export);
    }
    // With `#[rt_impl]` blocks, a chain like a struct's that carries them.
    let body = start_chain(quote!(enum { #item }), deps::paths(&deps));
    quote!(#rust #impl_checks #body)
}

/// The links of a type's `#[rt_impl]` blocks, as its attribute lists them
/// (`impl` at `with_impl`, `impl Trait` for each of `trait_impls`), and
/// the checks that the inherent block and its declaration go together.
fn impl_links(
    name: &syn::Ident,
    generics: &syn::Generics,
    with_impl: Option<Span>,
    trait_impls: &[syn::Path],
) -> (Vec<deps::Dep>, TokenStream) {
    // A generic struct's checks are generic over its parameters.
    let (impl_generics, ty_generics, where_clause) = generics.split_for_impl();
    let mut deps = Vec::new();
    let mut impl_checks = TokenStream::new();
    if let Some(span) = with_impl {
        // The impl's link: its macro where the type is (see `methods`),
        // at `impl`, so a missing block is reported there.
        let mac = syn::Ident::new(&crate::methods::macro_ident(name).to_string(), span);
        deps.push(deps::Dep { path: syn::Path::from(mac), kind: deps::DepKind::Type });
        impl_checks = quote_spanned! {span=>
            impl #impl_generics ::rt_std::data::__DeclaresRtImpl for #name #ty_generics #where_clause {}
            const _: () = {
                #[allow(dead_code)]
                fn __rt_impl_block #impl_generics () #where_clause {
                    ::rt_std::data::__require_impl_block::<#name #ty_generics>();
                }
            };
        };
    }
    for t in trait_impls {
        // Each trait impl's link (see `traits`, `operators`), at the
        // trait's name.
        let span = t.segments.last().map(|s| s.ident.span()).unwrap_or_else(|| t.span());
        let mac = crate::operators::link_ident(&syn::Ident::new(&name.to_string(), span), t);
        deps.push(deps::Dep { path: syn::Path::from(mac), kind: deps::DepKind::Type });
    }
    (deps, impl_checks)
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
    let (consts, deps) = plain_consts::take(Owner::Named(&c.ident.to_string()), deps::of_const(&c));
    let declared = declared_checks(&deps, &[]);
    let marker = crate::declared::marker(&c.vis, &c.ident, false);
    let body = start_chain_with(quote!(constant { #item }), deps::paths(&deps), consts);
    quote!(#item #marker const _: () = { #declared }; #body)
}

/// `#[rt_type]`: the alias as the CPU compiles it, a default for each of
/// its type parameters (so that the checks of the items that name it may
/// name it bare, as a generic struct's do), the function its uses look
/// for (see `declared`), and its link.
pub fn rt_type(attr: TokenStream, item: TokenStream) -> TokenStream {
    let t: syn::ItemType = match syn::parse2(item.clone()) {
        Ok(t) => t,
        Err(_) => {
            let span = syn::parse2::<syn::Item>(item.clone()).map(|i| i.span()).unwrap_or_else(|_| Span::call_site());
            let msg = "`#[rt_type]` goes on a type alias (`type Brdf = Vec3;`)";
            return with_errors(Error::new(span, msg).into(), item);
        }
    };
    if !attr.is_empty() {
        return with_errors(Error::new(attr.span(), "`#[rt_type]` takes no arguments").into(), item);
    }
    let marker = crate::declared::alias_marker(&t.vis, &t.ident);
    if let Err(e) = crate::aliases::check(&t) {
        // Exported all the same, so the items that name it say nothing
        // more.
        let errs = Errors::from(e).to_compile_errors();
        let export = export_macro(&t.ident, quote!(alias { #item }));
        return quote!(#errs #item #marker #export);
    }
    let deps = deps::of_alias(&t);
    let declared = declared_checks(&deps, &[]);
    let mut cpu = t.clone();
    for p in cpu.generics.type_params_mut() {
        if p.default.is_none() {
            p.eq_token = Some(Default::default());
            p.default = Some(syn::parse_quote!(::rt_std::data::__RtAnyType));
        }
    }
    let body = start_chain(quote!(alias { #item }), deps::paths(&deps));
    quote!(#cpu #marker const _: () = { #declared }; #body)
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
