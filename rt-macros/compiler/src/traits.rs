//! `#[rt_trait]`: traits with static dispatch.
//!
//! ## What a trait is to ray programs
//! WGSL has no traits and no function pointers, so every call of a trait
//! method is resolved where it is lowered, by the receiver's type, as an
//! inherent method is (`methods`): `x.eval(wi)` with `x: Lambert` calls
//! `rtm_Lambert__eval`. A generic helper bounded by a trait (`fn shade<B:
//! Bsdf>(b: B, ..)`) is instantiated per type (`lower/generics.rs`), so
//! its body's `b.eval(..)` is again a call on a known type. `dyn Trait` has
//! no static type and is refused, pointing at `Callable` ids, the
//! project's dynamic dispatch.
//!
//! ## How the pieces reach a program
//! - `#[rt_trait] trait Bsdf { .. }` keeps the trait for the CPU and
//!   exports a link named like the trait (`Bsdf!`, macros and traits live
//!   in different namespaces) that hands out the trait's tokens: its
//!   default methods and constants are lowered per impl that does not
//!   override them.
//! - `#[rt_impl] impl Bsdf for Lambert { .. }` exports the link
//!   `__rt_impl_Lambert__Bsdf` ([`impl_macro_ident`]) with the impl, the
//!   trait and what both name; `#[rt_struct(impl Bsdf)]` (with `impl` for
//!   an inherent block too: `#[rt_struct(impl, impl Bsdf)]`) puts it among
//!   the struct's links, as `(impl)` does for the inherent block, so the
//!   struct hands out its trait impls wherever it is used.
//! - The lowering completes each trait impl with the trait's defaults it
//!   does not override ([`complete`]) and then lowers it as any
//!   `#[rt_impl]`: its methods are helpers `rtm_<Type>__<name>`, its
//!   constants `<Type>__<NAME>`. Two impls of one type that both define a
//!   name are refused (a call could not say which).
//! - A generic struct's impl (`impl<T: Copy> Scale for Pair<T>`) is
//!   generic over the struct's parameters, as its inherent block is: each
//!   method is instantiated per instance of the receiver
//!   (`rtm_Pair__scaled__f32`). A blanket impl (`impl<T> Scale for T`) is
//!   refused: the lowering finds an impl by the type's name.
//!
//! Operator traits of std (`Add`, `Neg`, ...) are not `#[rt_trait]`s:
//! their impls lower to the operators (`crate::operators`). Other std
//! traits' impls are refused with what to write instead.

use crate::error::{Error, Errors};
use syn::spanned::Spanned;

/// The traits of std and glam that are not `#[rt_trait]`s, by name: an
/// `#[rt_impl]` implements the operators among them (`crate::operators`)
/// and none of the others, whose conversions do not call user code in
/// WGSL.
const STD_TRAITS: &[&str] = &[
    "Add",
    "Sub",
    "Mul",
    "Div",
    "Rem",
    "Neg",
    "Not",
    "BitAnd",
    "BitOr",
    "BitXor",
    "Shl",
    "Shr",
    "AddAssign",
    "SubAssign",
    "MulAssign",
    "DivAssign",
    "RemAssign",
    "Index",
    "IndexMut",
    "Default",
    "Clone",
    "Copy",
    "PartialEq",
    "Eq",
    "PartialOrd",
    "Ord",
    "Hash",
    "Debug",
    "Display",
    "From",
    "Into",
    "Drop",
    "Deref",
    "DerefMut",
    "Iterator",
];

/// Whether an impl's trait is one of std's (or glam's), which ray
/// programs do not implement.
pub fn is_std_trait(path: &syn::Path) -> bool {
    let first = path.segments.first().map(|s| s.ident.to_string()).unwrap_or_default();
    let last = path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
    matches!(first.as_str(), "std" | "core" | "glam" | "alloc")
        || STD_TRAITS.contains(&last.as_str())
        || crate::operators::operator(path).is_some()
}

/// The name of the `#[rt_trait]` an impl implements, if it implements
/// one. An impl of a std trait, which `#[rt_impl]` refuses, is taken for
/// the type's inherent block (its link and markers), so that the refusal
/// is the one error.
pub fn trait_name(i: &syn::ItemImpl) -> Option<String> {
    i.trait_
        .as_ref()
        .filter(|(_, p, _)| !is_std_trait(p))
        .and_then(|(_, p, _)| p.segments.last())
        .map(|s| s.ident.to_string())
}

/// The link `#[rt_impl] impl Trait for Type` exports, which
/// `#[rt_struct(impl Trait)]` collects: `__rt_impl_Type__Trait`.
pub fn impl_macro_ident(ty: &syn::Ident, trait_name: &syn::Ident) -> syn::Ident {
    syn::Ident::new(&format!("__rt_impl_{ty}__{trait_name}"), ty.span())
}

