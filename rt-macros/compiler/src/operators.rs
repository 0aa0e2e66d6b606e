//! Operator traits of std implemented for user types: `impl Add for Rgb`,
//! `impl Mul<f32> for Rgb`, `impl Neg for Rgb`, `impl AddAssign for Rgb`,
//! `impl Index<usize> for Rgb`, under `#[rt_impl]`.
//!
//! ## How they reach a program
//! As an impl of an `#[rt_trait]` does (see `traits`): the impl exports
//! the link `__rt_impl_Rgb__Mul__f32` ([`link_ident`]: the type, the
//! trait, and the right-hand type where it is not the type itself), and
//! `#[rt_struct(impl Mul<f32>)]` puts it among the struct's links, so
//! every program that has an `Rgb` has its operators.
//!
//! ## How they lower
//! The impl's method is a helper like any `#[rt_impl]` method, named by
//! the operator and its right-hand type (`rto_Rgb__mul__f32`, keyed
//! [`key`]), so `Mul` and `Mul<f32>` of one type live side by side. The
//! lowering of `a * b`, `-a`, `a *= b` and `a[i]` whose left operand is a
//! user type calls it, choosing the impl by the right operand's type as
//! rustc does. `Self::Output` is the impl's `type Output`; an `index`
//! returns its element by value (WGSL functions return no references).
//!
//! ## On the CPU
//! The impl stays a Rust impl. The CPU copy of a program writes the
//! arithmetic operators as calls of `rt_std::arith` ([`crate::cpu_semantics`]),
//! so each impl also implements the matching `rt_std::arith` trait by
//! calling it ([`cpu_glue`]): `a * b` on the CPU is the user's `mul`.
//! Bitwise operators and `!` are left as written there.
//!
//! A generic struct's impl (`impl<T: Add<Output = T>> Add for Pair<T>`)
//! is generic over the struct's parameters: its method is instantiated
//! per instance of the left operand (`rto_Pair__add__Pair__f32`), as the
//! struct's inherent methods are, and the right-hand type is the struct
//! itself or one type that does not name the parameters.
//!
//! Refused, with what to write instead: `IndexMut` (WGSL returns no
//! references: a method that sets the element), shifts, an operator impl
//! for a type that is not the user's (`impl Mul<Rgb> for f32`: write the
//! scalar on the right).

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// What an operator's method is called for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpKind {
    /// `a op b`.
    Binary,
    /// `op a`.
    Unary,
    /// `a op= b`: the method takes `&mut self`.
    Assign,
    /// `a[i]`.
    Index,
}

/// An operator trait of std that ray programs may implement.
#[derive(Debug)]
pub struct Operator {
    pub trait_name: &'static str,
    pub method: &'static str,
    pub kind: OpKind,
    /// `rt_std::arith`'s trait and method the CPU copy calls for it, if
    /// the CPU copy rewrites the operator.
    pub arith: Option<(&'static str, &'static str)>,
}

const fn op(
    trait_name: &'static str,
    method: &'static str,
    kind: OpKind,
    arith: Option<(&'static str, &'static str)>,
) -> Operator {
    Operator { trait_name, method, kind, arith }
}

/// The operator traits `#[rt_impl]` takes.
pub const OPERATORS: &[Operator] = &[
    op("Add", "add", OpKind::Binary, Some(("RtAdd", "add"))),
    op("Sub", "sub", OpKind::Binary, Some(("RtSub", "sub"))),
    op("Mul", "mul", OpKind::Binary, Some(("RtMul", "mul"))),
    op("Div", "div", OpKind::Binary, Some(("RtDiv", "div"))),
    op("Rem", "rem", OpKind::Binary, Some(("RtRem", "rem"))),
    op("BitAnd", "bitand", OpKind::Binary, None),
    op("BitOr", "bitor", OpKind::Binary, None),
    op("BitXor", "bitxor", OpKind::Binary, None),
    op("Neg", "neg", OpKind::Unary, Some(("RtNeg", "neg"))),
    op("Not", "not", OpKind::Unary, None),
    op("AddAssign", "add_assign", OpKind::Assign, Some(("RtAddAssign", "add_assign"))),
    op("SubAssign", "sub_assign", OpKind::Assign, Some(("RtSubAssign", "sub_assign"))),
    op("MulAssign", "mul_assign", OpKind::Assign, Some(("RtMulAssign", "mul_assign"))),
    op("DivAssign", "div_assign", OpKind::Assign, Some(("RtDivAssign", "div_assign"))),
    op("RemAssign", "rem_assign", OpKind::Assign, Some(("RtRemAssign", "rem_assign"))),
    op("BitAndAssign", "bitand_assign", OpKind::Assign, None),
    op("BitOrAssign", "bitor_assign", OpKind::Assign, None),
    op("BitXorAssign", "bitxor_assign", OpKind::Assign, None),
    op("Index", "index", OpKind::Index, Some(("RtIndex", "at"))),
];

