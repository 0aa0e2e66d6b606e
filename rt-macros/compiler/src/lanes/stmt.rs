//! A body's statements, lane-wise. Each local holds a value per lane
//! (`[T; LANES]`); `__mask` holds the running lanes. A statement runs as
//! one of:
//!
//! - **per lane** (most statements): the statement itself, renamed for one
//!   lane (`rename.rs`), run by `each`/`fill` for every running lane; a
//!   `return` in it takes its lane out of `__mask`;
//! - **a trace** (`rt_trace(object, ray, &mut payload)` with a lane-wise
//!   payload): the lanes' objects and rays first, then one call that hands
//!   them to the backend together;
//! - **a masked `if`** (one that holds such a trace): the condition per
//!   lane, then each branch under the lanes that take it, with the lanes
//!   that returned in either branch out of `__mask` after;
//! - a **block** (one that holds such a trace), its statements in turn.
//!
//! After a statement that may take lanes out, the rest of the block runs
//! only if a lane still runs (so a `let` always has a lane to fill from).

use super::Refusal;
use super::rename::{bound, for_lane};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use std::collections::HashSet;
use syn::spanned::Spanned;
use syn::visit::Visit;

pub(super) struct Writer {
    /// The lane-wise locals in scope.
    pub(super) varying: HashSet<String>,
    /// For fresh names.
    pub(super) next: usize,
}

impl Writer {
    /// A block's statements in a scope of their own.
    pub(super) fn block(&mut self, stmts: &[syn::Stmt]) -> Result<TokenStream, Refusal> {
        let outer = self.varying.clone();
        let r = self.stmts(stmts);
        self.varying = outer;
        r
    }

