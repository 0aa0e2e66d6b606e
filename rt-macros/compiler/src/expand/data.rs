//! A struct's Rust side: the struct with `#[repr(C)]` and the derives
//! programs rely on, its `RtData` impl (the heap layout, and the words
//! written and read field by field) and its role's marker trait
//! (`Payload`, or `Attributes` with `set_triangle`).

use crate::StructRole;
use crate::lower;
use crate::signature;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The struct with `#[repr(C)]` and the derives programs rely on.
pub(super) fn decorate_struct(s: &syn::ItemStruct) -> TokenStream {
    let derived = crate::enums::derived_traits(&s.attrs);
    let wanted = ["Clone", "Copy", "Debug", "Default", "PartialEq"];
    let missing: Vec<syn::Ident> =
        wanted.iter().filter(|w| !derived.iter().any(|d| d == *w)).map(|w| format_ident!("{}", w)).collect();
    let has_repr = s.attrs.iter().any(|a| a.path().is_ident("repr"));
    let repr = if has_repr { quote!() } else { quote!(#[repr(C)]) };
    let derive = if missing.is_empty() { quote!() } else { quote!(#[derive(#(#missing),*)]) };
    // A generic struct's parameters default to a hidden type, so that the
    // checks that name the types a program uses (`crate::declared`) may
    // name it without arguments, as the program may.
    let mut s = s.clone();
    for p in s.generics.type_params_mut() {
        if p.default.is_none() {
            p.eq_token = Some(Default::default());
            p.default = Some(syn::parse_quote!(::rt_std::data::__RtAnyType));
        }
    }
    quote!(#derive #repr #s)
}

/// `impl RtData` (and the role's marker trait) for a user struct.
pub(super) fn rt_data_impl(s: &syn::ItemStruct, role: StructRole) -> TokenStream {
    let name = &s.ident;
    let name_str = name.to_string();
    let wgsl = lower::wgsl_ident(&name_str);
    if matches!(s.fields, syn::Fields::Unit) {
        return TokenStream::new();
    }
    if !s.generics.params.is_empty() {
        // An instance's layout depends on its arguments, and a `TypeLayout`
        // is a constant of one spelling: a generic struct has no host layout
        // (`lower::generic_structs`), only the mark of its attribute.
        //
        // Its `RtData` impl exists only so that rustc does not add its own
        // "mark it with #[rt_struct]" to the lowering's error where an
        // instance is used as host data (a buffer element): the layout is a
        // constant that fails to evaluate, so host code that reads or writes
        // an instance fails to build with this message, and a program that
        // uses one stops at the lowering's error first.
        let (impl_generics, ty_generics, where_clause) = s.generics.split_for_impl();
        let mut copy_generics = s.generics.clone();
        for p in copy_generics.type_params_mut() {
            p.bounds.push(syn::parse_quote!(::core::marker::Copy));
            p.bounds.push(syn::parse_quote!('static));
            p.eq_token = None;
            p.default = None;
        }
        let (copy_impl_generics, _, _) = copy_generics.split_for_impl();
        let msg = format!(
            "`{name_str}` is a generic struct: an instance has no host layout, so the host cannot read or write one \
             (a buffer element, a variable); declare a struct with concrete fields for it"
        );
        return quote! {
            impl #impl_generics ::rt_std::data::DeclaredByAttribute for #name #ty_generics #where_clause {}
            impl #copy_impl_generics ::rt_std::RtData for #name #ty_generics #where_clause {
                const LAYOUT: ::rt_std::program::TypeLayout = ::core::panic!(#msg);
                fn write_words(&self, _: &mut [u32]) {
                    let _ = <Self as ::rt_std::RtData>::LAYOUT;
                }
                fn read_words(_: &[u32]) -> Self {
                    let _ = <Self as ::rt_std::RtData>::LAYOUT;
                    ::core::unreachable!()
                }
            }
        };
    }
    let mut offset = quote!(0u32);
    let mut field_layouts = Vec::new();
    let mut writes = Vec::new();
    let mut reads = Vec::new();
    let mut reads_into = Vec::new();
    // `Attributes::set_triangle`: the built-in triangle attributes into the
    // fields of their names and types (as the runtime's layout matches
    // them), zero into the rest.
    let mut triangle_sets = Vec::new();
    for (i, f) in s.fields.iter().enumerate() {
        // A tuple struct's fields are `0`, `1`, ...: `self.0`, `Self { 0: .. }`.
        let ident = match &f.ident {
            Some(id) => syn::Member::Named(id.clone()),
            None => syn::Member::Unnamed(syn::Index::from(i)),
        };
        let ident = &ident;
        let fname = f.ident.as_ref().map_or_else(|| i.to_string(), |id| id.to_string());
        let tyname = signature::type_text(&f.ty);
        let FieldCode { words, kind, write, read, read_into, zero } = field_code(ident, &f.ty, &offset);
        field_layouts.push(
            quote!(::rt_std::program::FieldLayout { name: #fname, ty: #tyname, kind: #kind, offset_words: #offset }),
        );
        triangle_sets.push(if is_triangle_builtin(&fname, &tyname) { quote!(self.#ident = t.#ident;) } else { zero });
        writes.push(write);
        reads.push(read);
        reads_into.push(read_into);
        offset = quote!(#offset + #words);
    }
    let marker = role_marker(role, name, &triangle_sets);
    quote! {
        impl ::rt_std::RtData for #name {
            const LAYOUT: ::rt_std::program::TypeLayout = ::rt_std::program::TypeLayout {
                kind: ::rt_std::program::LayoutKind::Struct,
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
        impl ::rt_std::data::DeclaredByAttribute for #name {}
        #marker
    }
}

/// One field's part of its struct's `RtData` impl, the field at `offset`
/// words (an expression over the fields before it).
struct FieldCode {
    /// The field's size in words (an expression).
    words: TokenStream,
    /// The field's `LayoutKind` (an expression).
    kind: TokenStream,
    /// `write_words`'s statement for the field.
    write: TokenStream,
    /// `read_words`'s `field: value`.
    read: TokenStream,
    /// `read_words_into`'s statement for the field.
    read_into: TokenStream,
    /// The statement that zeroes the field (`set_triangle`'s for a field
    /// that is not a triangle builtin).
    zero: TokenStream,
}

/// The code of the field `ident: ty` at `offset`: an array element by
/// element, a type the lowering rejects left out, any other through its
/// own `RtData`.
fn field_code(ident: &syn::Member, ty: &syn::Type, offset: &TokenStream) -> FieldCode {
    match ty {
        syn::Type::Array(a) => array_field(ident, a, offset),
        syn::Type::Path(p)
            if p.path.segments.last().is_some_and(|s| {
                let name = s.ident.to_string();
                crate::types::unsupported_type_advice(&name).is_some() || name == "Option" || names_generic_struct(s)
            }) =>
        {
            rejected_field(ident)
        }
        ty => plain_field(ident, ty, offset),
    }
}

/// Whether a field's type names a generic struct's instance (`Pair<f32>`):
/// a user type with arguments, which has no layout
/// (`lower::generic_structs`; the lowering says so).
fn names_generic_struct(s: &syn::PathSegment) -> bool {
    let name = s.ident.to_string();
    !s.arguments.is_none()
        && name != "Callable"
        && name != crate::types::BINDLESS_SAMPLER
        && crate::types::bindless_kind(&name).is_none()
        && crate::types::buffer_kind(&name).is_none()
}

/// An array field, element by element through the element's `RtData`.
fn array_field(ident: &syn::Member, a: &syn::TypeArray, offset: &TokenStream) -> FieldCode {
    let elem = &a.elem;
    let len = &a.len;
    let words = quote!(((#len) as u32 * <#elem as ::rt_std::RtData>::LAYOUT.words));
    let kind = quote!(::rt_std::program::LayoutKind::Array((#len) as u32));
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
    FieldCode { words, kind, write, read, read_into, zero }
}

/// A field of a type the subset rejects: the lowering rejects it and says
/// why, so it is left out of the layout rather than add rustc's `RtData`
/// errors to that.
fn rejected_field(ident: &syn::Member) -> FieldCode {
    FieldCode {
        words: quote!(0u32),
        kind: quote!(::rt_std::program::LayoutKind::Unit),
        write: quote!(),
        read: quote!(#ident: ::core::unreachable!()),
        read_into: quote!(::core::unreachable!();),
        zero: quote!(::core::unreachable!();),
    }
}

/// Any other field, through its type's own `RtData`.
fn plain_field(ident: &syn::Member, ty: &syn::Type, offset: &TokenStream) -> FieldCode {
    let words = quote!(<#ty as ::rt_std::RtData>::LAYOUT.words);
    let kind = quote!(<#ty as ::rt_std::RtData>::LAYOUT.kind);
    let write = quote!(::rt_std::RtData::write_words(&self.#ident, &mut out[(#offset) as usize..]););
    let read = quote!(#ident: <#ty as ::rt_std::RtData>::read_words(&words[(#offset) as usize..]));
    let read_into = quote!(::rt_std::RtData::read_words_into(&mut self.#ident, &words[(#offset) as usize..]););
    let zero = quote!(self.#ident = ::rt_std::data::zeroed::<#ty>(););
    FieldCode { words, kind, write, read, read_into, zero }
}

/// Whether the field `fname` of type `tyname` takes a built-in triangle
/// attribute, as `rt_std::program::TriangleBuiltin::of_field` matches the
/// layout: the type as written, or a path ending in it.
fn is_triangle_builtin(fname: &str, tyname: &str) -> bool {
    let ty_name = tyname.rsplit("::").next().unwrap_or(tyname).trim();
    TRIANGLE_BUILTINS.iter().any(|(n, t)| *n == fname && *t == ty_name)
}

/// The built-in attributes of a triangle hit, by name and type, as
/// [`is_triangle_builtin`] matches them.
const TRIANGLE_BUILTINS: [(&str, &str); 4] =
    [("geometric_normal", "Vec3"), ("shading_normal", "Vec3"), ("texcoord", "Vec2"), ("barycentrics", "Vec2")];

/// Errors for the fields of an `#[rt_attributes]` struct that look meant as
/// a triangle's built-in but would not receive it (`texcoords`,
/// `tex_coord`, `texcoord: Vec3`): on triangles such a field reads zero on
/// every backend, silently, so the macro refuses it and names the
/// built-ins.
pub(super) fn near_triangle_builtins(s: &syn::ItemStruct) -> crate::error::Errors {
    let mut errors = crate::error::Errors::default();
    let list = TRIANGLE_BUILTINS.iter().map(|(n, t)| format!("`{n}: {t}`")).collect::<Vec<_>>().join(", ");
    for f in &s.fields {
        let Some(ident) = &f.ident else { continue };
        let fname = ident.to_string();
        let tyname = signature::type_text(&f.ty);
        if is_triangle_builtin(&fname, &tyname) {
            continue;
        }
        let near = TRIANGLE_BUILTINS.iter().find(|(n, _)| *n == fname || looks_like(&fname, n));
        if let Some((n, t)) = near {
            let what = if *n == fname {
                format!("field `{fname}` has the name of a triangle's built-in attribute but not its type `{t}`")
            } else {
                format!("field `{fname}` is not a triangle's built-in attribute (did you mean `{n}: {t}`?)")
            };
            errors.push(crate::error::Error::new(
                ident.span(),
                format!("{what}: triangles fill only {list}, and a field they do not fill reads zero"),
            ));
        }
    }
    errors
}

/// Whether `name` is a near miss of the built-in `builtin`: the same once
/// case, `_` and a plural `s` are set aside, or one edit away.
fn looks_like(name: &str, builtin: &str) -> bool {
    let squash = |s: &str| s.to_ascii_lowercase().replace('_', "").trim_end_matches('s').to_string();
    squash(name) == squash(builtin) || edit_distance(name, builtin) <= 1
}

/// Levenshtein distance over bytes (field names are ASCII identifiers).
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (diag + usize::from(ca != cb)).min(up + 1).min(row[j] + 1);
            diag = up;
        }
    }
    row[b.len()]
}

/// The role's marker trait for the struct `name`: none for plain data,
/// `Payload`, or `Attributes` with `set_triangle` made of `triangle_sets`.
fn role_marker(role: StructRole, name: &syn::Ident, triangle_sets: &[TokenStream]) -> TokenStream {
    match role {
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
    }
}