/// The operator trait a path names (`Add`, `std::ops::Add`,
/// `core::ops::Mul<f32>`), if it is one ray programs implement.
pub fn operator(path: &syn::Path) -> Option<&'static Operator> {
    let first = path.segments.first()?.ident.to_string();
    if path.segments.len() > 1 && !matches!(first.as_str(), "std" | "core") {
        return None;
    }
    let last = path.segments.last()?.ident.to_string();
    OPERATORS.iter().find(|o| o.trait_name == last)
}

/// The operator an impl implements, with its written right-hand type
/// (the trait's argument; none where it is the type itself).
pub fn of_impl(i: &syn::ItemImpl) -> Option<(&'static Operator, Option<syn::Type>)> {
    let (_, path, _) = i.trait_.as_ref()?;
    let o = operator(path)?;
    let self_name = match &*i.self_ty {
        syn::Type::Path(p) if p.qself.is_none() => p.path.segments.last().map(|s| s.ident.to_string()),
        _ => None,
    };
    Some((o, rhs_of(path, &self_name.unwrap_or_default())))
}

/// The trait's type argument, unless it is `Self` or the type itself.
fn rhs_of(path: &syn::Path, self_name: &str) -> Option<syn::Type> {
    let syn::PathArguments::AngleBracketed(a) = &path.segments.last()?.arguments else { return None };
    let ty = a.args.iter().find_map(|g| match g {
        syn::GenericArgument::Type(t) => Some(t.clone()),
        _ => None,
    })?;
    match &ty {
        // `Rgb`, and a generic struct's `Pair<T>`.
        syn::Type::Path(p)
            if p.qself.is_none()
                && (p.path.is_ident("Self") || p.path.segments.len() == 1 && p.path.segments[0].ident == self_name) =>
        {
            None
        }
        _ => Some(ty),
    }
}

/// A WGSL-identifier-safe spelling of a written type (`[f32; 3]` is
/// `f32_3`).
pub fn mangle(ty: &syn::Type) -> String {
    let mut out = String::new();
    for c in quote!(#ty).to_string().chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}

/// The part of the link's and the item's name that says which trait (and
/// right-hand type): `Mul__f32`, `Add`; for a path that is not an
/// operator, its last identifier.
pub fn suffix(path: &syn::Path, self_name: &str) -> String {
    let last = path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
    match rhs_of(path, self_name) {
        Some(r) if operator(path).is_some() => format!("{last}__{}", mangle(&r)),
        _ => last,
    }
}

/// The link `#[rt_impl] impl Op<Rhs> for Type` exports and
/// `#[rt_struct(impl Op<Rhs>)]` collects.
pub fn link_ident(ty: &syn::Ident, path: &syn::Path) -> syn::Ident {
    format_ident!("__rt_impl_{}__{}", ty, suffix(path, &ty.to_string()), span = ty.span())
}

/// The key the lowering finds an operator's method by: the type, the
/// method and the right-hand type (mangled, empty for a unary operator):
/// `Rgb op mul f32`, which no Rust path spells.
pub fn key(ty: &str, method: &str, rhs: &str) -> String {
    format!("{ty} op {method} {rhs}")
}

/// The prefix of the keys of `ty`'s impls of the operator `method`.
pub fn key_prefix(ty: &str, method: &str) -> String {
    format!("{ty} op {method} ")
}

/// The WGSL function of an operator's method: `rto_Rgb__mul__f32`,
/// `rto_Rgb__neg` (an instance of a generic struct's adds its arguments,
/// `generics::Instance::wgsl_name`).
pub fn wgsl_name(ty: &str, method: &str, rhs: &str) -> String {
    if rhs.is_empty() { format!("rto_{ty}__{method}") } else { format!("rto_{ty}__{method}__{rhs}") }
}

/// The types an operator impl cannot be for: they are not the user's, and
/// their operators are the built-in ones in WGSL.
const BUILTIN_TYPES: &[&str] = &[
    "f32", "i32", "u32", "usize", "bool", "Vec2", "Vec3", "Vec4", "IVec2", "IVec3", "IVec4", "UVec2", "UVec3", "UVec4",
    "BVec2", "BVec3", "BVec4", "Mat2", "Mat3", "Mat4", "Quat",
];

/// Whether `name` is a type of the subset whose operators are built in.
pub fn is_builtin_type(name: &str) -> bool {
    BUILTIN_TYPES.contains(&name)
}

/// The impls of `rt_std::arith`'s traits that make the CPU copy's calls
/// reach the user's operator (see the module's essay); none for an
/// operator the CPU copy leaves as written.
pub fn cpu_glue(i: &syn::ItemImpl) -> TokenStream {
    let Some((o, _)) = of_impl(i) else { return TokenStream::new() };
    let Some((arith, arith_method)) = o.arith else { return TokenStream::new() };
    let self_ty = &i.self_ty;
    // A generic struct's impl (`impl<T: Add<Output = T>> Add for Pair<T>`):
    // the glue is generic with the impl's own bounds.
    let (impl_generics, _, where_clause) = i.generics.split_for_impl();
    let arith = format_ident!("{arith}");
    let arith_method = format_ident!("{arith_method}");
    let trait_name = format_ident!("{}", o.trait_name);
    let method = format_ident!("{}", o.method);
    let rhs: syn::Type = rhs_of(&i.trait_.as_ref().unwrap().1, "").unwrap_or_else(|| syn::parse_quote!(#self_ty));
    match o.kind {
        OpKind::Binary => quote! {
            impl #impl_generics ::rt_std::arith::#arith<#rhs> for #self_ty #where_clause {
                type Output = <#self_ty as ::core::ops::#trait_name<#rhs>>::Output;
                #[inline(always)]
                fn #arith_method(self, r: #rhs) -> Self::Output {
                    ::core::ops::#trait_name::<#rhs>::#method(self, r)
                }
            }
        },
        OpKind::Unary => quote! {
            impl #impl_generics ::rt_std::arith::#arith for #self_ty #where_clause {
                type Output = <#self_ty as ::core::ops::#trait_name>::Output;
                #[inline(always)]
                fn #arith_method(self) -> Self::Output {
                    ::core::ops::#trait_name::#method(self)
                }
            }
        },
        OpKind::Assign => quote! {
            impl #impl_generics ::rt_std::arith::#arith<#rhs> for #self_ty #where_clause {
                #[inline(always)]
                fn #arith_method(&mut self, r: #rhs) {
                    ::core::ops::#trait_name::<#rhs>::#method(self, r)
                }
            }
        },
        OpKind::Index => quote! {
            impl #impl_generics ::rt_std::arith::#arith<#rhs> for #self_ty #where_clause {
                type Output = <#self_ty as ::core::ops::#trait_name<#rhs>>::Output;
                #[inline(always)]
                fn #arith_method(&self, i: #rhs) -> &Self::Output {
                    ::core::ops::#trait_name::<#rhs>::#method(self, i)
                }
            }
        },
    }
}

