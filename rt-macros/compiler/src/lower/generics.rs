//! Generic `#[rt_function]`s, monomorphized per use.
//!
//! WGSL functions are monomorphic, so a generic helper becomes one WGSL
//! function per list of type (and array-length) arguments it is called
//! with: an *instance*. Where the instantiation happens follows from how
//! items reach a program: the dependency chain (`expand/chain.rs`) hands
//! the caller's macro every helper it names *with its body*, so the unit
//! that lowers a caller has the generic's whole `syn::ItemFn`. The caller's
//! unit instantiates it, and the descriptors and the linker need nothing
//! new: an instance is an ordinary helper of the unit.
//!
//! - **Arguments.** At a call `lerp(a, b, t)` (`generic_call` in
//!   `func/generic_calls.rs`), the type parameters are bound by the
//!   turbofish (`lerp::<Vec3>(..)`), else by matching each parameter's
//!   written type (`T`, `&mut T`, `[T; N]`, tuples of them) against the
//!   argument's type as the lowering infers it, else by the type the
//!   call's context expects for the result; an integer literal alone binds
//!   `i32`, as in Rust. A parameter still unbound is an error naming it.
//! - **Instances.** An instance is the generic's `syn::ItemFn` with each
//!   type parameter replaced by its argument's Rust spelling and each const
//!   parameter by its value (`instantiate`), lowered by the same path as
//!   any helper (signature, body, typed form, resumable form, sites).
//!   Its key is `lerp<Vec3>` (no Rust name can collide with it) and its
//!   WGSL name `rtf_lerp__Vec3` (`wgsl_name`): the same in every unit, so
//!   the linker, which keeps one function per name, emits it once however
//!   many programs use it.
//! - **Discovery.** Which instances a unit needs is known only once its
//!   bodies are typed, and an instance's body may call further instances.
//!   The unit is therefore lowered in passes (`lower_impl`): a call of an
//!   instance the pass lacks is recorded (`ModuleCtx::wanted`) and typed
//!   from the instantiated signature; when a pass ends with new instances
//!   wanted, it is dropped and the unit lowered again with them, until no
//!   new one appears (at most [`MAX_INSTANCES`], of keys at most
//!   [`MAX_KEY`] long: polymorphic recursion never ends, and is refused;
//!   a generic calling itself at another type is refused at the call).
//! - **Errors.** A generic's own macro can only check its shape
//!   (`check_alone`): its body has no types until a caller gives them. An
//!   instance's errors are therefore the caller's (reported there, at the
//!   span in the generic's body, with the instance named).
//! - **Bounds** are Rust's business: the generic is also compiled by rustc
//!   for the CPU backend, with its bounds, and the caller's CPU copy
//!   instantiates it there, so a type that lacks a bound is rustc's error
//!   at the call. The lowering needs no bound: it types the instance.

use crate::error::{Error, Errors};
use crate::types::Ty;
use std::collections::HashMap;
use syn::spanned::Spanned;
use syn::visit_mut::VisitMut;

/// How many instances one unit may have: past it, the instances are
/// taken to recurse without end.
pub const MAX_INSTANCES: usize = 64;

/// How long an instance's key may be: a generic that calls another at a
/// type built from its own (`(T, T)`) doubles it at each step.
pub const MAX_KEY: usize = 256;

/// One argument of an instance: a type, or a const parameter's value.
#[derive(Clone, Debug, PartialEq)]
pub enum GenericArg {
    Type(Ty),
    Const(u32),
}

impl GenericArg {
    fn rust(&self) -> String {
        match self {
            GenericArg::Type(t) => t.to_string(),
            GenericArg::Const(n) => n.to_string(),
        }
    }

    /// A WGSL-identifier-safe spelling of the argument, from its Rust one
    /// (`[f32; 4]` is `f32_4`): distinct Rust types give distinct names
    /// (an enum is not a `u32` here, as it is in WGSL).
    pub fn mangle(&self) -> String {
        let mut out = String::new();
        for c in self.rust().chars() {
            if c.is_ascii_alphanumeric() {
                out.push(c);
            } else if !out.ends_with('_') {
                out.push('_');
            }
        }
        out.trim_matches('_').to_string()
    }
}

