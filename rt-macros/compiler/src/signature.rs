//! The shape of a program's signature: which parameter is the payload, the
//! attributes, the primitive index, and which are `#[var]` variables. Used by
//! the lowering (WGSL parameters) and by `expand` (the CPU thunk) alike.

use crate::error::{Error, Errors};
use crate::kinds::Kind;
use proc_macro2::Span;
use syn::spanned::Spanned;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// `prd: &mut P` (or `&P` for visit).
    Payload { mutable: bool },
    /// `attr: &A` in hit programs, `attr: &mut A` in intersection.
    Attributes { mutable: bool },
    /// `prim: u32` of intersection and bounding-box programs.
    Primitive,
    /// `#[var] name: T`.
    Variable,
    /// An argument of a callable program, by value.
    Argument,
}

#[derive(Clone, Debug)]
pub struct Param {
    pub name: syn::Ident,
    pub role: Role,
    /// The declared type; for references, the referenced type.
    pub ty: syn::Type,
    pub span: Span,
}

/// Whether an attribute is `#[var]`.
pub fn is_var_attr(a: &syn::Attribute) -> bool {
    a.path().is_ident("var")
}

/// Classifies the parameters of a program of `kind`.
pub fn program_params(kind: Kind, f: &syn::ItemFn) -> Result<Vec<Param>, Errors> {
    let mut errors = Errors::default();
    let mut params = Vec::new();
    for input in &f.sig.inputs {
        let pt = match input {
            syn::FnArg::Typed(pt) => pt,
            syn::FnArg::Receiver(r) => {
                errors.push(Error::unsupported(r.span(), "a `self` parameter", "programs are free functions"));
                continue;
            }
        };
        let name = match &*pt.pat {
            syn::Pat::Ident(pi) if pi.by_ref.is_none() && pi.subpat.is_none() => pi.ident.clone(),
            other => {
                errors.push(Error::unsupported(other.span(), "this parameter pattern", "use a plain name"));
                continue;
            }
        };
        let span = pt.span();
        // A callable's parameters are its arguments, but for its `#[var]`
        // variables (resolved as OptiX resolves a bindless callable's: the
        // program's scope, then the context's).
        if kind == Kind::Callable && !pt.attrs.iter().any(is_var_attr) {
            params.push(Param { name, role: Role::Argument, ty: (*pt.ty).clone(), span });
            continue;
        }
        if pt.attrs.iter().any(is_var_attr) {
            if let syn::Type::Reference(r) = &*pt.ty {
                errors.push(Error::new(
                    r.span(),
                    format!("variable `{name}` must be taken by value: write `#[var] {name}: {}`", type_text(&r.elem)),
                ));
                continue;
            }
            params.push(Param { name, role: Role::Variable, ty: (*pt.ty).clone(), span });
            continue;
        }
        let taken =
            |r: Role| params.iter().any(|p: &Param| std::mem::discriminant(&p.role) == std::mem::discriminant(&r));
        let role = match (&*pt.ty, kind) {
            (syn::Type::Reference(r), Kind::ClosestHit | Kind::AnyHit) => {
                let role = if r.mutability.is_some() {
                    Role::Payload { mutable: true }
                } else {
                    Role::Attributes { mutable: false }
                };
                if taken(role) {
                    Err(format!("{} takes {}", kind.a_program(), kind.signature_help()))
                } else {
                    Ok((role, (*r.elem).clone()))
                }
            }
            (syn::Type::Reference(r), Kind::Miss)
                if r.mutability.is_some() && !taken(Role::Payload { mutable: true }) =>
            {
                Ok((Role::Payload { mutable: true }, (*r.elem).clone()))
            }
            (syn::Type::Reference(r), Kind::Visit)
                if r.mutability.is_none() && !taken(Role::Payload { mutable: false }) =>
            {
                Ok((Role::Payload { mutable: false }, (*r.elem).clone()))
            }
            (syn::Type::Reference(r), Kind::Intersection)
                if r.mutability.is_some() && !taken(Role::Attributes { mutable: true }) =>
            {
                Ok((Role::Attributes { mutable: true }, (*r.elem).clone()))
            }
            (ty, Kind::Intersection | Kind::BoundingBox) if is_u32(ty) && !taken(Role::Primitive) => {
                Ok((Role::Primitive, ty.clone()))
            }
            _ => Err(format!(
                "parameter `{name}` does not fit {}, which takes {} (mark variables with `#[var]`)",
                kind.a_program(),
                kind.signature_help()
            )),
        };
        match role {
            Ok((role, ty)) => params.push(Param { name, role, ty, span }),
            Err(msg) => errors.push(Error::new(span, msg)),
        }
    }
    if matches!(kind, Kind::Intersection | Kind::BoundingBox) && !params.iter().any(|p| p.role == Role::Primitive) {
        errors.push(Error::new(
            f.sig.ident.span(),
            format!("{} takes the primitive index as its first parameter: `prim: u32`", kind.a_program()),
        ));
    }
    if errors.is_empty() { Ok(params) } else { Err(errors) }
}

fn is_u32(ty: &syn::Type) -> bool {
    matches!(ty, syn::Type::Path(p) if p.path.is_ident("u32"))
}

pub fn type_text(ty: &syn::Type) -> String {
    quote::quote!(#ty).to_string().replace(" < ", "<").replace(" >", ">").replace(" ,", ",")
}
