//! `#[rt_enum]`: C-like enums. In WGSL an enum is a `u32` holding the
//! variant's discriminant (one heap word); in Rust it stays the user's enum,
//! `#[repr(u32)]`, with `RtData` reading and writing that word. This file
//! checks an enum's shape once (the macro and the lowering both ask it) and
//! emits its Rust side; the lowering's use of the values is in
//! `lower/func/expr.rs` (paths), `ops.rs` (`==`, `as`) and `control.rs`
//! (`match`).

use crate::error::{Error, Result};
use crate::types::EnumDef;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::spanned::Spanned;

/// Checks that `e` is an enum the subset has a meaning for: unit variants
/// only, discriminants that are `u32` literals and distinct, `#[repr(u32)]`
/// or no `repr`, no generics. Returns its definition.
pub fn check(e: &syn::ItemEnum) -> Result<EnumDef> {
    if !e.generics.params.is_empty() {
        return Err(Error::unsupported(
            e.generics.span(),
            "a generic enum",
            "list the variants without type parameters",
        ));
    }
    for a in &e.attrs {
        if a.path().is_ident("repr") {
            let mut ok = true;
            let _ = a.parse_nested_meta(|m| {
                ok &= m.path.is_ident("u32");
                Ok(())
            });
            if !ok {
                let span = match &a.meta {
                    syn::Meta::List(l) => l.tokens.span(),
                    m => m.span(),
                };
                return Err(Error::unsupported(
                    span,
                    "this `repr` on an `#[rt_enum]`",
                    "an enum is a `u32` in WGSL; write `#[repr(u32)]` or leave the `repr` out",
                ));
            }
        }
    }
    if e.variants.is_empty() {
        return Err(Error::unsupported(e.ident.span(), "an enum without variants", "give it at least one variant"));
    }
    let mut variants: Vec<(String, u32)> = Vec::new();
    let mut next: u64 = 0;
    for v in &e.variants {
        if !matches!(v.fields, syn::Fields::Unit) {
            return Err(Error::new(
                v.fields.span(),
                format!(
                    "an enum variant with fields (`{}::{}`) is not supported in ray programs: WGSL has no sum types; \
                     use a C-like `#[rt_enum]` for the kind and a `#[rt_struct]` with a `kind` field and the fields \
                     of every variant",
                    e.ident, v.ident
                ),
            ));
        }
        let value = match &v.discriminant {
            None => next,
            Some((_, syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }))) => {
                if !matches!(i.suffix(), "" | "u32") {
                    return Err(Error::new(i.span(), "an `#[rt_enum]` discriminant is a `u32`: drop the suffix"));
                }
                i.base10_parse::<u64>()?
            }
            Some((_, other)) => {
                return Err(Error::unsupported(
                    other.span(),
                    "a computed discriminant",
                    "write the discriminant as a `u32` literal",
                ));
            }
        };
        if value > u32::MAX as u64 {
            return Err(Error::new(v.span(), format!("the discriminant of `{}` does not fit in a `u32`", v.ident)));
        }
        if let Some((other, _)) = variants.iter().find(|(_, d)| *d as u64 == value) {
            return Err(Error::new(
                v.span(),
                format!("`{}` has the discriminant {value}, as `{other}` has: each variant needs its own", v.ident),
            ));
        }
        variants.push((v.ident.to_string(), value as u32));
        next = value + 1;
    }
    Ok(EnumDef { name: e.ident.to_string(), variants, span: e.ident.span() })
}

/// The enum with `#[repr(u32)]` and the derives programs rely on, its
/// `Default` (the first variant, unless the user derives it) and `RtData`
/// (the discriminant as one word; a word that is no variant's reads as the
/// first variant, as the CPU backend must give some value where the GPU
/// would hold that word).
pub fn rust_side(e: &syn::ItemEnum, def: &EnumDef) -> TokenStream {
    let derived = derived_traits(&e.attrs);
    let wanted = ["Clone", "Copy", "Debug", "PartialEq", "Eq"];
    let missing: Vec<syn::Ident> =
        wanted.iter().filter(|w| !derived.iter().any(|d| d == *w)).map(|w| format_ident!("{}", w)).collect();
    let derive = if missing.is_empty() { quote!() } else { quote!(#[derive(#(#missing),*)]) };
    let repr = if e.attrs.iter().any(|a| a.path().is_ident("repr")) { quote!() } else { quote!(#[repr(u32)]) };
    let name = &e.ident;
    let name_str = name.to_string();
    let first = format_ident!("{}", def.variants[0].0);
    let default = if derived.iter().any(|d| d == "Default") {
        quote!()
    } else {
        quote! {
            impl ::core::default::Default for #name {
                fn default() -> Self {
                    Self::#first
                }
            }
        }
    };
    let arms = def.variants.iter().map(|(v, d)| {
        let v = format_ident!("{}", v);
        quote!(#d => Self::#v,)
    });
    quote! {
        #derive
        #repr
        #e
        #default
        impl ::rt_std::data::DeclaredByAttribute for #name {}
        impl ::rt_std::RtData for #name {
            const LAYOUT: ::rt_std::program::TypeLayout =
                ::rt_std::program::TypeLayout {
                    kind: ::rt_std::program::LayoutKind::Enum,
                    rust: #name_str,
                    wgsl: "u32",
                    words: 1,
                    fields: &[],
                };
            #[inline]
            fn write_words(&self, out: &mut [u32]) {
                out[0] = *self as u32;
            }
            #[inline]
            fn read_words(words: &[u32]) -> Self {
                match words[0] {
                    #(#arms)*
                    _ => Self::#first,
                }
            }
        }
    }
}

/// The traits an item's `#[derive]`s name (last path segments).
pub(crate) fn derived_traits(attrs: &[syn::Attribute]) -> Vec<String> {
    let mut derived: Vec<String> = Vec::new();
    for a in attrs {
        if a.path().is_ident("derive") {
            let _ = a.parse_nested_meta(|m| {
                if let Some(seg) = m.path.segments.last() {
                    derived.push(seg.ident.to_string());
                }
                Ok(())
            });
        }
    }
    derived
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checked(src: &str) -> std::result::Result<Vec<(String, u32)>, String> {
        let e: syn::ItemEnum = syn::parse_str(src).unwrap();
        check(&e).map(|d| d.variants).map_err(|e| e.message)
    }

    #[test]
    fn discriminants_count_on_from_the_last_given() {
        let v = checked("#[repr(u32)] enum K { A, B = 5, C }").unwrap();
        assert_eq!(v, vec![("A".into(), 0), ("B".into(), 5), ("C".into(), 6)]);
    }

    #[test]
    fn shapes_without_a_wgsl_meaning_are_errors_that_say_what_to_use() {
        assert!(checked("enum K { A(f32), B }").unwrap_err().contains("use a C-like `#[rt_enum]`"));
        assert!(checked("enum K { A { x: f32 } }").unwrap_err().contains("`K::A`"));
        assert!(checked("#[repr(u8)] enum K { A }").unwrap_err().contains("#[repr(u32)]"));
        assert!(checked("enum K { A = 1, B = 1 }").unwrap_err().contains("as `A` has"));
        assert!(checked("enum K {}").unwrap_err().contains("at least one variant"));
        assert!(checked("enum K { A = 1 + 1 }").unwrap_err().contains("`u32` literal"));
    }
}