/// A generic function with its arguments.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The generic function's name.
    pub generic: String,
    /// Per generic parameter (lifetimes aside), in order.
    pub args: Vec<GenericArg>,
}

impl Instance {
    /// The key calls name the instance by: `lerp<Vec3>`.
    pub fn key(&self) -> String {
        let args: Vec<String> = self.args.iter().map(GenericArg::rust).collect();
        format!("{}<{}>", self.generic, args.join(", "))
    }

    /// The instance's WGSL name: `rtf_lerp__Vec3`, `rtf_sum__4`; of a
    /// generic method `Disc::scaled` (its key, `methods::member_key`),
    /// `rtm_Disc__scaled__f32`.
    pub fn wgsl_name(&self) -> String {
        let args: Vec<String> = self.args.iter().map(GenericArg::mangle).collect();
        if let Some((ty, rest)) = self.generic.split_once(" op ") {
            // A generic struct's operator (`operators::key`): its WGSL
            // name with the arguments after it.
            let (method, rhs) = rest.split_once(' ').unwrap_or((rest, ""));
            return format!("{}__{}", crate::operators::wgsl_name(ty, method, rhs), args.join("__"));
        }
        match self.generic.split_once("::") {
            // The method's own name (`rtm_<Type>__<name>`), then the arguments.
            Some((ty, name)) => format!("rtm_{ty}__{name}__{}", args.join("__")),
            None => format!("rtf_{}__{}", self.generic, args.join("__")),
        }
    }

    /// What an error inside the instance adds: which instance it is.
    pub fn describe(&self, g: &syn::ItemFn) -> String {
        let binds: Vec<String> =
            params(g).iter().zip(&self.args).map(|(p, a)| format!("{} = {}", p.name, a.rust())).collect();
        format!("in `{}` with {}", self.generic, binds.join(", "))
    }
}

/// Whether a generic parameter is a type or an array length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    Type,
    Const,
}

/// A generic parameter of a function, lifetimes aside.
#[derive(Clone, Debug)]
pub struct Param {
    pub name: String,
    pub kind: ParamKind,
}

/// The type and const parameters of `f`, in order.
pub fn params(f: &syn::ItemFn) -> Vec<Param> {
    f.sig
        .generics
        .params
        .iter()
        .filter_map(|p| match p {
            syn::GenericParam::Type(t) => Some(Param { name: t.ident.to_string(), kind: ParamKind::Type }),
            syn::GenericParam::Const(c) => Some(Param { name: c.ident.to_string(), kind: ParamKind::Const }),
            syn::GenericParam::Lifetime(_) => None,
        })
        .collect()
}

/// Whether `f` has type or const parameters.
pub fn is_generic(f: &syn::ItemFn) -> bool {
    !params(f).is_empty()
}

