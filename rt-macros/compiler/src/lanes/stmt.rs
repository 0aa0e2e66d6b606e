//! A body's statements, lane-wise. `__mask` holds the running lanes; a
//! local that statements after its own run read holds a value per lane
//! (`[T; LANES]`). Statements run as:
//!
//! - **runs of plain statements**, fused: the statements themselves, run
//!   for one lane after the other (`each`), each lane through the whole
//!   run, as the scalar copy runs them (`rename.rs` reads the lane-wise
//!   locals of earlier statements as `x[__l]`); the run's own `let`s are
//!   plain locals inside it, and their values go to per-lane slots at the
//!   run's end (`Slots`), which become lane-wise locals after it. A
//!   `return` in the run takes its lane out of `__mask`;
//! - **a trace** (`rt_trace(object, ray, &mut payload)` with a lane-wise
//!   payload): the lanes' objects and rays first, then one call that hands
//!   them to the backend together;
//! - **a masked `if`** (one that holds such a trace): the condition per
//!   lane, then each branch under the lanes that take it, with the lanes
//!   that returned in either branch out of `__mask` after;
//! - a **block** (one that holds such a trace), its statements in turn.
//!
//! After a statement or run that may take lanes out, the rest of the block
//! runs only if a lane still runs (so each slot has a lane's value).

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
    /// A block's statements in a scope of their own. Its items (nested
    /// `fn`s, `const`s) come first, outside the runs, so every run sees
    /// them, as the whole block does in Rust.
    pub(super) fn block(&mut self, stmts: &[syn::Stmt]) -> Result<TokenStream, Refusal> {
        let outer = self.varying.clone();
        let (items, rest): (Vec<&syn::Stmt>, Vec<&syn::Stmt>) =
            stmts.iter().partition(|s| matches!(s, syn::Stmt::Item(_)));
        let rest: Vec<syn::Stmt> = rest.into_iter().cloned().collect();
        let r = self.stmts(&rest).map(|code| quote!(#(#items)* #code));
        self.varying = outer;
        r
    }

    fn stmts(&mut self, stmts: &[syn::Stmt]) -> Result<TokenStream, Refusal> {
        let Some(first) = stmts.first() else { return Ok(TokenStream::new()) };
        let (code, retires, locals, rest) = if self.structural_in(first, &self.varying) {
            let (code, retires) = self.stmt(first)?;
            (code, retires, TokenStream::new(), &stmts[1..])
        } else {
            // (A `let` of the run makes its local lane-wise for a trace
            // that ends the run.)
            let mut names = self.varying.clone();
            let n = stmts
                .iter()
                .take_while(|s| {
                    if let syn::Stmt::Local(l) = s {
                        names.extend(bound(untyped(&l.pat).0).iter().map(|i| i.to_string()));
                    }
                    !self.structural_in(s, &names)
                })
                .count();
            let (code, retires, locals) = self.fused(&stmts[..n])?;
            (code, retires, locals, &stmts[n..])
        };
        let mut out = code;
        let rest = self.stmts(rest)?;
        if rest.is_empty() {
            return Ok(out);
        }
        if retires {
            out.extend(quote!(if ::rt_std::cpu::lanes::any(&__mask) { #locals #rest }));
        } else {
            out.extend(locals);
            out.extend(rest);
        }
        Ok(out)
    }

    /// A run of plain statements for each lane in turn (see the module's
    /// doc), the slots of its `let`s after it; whether a lane may return.
    /// The code, whether a lane may return, and the slots' lane-wise locals
    /// for the statements after the run (to run only while a lane runs).
    fn fused(&mut self, stmts: &[syn::Stmt]) -> Result<(TokenStream, bool, TokenStream), Refusal> {
        let outer = self.varying.clone();
        let mut body = TokenStream::new();
        let mut retires = false;
        // The run's locals by name: the slot its last binding goes to.
        let mut exports: Vec<(syn::Ident, syn::Ident, Option<syn::Token![mut]>)> = Vec::new();
        for s in stmts {
            match s {
                syn::Stmt::Local(l) => {
                    self.check_local(l)?;
                    let mut l = l.clone();
                    if let Some(init) = &mut l.init {
                        // (`let x = if c { return; } else { .. };`)
                        retires |= returns(&init.expr);
                        for_lane(&mut init.expr, &self.varying, true)?;
                    }
                    let (pat, _) = untyped(&l.pat);
                    for n in bound(pat) {
                        self.varying.remove(&n.to_string());
                        exports.retain(|(name, _, _)| *name != n);
                        let slot = format_ident!("__slot{}", self.next);
                        self.next += 1;
                        exports.push((n.clone(), slot, mutability_of(pat, &n)));
                    }
                    body.extend(quote!(#l));
                }
                syn::Stmt::Item(item) => body.extend(quote!(#item)),
                syn::Stmt::Macro(m) => {
                    let mut e = syn::Expr::Macro(syn::ExprMacro { attrs: m.attrs.clone(), mac: m.mac.clone() });
                    for_lane(&mut e, &self.varying, true)?;
                    body.extend(quote!(#e;));
                }
                syn::Stmt::Expr(e, _) => {
                    retires |= returns(e);
                    let mut e = e.clone();
                    for_lane(&mut e, &self.varying, true)?;
                    body.extend(quote!(#e;));
                }
            }
        }
        let slots = exports.iter().map(|(_, slot, _)| quote!(let mut #slot = ::rt_std::cpu::lanes::Slots::new();));
        let sets = exports.iter().map(|(name, slot, _)| quote!(#slot.set(__l, #name);));
        let finishes =
            exports.iter().map(|(name, slot, m)| quote!(#[allow(unused_mut)] let #m #name = #slot.finish();));
        let code = quote! {
            #(#slots)*
            ::rt_std::cpu::lanes::each(&mut __mask, |__l| {
                #[allow(unreachable_code)]
                {
                    #body
                    #(#sets)*
                    false
                }
            });
        };
        self.varying = outer;
        for (name, _, _) in &exports {
            self.varying.insert(name.to_string());
        }
        Ok((code, retires, quote!(#(#finishes)*)))
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
        let Some((c, payload)) = packet_payload(e, &self.varying) else { return Ok(None) };
        let (object, ray) = (&c.args[0], &c.args[1]);
        // (Refused here, at the argument's own line: the tuple below has
        // no span of the user's.)
        if let Some(a) = [object, ray].into_iter().find(|a| returns(a)) {
            return Err(Refusal::new(a.span(), "a `return` inside a value".into()));
        }
        let both = self.lanes_of(&syn::parse_quote!((#object, #ray)))?;
        Ok(Some(quote! {
            {
                let __both = #both;
                let __objects = ::core::array::from_fn(|l| __both[l].0);
                let __rays = ::core::array::from_fn(|l| __both[l].1);
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

    /// A `let` the fused run takes: with a value, without `else`, not a
    /// closure (whose value has no slot).
    fn check_local(&self, l: &syn::Local) -> Result<(), Refusal> {
        let Some(init) = &l.init else {
            return Err(Refusal::new(l.span(), "a `let` without a value".into()));
        };
        if init.diverge.is_some() {
            return Err(Refusal::new(l.span(), "`let ... else`".into()));
        }
        if matches!(&*init.expr, syn::Expr::Closure(_)) {
            return Err(Refusal::new(init.expr.span(), "a closure bound to a local".into()));
        }
        Ok(())
    }

    /// Whether `s` runs for all lanes at once: a `return`, or a trace with
    /// a lane-wise payload, alone or in an `if` or a block.
    /// `varying`: the lane-wise locals at `s`.
    fn structural_in(&self, s: &syn::Stmt, varying: &HashSet<String>) -> bool {
        let syn::Stmt::Expr(e, _) = s else { return false };
        match e {
            syn::Expr::Return(_) => true,
            syn::Expr::Call(_) => packet_payload(e, varying).is_some(),
            syn::Expr::If(i) => !matches!(&*i.cond, syn::Expr::Let(_)) && traces(e),
            syn::Expr::Block(b) => b.label.is_none() && traces(e),
            _ => false,
        }
    }

    /// A structural statement's code, and whether it may take lanes out.
    fn stmt(&mut self, s: &syn::Stmt) -> Result<(TokenStream, bool), Refusal> {
        match s {
            syn::Stmt::Expr(e, _) => self.expr_stmt(e),
            other => Err(Refusal::new(other.span(), "a statement the lane-wise form does not take".into())),
        }
    }
}

/// `rt_trace(object, ray, &mut p)` with `p` a lane-wise local: the call
/// and `p`.
fn packet_payload<'e>(e: &'e syn::Expr, varying: &HashSet<String>) -> Option<(&'e syn::ExprCall, &'e syn::Ident)> {
    let syn::Expr::Call(c) = e else { return None };
    let syn::Expr::Path(f) = &*c.func else { return None };
    if f.path.segments.last().is_none_or(|s| s.ident != "rt_trace") || c.args.len() != 3 {
        return None;
    }
    let syn::Expr::Reference(r) = &c.args[2] else { return None };
    let syn::Expr::Path(p) = &*r.expr else { return None };
    let payload = p.path.get_ident().filter(|i| varying.contains(&i.to_string()))?;
    r.mutability.is_some().then_some((c, payload))
}

/// A `let`'s pattern without its type.
fn untyped(p: &syn::Pat) -> (&syn::Pat, Option<&syn::Type>) {
    match p {
        syn::Pat::Type(t) => (&t.pat, Some(&t.ty)),
        p => (p, None),
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