/// Rejects trait declarations the subset has no meaning for, at the part
/// at fault. Default bodies are checked in each impl that uses them.
pub fn check_trait(t: &syn::ItemTrait) -> Result<(), Errors> {
    let mut errors = Errors::default();
    if !t.generics.params.is_empty() {
        errors.push(Error::unsupported(
            t.generics.span(),
            "a generic trait",
            "declare the trait without parameters; make its methods' callers generic instead",
        ));
    }
    if let Some(u) = &t.unsafety {
        errors.push(Error::unsupported(u.span(), "an `unsafe trait`", "ray programs are safe code"));
    }
    if let Some(a) = &t.auto_token {
        errors.push(Error::unsupported(a.span(), "an `auto trait`", "declare a plain trait"));
    }
    for item in &t.items {
        match item {
            syn::TraitItem::Fn(f) => {
                if !f.sig.generics.params.is_empty() {
                    errors.push(Error::unsupported(
                        f.sig.generics.span(),
                        "a generic trait method",
                        "write one method per type, or a generic #[rt_function]",
                    ));
                }
                if let Some(a) = &f.sig.asyncness {
                    errors.push(Error::unsupported(a.span(), "an `async` method", "ray programs are synchronous"));
                }
            }
            syn::TraitItem::Const(c) => {
                if !c.generics.params.is_empty() {
                    errors.push(Error::unsupported(c.generics.span(), "a generic constant", "use a concrete type"));
                }
            }
            syn::TraitItem::Type(ty) => errors.push(Error::unsupported(
                ty.span(),
                "an associated type",
                "name the type itself in the trait's methods",
            )),
            other => errors.push(Error::unsupported(
                other.span(),
                "this item in an #[rt_trait]",
                "declare methods (with or without a default body) and associated constants",
            )),
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

/// The impl with the trait's default methods and constants it does not
/// define copied in (their `Self` is the impl's type once the impl is
/// lowered, see `methods::lowerable`). A method or constant the trait
/// declares without a default and the impl leaves out is rustc's error; it
/// is left out here.
pub fn complete(i: &syn::ItemImpl, t: &syn::ItemTrait) -> syn::ItemImpl {
    let mut i = i.clone();
    let defined: Vec<String> = i
        .items
        .iter()
        .filter_map(|it| match it {
            syn::ImplItem::Fn(f) => Some(f.sig.ident.to_string()),
            syn::ImplItem::Const(c) => Some(c.ident.to_string()),
            _ => None,
        })
        .collect();
    for item in &t.items {
        match item {
            syn::TraitItem::Fn(f) if !defined.contains(&f.sig.ident.to_string()) => {
                if let Some(block) = &f.default {
                    i.items.push(syn::ImplItem::Fn(syn::ImplItemFn {
                        attrs: Vec::new(),
                        vis: syn::Visibility::Inherited,
                        defaultness: None,
                        sig: f.sig.clone(),
                        block: block.clone(),
                    }));
                }
            }
            // A generic impl has only constants that name neither its
            // parameters nor `Self` (a WGSL constant has one type,
            // `methods::check_impl`): another default stays the CPU's.
            syn::TraitItem::Const(c) if !defined.contains(&c.ident.to_string()) => {
                if let Some((eq, expr)) = &c.default
                    && (i.generics.params.is_empty() || !const_names_params(&c.ty, expr, &i.generics))
                {
                    i.items.push(syn::ImplItem::Const(syn::ImplItemConst {
                        attrs: Vec::new(),
                        vis: syn::Visibility::Inherited,
                        defaultness: None,
                        const_token: c.const_token,
                        ident: c.ident.clone(),
                        generics: c.generics.clone(),
                        colon_token: c.colon_token,
                        ty: c.ty.clone(),
                        eq_token: *eq,
                        expr: expr.clone(),
                        semi_token: c.semi_token,
                    }));
                }
            }
            _ => {}
        }
    }
    i
}

/// Whether a constant's type or value names one of `generics`' type
/// parameters, or `Self` (one WGSL constant serves every instance of a
/// generic impl only where neither does).
pub fn const_names_params(ty: &syn::Type, expr: &syn::Expr, generics: &syn::Generics) -> bool {
    let named = |i: &proc_macro2::Ident| *i == "Self" || generics.type_params().any(|t| *i == t.ident);
    crate::lower::generics::names_any(quote::quote!(#ty), &named)
        || crate::lower::generics::names_any(quote::quote!(#expr), &named)
}