/// What a generic's own macro checks beside the function's shape
/// (`items::check_fn_shape`): its generic parameters (the body is checked
/// per instance, where a caller gives the types).
pub fn check_alone(f: &syn::ItemFn) -> Result<(), Errors> {
    let mut errors = Errors::default();
    check_params(&f.sig.generics, &mut errors);
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

/// Refuses the generic parameters WGSL has no meaning for: lifetimes and
/// const parameters that are not array lengths (of a generic helper or
/// method).
pub fn check_params(generics: &syn::Generics, errors: &mut Errors) {
    for p in &generics.params {
        match p {
            syn::GenericParam::Lifetime(l) => {
                errors.push(Error::unsupported(l.span(), "a lifetime parameter", "leave lifetimes out"))
            }
            syn::GenericParam::Const(c) => {
                let ok = matches!(&c.ty, syn::Type::Path(t) if t.path.is_ident("usize"));
                if !ok {
                    errors.push(Error::unsupported(
                        c.ty.span(),
                        "a const parameter of a type other than `usize`",
                        "const parameters are array lengths: `const N: usize`",
                    ));
                }
            }
            syn::GenericParam::Type(_) => {}
        }
    }
}

/// The instance's function: `g` with its generics removed and each
/// parameter replaced by its argument (a type by its Rust spelling, an
/// array length by its value).
pub fn instantiate(g: &syn::ItemFn, args: &[GenericArg]) -> syn::ItemFn {
    let mut types = HashMap::new();
    let mut consts = HashMap::new();
    for (p, a) in params(g).iter().zip(args) {
        match a {
            GenericArg::Type(t) => {
                let ty: syn::Type = syn::parse_str(&t.to_string()).unwrap_or_else(|_| syn::parse_quote!(()));
                types.insert(p.name.clone(), ty);
            }
            GenericArg::Const(n) => {
                consts.insert(p.name.clone(), *n);
            }
        }
    }
    let mut f = g.clone();
    f.sig.generics = syn::Generics::default();
    Subst { types, consts }.visit_item_fn_mut(&mut f);
    f
}

struct Subst {
    types: HashMap<String, syn::Type>,
    consts: HashMap<String, u32>,
}

impl Subst {
    fn single(path: &syn::Path) -> Option<String> {
        (path.leading_colon.is_none() && path.segments.len() == 1 && path.segments[0].arguments.is_none())
            .then(|| path.segments[0].ident.to_string())
    }
}

impl VisitMut for Subst {
    fn visit_type_mut(&mut self, t: &mut syn::Type) {
        if let syn::Type::Path(p) = t
            && p.qself.is_none()
            && let Some(name) = Self::single(&p.path)
        {
            if let Some(ty) = self.types.get(&name) {
                *t = ty.clone();
                return;
            }
            if let Some(n) = self.consts.get(&name) {
                // `sum::<N>(..)` passes a const parameter on.
                let lit = syn::LitInt::new(&n.to_string(), p.span());
                *t = syn::parse_quote!({ #lit });
                return;
            }
        }
        if let syn::Type::Array(a) = t {
            self.visit_type_mut(&mut a.elem);
            if let syn::Expr::Path(p) = &a.len
                && let Some(n) = Self::single(&p.path).and_then(|n| self.consts.get(&n))
            {
                a.len = syn::Expr::Lit(syn::ExprLit {
                    attrs: Vec::new(),
                    lit: syn::Lit::Int(syn::LitInt::new(&n.to_string(), p.span())),
                });
            } else {
                self.visit_expr_mut(&mut a.len);
            }
            return;
        }
        syn::visit_mut::visit_type_mut(self, t);
    }

    fn visit_generic_argument_mut(&mut self, a: &mut syn::GenericArgument) {
        // `sum::<N>`: syn reads a lone name as a type.
        if let syn::GenericArgument::Type(syn::Type::Path(p)) = a
            && let Some(n) = Self::single(&p.path).and_then(|n| self.consts.get(&n))
        {
            let lit = syn::LitInt::new(&n.to_string(), p.span());
            *a = syn::GenericArgument::Const(syn::parse_quote!(#lit));
            return;
        }
        syn::visit_mut::visit_generic_argument_mut(self, a);
    }

    fn visit_expr_path_mut(&mut self, e: &mut syn::ExprPath) {
        // `T::default()`, `T::ZERO`: the argument's path in `T`'s place,
        // where it is one (`Vec3::ZERO`).
        if e.qself.is_none()
            && e.path.segments.len() >= 2
            && e.path.segments[0].arguments.is_none()
            && let Some(syn::Type::Path(t)) = self.types.get(&e.path.segments[0].ident.to_string())
            && t.qself.is_none()
        {
            let rest: Vec<syn::PathSegment> = e.path.segments.iter().skip(1).cloned().collect();
            let mut path = t.path.clone();
            path.segments.extend(rest);
            e.path = path;
        }
        syn::visit_mut::visit_expr_path_mut(self, e);
    }

    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        if let syn::Expr::Path(p) = e
            && p.qself.is_none()
            && let Some(n) = Self::single(&p.path).and_then(|n| self.consts.get(&n))
        {
            // A length used as a value: `usize`, as the parameter is.
            let lit = syn::LitInt::new(&format!("{n}usize"), p.span());
            *e = syn::parse_quote!(#lit);
            return;
        }
        syn::visit_mut::visit_expr_mut(self, e);
    }
}

/// Binds the parameters `pattern` (a parameter's written type) names by
/// matching it against `ty`, the argument's type. A binding already made
/// stands (a mismatch is the argument's type error, reported where it is
/// passed), except that a concrete scalar replaces an integer literal's
/// `i32` guess (`binds` records which came from a literal).
pub fn bind(
    pattern: &syn::Type,
    ty: &Ty,
    params: &[Param],
    binds: &mut HashMap<String, (GenericArg, bool)>,
    from_literal: bool,
) {
    let is = |name: &str, kind: ParamKind| params.iter().any(|p| p.name == name && p.kind == kind);
    match (pattern, ty) {
        (syn::Type::Paren(p), _) => bind(&p.elem, ty, params, binds, from_literal),
        (syn::Type::Group(g), _) => bind(&g.elem, ty, params, binds, from_literal),
        (syn::Type::Reference(r), Ty::Ref(_, inner)) => bind(&r.elem, inner, params, binds, from_literal),
        (syn::Type::Reference(r), _) => bind(&r.elem, ty, params, binds, from_literal),
        (syn::Type::Path(p), _) if p.qself.is_none() => {
            if let Some(name) = Subst::single(&p.path)
                && is(&name, ParamKind::Type)
            {
                let replace = match binds.get(&name) {
                    None => true,
                    Some((_, guessed)) => *guessed && !from_literal,
                };
                if replace {
                    binds.insert(name, (GenericArg::Type(ty.clone()), from_literal));
                }
            } else if let (Some(seg), Ty::Struct(d)) = (p.path.segments.last(), ty)
                && let syn::PathArguments::AngleBracketed(a) = &seg.arguments
                && let Some((generic, args)) = &d.generic
                && seg.ident == generic
            {
                // `Pair<T>` against an instance of `Pair` (a generic
                // struct's method's receiver, `lower::generic_structs`).
                let patterns = a.args.iter().filter_map(|g| match g {
                    syn::GenericArgument::Type(t) => Some(t),
                    _ => None,
                });
                for (pattern, arg) in patterns.zip(args) {
                    bind(pattern, arg, params, binds, from_literal);
                }
            }
        }
        (syn::Type::Array(a), Ty::Array(elem, n)) => {
            bind(&a.elem, elem, params, binds, from_literal);
            if let syn::Expr::Path(p) = &a.len
                && let Some(name) = Subst::single(&p.path)
                && is(&name, ParamKind::Const)
            {
                binds.entry(name).or_insert((GenericArg::Const(*n), false));
            }
        }
        (syn::Type::Tuple(t), Ty::Tuple(elems)) if t.elems.len() == elems.len() => {
            for (p, e) in t.elems.iter().zip(elems) {
                bind(p, e, params, binds, from_literal);
            }
        }
        _ => {}
    }
}

/// Whether `pattern` names one of `params`.
pub fn mentions(pattern: &syn::Type, params: &[Param]) -> bool {
    names_any(quote::quote!(#pattern), &|i| params.iter().any(|p| *i == p.name))
}

/// Whether `ts` has, at any depth, an identifier `is_name` takes.
pub fn names_any(ts: proc_macro2::TokenStream, is_name: &dyn Fn(&proc_macro2::Ident) -> bool) -> bool {
    ts.into_iter().any(|t| match t {
        proc_macro2::TokenTree::Ident(i) => is_name(&i),
        proc_macro2::TokenTree::Group(g) => names_any(g.stream(), is_name),
        _ => false,
    })
}
