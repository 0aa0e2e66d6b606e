//! Calls of generic `#[rt_function]`s: the arguments of the instance
//! called, from the turbofish, the arguments' types and the type the
//! result is wanted at; the call of the instance, or, where the unit does
//! not have it yet, its recording (see `lower/generics.rs`).

use super::*;
use crate::lower::generics::{self, GenericArg, Instance, ParamKind};
use std::collections::HashMap;

impl FnLowerer<'_> {
    /// `name(args)` or `name::<..>(args)`, `g` the generic `name` names;
    /// `key` is what the unit keys the generic by (`name`, or `Type::name`
    /// for a generic method called by path).
    pub(super) fn generic_call(
        &mut self,
        g: &syn::ItemFn,
        key: &str,
        path: &syn::Path,
        args: &[&Expr],
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Val> {
        let inst = self.instance(g, key, path, args, want, span)?;
        let key = inst.key();
        self.method_calls.push((key.clone(), span));
        if let Some(sig) = self.m.helpers.get(&key) {
            let sig = sig.clone();
            return self.helper_call(&sig, args, span);
        }
        self.pending_instance(g, inst, args, span)
    }

    /// `recv.name(args)` or `recv.name::<..>(args)` of a generic
    /// `#[rt_impl]` method `g`, keyed `key` (`Type::name`): the instance
    /// called as any method, its receiver borrowed as it takes it.
    pub(super) fn generic_method_call(
        &mut self,
        g: &syn::ItemFn,
        key: &str,
        m: &syn::ExprMethodCall,
        want: Option<&Ty>,
    ) -> Result<Val> {
        let mut seg = syn::PathSegment::from(m.method.clone());
        if let Some(t) = &m.turbofish {
            seg.arguments = syn::PathArguments::AngleBracketed(t.clone());
        }
        let path = syn::Path::from(seg);
        let args: Vec<&Expr> = m.args.iter().collect();
        let mut all: Vec<&Expr> = vec![&m.receiver];
        all.extend_from_slice(&args);
        let inst = self.instance(g, key, &path, &all, want, m.span())?;
        if let Some(sig) = self.m.helpers.get(&inst.key()) {
            let sig = sig.clone();
            return self.user_method_call(&sig, &m.receiver, &args, m.span());
        }
        self.method_calls.push((inst.key(), m.span()));
        self.pending_instance(g, inst, &all, m.span())
    }

    /// The instance of `g` (keyed `generic`) a call with `args` names.
    fn instance(
        &mut self,
        g: &syn::ItemFn,
        generic: &str,
        path: &syn::Path,
        args: &[&Expr],
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Instance> {
        let name = g.sig.ident.to_string();
        let inputs: Vec<&syn::Type> = g
            .sig
            .inputs
            .iter()
            .filter_map(|i| match i {
                syn::FnArg::Typed(pt) => Some(&*pt.ty),
                syn::FnArg::Receiver(_) => None,
            })
            .collect();
        if args.len() != inputs.len() {
            return Err(Error::new(span, format!("`{name}` takes {} argument(s), found {}", inputs.len(), args.len())));
        }
        // A method of a generic struct's block takes the struct's
        // parameters first (`methods`).
        let impl_params =
            generic.split_once("::").and_then(|(t, _)| self.m.generic_structs.params(t)).map_or(0, |p| p.len());
        let inst = Instance {
            generic: generic.to_string(),
            args: self.generic_args(g, path, impl_params, &inputs, args, want, span)?,
        };
        let key = inst.key();
        if self.fn_name != key && self.fn_name.strip_prefix(generic).is_some_and(|r| r.starts_with('<')) {
            // Each instance would call a new one, without end.
            return Err(Error::unsupported(
                span,
                &format!("recursion (`{}` calls `{key}`)", self.fn_name),
                "WGSL has no recursion; rewrite it as a loop",
            ));
        }
        Ok(inst)
    }

    /// A call of an instance the unit does not have in this pass: wanted,
    /// and typed from its signature so the rest of the body is lowered
    /// (and its own instances found).
    fn pending_instance(&mut self, g: &syn::ItemFn, inst: Instance, args: &[&Expr], span: Span) -> Result<Val> {
        if self.m.failed.contains(&inst.key()) {
            // The instance's signature failed: its errors say why.
            return Err(Error::silent(span));
        }
        for a in args {
            let a = match a {
                Expr::Reference(r) => &*r.expr,
                a => a,
            };
            self.peek_type(a)?;
        }
        let f = generics::instantiate(g, &inst.args);
        {
            let mut wanted = self.m.wanted.borrow_mut();
            if !wanted.contains(&inst) {
                wanted.push(inst);
            }
        }
        let ret = match &f.sig.output {
            syn::ReturnType::Default => Ty::Unit,
            syn::ReturnType::Type(_, t) => self.m.resolve_type(t).map_err(|e| Error::silent(e.span))?,
        };
        let code = if ret == Ty::Unit { String::new() } else { builtins::zero_value(&ret) };
        Ok(Val::new(code, ret))
    }

    /// The instance's arguments, in the generic's order: each given by the
    /// turbofish, else bound by an argument's type, else by `want`. The
    /// first `impl_params` are a generic struct's, given on its name
    /// (`Pair::<f32>::new(..)`), the rest on the function's.
    #[allow(clippy::too_many_arguments)]
    fn generic_args(
        &mut self,
        g: &syn::ItemFn,
        path: &syn::Path,
        impl_params: usize,
        inputs: &[&syn::Type],
        args: &[&Expr],
        want: Option<&Ty>,
        span: Span,
    ) -> Result<Vec<GenericArg>> {
        let name = g.sig.ident.to_string();
        let params = generics::params(g);
        let mut binds: HashMap<String, (GenericArg, bool)> = HashMap::new();
        let n = path.segments.len();
        let owner = (impl_params > 0 && n >= 2).then(|| (&path.segments[n - 2], &params[..impl_params]));
        let own = path.segments.last().map(|s| (s, &params[impl_params.min(params.len())..]));
        for (seg, params) in owner.into_iter().chain(own) {
            let syn::PathArguments::AngleBracketed(ab) = &seg.arguments else { continue };
            let given: Vec<&syn::GenericArgument> =
                ab.args.iter().filter(|a| !matches!(a, syn::GenericArgument::Lifetime(_))).collect();
            if given.len() != params.len() {
                let name = if std::ptr::eq(seg, &path.segments[n - 1]) { name.clone() } else { seg.ident.to_string() };
                return Err(Error::new(
                    ab.span(),
                    format!("`{name}` takes {} generic argument(s), found {}", params.len(), given.len()),
                ));
            }
            for (p, a) in params.iter().zip(given) {
                let arg = match (p.kind, a) {
                    (_, syn::GenericArgument::Type(syn::Type::Infer(_))) => continue,
                    (ParamKind::Type, syn::GenericArgument::Type(t)) => GenericArg::Type(self.m.resolve_type(t)?),
                    (ParamKind::Const, syn::GenericArgument::Const(e)) => {
                        // The typed form has every expression: a length is a `usize`.
                        self.expr_types.insert(crate::typed::address(e), Ty::Scalar(Scalar::Usize));
                        GenericArg::Const(const_arg(e)?)
                    }
                    (ParamKind::Type, _) => {
                        return Err(Error::new(a.span(), format!("`{}` of `{name}` is a type", p.name)));
                    }
                    (ParamKind::Const, _) => {
                        return Err(Error::new(
                            a.span(),
                            format!("`{}` of `{name}` is an array length: write it as a number", p.name),
                        ));
                    }
                };
                binds.insert(p.name.clone(), (arg, false));
            }
        }
        for (pattern, a) in inputs.iter().zip(args) {
            if !generics::mentions(pattern, &params) {
                continue;
            }
            // `&mut x` for a `&mut T`: the place's type.
            let a = match a {
                Expr::Reference(r) => &*r.expr,
                a => a,
            };
            let Some(t) = self.peek_type(a)? else { continue };
            let mut literal = false;
            let t = self.probed_arg(&t, &mut literal);
            generics::bind(pattern, &t, &params, &mut binds, literal);
        }
        if let (Some(w), syn::ReturnType::Type(_, r)) = (want, &g.sig.output) {
            let w = self.resolved(w);
            if !matches!(w, Ty::IntVar(_)) {
                generics::bind(r, &w, &params, &mut binds, false);
            }
        }
        params
            .iter()
            .map(|p| {
                binds.remove(&p.name).map(|(a, _)| a).ok_or_else(|| {
                    let what = match p.kind {
                        ParamKind::Type => "type parameter",
                        ParamKind::Const => "array length",
                    };
                    Error::new(
                        span,
                        format!(
                            "cannot infer the {what} `{}` of `{name}` from the arguments: give it, as in `{name}::<..>(..)`",
                            p.name
                        ),
                    )
                })
            })
            .collect()
    }
}

impl FnLowerer<'_> {
    /// A probed argument's type with its integer literals settled: an
    /// inference variable still open (or the probe's own, gone with it)
    /// is `i32`, as Rust's default, and sets `literal`.
    pub(super) fn probed_arg(&self, t: &Ty, literal: &mut bool) -> Ty {
        match t {
            Ty::IntVar(v) if (*v as usize) < self.ivars.len() => match self.resolved(t) {
                Ty::IntVar(_) => {
                    *literal = true;
                    I32
                }
                t => t,
            },
            Ty::IntVar(_) => {
                *literal = true;
                I32
            }
            Ty::Array(e, n) => Ty::Array(Box::new(self.probed_arg(e, literal)), *n),
            Ty::Tuple(ts) => Ty::Tuple(ts.iter().map(|t| self.probed_arg(t, literal)).collect()),
            Ty::Ref(m, e) => Ty::Ref(*m, Box::new(self.probed_arg(e, literal))),
            other => other.clone(),
        }
    }
}

/// A const argument written in the turbofish: `4`, `{ 4 }`.
fn const_arg(e: &Expr) -> Result<u32> {
    match e {
        Expr::Block(b) if b.block.stmts.len() == 1 => match &b.block.stmts[0] {
            syn::Stmt::Expr(inner, None) => const_arg(inner),
            _ => Err(Error::new(e.span(), "write the array length as a number")),
        },
        Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) => Ok(i.base10_parse()?),
        _ => Err(Error::new(e.span(), "write the array length as a number")),
    }
}