/// The impl as the lowering takes it: `Self::Output` spelled as the
/// impl's `type Output` (which is then dropped), and an `index` method
/// returning its element by value.
pub fn prepare_impl(i: &mut syn::ItemImpl) {
    use syn::visit_mut::VisitMut;
    let output = i.items.iter().find_map(|it| match it {
        syn::ImplItem::Type(t) if t.ident == "Output" => Some(t.ty.clone()),
        _ => None,
    });
    i.items.retain(|it| !matches!(it, syn::ImplItem::Type(_)));
    if let Some(output) = output {
        SelfOutput(output).visit_item_impl_mut(i);
    }
    if of_impl(i).is_some_and(|(o, _)| o.kind == OpKind::Index) {
        for it in i.items.iter_mut() {
            if let syn::ImplItem::Fn(f) = it {
                if let syn::ReturnType::Type(_, ty) = &mut f.sig.output
                    && let syn::Type::Reference(r) = &**ty
                    && r.mutability.is_none()
                {
                    *ty = r.elem.clone();
                }
                ByValue.visit_block_mut(&mut f.block);
            }
        }
    }
}

/// Spells `Self::Output` as the impl's output type.
struct SelfOutput(syn::Type);

impl syn::visit_mut::VisitMut for SelfOutput {
    fn visit_type_mut(&mut self, t: &mut syn::Type) {
        if let syn::Type::Path(p) = t
            && p.qself.is_none()
            && p.path.segments.len() == 2
            && p.path.segments[0].ident == "Self"
            && p.path.segments[1].ident == "Output"
        {
            *t = self.0.clone();
            return;
        }
        syn::visit_mut::visit_type_mut(self, t);
    }
}

/// Drops the shared borrows of an `index` body: its element is returned
/// by value.
struct ByValue;

impl syn::visit_mut::VisitMut for ByValue {
    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        if let syn::Expr::Reference(r) = e
            && r.mutability.is_none()
        {
            *e = (*r.expr).clone();
            self.visit_expr_mut(e);
            return;
        }
        syn::visit_mut::visit_expr_mut(self, e);
    }
}