    fn stmts(&mut self, stmts: &[syn::Stmt]) -> Result<TokenStream, Refusal> {
        let mut out = TokenStream::new();
        for (i, s) in stmts.iter().enumerate() {
            let (code, retires) = self.stmt(s)?;
            out.extend(code);
            if retires && i + 1 < stmts.len() {
                let rest = self.stmts(&stmts[i + 1..])?;
                out.extend(quote!(if ::rt_std::cpu::lanes::any(&__mask) { #rest }));
                break;
            }
        }
        Ok(out)
    }

    /// One statement's code, and whether it may take lanes out.
    fn stmt(&mut self, s: &syn::Stmt) -> Result<(TokenStream, bool), Refusal> {
        match s {
            syn::Stmt::Local(l) => self.local(l).map(|c| (c, false)),
            syn::Stmt::Item(item) => Ok((quote!(#item), false)),
            syn::Stmt::Macro(m) => {
                let e = syn::Expr::Macro(syn::ExprMacro { attrs: m.attrs.clone(), mac: m.mac.clone() });
                self.per_lane(&e)
            }
            syn::Stmt::Expr(e, _) => self.expr_stmt(e),
        }
    }

    fn expr_stmt(&mut self, e: &syn::Expr) -> Result<(TokenStream, bool), Refusal> {
        if let syn::Expr::Return(r) = e {
            if r.expr.is_some() {
                return Err(Refusal::new(r.span(), "a `return` with a value".into()));
            }
            return Ok((quote!(__mask = [false; ::rt_std::cpu::lanes::LANES];), true));
        }
        if !traces(e) {
            return self.per_lane(e);
        }
        if let Some(code) = self.trace(e)? {
            return Ok((code, false));
        }
        match e {
            syn::Expr::If(i) if !matches!(&*i.cond, syn::Expr::Let(_)) => self.masked_if(i),
            syn::Expr::Block(b) if b.label.is_none() => {
                let code = self.block(&b.block.stmts)?;
                Ok((quote!({ #code }), returns(e)))
            }
            // A trace in a loop or a `match` runs lane by lane.
            _ => self.per_lane(e),
        }
    }

    /// `rt_trace(object, ray, &mut p)` with `p` lane-wise, as a packet.
    fn trace(&mut self, e: &syn::Expr) -> Result<Option<TokenStream>, Refusal> {
        let syn::Expr::Call(c) = e else { return Ok(None) };
        let syn::Expr::Path(f) = &*c.func else { return Ok(None) };
        if f.path.segments.last().is_none_or(|s| s.ident != "rt_trace") || c.args.len() != 3 {
            return Ok(None);
        }
        let syn::Expr::Reference(r) = &c.args[2] else { return Ok(None) };
        let syn::Expr::Path(p) = &*r.expr else { return Ok(None) };
        let Some(payload) = p.path.get_ident().filter(|i| self.varying.contains(&i.to_string())) else {
            return Ok(None);
        };
        if r.mutability.is_none() {
            return Ok(None);
        }
        let object = self.lanes_of(&c.args[0])?;
        let ray = self.lanes_of(&c.args[1])?;
        Ok(Some(quote! {
            {
                let __objects = #object;
                let __rays = #ray;
                ::rt_std::cpu::lanes::trace(&__mask, &__objects, &__rays, &mut #payload);
            }
        }))
    }

    /// `if` holding a trace: each branch under its lanes.
    fn masked_if(&mut self, i: &syn::ExprIf) -> Result<(TokenStream, bool), Refusal> {
        let cond = self.lanes_of(&i.cond)?;
        let then = self.block(&i.then_branch.stmts)?;
        let els = match &i.else_branch {
            None => TokenStream::new(),
            Some((_, e)) => match &**e {
                syn::Expr::Block(b) => self.block(&b.block.stmts)?,
                other => self.expr_stmt(other)?.0,
            },
        };
        let c = format_ident!("__cond{}", self.next);
        self.next += 1;
        let code = quote! {
            {
                let #c = #cond;
                let __then = {
                    let mut __mask = ::rt_std::cpu::lanes::and(&__mask, &#c);
                    if ::rt_std::cpu::lanes::any(&__mask) { #then }
                    __mask
                };
                let __else = {
                    let mut __mask = ::rt_std::cpu::lanes::and_not(&__mask, &#c);
                    if ::rt_std::cpu::lanes::any(&__mask) { #els }
                    __mask
                };
                __mask = ::rt_std::cpu::lanes::or(&__then, &__else);
            }
        };
        Ok((code, true))
    }

    /// A statement run lane by lane.
    fn per_lane(&mut self, e: &syn::Expr) -> Result<(TokenStream, bool), Refusal> {
        let retires = returns(e);
        let mut e = e.clone();
        for_lane(&mut e, &self.varying, retires)?;
        let code = quote! {
            ::rt_std::cpu::lanes::each(&mut __mask, |__l| {
                #[allow(unreachable_code)]
                {
                    #e;
                    false
                }
            });
        };
        Ok((code, retires))
    }

    /// An expression's value in each running lane.
    fn lanes_of(&mut self, e: &syn::Expr) -> Result<TokenStream, Refusal> {
        if returns(e) {
            return Err(Refusal::new(e.span(), "a `return` inside a value".into()));
        }
        let mut e = e.clone();
        for_lane(&mut e, &self.varying, false)?;
        Ok(quote!(::rt_std::cpu::lanes::fill(&__mask, |__l| #e)))
    }

    fn local(&mut self, l: &syn::Local) -> Result<TokenStream, Refusal> {
        let Some(init) = &l.init else {
            return Err(Refusal::new(l.span(), "a `let` without a value".into()));
        };
        if init.diverge.is_some() {
            return Err(Refusal::new(l.span(), "`let ... else`".into()));
        }
        if matches!(&*init.expr, syn::Expr::Closure(_)) {
            return Err(Refusal::new(init.expr.span(), "a closure bound to a local".into()));
        }
        let (pat, ty) = match &l.pat {
            syn::Pat::Type(t) => (&*t.pat, Some(&*t.ty)),
            p => (p, None),
        };
        let value = self.lanes_of(&init.expr)?;
        let code = match pat {
            syn::Pat::Ident(p) if p.by_ref.is_none() && p.subpat.is_none() => {
                let (m, name) = (&p.mutability, &p.ident);
                let annot = ty.map(|t| quote!(: [#t; ::rt_std::cpu::lanes::LANES]));
                quote!(#[allow(unused_mut)] let #m #name #annot = #value;)
            }
            // A pattern: the value per lane, then each name it binds.
            _ => {
                let tmp = format_ident!("__value{}", self.next);
                self.next += 1;
                let annot = ty.map(|t| quote!(: #t));
                let names = bound(pat);
                let mut out = quote!(let #tmp = #value;);
                for n in &names {
                    let m = mutability_of(pat, n);
                    out.extend(quote! {
                        #[allow(unused_mut)]
                        let #m #n = ::rt_std::cpu::lanes::fill(&__mask, |__l| {
                            #[allow(unused_variables, unused_mut)]
                            let #pat #annot = #tmp[__l];
                            #n
                        });
                    });
                }
                out
            }
        };
        for n in bound(pat) {
            self.varying.insert(n.to_string());
        }
        Ok(code)
    }
}

/// `mut` where the pattern binds `name` mutably.
fn mutability_of(pat: &syn::Pat, name: &syn::Ident) -> Option<syn::Token![mut]> {
    struct M<'n>(&'n syn::Ident, Option<syn::Token![mut]>);
    impl<'a> Visit<'a> for M<'_> {
        fn visit_pat_ident(&mut self, p: &'a syn::PatIdent) {
            if &p.ident == self.0 {
                self.1 = p.mutability;
            }
            syn::visit::visit_pat_ident(self, p);
        }
    }
    let mut m = M(name, None);
    m.visit_pat(pat);
    m.1
}

/// Whether `e` calls `rt_trace` (outside closures and items).
pub(super) fn traces(e: &syn::Expr) -> bool {
    struct T(bool);
    impl<'a> Visit<'a> for T {
        fn visit_expr_call(&mut self, c: &'a syn::ExprCall) {
            if let syn::Expr::Path(p) = &*c.func
                && p.path.segments.last().is_some_and(|s| s.ident.to_string().starts_with("rt_trace"))
            {
                self.0 = true;
            }
            syn::visit::visit_expr_call(self, c);
        }
        fn visit_expr_closure(&mut self, _: &'a syn::ExprClosure) {}
        fn visit_item(&mut self, _: &'a syn::Item) {}
    }
    let mut t = T(false);
    t.visit_expr(e);
    t.0
}

/// Whether `e` holds a `return` of the program (outside closures and items).
pub(super) fn returns(e: &syn::Expr) -> bool {
    struct R(bool);
    impl<'a> Visit<'a> for R {
        fn visit_expr_return(&mut self, _: &'a syn::ExprReturn) {
            self.0 = true;
        }
        fn visit_expr_closure(&mut self, _: &'a syn::ExprClosure) {}
        fn visit_item(&mut self, _: &'a syn::Item) {}
    }
    let mut r = R(false);
    r.visit_expr(e);
    r.0
}
